#pragma once
// The `calibration:` section of a machine file (docs/machine-file.md, "Calibration"): the values a
// calibration identified, which replace the drawing's. Its keys are the group keys of the built mechanism
// (Mechanism::geometry_parameters: `base_joints`, `platform_joints_from_tool`, …), `actuator_offsets` (the
// drives' zero offsets, machine/actuator_offsets.hpp) and a free-text `note`. A calibrated machine file is
// the drawing plus this section, so the drawing stays readable and the calibration can be replaced whole.
#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "io/yaml_reader.hpp"
#include "machine/mechanism.hpp"

namespace pkm {

/// `mechanism` with the `calibration:` section of `root` applied: each given group replaces the drawing's
/// values (rows × columns checked, numbers finite; groups in rad are written in degrees), groups not given
/// keep them, and `actuator_offsets` wraps the result with the drive offsets. Without the section,
/// `mechanism` itself. Errors name file:line:column and the key (`calibration.base_joints[2]`); an unknown
/// key is listed with the allowed ones.
Result<std::unique_ptr<Mechanism>> apply_calibration_section(const YAML::Node& root, const YamlReader& reader,
                                                             std::unique_ptr<Mechanism> mechanism);

/// `original_yaml` (a machine file's text) with any earlier top-level `calibration:` block removed and a new
/// one appended: a comment saying pkm calibrate wrote it, `note`, and every group of `groups` (a calibrated
/// mechanism's geometry_parameters()) at full precision. Loading the result gives a mechanism whose inverse
/// kinematics equal the calibrated one's (to rounding, 1e-12 mm).
std::string calibrated_machine_text(std::string_view original_yaml, const std::vector<GeometryGroup>& groups,
                                    std::string_view note);

}  // namespace pkm
