#pragma once
// Loading and validating machine files (schema: docs/machine-file.md). Checked once, at load.
#include <yaml-cpp/yaml.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "io/yaml_reader.hpp"
#include "machine/machine.hpp"

namespace pkm {

/// Everything a mechanism builder needs from the file; keys common to all mechanisms are already read.
struct MechanismSpec {
  const YAML::Node& root;
  const YamlReader& reader;
  AngleConvention convention;
  Eigen::Vector3d tool_mm;         ///< tool point in the platform frame
  std::optional<PoseVector> home;  ///< from `home:` (mm, rad), dependent coordinates not yet completed
  const ActuatorLimits& limits;    ///< to choose a default home in the middle of the actuator range
};

using MechanismBuilder = std::function<Result<std::unique_ptr<Mechanism>>(const MechanismSpec&)>;

struct MechanismFileEntry {
  MechanismType type;
  std::vector<std::string_view> keys;  ///< mechanism-specific keys accepted at the top level
  int home_values;                     ///< numbers in `home:` (2 planar2, 3 planar3, else 6)
  MechanismBuilder build;
};

/// The table of mechanisms a machine file can name (one entry per mechanism file).
const std::vector<MechanismFileEntry>& mechanism_file_entries();

Result<Machine> load_machine_file(const std::string& path);
Result<Machine> parse_machine_text(const std::string& yaml_text, const std::string& source_name);

}  // namespace pkm
