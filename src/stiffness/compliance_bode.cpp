#include "stiffness/compliance_bode.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/units.hpp"

namespace pkm::stiffness {
namespace {

// A sweep of more points than this is a mistyped count, not a plot (each point is a 6 × 6 complex solve).
constexpr int kMaxBodePoints = 100000;
constexpr double kBodeUmPerMm = 1e3;

}  // namespace

std::vector<BodeEntry> default_bode_entries(const Mechanism& mechanism, const Pose& pose) {
  // The tool axis as run_deflection takes it: base z at home, turned with the platform.
  const Eigen::Vector3d axis =
      (pose.rotation * mechanism.home().rotation.transpose() * Eigen::Vector3d::UnitZ()).normalized();
  return {{"xx", Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX()},
          {"yy", Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitY()},
          {"zz", Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()},
          {"tool_axis", axis, axis}};
}

Result<std::vector<double>> log_spaced_frequencies(double f_min_Hz, double f_max_Hz, int points) {
  if (!(std::isfinite(f_min_Hz) && f_min_Hz > 0.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("lowest frequency must be a finite number > 0 Hz, got {}", f_min_Hz));
  }
  if (!(std::isfinite(f_max_Hz) && f_max_Hz > f_min_Hz)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("highest frequency must be finite and above the lowest ({} Hz), got {}",
                                  f_min_Hz, f_max_Hz));
  }
  if (points < 2 || points > kMaxBodePoints) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("frequency points must be 2…{}, got {}", kMaxBodePoints, points));
  }
  std::vector<double> f(static_cast<std::size_t>(points));
  const double ratio = std::log(f_max_Hz / f_min_Hz);
  // Each point from the ends, not by repeated multiplication: the last one is f_max exactly.
  for (int k = 0; k < points; ++k) f[k] = f_min_Hz * std::exp(ratio * k / (points - 1));
  f.back() = f_max_Hz;
  return f;
}

Result<BodeData> bode_data(const ToolDynamics& dynamics, const std::vector<BodeEntry>& entries,
                           const std::vector<double>& frequencies_Hz) {
  BodeData out;
  out.frequency_Hz = frequencies_Hz;
  out.entries = entries;
  out.natural_frequency_Hz = dynamics.frequency_Hz;
  out.damping_ratio = dynamics.damping_ratio;
  out.damping = dynamics.assumption;
  out.magnitude_um_N.assign(entries.size(), std::vector<double>(frequencies_Hz.size()));
  out.phase_deg.assign(entries.size(), std::vector<double>(frequencies_Hz.size()));
  for (std::size_t k = 0; k < frequencies_Hz.size(); ++k) {
    auto w = dynamic_compliance(dynamics, frequencies_Hz[k]);
    if (!w) return w.error();
    const Eigen::Matrix<std::complex<double>, 3, 3> translational = w->topLeftCorner<3, 3>();
    for (std::size_t e = 0; e < entries.size(); ++e) {
      const std::complex<double> value =
          (entries[e].displacement_direction.cast<std::complex<double>>().transpose() * translational *
           entries[e].force_direction.cast<std::complex<double>>())(0, 0);
      out.magnitude_um_N[e][k] = std::abs(value) * kBodeUmPerMm;
      out.phase_deg[e][k] = deg_from_rad(std::arg(value));
    }
  }
  return out;
}

Result<BodeData> machine_bode(const Machine& machine, const Pose& pose, const BodeRequest& request) {
  auto model = dynamics::make_elastic_model(machine);
  if (!model) return model.error();
  auto frequencies = log_spaced_frequencies(request.f_min_Hz, request.f_max_Hz, request.points);
  if (!frequencies) return frequencies.error();
  auto linear = tool_dynamics(*model, pose, request.options);
  if (!linear) return linear.error();
  return bode_data(*linear, default_bode_entries(*machine.mechanism, linear->pose), *frequencies);
}

}  // namespace pkm::stiffness
