#include "dynamics/run_elastic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "dynamics/natural_frequencies.hpp"

namespace pkm::dynamics {

void RunElastic::TickHistory::setpoint(double time_s, DriveSetpoint& out) const {
  const long first = std::max(0L, count - kRing);
  const Tick& oldest = at(first);
  const Tick& newest = at(with_slope - 1);
  if (time_s < oldest.time_s || (finished && time_s >= newest.time_s)) {
    const Tick& held = time_s < oldest.time_s ? oldest : newest;  // at rest before the start, after the end
    out.position_mm = held.actuators;
    out.rate_mm_s = ActuatorVector::Zero(held.actuators.size());
    out.load = held.load;
    return;
  }
  // The interval holding time_s among the ticks with known slopes (beyond the last: its extrapolation, which
  // the step limit keeps from being asked for).
  long i = first;
  while (i + 2 < with_slope && at(i + 1).time_s < time_s) ++i;
  const Tick& a = at(i);
  const Tick& b = at(i + 1);
  const double h = b.time_s - a.time_s;
  const double s = (time_s - a.time_s) / h, s2 = s * s, s3 = s2 * s;
  // The cubic Hermite basis in s = (t − t_a)/h and its derivatives; slopes per unit s are q̇·h.
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -6 * s2 + 6 * s, d11 = 3 * s2 - 2 * s;
  out.position_mm = h00 * a.actuators + (h10 * h) * a.slope + h01 * b.actuators + (h11 * h) * b.slope;
  out.rate_mm_s = (d00 / h) * a.actuators + d10 * a.slope + (d01 / h) * b.actuators + d11 * b.slope;
  out.load.force_N = (1.0 - s) * a.load.force_N + s * b.load.force_N;
  out.load.moment_Nmm = (1.0 - s) * a.load.moment_Nmm + s * b.load.moment_Nmm;
}

RunElastic::RunElastic(std::unique_ptr<ElasticModel> model, std::function<Status(const ElasticTick&)> on_tick,
                       const ElasticIntegration& integration, const statics::LoadModel* load)
    : model_(std::move(model)),
      history_(std::make_unique<TickHistory>()),
      on_tick_(std::move(on_tick)),
      load_(load),
      tool_axis_platform_(model_->mechanism->home().rotation.transpose() * Eigen::Vector3d::UnitZ()),
      simulator_(*model_, integration) {}

statics::Wrench RunElastic::load_at(const Tick& tick, const Eigen::Vector3d& velocity_mm_s) const {
  if (load_ == nullptr) return {};
  return load_->wrench_at(
      statics::travel_load_point(tick.pose, velocity_mm_s, tool_axis_platform_, tick.line, tick.cutting));
}

Result<RunElastic> RunElastic::make(const Machine& machine, double period_s,
                                    std::function<Status(const ElasticTick&)> on_tick,
                                    ElasticIntegration integration, const statics::LoadModel* load) {
  if (!(period_s > 0.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("elastic run: period {} s is not positive", period_s));
  }
  auto model = make_elastic_model(machine);
  if (!model) return model.error();
  // A step may pass the tick reported by at most one period: the drives are known that far (see above).
  integration.max_step_s =
      integration.max_step_s > 0.0 ? std::min(integration.max_step_s, period_s) : period_s;
  return RunElastic(std::make_unique<ElasticModel>(*model), std::move(on_tick), integration, load);
}

Status RunElastic::add(double time_s, int line, const Pose& commanded, const ActuatorVector& actuators,
                       bool cutting) {
  TickHistory& h = *history_;
  const long k = h.count;
  Tick& t = h.at(k);
  t = Tick{time_s, line, commanded, actuators, ActuatorVector::Zero(actuators.size()), cutting, {}};
  ++h.count;
  if (k == 0) {
    h.with_slope = 1;  // at rest
    t.load = load_at(t, Eigen::Vector3d::Zero());
    return begin(t);
  }
  if (k >= 2) {
    // The central difference at tick k − 1: q(t) is now known up to it.
    Tick& middle = h.at(k - 1);
    const Tick& before = h.at(k - 2);
    middle.slope = (actuators - before.actuators) / (time_s - before.time_s);
    middle.load =
        load_at(middle, (commanded.position_mm - before.pose.position_mm) / (time_s - before.time_s));
    h.with_slope = k;
    return report_until(k - 2);  // its steps may reach one period past it, to tick k − 1
  }
  return ok_status();
}

Status RunElastic::finish() {
  TickHistory& h = *history_;
  if (h.count == 0) return ok_status();
  Tick& last = h.at(h.count - 1);
  last.slope.setZero();  // the end, at rest
  last.load = load_at(last, Eigen::Vector3d::Zero());
  h.with_slope = h.count;
  h.finished = true;
  return report_until(h.count - 1);
}

Status RunElastic::begin(const Tick& first) {
  auto modes = natural_modes(*model_, first.pose);
  if (!modes) {
    return Error{modes.error().code, fmt::format("at {:.3f} s: {}", first.time_s, modes.error().message),
                 ErrorLocation{"", first.line, 0, ""}};
  }
  summary_.lowest_frequency_Hz = modes->frequency_Hz[0];
  summary_.start_deflection_mm = (modes->equilibrium.pose.position_mm - first.pose.position_mm).norm();
  if (Status started = simulator_.start(first.time_s, modes->equilibrium.pose,
                                        CoordinateVector::Zero(model_->coordinates));
      !started) {
    return started;
  }
  return report_until(0);
}

Status RunElastic::report_until(long last_index) {
  for (; reported_ <= last_index; ++reported_) {
    const Tick& tick = history_->at(reported_);
    if (reported_ > 0) {
      if (Status advanced = simulator_.advance_to(tick.time_s, *history_); !advanced) {
        return Error{advanced.error().code,
                     fmt::format("at {:.3f} s: {}", tick.time_s, advanced.error().message),
                     ErrorLocation{"", tick.line, 0, ""}};
      }
    }
    const Pose actual = simulator_.pose();
    ElasticTick t;
    t.time_s = tick.time_s;
    t.line = tick.line;
    t.deviation_mm = actual.position_mm - tick.pose.position_mm;
    t.rotation_deg =
        deg_from_rad(rotation_vector_from_rotation(actual.rotation * tick.pose.rotation.transpose()).norm());
    t.tool_error_mm = t.deviation_mm.norm();
    if (t.tool_error_mm > summary_.max_tool_error_mm) {
      summary_.max_tool_error_mm = t.tool_error_mm;
      summary_.max_tool_error_time_s = t.time_s;
      summary_.max_tool_error_line = t.line;
    }
    summary_.max_rotation_deg = std::max(summary_.max_rotation_deg, t.rotation_deg);
    ++summary_.ticks;
    summary_.counters = simulator_.counters();
    if (on_tick_) {
      if (Status written = on_tick_(t); !written) return written;
    }
  }
  return ok_status();
}

}  // namespace pkm::dynamics
