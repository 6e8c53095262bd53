// Machine-file entry of the glide machines (docs/mechanisms/glide.md): `guides` (3 or 6 maps {point,
// direction}, base frame), `strut_lengths` and `platform_joints` (same count), optional `branch` (±1 per
// carriage). Branch rule: given `branch` wins; else with `home:` each carriage takes the root nearer its
// guide point at home; else every branch is +1 and the home is glide_default_home (a level platform with its
// struts near 45° to their guides).
#include <fmt/format.h>

#include <cmath>

#include "io/mechanism_files.hpp"
#include "machine/glide.hpp"

namespace pkm {
namespace {

Result<Eigen::Vector3d> required_subpoint(const YamlReader& reader, const YAML::Node& parent,
                                          const std::string& where, const char* key) {
  const std::string full_key = fmt::format("{}.{}", where, key);
  const YAML::Node node = parent[key];
  if (!node) return reader.error_missing(parent, full_key, "a list of 3 numbers");
  return reader.point(node, full_key, 3);
}

Result<int> read_guides(const YamlReader& reader, const YAML::Node& root, GlideGeometry& geometry) {
  const YAML::Node guides = root["guides"];
  if (!guides) return reader.error_missing(root, "guides", "a list of 3 or 6 guides {point, direction}");
  if (!guides.IsSequence() || (guides.size() != 3 && guides.size() != 6)) {
    return reader.error_at(
        guides, "guides",
        fmt::format("expected a list of 3 or 6 guides {{point, direction}}, got {}",
                    guides.IsSequence() ? std::to_string(guides.size()) : std::string("no list")));
  }
  const int n = static_cast<int>(guides.size());
  for (int j = 0; j < n; ++j) {
    const std::string where = fmt::format("guides[{}]", j);
    if (auto keys = reader.check_keys(guides[j], where, {"point", "direction"}); !keys) return keys.error();
    auto point = required_subpoint(reader, guides[j], where, "point");
    if (!point) return point.error();
    auto direction = required_subpoint(reader, guides[j], where, "direction");
    if (!direction) return direction.error();
    if (!(direction->norm() > 1e-9)) {
      return reader.error_at(guides[j]["direction"], where + ".direction",
                             "a guide direction must not be zero");
    }
    geometry.guide_points_mm[j] = *point;
    geometry.guide_directions[j] = direction->normalized();
  }
  return n;
}

}  // namespace

MechanismFileEntry glide_file_entry() {
  return {MechanismType::glide,
          {"guides", "strut_lengths", "platform_joints", "branch"},
          6,
          [](const MechanismSpec& spec) -> Result<std::unique_ptr<Mechanism>> {
            const YamlReader& reader = spec.reader;
            GlideGeometry geometry;
            auto count = read_guides(reader, spec.root, geometry);
            if (!count) return count.error();
            const int n = *count;
            geometry.count = n;

            auto lengths = reader.numbers(spec.root, "strut_lengths", n);
            if (!lengths) return lengths.error();
            auto platform = reader.points(spec.root, "platform_joints", n, 3);
            if (!platform) return platform.error();
            for (int j = 0; j < n; ++j) {
              if (!((*lengths)[j] > 0.0)) {
                return reader.error_at(spec.root["strut_lengths"][j], fmt::format("strut_lengths[{}]", j),
                                       "a strut length must be positive");
              }
              geometry.strut_lengths_mm[j] = (*lengths)[j];
              geometry.platform_joints_mm[j] = (*platform)[j] - spec.tool_mm;
            }

            const bool branch_given = static_cast<bool>(spec.root["branch"]);
            if (branch_given) {
              auto branch = reader.numbers(spec.root, "branch", n);
              if (!branch) return branch.error();
              for (int j = 0; j < n; ++j) {
                if ((*branch)[j] != 1.0 && (*branch)[j] != -1.0) {
                  return reader.error_at(spec.root["branch"][j], fmt::format("branch[{}]", j),
                                         fmt::format("expected +1 or -1, got {}", (*branch)[j]));
                }
                geometry.branches[j] = static_cast<int>((*branch)[j]);
              }
            }

            Pose home;
            if (spec.home) {
              if (n == 3 && spec.home->tail<3>().cwiseAbs().maxCoeff() > 0.0) {
                return reader.error_at(
                    spec.root["home"], "home",
                    "a three-guide glide keeps its platform orientation fixed; the home angles "
                    "must be 0");
              }
              home = pose_from_vector(spec.convention, *spec.home);
              if (!branch_given) {
                // The root nearer the guide point: |t + r| <= |t − r| exactly when t = e·(B − P) <= 0.
                for (int j = 0; j < n; ++j) {
                  const Eigen::Vector3d w =
                      home.to_base(geometry.platform_joints_mm[j]) - geometry.guide_points_mm[j];
                  geometry.branches[j] = geometry.guide_directions[j].dot(w) <= 0.0 ? 1 : -1;
                }
              }
            } else {
              auto default_home = glide_default_home(geometry, spec.convention);
              if (!default_home) {
                return reader.error_at(spec.root["guides"], "home",
                                       "no default home: " + default_home.error().message + "; give `home:`");
              }
              home = *default_home;
            }

            auto glide = std::make_unique<Glide>(geometry, spec.convention, home);
            const YAML::Node where = spec.root["home"] ? spec.root["home"] : spec.root["guides"];
            if (auto reachable = glide->inverse(glide->home()); !reachable) {
              return reader.error_at(where, "home",
                                     "the home pose is not reachable: " + reachable.error().message);
            }
            // Singular homes make every FK from them ill-posed: struts perpendicular to their guides
            // (inverse) or dependent strut lines (forward).
            if (!(glide->guide_conditioning(glide->home()) > 1e-6)) {
              return reader.error_at(where, "home", "a strut is perpendicular to its guide at the home pose");
            }
            if (!(std::abs(glide->strut_line_determinant(glide->home())) > 1e-9)) {
              return reader.error_at(where, "home",
                                     "the glide machine is singular at its home pose (det = 0)");
            }
            return std::unique_ptr<Mechanism>(std::move(glide));
          }};
}

}  // namespace pkm
