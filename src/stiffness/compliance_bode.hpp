#pragma once
// Bode data of the tool's dynamic compliance (dynamic_compliance.hpp): magnitude (µm/N) and phase (deg) of
// chosen entries of W(iω) over a log-spaced frequency range, and its CSV file (for the Bode plots of
// the tool compliance in the report; Rusanov et al.'s "Tools App"). An entry is the
// displacement along a unit direction r per unit force along a unit direction l: rᵀ W_dd l, W_dd the
// translational block. Direct entries (r = l) have a phase in [−180°, 0°]: the displacement lags the force,
// by 90° at a lightly damped resonance and towards 180° above it.
#include <string>
#include <vector>

#include "stiffness/dynamic_compliance.hpp"

namespace pkm::stiffness {

struct BodeEntry {
  std::string name;  ///< the CSV's column stem: "xx" gives xx_magnitude_um_N, xx_phase_deg
  Eigen::Vector3d displacement_direction = Eigen::Vector3d::UnitX();  ///< r, unit, base frame
  Eigen::Vector3d force_direction = Eigen::Vector3d::UnitX();         ///< l, unit, base frame
};

/// The direct compliances along x, y, z ("xx", "yy", "zz") and along the tool axis ("tool_axis": the
/// platform's z axis turned as at home, the axis run_deflection.hpp takes for the surface normal) of a
/// machine at `pose`.
std::vector<BodeEntry> default_bode_entries(const Mechanism& mechanism, const Pose& pose);

/// `points` frequencies from `f_min_Hz` to `f_max_Hz` evenly spaced on a log scale, both ends included.
/// Fails (bad_input) unless 0 < f_min < f_max, both finite, and 2 ≤ points ≤ 100 000.
Result<std::vector<double>> log_spaced_frequencies(double f_min_Hz, double f_max_Hz, int points);

struct BodeData {
  std::vector<double> frequency_Hz;
  std::vector<BodeEntry> entries;
  /// [entry][frequency]: |rᵀ W l| in µm/N, and its argument in degrees (−180…180).
  std::vector<std::vector<double>> magnitude_um_N;
  std::vector<std::vector<double>> phase_deg;
  dynamics::CoordinateVector natural_frequency_Hz;  ///< the model's, for the record
  dynamics::CoordinateVector damping_ratio;         ///< ζ of each mode under the assumption
  DampingAssumption damping;
};

/// The Bode data of `dynamics` for `entries` at `frequencies_Hz`.
Result<BodeData> bode_data(const ToolDynamics& dynamics, const std::vector<BodeEntry>& entries,
                           const std::vector<double>& frequencies_Hz);

/// What a Bode request of a machine is: the frequency range and the model's options.
struct BodeRequest {
  double f_min_Hz = 10.0;
  double f_max_Hz = 2000.0;
  int points = 200;
  DynamicComplianceOptions options;
};

/// The whole chain for a machine at a pose: its elastic model (the `dynamics:` section; errors name the
/// file and the key), the linear model at the pose, the default entries over the requested range.
Result<BodeData> machine_bode(const Machine& machine, const Pose& pose, const BodeRequest& request);

}  // namespace pkm::stiffness
