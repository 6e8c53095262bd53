#pragma once
// Helpers for the redundancy-law tests: the machines and test paths of Smirnov 2019, §3.4 and §3.5.1.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "planning/plan_test_support.hpp"
#include "redundancy/optimize_program.hpp"
#include "test_support.hpp"

namespace pkm::test {

/// The hexapod of Smirnov 2019, §3.5.1, as reconstructed to reproduce Table 2: base joints on R 500 every
/// 60°, platform joints on R 300, the pair of each merged point separated by δ (each joint δ/2 towards its
/// own base joint), tool 200 mm out.
inline std::string ch3_hexapod_text(double separation_deg) {
  std::string text = "type: hexapod\nangles: krylov\nbase_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const double a = 60.0 * j * std::numbers::pi / 180.0;
    text += fmt::format("  - [{:.12f}, {:.12f}, 0]\n", 500.0 * std::cos(a), 500.0 * std::sin(a));
  }
  text += "platform_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const int pair = j / 2;
    const double side = j % 2 == 0 ? -0.5 : 0.5;
    const double a = (30.0 + 120.0 * pair + side * separation_deg) * std::numbers::pi / 180.0;
    text += fmt::format("  - [{:.12f}, {:.12f}, 0]\n", 300.0 * std::cos(a), 300.0 * std::sin(a));
  }
  text += "tool: [0, 0, 200]\nhome: [0, 0, 700, 0, 0, 0]\n";
  return text;
}

/// A full circle of the tool point, radius r about the z axis at height z, starting at (r, 0, z).
inline std::string circle_program(double radius_mm, double z_mm, double start_c_deg = 0.0, bool ccw = true) {
  return fmt::format("G21 G90 G17\nG0 X{} Y0 Z{} C{}\n{} X{} Y0 I{} J0 F600\nM2\n", radius_mm, z_mm,
                     start_c_deg, ccw ? "G3" : "G2", radius_mm, -radius_mm);
}

inline redundancy::OptimizeResult optimize_or_fail(const Machine& machine,
                                                   const program::CanonicalProgram& program,
                                                   const redundancy::OptimizeOptions& options) {
  auto result = redundancy::optimize_program(program, machine, options);
  if (!result) {
    ADD_FAILURE() << result.error().message;
    throw std::runtime_error(result.error().message);
  }
  return std::move(result.value());
}

/// One degree of a circle of this radius, the path step of Smirnov 2019, §3.4–3.5.
inline double one_degree_mm(double radius_mm) {
  return radius_mm * std::numbers::pi / 180.0;
}

}  // namespace pkm::test
