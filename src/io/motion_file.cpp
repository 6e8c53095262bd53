// The `motion:` section: path speeds, acceleration, jerk, blending tolerance and where the part program's
// origin is. Every key is optional; a missing section gives the defaults of MotionSettings.
#include <fmt/format.h>

#include "io/machine_file_sections.hpp"

namespace pkm {

Result<MotionSettings> read_motion_settings(const YAML::Node& root, const YamlReader& reader, bool planar) {
  MotionSettings motion;
  const YAML::Node node = root["motion"];
  if (!node) return motion;
  if (auto keys = reader.check_keys(node, "motion",
                                    {"rapid_mm_min", "max_feed_mm_min", "path_accel_mm_s2", "path_jerk_mm_s3",
                                     "path_tolerance_mm", "angular_feed_deg_min", "program_origin_mm"});
      !keys) {
    return keys.error();
  }
  motion.line = yaml_key_line(root, "motion");

  struct Field {
    const char* key;
    double* value;
  };
  for (Field f :
       {Field{"rapid_mm_min", &motion.rapid_mm_min}, Field{"max_feed_mm_min", &motion.max_feed_mm_min},
        Field{"path_accel_mm_s2", &motion.path_accel_mm_s2},
        Field{"path_jerk_mm_s3", &motion.path_jerk_mm_s3},
        Field{"path_tolerance_mm", &motion.path_tolerance_mm},
        Field{"angular_feed_deg_min", &motion.angular_feed_deg_min}}) {
    const YAML::Node value = node[f.key];
    if (!value) continue;
    const std::string key = fmt::format("motion.{}", f.key);
    auto v = reader.number(value, key);
    if (!v) return v.error();
    // Zero would stall the planner (speeds, acceleration, jerk) or forbid every corner (tolerance).
    if (!(*v > 0.0)) return reader.error_at(value, key, fmt::format("must be positive, got {}", *v));
    *f.value = *v;
  }

  if (const YAML::Node origin = node["program_origin_mm"]) {
    const char* key = "motion.program_origin_mm";
    // Planar machines move in z = 0: [x, y] or, for files shared with spatial tools, [x, y, 0].
    const int dims = planar && origin.IsSequence() && origin.size() == 2 ? 2 : 3;
    if (planar && origin.IsSequence() && origin.size() != 2 && origin.size() != 3) {
      return reader.error_at(origin, key,
                             fmt::format("expected [x, y] or [x, y, 0], got {} numbers", origin.size()));
    }
    auto p = reader.point(origin, key, dims);
    if (!p) return p.error();
    if (planar && p->z() != 0.0) {
      return reader.error_at(origin, key, fmt::format("a planar machine moves in z = 0, got z = {}", p->z()));
    }
    motion.program_origin_mm = *p;
  }
  return motion;
}

}  // namespace pkm
