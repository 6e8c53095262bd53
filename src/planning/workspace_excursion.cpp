#include "planning/workspace_excursion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <nlopt.hpp>

#include "core/units.hpp"
#include "io/json_text.hpp"
#include "machine/joint_limits.hpp"

namespace pkm::planning {

namespace {

// The kinds of limit a sample can break, in the order they are reported.
enum LimitKind { kReach, kActuatorMin, kActuatorMax, kBaseJoint, kPlatformJoint, kLimitKinds };
constexpr const char* kLimitKeys[kLimitKinds] = {"reach", "actuator_min", "actuator_max",
                                                 "base_joint_max_deg", "platform_joint_max_deg"};

// The translation search: how far (mm each way), how long, and how deep inside it aims before it stops (then
// the program clears every limit by this much, mm or deg).
constexpr double kOffsetRangeMm = 1000.0;
constexpr int kOffsetEvaluations = 3000;
constexpr double kOffsetClearance = 1.0;
constexpr std::size_t kOffsetSamples = 400;  // the thinned copy the search evaluates
// Out of reach counts as this much excess in the search's objective, per sample: any pose in reach is better.
constexpr double kUnreachedPenalty = 1e4;

/// One sample's signed excess per limit (negative: inside by that much; mm, or deg for angles and angular
/// actuators), with the actuator or joint that sets it.
struct SampleExcess {
  bool reached = true;
  std::array<double, kLimitKinds> value;
  std::array<int, kLimitKinds> index{};
  double worst() const { return *std::max_element(value.begin() + 1, value.end()); }
};

SampleExcess sample_excess(const Machine& machine, const Pose& pose) {
  SampleExcess e;
  e.value.fill(-std::numeric_limits<double>::infinity());
  auto ik = machine.mechanism->inverse(pose);
  if (!ik) {
    e.reached = false;
    return e;
  }
  const double scale = machine.mechanism->actuators_are_angles() ? deg_from_rad(1.0) : 1.0;
  const auto raise = [&e](LimitKind kind, double value, int index) {
    if (value > e.value[kind]) e.value[kind] = value, e.index[kind] = index;
  };
  for (int j = 0; j < static_cast<int>(ik->size()); ++j) {
    if (machine.limits.min) raise(kActuatorMin, (*machine.limits.min - (*ik)[j]) * scale, j + 1);
    if (machine.limits.max) raise(kActuatorMax, ((*ik)[j] - *machine.limits.max) * scale, j + 1);
  }
  const JointLimits& joints = machine.joint_limits;
  if (joints.base_joint_max_rad || joints.platform_joint_max_rad) {
    const PassiveJointAngles angles = passive_joint_angles(machine, pose);
    for (int j = 0; j < angles.count; ++j) {
      if (joints.base_joint_max_rad)
        raise(kBaseJoint, deg_from_rad(angles.base_rad[j] - *joints.base_joint_max_rad), j + 1);
      if (joints.platform_joint_max_rad)
        raise(kPlatformJoint, deg_from_rad(angles.platform_rad[j] - *joints.platform_joint_max_rad), j + 1);
    }
  }
  return e;
}

bool outside(const SampleExcess& e) {
  return !e.reached || e.worst() > 0.0;
}

Pose sample_pose(const path::Path& path, double s, int segment, const Eigen::Vector3d& offset_mm) {
  const path::PathPoint point = path.evaluate(segment, s);
  return Pose{point.position_mm + offset_mm, point.rotation.toRotationMatrix()};
}

/// The search's objective at a translation: the largest excess over the thinned samples, out of reach
/// counting kUnreachedPenalty each.
struct OffsetObjective {
  const Machine& machine;
  const path::Path& path;
  std::vector<std::pair<double, int>> samples;  // (s, segment)
  std::array<int, 3> axes{};                    // program axes the search moves
  int dimensions = 0;

