// The `dynamics:` section: mass, centre of mass and inertia of the platform, the payload and the two parts of
// every strut, the struts' elastic elements and their friction, and the drive model (Smirnov 2019, §4.2,
// §4.3, §4.5). Inertias are written in kg·m², as Smirnov gives them, and kept in kg·mm² (× 10⁶).
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "io/machine_file_sections.hpp"

namespace pkm {
namespace {

constexpr double kMm2PerM2 = 1e6;  // kg·m² → kg·mm²
// Slack of the inertia checks, relative to the largest principal moment: a tensor typed with rounded digits
// sits on an equality (a thin plate's Izz = Ixx + Iyy, a slender rod's zero axial moment) only up to its
// rounding, and its computed eigenvalues only up to a few ulps more.
constexpr double kInertiaRelativeSlack = 1e-9;

std::string key_path(std::string_view path, std::string_view key) {
  return fmt::format("{}.{}", path, key);
}

// The key itself (not its value): the place to name when the value is empty.
YAML::Node key_itself(const YAML::Node& mapping, std::string_view key) {
  for (const auto& item : mapping) {
    if (item.first.IsScalar() && item.first.Scalar() == key) return item.first;
  }
  return mapping;
}

// `key` of `mapping` if given, named `path.key` in messages; an empty value is an error, not "not given".
Result<std::optional<double>> number_if_given(const YamlReader& reader, const YAML::Node& mapping,
                                              std::string_view key, std::string_view path) {
  const YAML::Node value = mapping[std::string(key)];
  if (!value) return std::optional<double>{};
  if (value.IsNull())
    return reader.error_at(key_itself(mapping, key), key_path(path, key), "expected a number, got nothing");
  auto v = reader.number(value, key_path(path, key));
  if (!v) return v.error();
  return std::optional<double>{*v};
}

Result<double> number_required(const YamlReader& reader, const YAML::Node& mapping, std::string_view key,
                               std::string_view path, std::string_view what) {
  auto v = number_if_given(reader, mapping, key, path);
  if (!v) return v.error();
  if (!*v) return reader.error_missing(mapping, key_path(path, key), what);
  return **v;
}

// The mapping at `key` of `parent`, with only the keys in `allowed`.
Status check_mapping(const YamlReader& reader, const YAML::Node& parent, std::string_view key,
                     std::string_view path, std::initializer_list<std::string_view> allowed) {
  const YAML::Node value = parent[std::string(key)];
  if (value.IsNull())
    return reader.error_at(key_itself(parent, key), path, "expected a mapping of keys, got nothing");
  return reader.check_keys(value, path, allowed);
}

// `model:` of the mapping `node` at `path`: the index of its word in `names`.
Result<int> read_model(const YamlReader& reader, const YAML::Node& node, std::string_view path,
                       std::string_view what, std::initializer_list<std::string_view> names) {
  std::string known;
  for (std::string_view n : names) known += (known.empty() ? "" : " | ") + std::string(n);
  const YAML::Node model = node["model"];
  if (!model) return reader.error_missing(node, key_path(path, "model"), known);
  if (!model.IsScalar()) {
    return reader.error_at(model.IsNull() ? key_itself(node, "model") : model, key_path(path, "model"),
                           fmt::format("expected one of {}", known));
  }
  const auto found = std::find(names.begin(), names.end(), model.Scalar());
  if (found == names.end()) {
    return reader.error_at(model, key_path(path, "model"),
                           fmt::format("unknown {} model '{}' (known: {})", what, model.Scalar(), known));
  }
  return static_cast<int>(found - names.begin());
}

Result<double> read_mass(const YamlReader& reader, const YAML::Node& body, std::string_view path) {
  auto mass = number_required(reader, body, "mass_kg", path, "a mass in kg");
  if (!mass) return mass.error();
  if (*mass < 0.0) {
    return reader.error_at(body["mass_kg"], key_path(path, "mass_kg"),
                           fmt::format("a mass cannot be negative, got {} kg", *mass));
  }
  return *mass;
}

// 3 principal moments or the 6 components [Ixx, Iyy, Izz, Ixy, Iyz, Izx] of a tensor, kg·m². Every real
// body's tensor is positive semi-definite and its principal moments obey the triangle inequality (I₁ ≤ I₂ +
// I₃: I₂ + I₃ − I₁ = 2∫x₁² dm ≥ 0), so anything else is a typing error, and would make the mass matrix wrong.
Result<Eigen::Matrix3d> read_inertia_tensor(const YamlReader& reader, const YAML::Node& node,
                                            const std::string& name) {
  if (!node.IsSequence() || (node.size() != 3 && node.size() != 6)) {
    const std::string got = node.IsSequence() ? fmt::format("{} numbers", node.size()) : "a single value";
    return reader.error_at(node, name,
                           "expected 3 principal moments [Ixx, Iyy, Izz] or 6 tensor components [Ixx, Iyy, "
                           "Izz, Ixy, Iyz, Izx] in kg·m², got " +
                               got);
  }
  double v[6] = {0, 0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < node.size(); ++i) {
    auto number = reader.number(node[i], fmt::format("{}[{}]", name, i));
    if (!number) return number.error();
    v[i] = *number;
  }
  Eigen::Matrix3d tensor;
  tensor << v[0], v[3], v[5], v[3], v[1], v[4], v[5], v[4], v[2];
  const Eigen::Vector3d moments =  // ascending
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(tensor, Eigen::EigenvaluesOnly).eigenvalues();
  const double slack = kInertiaRelativeSlack * moments.cwiseAbs().maxCoeff();
  if (moments[0] < -slack) {
    return reader.error_at(
        node, name,
        fmt::format("not positive semi-definite: principal moment {:.6g} kg·m² is negative", moments[0]));
  }
  if (moments[2] > moments[0] + moments[1] + slack) {
    return reader.error_at(
        node, name,
        fmt::format("not the inertia of a real body: principal moment {:.6g} kg·m² exceeds the sum of the "
                    "other two, {:.6g} kg·m²",
                    moments[2], moments[0] + moments[1]));
  }
  return tensor;
}

// The platform or the payload: a mass (required), its centre of mass in the tool frame and its inertia tensor
// about that centre (both optional: the tool point, a point mass).
Result<BodyInertia> read_body(const YamlReader& reader, const YAML::Node& section, std::string_view key,
                              bool planar) {
  const std::string path = key_path("dynamics", key);
  if (auto keys = check_mapping(reader, section, key, path, {"mass_kg", "com_mm", "inertia_kg_m2"}); !keys)
    return keys.error();
  const YAML::Node node = section[std::string(key)];
  BodyInertia body;
  auto mass = read_mass(reader, node, path);
  if (!mass) return mass.error();
  body.mass_kg = *mass;
  if (const YAML::Node com = node["com_mm"]) {
    if (com.IsNull())
      return reader.error_at(key_itself(node, "com_mm"), key_path(path, "com_mm"),
                             "expected a point, got nothing");
    // Planar machines give points as [x, y], as everywhere else in their files; [x, y, z] is accepted too.
    const int dims = planar && com.IsSequence() && com.size() == 2 ? 2 : 3;
    auto p = reader.point(com, key_path(path, "com_mm"), dims);
    if (!p) return p.error();
    body.com_mm = *p;
  }
  if (const YAML::Node inertia = node["inertia_kg_m2"]) {
    if (inertia.IsNull()) {
      return reader.error_at(key_itself(node, "inertia_kg_m2"), key_path(path, "inertia_kg_m2"),
                             "expected 3 or 6 numbers, got nothing");
    }
    auto tensor = read_inertia_tensor(reader, inertia, key_path(path, "inertia_kg_m2"));
    if (!tensor) return tensor.error();
    body.inertia_kg_mm2 = *tensor * kMm2PerM2;
  }
  return body;
}

// A strut's lower or upper part: mass and centre-of-mass distance required, transverse inertia optional.
Result<StrutPart> read_strut_part(const YamlReader& reader, const YAML::Node& strut, std::string_view key,
                                  std::string_view strut_path) {
  const std::string path = key_path(strut_path, key);
  if (auto keys = check_mapping(reader, strut, key, path, {"mass_kg", "com_mm", "inertia_kg_m2"}); !keys)
    return keys.error();
  const YAML::Node node = strut[std::string(key)];
  StrutPart part;
  auto mass = read_mass(reader, node, path);
  if (!mass) return mass.error();
  part.mass_kg = *mass;
  // Any finite distance: a motor behind the base joint puts the lower part's centre of mass behind A.
  auto com =
      number_required(reader, node, "com_mm", path, "the distance of the centre of mass from the joint, mm");
  if (!com) return com.error();
  part.com_mm = *com;
  auto inertia = number_if_given(reader, node, "inertia_kg_m2", path);
  if (!inertia) return inertia.error();
  if (*inertia && **inertia < 0.0) {
    return reader.error_at(node["inertia_kg_m2"], key_path(path, "inertia_kg_m2"),
                           fmt::format("a moment of inertia cannot be negative, got {} kg·m²", **inertia));
  }
  part.transverse_inertia_kg_mm2 = inertia->value_or(0.0) * kMm2PerM2;
  return part;
}

// The friction of the strut's elastic element; its coefficient's unit depends on the model (StrutDynamics).
Status read_damping(const YamlReader& reader, const YAML::Node& strut, std::string_view strut_path,
                    StrutDynamics& out) {
  const std::string path = key_path(strut_path, "damping");
  if (auto keys = check_mapping(reader, strut, "damping", path, {"model", "coefficient"}); !keys) return keys;
  const YAML::Node node = strut["damping"];
  auto model = read_model(reader, node, path, "damping", {"none", "viscous", "quadratic", "coulomb"});
  if (!model) return model.error();
  out.damping = std::array{StrutDamping::none, StrutDamping::viscous, StrutDamping::quadratic,
                           StrutDamping::coulomb}[*model];
  if (out.damping == StrutDamping::none) {
    if (node["coefficient"]) {
      return reader.error_at(key_itself(node, "coefficient"), key_path(path, "coefficient"),
                             "model none has no coefficient; remove this key");
    }
    return ok_status();
  }
  auto coefficient = number_required(reader, node, "coefficient", path, "β ≥ 0");
  if (!coefficient) return coefficient.error();
  if (*coefficient < 0.0) {
    return reader.error_at(node["coefficient"], key_path(path, "coefficient"),
                           fmt::format("a friction coefficient cannot be negative, got {}", *coefficient));
  }
  out.damping_coefficient = *coefficient;
  return ok_status();
}

// Glide machines and rotopods: struts of constant length (no sliding upper part) on moving carriages.
bool has_carriages(MechanismType type) {
  return type == MechanismType::glide || type == MechanismType::rotopod;
}

// `stiffness_N_mm` and `damping` (Smirnov 2019, §4.2, §4.5); neither given: a rigid strut.
Status read_elastic_element(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                            StrutDynamics& strut) {
  auto stiffness = number_if_given(reader, node, "stiffness_N_mm", path);
  if (!stiffness) return stiffness.error();
  if (*stiffness && !(**stiffness > 0.0)) {
    return reader.error_at(
        node["stiffness_N_mm"], key_path(path, "stiffness_N_mm"),
        fmt::format("must be positive, got {} N/mm (leave it out for a rigid strut)", **stiffness));
  }
  strut.stiffness_N_mm = stiffness->value_or(0.0);
  if (!node["damping"]) return ok_status();
  if (auto damping = read_damping(reader, node, path, strut); !damping) return damping;
  // Smirnov's friction is that of the elastic element (§4.2): without one it has nothing to act on.
  if (strut.damping != StrutDamping::none && strut.stiffness_N_mm == 0.0) {
    return reader.error_at(
        key_itself(node, "damping"), key_path(path, "damping"),
        "the friction of an elastic element needs stiffness_N_mm (a rigid strut has none)");
  }
  return ok_status();
}

Result<double> read_carriage(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                             MechanismType type) {
  auto carriage = number_if_given(reader, node, "carriage_kg", path);
  if (!carriage) return carriage.error();
  if (*carriage && **carriage < 0.0) {
    return reader.error_at(node["carriage_kg"], key_path(path, "carriage_kg"),
                           fmt::format("a mass cannot be negative, got {} kg", **carriage));
  }
  if (*carriage && **carriage > 0.0 && !has_carriages(type)) {
    return reader.error_at(
        node["carriage_kg"], key_path(path, "carriage_kg"),
        fmt::format("a {} has no carriages (only glide machines and rotopods have them)", to_string(type)));
  }
  return carriage->value_or(0.0);
}

Result<StrutDynamics> read_strut(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                                 MechanismType type) {
  if (auto keys =
          reader.check_keys(node, path, {"lower", "upper", "stiffness_N_mm", "damping", "carriage_kg"});
      !keys) {
    return keys.error();
  }
  StrutDynamics strut;
  if (!node["lower"])
    return reader.error_missing(node, key_path(path, "lower"), "a mapping with mass_kg and com_mm");
  auto lower = read_strut_part(reader, node, "lower", path);
  if (!lower) return lower.error();
  strut.lower = *lower;
  if (node["upper"]) {
    if (has_carriages(type)) {
      return reader.error_at(key_itself(node, "upper"), key_path(path, "upper"),
                             fmt::format("the struts of a {} have a constant length: no sliding upper part; "
                                         "give the whole strut as lower",
                                         to_string(type)));
    }
    auto upper = read_strut_part(reader, node, "upper", path);
    if (!upper) return upper.error();
    strut.upper = *upper;
  }
  if (auto elastic = read_elastic_element(reader, node, path, strut); !elastic) return elastic.error();
  auto carriage = read_carriage(reader, node, path, type);
  if (!carriage) return carriage.error();
  strut.carriage_kg = *carriage;
  return strut;
}

// `struts:` as one mapping for every strut or a list of one mapping per strut; not given: massless and rigid.
Status read_struts(const YamlReader& reader, const YAML::Node& section, const Mechanism& mechanism,
                   DynamicsParameters& out) {
  const int count = mechanism.actuator_count();
  out.strut_count = count;
  const YAML::Node struts = section["struts"];
  if (!struts) return ok_status();
  if (struts.IsMap()) {
    auto strut = read_strut(reader, struts, "dynamics.struts", mechanism.type());
    if (!strut) return strut.error();
    std::fill(out.struts.begin(), out.struts.begin() + count, *strut);
    return ok_status();
  }
  if (!struts.IsSequence() || static_cast<int>(struts.size()) != count) {
    const std::string got = struts.IsSequence() ? fmt::format("a list of {}", struts.size())
                                                : (struts.IsNull() ? "nothing" : "a single value");
    return reader.error_at(
        struts.IsNull() ? key_itself(section, "struts") : struts, "dynamics.struts",
        fmt::format("expected one mapping for every strut or a list of {} mappings (one per "
                    "actuator), got {}",
                    count, got));
  }
  for (int j = 0; j < count; ++j) {
    auto strut = read_strut(reader, struts[j], fmt::format("dynamics.struts[{}]", j), mechanism.type());
    if (!strut) return strut.error();
    out.struts[j] = *strut;
  }
  return ok_status();
}

// `drive:` {model: ideal | lag | static} with the one parameter its model has (Smirnov 2019, §4.2).
Status read_drive(const YamlReader& reader, const YAML::Node& section, DynamicsParameters& out) {
  const char* path = "dynamics.drive";
  if (auto keys = check_mapping(reader, section, "drive", path, {"model", "tau_s", "speed_gain_N_s_mm"});
      !keys)
    return keys;
  const YAML::Node node = section["drive"];
  auto model = read_model(reader, node, path, "drive", {"ideal", "lag", "static"});
  if (!model) return model.error();
  out.drive =
      std::array{DriveModel::ideal, DriveModel::first_order_lag, DriveModel::static_characteristic}[*model];
  // The key the model needs; the other one is an error.
  const char* parameter = std::array<const char*, 3>{nullptr, "tau_s", "speed_gain_N_s_mm"}[*model];
  for (const char* key : {"tau_s", "speed_gain_N_s_mm"}) {
    if (node[key] && (parameter == nullptr || std::string_view(key) != parameter)) {
      return reader.error_at(key_itself(node, key), key_path(path, key),
                             fmt::format("model {} has no {}; remove this key", node["model"].Scalar(), key));
    }
  }
  if (out.drive == DriveModel::first_order_lag) {
    auto tau = number_required(reader, node, "tau_s", path, "the time constant τ in s");
    if (!tau) return tau.error();
    if (!(*tau > 0.0))
      return reader.error_at(node["tau_s"], key_path(path, "tau_s"),
                             fmt::format("must be positive, got {} s", *tau));
    out.drive_lag_s = *tau;
  } else if (out.drive == DriveModel::static_characteristic) {
    auto gain = number_required(reader, node, "speed_gain_N_s_mm", path, "the speed gain in N·s/mm");
    if (!gain) return gain.error();
    if (*gain < 0.0) {
      return reader.error_at(node["speed_gain_N_s_mm"], key_path(path, "speed_gain_N_s_mm"),
                             fmt::format("cannot be negative, got {} N·s/mm", *gain));
    }
    out.drive_speed_gain_N_s_mm = *gain;
  }
  return ok_status();
}

}  // namespace

Result<DynamicsParameters> read_dynamics(const YAML::Node& root, const YamlReader& reader,
                                         const Mechanism& mechanism, bool planar) {
  DynamicsParameters out;
  const YAML::Node node = root["dynamics"];
  if (!node) return out;
  if (node.IsNull())
    return reader.error_at_value(root, "dynamics", "expected a mapping with platform:, got nothing");
  if (auto keys =
          reader.check_keys(node, "dynamics", {"gravity_mm_s2", "platform", "payload", "struts", "drive"});
      !keys) {
    return keys.error();
  }
  out.line = yaml_key_line(root, "dynamics");
  if (const YAML::Node g = node["gravity_mm_s2"]) {
    if (g.IsNull())
      return reader.error_at(key_itself(node, "gravity_mm_s2"), "dynamics.gravity_mm_s2",
                             "expected 3 numbers, got nothing");
    auto gravity = reader.point(g, "dynamics.gravity_mm_s2", 3);
    if (!gravity) return gravity.error();
    out.gravity_mm_s2 = *gravity;
  }
  if (!node["platform"]) return reader.error_missing(node, "dynamics.platform", "a mapping with mass_kg");
  auto platform = read_body(reader, node, "platform", planar);
  if (!platform) return platform.error();
  out.platform = *platform;
  if (node["payload"]) {
    auto payload = read_body(reader, node, "payload", planar);
    if (!payload) return payload.error();
    out.payload = *payload;
  }
  if (auto struts = read_struts(reader, node, mechanism, out); !struts) return struts.error();
  if (node["drive"]) {
    if (auto drive = read_drive(reader, node, out); !drive) return drive.error();
  }
  return out;
}

}  // namespace pkm
