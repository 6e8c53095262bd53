#pragma once
// The keys of a load case, shared by the CLI's --load text and load files (load_model.hpp), so that both
// accept the same names with the same checks.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "statics/load_model.hpp"

namespace pkm::statics {

inline constexpr std::array<std::string_view, 7> kLoadKeys = {
    "tangential", "normal", "axial", "cutter_radius", "contact", "force", "moment"};

/// "tangential, normal, …" for messages.
std::string load_key_list();

/// The number field a key sets (tangential, normal, axial, cutter_radius), or null for the others.
double* load_number_field(CuttingLoad& load, std::string_view key);
/// The vector field a key sets (force, moment), or null.
Eigen::Vector3d* load_vector_field(CuttingLoad& load, std::string_view key);
/// The largest loads a load case may give: 100 MN (the largest presses make 80 MN), its moment at 1 m, and
/// a 10 m cutter radius.
inline constexpr double kMaxLoadForce_N = 1e8;
inline constexpr double kMaxLoadMoment_Nmm = 1e11;
inline constexpr double kMaxCutterRadius_mm = 1e4;

/// Why a number is not acceptable for `key` (a negative cutter radius, a force beyond kMaxLoadForce_N), or
/// nothing. `key` is a number key or "force" / "moment" for one component of those vectors.
std::optional<std::string> load_number_problem(std::string_view key, double value);
/// +1 for "left", −1 for "right", nothing otherwise.
std::optional<int> contact_side_from_word(std::string_view word);

}  // namespace pkm::statics
