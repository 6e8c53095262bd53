#pragma once
// The CSV files of the stiffness analyses: a stiffness map over a grid of poses (`pkm compliance --map`) and
// the dynamic compliance's Bode data (`--bode`). Written atomically (io/output_file.hpp): no half-written
// file, also when the write fails.
#include <string>
#include <vector>

#include "stiffness/compliance_bode.hpp"
#include "stiffness/stiffness_map.hpp"

namespace pkm::formats {

/// The map: the pose columns of `--pose` (dynamics/pose_grid_columns.hpp), lowest_stiffness_N_um,
/// direction_x, direction_y, direction_z (empty where there is none) and status ("ok", "unreachable",
/// "out_of_range", "singular"); one row per pose, the grid's order (its first axis fastest).
std::string stiffness_map_csv(const Mechanism& mechanism, const std::vector<Pose>& poses,
                              const std::vector<stiffness::StiffnessMapPoint>& points);
Status write_stiffness_map_csv(const std::string& path, const Mechanism& mechanism,
                               const std::vector<Pose>& poses,
                               const std::vector<stiffness::StiffnessMapPoint>& points);

/// The Bode data: a header `frequency_Hz,<name>_magnitude_um_N,<name>_phase_deg,…` and one row per frequency.
std::string bode_csv(const stiffness::BodeData& data);
Status write_bode_csv(const std::string& path, const stiffness::BodeData& data);

}  // namespace pkm::formats
