#pragma once
// Shared helpers for the tests: machine files from strings, seeded random poses and geometries.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "core/units.hpp"
#include "io/machine_file.hpp"
#include "source_paths.hpp"

namespace pkm::test {

/// Parses a machine file given as text; fails the test (fatally) with the loader's message on error.
inline Machine machine_from_text(const std::string& yaml, const std::string& name = "test.yaml") {
  auto machine = parse_machine_text(yaml, name);
  if (!machine) {
    ADD_FAILURE() << machine.error().message;
    throw std::runtime_error(machine.error().message);
  }
  return std::move(machine.value());
}

/// Whether `message` holds "PLACE:COLUMN: TEXT" for some column, PLACE being "FILE:LINE": for tests whose
/// input puts the key at a column that varies from case to case.
inline bool names_yaml_place(const std::string& message, const std::string& place, const std::string& text) {
  for (std::size_t at = message.find(place + ":"); at != std::string::npos;
       at = message.find(place + ":", at + 1)) {
    std::size_t p = at + place.size() + 1;
    const std::size_t digits = p;
    while (p < message.size() && message[p] >= '0' && message[p] <= '9') ++p;
    if (p > digits && message.compare(p, 2 + text.size(), ": " + text) == 0) return true;
  }
  return false;
}

/// A pose from x, y, z (mm) and A, B, C (deg) in the abc convention.
inline Pose abc_pose(double x, double y, double z, double a_deg, double b_deg, double c_deg) {
  PoseVector c;
  c << x, y, z, rad_from_deg(a_deg), rad_from_deg(b_deg), rad_from_deg(c_deg);
  return pose_from_vector(AngleConvention::abc, c);
}

inline Machine machine_from_example(const std::string& relative_path) {
  auto machine = load_machine_file(source_path(relative_path));
  if (!machine) {
    ADD_FAILURE() << machine.error().message;
    throw std::runtime_error(machine.error().message);
  }
  return std::move(machine.value());
}

/// The ch5 test hexapod's geometry (Smirnov 2019, §5.2) without its `type:` line, tool frame 150 mm above the
/// platform-joint plane, home at z = 700 mm; and the whole machine file of the ideal hexapod.
inline const char* kCh5HexapodGeometry = R"(angles: krylov
base_joints:
  - [400.0, 0.0, 0.0]
  - [200.0, 346.41016151377545, 0.0]
  - [-200.0, 346.41016151377545, 0.0]
  - [-400.0, 0.0, 0.0]
  - [-200.0, -346.41016151377545, 0.0]
  - [200.0, -346.41016151377545, 0.0]
platform_joints:
  - [173.20508075688772, 100, 0]
  - [173.20508075688772, 100, 0]
  - [-173.20508075688772, 100, 0]
  - [-173.20508075688772, 100, 0]
  - [0, -200, 0]
  - [0, -200, 0]
tool: [0, 0, 150]
home: [0, 0, 700, 0, 0, 0]
)";
inline const std::string kCh5HexapodText = std::string("type: hexapod\n") + kCh5HexapodGeometry;

/// Uniform in [lo, hi].
inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

}  // namespace pkm::test
