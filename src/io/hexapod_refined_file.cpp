// Machine-file entry of the refined hexapod (docs/mechanisms/hexapod_refined.md): the hexapod's keys plus
// `cardan`, a list of 6 maps of joint calibration constants, each key optional with the ideal joint as
// default:
//   axis1 [0,1,0], offset1 [0,0,0] mm, axis2 [1,0,0], offset2 [0,0,0] mm, strut_offset [0,0,0] mm, strut_axis
//   [0,0,1].
#include <fmt/format.h>

#include <cmath>

#include "core/units.hpp"
#include "io/mechanism_files.hpp"
#include "machine/hexapod_refined.hpp"

namespace pkm {
namespace {

// Real joints are close to ideal ones: axes within 30° of perpendicular, offsets below 10 % of the strut
// length. Beyond that the model is no longer "an ideal joint plus calibration errors" and the ideal-joint
// start of the per-leg Newton (and the ±90° fold rule) would not be meaningful.
constexpr double kMaxAxisCosine = 0.5;
constexpr double kMaxOffsetFraction = 0.1;

Result<CardanJoint> read_cardan_joint(const YAML::Node& node, int j, const YamlReader& reader) {
  const std::string where = fmt::format("cardan[{}]", j);
  if (auto keys = reader.check_keys(node, where,
                                    {"axis1", "offset1", "axis2", "offset2", "strut_offset", "strut_axis"});
      !keys) {
    return keys.error();
  }
  CardanJoint joint;
  struct Field {
    const char* key;
    Eigen::Vector3d* value;
    bool direction;
  };
  for (Field f :
       {Field{"axis1", &joint.axis1, true}, Field{"offset1", &joint.offset1_mm, false},
        Field{"axis2", &joint.axis2, true}, Field{"offset2", &joint.offset2_mm, false},
        Field{"strut_offset", &joint.strut_offset_mm, false}, Field{"strut_axis", &joint.strut_axis, true}}) {
    const YAML::Node value = node[f.key];
    if (!value) continue;
    const std::string key = fmt::format("{}.{}", where, f.key);
    auto p = reader.point(value, key, 3);
    if (!p) return p.error();
    if (f.direction) {
      if (!(p->norm() > 1e-9)) return reader.error_at(value, key, "a direction must not be zero");
      *f.value = p->normalized();
    } else {
      *f.value = *p;
    }
  }
  if (std::abs(joint.axis1.dot(joint.axis2)) > kMaxAxisCosine) {
    return reader.error_at(
        node, where + ".axis2",
        fmt::format("the two joint axes are {:.1f}° apart; a cardan joint needs them within 30° "
                    "of perpendicular",
                    deg_from_rad(std::acos(std::abs(joint.axis1.dot(joint.axis2))))));
  }
  if (std::abs(joint.axis2.dot(joint.strut_axis)) > kMaxAxisCosine) {
    return reader.error_at(node, where + ".strut_axis",
                           "the strut axis must be within 30° of perpendicular to axis2");
  }
  return joint;
}

}  // namespace

MechanismFileEntry hexapod_refined_file_entry() {
  return {MechanismType::hexapod_refined,
          {"base_joints", "platform_joints", "cardan"},
          6,
          [](const MechanismSpec& spec) -> Result<std::unique_ptr<Mechanism>> {
            auto read = read_hexapod_geometry(spec);
            if (!read) return read.error();
            const HexapodGeometry& geometry = read->geometry;
            const Pose& home_pose = read->home;
            const YAML::Node cardan = spec.root["cardan"];
            if (!cardan)
              return spec.reader.error_missing(spec.root, "cardan", "a list of 6 joint maps ({} = ideal)");
            if (!cardan.IsSequence() || cardan.size() != 6) {
              return spec.reader.error_at(
                  cardan, "cardan",
                  fmt::format("expected a list of 6 joint maps, got {}",
                              cardan.IsSequence() ? std::to_string(cardan.size()) : std::string("no list")));
            }
            std::array<CardanJoint, 6> joints;
            for (int j = 0; j < 6; ++j) {
              auto joint = read_cardan_joint(cardan[j], j, spec.reader);
              if (!joint) return joint.error();
              joints[j] = *joint;
            }

            for (int j = 0; j < 6; ++j) {
              const double length_mm =
                  (home_pose.to_base(geometry.platform_joints_mm[j]) - geometry.base_joints_mm[j]).norm();
              const double offsets_mm = joints[j].offset1_mm.norm() + joints[j].offset2_mm.norm() +
                                        joints[j].strut_offset_mm.norm();
              if (offsets_mm > kMaxOffsetFraction * length_mm) {
                return spec.reader.error_at(
                    cardan[j], fmt::format("cardan[{}]", j),
                    fmt::format("joint offsets add up to {:.3f} mm, more than 10 % of the "
                                "{:.3f} mm strut at home; they are calibration errors",
                                offsets_mm, length_mm));
              }
            }
            auto hexapod = std::make_unique<HexapodRefined>(geometry, joints, spec.convention, home_pose);
            // A singular home would make every FK from it ill-posed.
            const YAML::Node where = spec.root["home"] ? spec.root["home"] : spec.root["platform_joints"];
            auto twist = hexapod->twist_jacobian(hexapod->home());
            if (!twist)
              return spec.reader.error_at(where, "home", "not a valid pose: " + twist.error().message);
            if (!(std::abs(twist->determinant()) > 1e-9)) {
              return spec.reader.error_at(where, "home",
                                          "the refined hexapod is singular at its home pose (det J = 0)");
            }
            return std::unique_ptr<Mechanism>(std::move(hexapod));
          }};
}

}  // namespace pkm
