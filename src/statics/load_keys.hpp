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
/// Why a number is not acceptable for `key` (a negative cutter radius), or nothing.
std::optional<std::string> load_number_problem(std::string_view key, double value);
/// +1 for "left", −1 for "right", nothing otherwise.
std::optional<int> contact_side_from_word(std::string_view word);

}  // namespace pkm::statics
