// Machine-file entry of the rotopod (docs/mechanisms/rotopod.md): `circle: {center: [x, y], radius: R}`,
// `joint_heights` (6 numbers or one for all), `strut_lengths` (6), `platform_joints` (6, platform frame),
// optional `branch` (6 × ±1, default +1). Carriage angles are degrees in files and on the command line,
// radians inside.
#include <fmt/format.h>

#include <cmath>

#include "io/mechanism_files.hpp"
#include "machine/rotopod.hpp"

namespace pkm {
namespace {

Status read_circle(const YamlReader& reader, const YAML::Node& root, RotopodGeometry& geometry) {
  const YAML::Node circle = root["circle"];
  if (!circle) return reader.error_missing(root, "circle", "a map {center: [x, y], radius: R}");
  if (auto keys = reader.check_keys(circle, "circle", {"center", "radius"}); !keys) return keys;
  const YAML::Node center = circle["center"];
  if (!center) return reader.error_missing(circle, "circle.center", "a list of 2 numbers");
  auto c = reader.point(center, "circle.center", 2);
  if (!c) return c.error();
  const YAML::Node radius = circle["radius"];
  if (!radius) return reader.error_missing(circle, "circle.radius", "a number (mm)");
  auto r = reader.number(radius, "circle.radius");
  if (!r) return r.error();
  if (!(*r > 0.0)) return reader.error_at(radius, "circle.radius", "the circle radius must be positive");
  geometry.circle_center_mm = c->head<2>();
  geometry.circle_radius_mm = *r;
  return ok_status();
}

Status read_heights(const YamlReader& reader, const YAML::Node& root, RotopodGeometry& geometry) {
  const YAML::Node node = root["joint_heights"];
  if (!node) return reader.error_missing(root, "joint_heights", "one number or a list of 6 numbers (mm)");
  if (node.IsScalar()) {
    auto z = reader.number(node, "joint_heights");
    if (!z) return z.error();
    geometry.joint_heights_mm.fill(*z);
    return ok_status();
  }
  auto heights = reader.numbers(root, "joint_heights", 6);
  if (!heights) return heights.error();
  for (int j = 0; j < 6; ++j) geometry.joint_heights_mm[j] = (*heights)[j];
  return ok_status();
}

}  // namespace

MechanismFileEntry rotopod_file_entry() {
  return {MechanismType::rotopod,
          {"circle", "joint_heights", "strut_lengths", "platform_joints", "branch"},
          6,
          [](const MechanismSpec& spec) -> Result<std::unique_ptr<Mechanism>> {
            const YamlReader& reader = spec.reader;
            RotopodGeometry geometry;
            if (auto circle = read_circle(reader, spec.root, geometry); !circle) return circle.error();
            if (auto heights = read_heights(reader, spec.root, geometry); !heights) return heights.error();
            auto lengths = reader.numbers(spec.root, "strut_lengths", 6);
            if (!lengths) return lengths.error();
            auto platform = reader.points(spec.root, "platform_joints", 6, 3);
            if (!platform) return platform.error();
            for (int j = 0; j < 6; ++j) {
              if (!((*lengths)[j] > 0.0)) {
                return reader.error_at(spec.root["strut_lengths"][j], fmt::format("strut_lengths[{}]", j),
                                       "a strut length must be positive");
              }
              geometry.strut_lengths_mm[j] = (*lengths)[j];
              geometry.platform_joints_mm[j] = (*platform)[j] - spec.tool_mm;
            }
            if (spec.root["branch"]) {
              auto branch = reader.numbers(spec.root, "branch", 6);
              if (!branch) return branch.error();
              for (int j = 0; j < 6; ++j) {
                if ((*branch)[j] != 1.0 && (*branch)[j] != -1.0) {
                  return reader.error_at(spec.root["branch"][j], fmt::format("branch[{}]", j),
                                         fmt::format("expected +1 or -1, got {}", (*branch)[j]));
                }
                geometry.branches[j] = static_cast<int>((*branch)[j]);
              }
            }

            const Pose home =
                spec.home ? pose_from_vector(spec.convention, *spec.home) : rotopod_default_home(geometry);
            auto rotopod = std::make_unique<Rotopod>(geometry, spec.convention, home);
            const YAML::Node where = spec.root["home"] ? spec.root["home"] : spec.root["circle"];
            if (auto reachable = rotopod->inverse(rotopod->home()); !reachable) {
              return reader.error_at(where, "home",
                                     "the home pose is not reachable: " + reachable.error().message);
            }
            // Singular homes make every FK from them ill-posed.
            if (!(rotopod->path_conditioning(rotopod->home()) > 1e-6)) {
              return reader.error_at(where, "home",
                                     "a strut is perpendicular to its carriage's circle at the home pose");
            }
            if (!(std::abs(rotopod->strut_line_determinant(rotopod->home())) > 1e-9)) {
              return reader.error_at(where, "home", "the rotopod is singular at its home pose (det = 0)");
            }
            return std::unique_ptr<Mechanism>(std::move(rotopod));
          }};
}

}  // namespace pkm
