#include "statics/load_keys.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm::statics {

std::string load_key_list() {
  std::string list;
  for (std::string_view k : kLoadKeys) list += (list.empty() ? "" : ", ") + std::string(k);
  return list;
}

double* load_number_field(CuttingLoad& load, std::string_view key) {
  if (key == "tangential") return &load.tangential_N;
  if (key == "normal") return &load.normal_N;
  if (key == "axial") return &load.axial_N;
  if (key == "cutter_radius") return &load.cutter_radius_mm;
  return nullptr;
}

Eigen::Vector3d* load_vector_field(CuttingLoad& load, std::string_view key) {
  if (key == "force") return &load.force_N;
  if (key == "moment") return &load.moment_Nmm;
  return nullptr;
}

std::optional<std::string> load_number_problem(std::string_view key, double value) {
  // Forces may have either sign (a negative tangential force pushes along the feed); a radius may not.
  if (key == "cutter_radius" && value < 0.0) {
    return fmt::format("a cutter radius cannot be negative, got {} mm", value);
  }
  // Beyond these a load is a typo, and 1e300 N would come out of the compliance as an infinite deflection.
  const bool moment = key == "moment";
  const double limit = key == "cutter_radius" ? kMaxCutterRadius_mm
                       : moment               ? kMaxLoadMoment_Nmm
                                              : kMaxLoadForce_N;
  if (std::abs(value) > limit) {
    const char* unit = key == "cutter_radius" ? "mm" : moment ? "N·mm" : "N";
    return fmt::format("{:g} {} is beyond any machine's load (at most {:g} {} in size)", value, unit, limit,
                       unit);
  }
  return std::nullopt;
}

std::optional<int> contact_side_from_word(std::string_view word) {
  if (word == "left") return +1;
  if (word == "right") return -1;
  return std::nullopt;
}

}  // namespace pkm::statics
