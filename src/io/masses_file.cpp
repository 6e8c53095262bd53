// The `masses:` section: platform and strut masses, the platform's centre of mass and gravity, for the
// gravity load of statics (statics/gravity.hpp). Every key is optional.
#include <fmt/format.h>

#include "io/machine_file_sections.hpp"

namespace pkm {

Result<MassProperties> read_mass_properties(const YAML::Node& root, const YamlReader& reader, bool planar) {
  MassProperties masses;
  const YAML::Node node = root["masses"];
  if (!node) return masses;
  if (auto keys =
          reader.check_keys(node, "masses", {"platform_kg", "platform_com_mm", "strut_kg", "gravity_mm_s2"});
      !keys) {
    return keys.error();
  }
  masses.line = yaml_key_line(root, "masses");

  struct MassField {
    const char* key;
    double* value;
    int* line;
  };
  for (MassField f : {MassField{"platform_kg", &masses.platform_kg, &masses.platform_kg_line},
                      MassField{"strut_kg", &masses.strut_kg, &masses.strut_kg_line}}) {
    const YAML::Node value = node[f.key];
    if (!value) continue;
    const std::string key = fmt::format("masses.{}", f.key);
    auto v = reader.number(value, key);
    if (!v) return v.error();
    if (!(*v >= 0.0))
      return reader.error_at(value, key, fmt::format("a mass cannot be negative, got {} kg", *v));
    *f.value = *v;
    *f.line = yaml_line(value);
  }

  if (const YAML::Node com = node["platform_com_mm"]) {
    const char* key = "masses.platform_com_mm";
    // Planar machines give points as [x, y], as everywhere else in their files; [x, y, z] is accepted too.
    const int dims = planar && com.IsSequence() && com.size() == 2 ? 2 : 3;
    if (planar && com.IsSequence() && com.size() != 2 && com.size() != 3) {
      return reader.error_at(com, key,
                             fmt::format("expected [x, y] or [x, y, z], got {} numbers", com.size()));
    }
    auto p = reader.point(com, key, dims);
    if (!p) return p.error();
    masses.platform_com_mm = *p;
    masses.platform_com_line = yaml_line(com);
  }
  if (const YAML::Node g = node["gravity_mm_s2"]) {
    auto v = reader.point(g, "masses.gravity_mm_s2", 3);
    if (!v) return v.error();
    masses.gravity_mm_s2 = *v;
    masses.gravity_line = yaml_line(g);
  }
  return masses;
}

}  // namespace pkm