  Eigen::Vector3d offset(const std::vector<double>& x) const {
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    for (int k = 0; k < dimensions; ++k) t[axes[k]] = x[k];
    return t;
  }
  double operator()(const Eigen::Vector3d& t) const {
    double worst = -std::numeric_limits<double>::infinity(), unreached = 0.0;
    for (const auto& [s, segment] : samples) {
      const SampleExcess e = sample_excess(machine, sample_pose(path, s, segment, t));
      if (e.reached) {
        worst = std::max(worst, e.worst());
      } else {
        unreached += kUnreachedPenalty;
      }
    }
    return unreached + (std::isfinite(worst) ? worst : 0.0);
  }
};

std::optional<Eigen::Vector3d> search_offset(const Machine& machine, const path::Path& path,
                                             const std::vector<double>& s, const std::vector<int>& segment) {
  OffsetObjective objective{machine, path, {}, {}, 0};
  const AxisMask mask = machine.mechanism->controlled_axes();
  for (int c = 0; c < 3; ++c) {
    if (mask.controlled[c]) objective.axes[objective.dimensions++] = c;
  }
  if (objective.dimensions == 0) return std::nullopt;
  const bool limited = machine.limits.min || machine.limits.max || machine.joint_limits.base_joint_max_rad ||
                       machine.joint_limits.platform_joint_max_rad;
  const std::size_t stride = std::max<std::size_t>(1, s.size() / kOffsetSamples);
  for (std::size_t i = 0; i < s.size(); i += stride) objective.samples.emplace_back(s[i], segment[i]);
  objective.samples.emplace_back(s.back(), segment.back());

  nlopt::opt optimizer(nlopt::LN_SBPLX, static_cast<unsigned>(objective.dimensions));
  optimizer.set_lower_bounds(std::vector<double>(objective.dimensions, -kOffsetRangeMm));
  optimizer.set_upper_bounds(std::vector<double>(objective.dimensions, kOffsetRangeMm));
  optimizer.set_maxeval(kOffsetEvaluations);
  optimizer.set_initial_step(10.0);
  optimizer.set_xtol_abs(1e-3);
  // Without position limits only reach can be wrong: the first translation that reaches everything will do.
  optimizer.set_stopval(limited ? -kOffsetClearance : 0.5 * kUnreachedPenalty);
  optimizer.set_min_objective(
      [](const std::vector<double>& x, std::vector<double>&, void* data) {
        const auto* o = static_cast<const OffsetObjective*>(data);
        return (*o)(o->offset(x));
      },
      &objective);
  std::vector<double> x(objective.dimensions, 0.0);
  double best = 0.0;
  try {
    optimizer.optimize(x, best);
  } catch (const std::exception&) {
    return std::nullopt;  // NLopt's failures (roundoff limited, forced stop): no translation to offer
  }
  const Eigen::Vector3d t = objective.offset(x);
  for (std::size_t i = 0; i < s.size(); ++i) {  // the thinned search proves nothing about the samples between
    if (outside(sample_excess(machine, sample_pose(path, s[i], segment[i], t)))) return std::nullopt;
  }
  return t;
}

}  // namespace

WorkspaceExcursions find_excursions(const Machine& machine, const path::Path& path,
                                    const std::vector<double>& s, const std::vector<int>& segment) {
  WorkspaceExcursions found;
  std::array<LimitExcess, kLimitKinds> largest;
  for (int k = 0; k < kLimitKinds; ++k) largest[k].limit = kLimitKeys[k];
  const bool angular_actuators = machine.mechanism->actuators_are_angles();
  bool in_excursion = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const int line = path.segment(segment[i]).line;
    const SampleExcess e =
        sample_excess(machine, sample_pose(path, s[i], segment[i], Eigen::Vector3d::Zero()));
    if (!outside(e)) {
      in_excursion = false;
      continue;
    }
    if (!in_excursion) found.excursions.push_back({line, line, 0.0});
    Excursion& current = found.excursions.back();
    if (in_excursion) current.length_mm += s[i] - s[i - 1];
    current.last_line = line;
    in_excursion = true;
    if (!e.reached) {
      if (largest[kReach].excess == 0.0) largest[kReach].line = line;
      largest[kReach].excess += 1.0;
      continue;
    }
    for (int k = kActuatorMin; k < kLimitKinds; ++k) {
      if (e.value[k] > largest[k].excess)
        largest[k].excess = e.value[k], largest[k].index = e.index[k], largest[k].line = line;
    }
  }
  for (int k = 0; k < kLimitKinds; ++k) {
    if (largest[k].excess <= 0.0) continue;
    largest[k].unit = k == kReach                                                      ? "samples"
                      : (k == kActuatorMin || k == kActuatorMax) && !angular_actuators ? "mm"
                                                                                       : "deg";
    found.largest.push_back(largest[k]);
  }
  if (!found.excursions.empty()) found.offset_mm = search_offset(machine, path, s, segment);
  return found;
}

std::string describe_excursions(const WorkspaceExcursions& found) {
  std::string text;
  for (std::size_t k = 0; k < found.excursions.size(); ++k) {
    const Excursion& e = found.excursions[k];
    text +=
        fmt::format("{}line {} to line {} ({:.1f} mm of path)", k == 0 ? "outside the workspace from " : ", ",
                    e.first_line, e.last_line, e.length_mm);
  }
  for (std::size_t k = 0; k < found.largest.size(); ++k) {
    const LimitExcess& l = found.largest[k];
    text += k == 0 ? "; largest excess: " : ", ";
    if (l.limit == "reach") {
      text += fmt::format("{:g} samples no actuator setting reaches (from line {})", l.excess, l.line);
    } else {
      text += fmt::format("{} by {:.3f} {} ({} {}, line {})", l.limit, l.excess, l.unit,
                          l.limit.starts_with("actuator") ? "actuator" : "joint", l.index, l.line);
    }
  }
  if (found.offset_mm) {
    const Eigen::Vector3d& t = *found.offset_mm;
    text += fmt::format(
        "; moving the program by X{:+.3f} Y{:+.3f} Z{:+.3f} mm (motion.program_origin_mm) brings "
        "all of it inside",
        t.x(), t.y(), t.z());
  } else if (!found.excursions.empty()) {
    text += fmt::format("; no translation of the program within ±{:g} mm brings all of it inside",
                        kOffsetRangeMm);
  }
  return text;
}

std::string excursions_json(const WorkspaceExcursions& found) {
  nlohmann::json out = {{"excursions", nlohmann::json::array()}, {"largest", nlohmann::json::array()}};
  for (const Excursion& e : found.excursions)
    out["excursions"].push_back(
        {{"first_line", e.first_line}, {"last_line", e.last_line}, {"length_mm", e.length_mm}});
  for (const LimitExcess& l : found.largest) {
    out["largest"].push_back(
        {{"limit", l.limit}, {"index", l.index}, {"excess", l.excess}, {"unit", l.unit}, {"line", l.line}});
  }
  out["offset_mm"] =
      found.offset_mm
          ? nlohmann::json::array({found.offset_mm->x(), found.offset_mm->y(), found.offset_mm->z()})
          : nlohmann::json(nullptr);
  return json_text(out, -1);
}

}  // namespace pkm::planning
