// The `drives:` section: what the actuators' step/servo drives can do (Smirnov, §5.2.2: the drive resolution
// Δ and the servo period h). Every key is optional; `pkm interpolate` takes its defaults from here.
#include <fmt/format.h>

#include "io/machine_file_sections.hpp"

namespace pkm {

Result<DriveSettings> read_drive_settings(const YAML::Node& root, const YamlReader& reader,
                                          bool angular_actuators) {
  DriveSettings drives;
  const YAML::Node node = root["drives"];
  if (!node) return drives;
  // The resolution is in the actuators' own unit, and the key says which: a misread unit would be silent.
  const char* step_key = angular_actuators ? "step_deg" : "step_mm";
  if (auto keys = reader.check_keys(node, "drives", {step_key, "max_step_rate_hz", "period_ms"}); !keys) {
    return keys.error();
  }
  drives.line = yaml_key_line(root, "drives");

  struct Field {
    const char* key;
    std::optional<double>* value;
  };
  for (Field f : {Field{step_key, &drives.step}, Field{"max_step_rate_hz", &drives.max_step_rate_hz},
                  Field{"period_ms", &drives.period_ms}}) {
    const YAML::Node value = node[f.key];
    if (!value) continue;
    const std::string key = fmt::format("drives.{}", f.key);
    auto v = reader.number(value, key);
    if (!v) return v.error();
    if (!(*v > 0.0)) return reader.error_at(value, key, fmt::format("must be positive, got {}", *v));
    *f.value = *v;
  }
  // The interpolator's carrier period range (Smirnov 2019, §5.1: 100 Hz … 10 kHz).
  if (drives.period_ms && (*drives.period_ms < 0.1 || *drives.period_ms > 20.0)) {
    return reader.error_at(node["period_ms"], "drives.period_ms",
                           fmt::format("{} ms is outside 0.1…20 ms", *drives.period_ms));
  }
  return drives;
}

}  // namespace pkm
