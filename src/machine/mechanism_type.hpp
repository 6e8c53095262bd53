#pragma once
#include <optional>
#include <string_view>

namespace pkm {

/// Every mechanism of the publications (Smirnov 2019, ch. 2; Rusanov et al.).
enum class MechanismType {
  planar2,          ///< two struts to one point in a plane (§2.1.1)
  planar3,          ///< planar 3-RPR platform (§2.1.2)
  hexapod,          ///< 6-UPS, 6-6 or 6-3 (§2.2.3)
  hexapod_refined,  ///< 6-UPS with real cardan joints (§2.2.5)
  tripod,           ///< spatial 3-RPS (§2.2.6, §2.3.4)
  tricept,          ///< three struts plus a passive central leg (§2.2.7)
  glide,    ///< constant-length struts on straight guides: hexaglide (6) or triglide (3) (Smirnov §2.2.8)
  rotopod,  ///< constant-length struts on carriages moving on one circle (Smirnov 2019, §2.2.8)
};

std::string_view to_string(MechanismType type);
std::optional<MechanismType> mechanism_type_from_string(std::string_view name);

}  // namespace pkm
