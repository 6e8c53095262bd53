#pragma once
// Shared by the dynamics tests: random inertial (and elastic) parameters and random hexapod geometries, made
// from a seeded generator so that every run tests the same cases.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "core/units.hpp"
#include "machine/dynamics_parameters.hpp"
#include "test_support.hpp"

namespace pkm::test {

/// An inertia tensor of a real body (principal moments a, b, c with |a − b| ≤ c ≤ a + b), random axes,
/// moments around `scale` kg·mm².
inline Eigen::Matrix3d random_inertia_tensor(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double a = scale * (0.5 + unit(rng)), b = scale * (0.5 + unit(rng));
  const double c = std::abs(a - b) + (a + b - std::abs(a - b)) * unit(rng);
  const Eigen::Matrix3d axes =
      Eigen::AngleAxisd(2 * kPi * unit(rng), Eigen::Vector3d(unit(rng), unit(rng), 1).normalized())
          .toRotationMatrix();
  return axes * Eigen::Vector3d(a, b, c).asDiagonal() * axes.transpose();
}

/// Random masses and inertias of every body, gravity slightly off the vertical, struts rigid; carriages of
/// 0–10 kg unless `carriages` is false (mechanisms with fixed base joints ignore them).
inline DynamicsParameters random_dynamics_parameters(std::mt19937_64& rng, int struts,
                                                     bool carriages = true) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  DynamicsParameters p;
  p.platform.mass_kg = 20 + 60 * unit(rng);
  p.platform.com_mm = Eigen::Vector3d(40 * unit(rng) - 20, 40 * unit(rng) - 20, -150 * unit(rng));
  p.platform.inertia_kg_mm2 = random_inertia_tensor(rng, 5e5);
  p.payload.mass_kg = 5 * unit(rng);
  p.payload.com_mm = Eigen::Vector3d(0, 0, 50 * unit(rng));
  p.payload.inertia_kg_mm2 = random_inertia_tensor(rng, 1e4);
  p.strut_count = struts;
  for (int j = 0; j < struts; ++j) {
    StrutDynamics& s = p.struts[j];
    s.lower = {5 + 15 * unit(rng), 50 + 200 * unit(rng), 1e5 + 4e5 * unit(rng)};
    s.upper = {2 + 10 * unit(rng), 50 + 200 * unit(rng), 1e5 + 3e5 * unit(rng)};
    s.carriage_kg = carriages ? 10 * unit(rng) : 0.0;
  }
  p.gravity_mm_s2 = Eigen::Vector3d(300 * unit(rng) - 150, 300 * unit(rng) - 150, -9810);
  return p;
}

/// A friction coefficient for `damping` that damps a 10 µm vibration by a few per cent (one draw unless
/// none).
inline double random_damping_coefficient(std::mt19937_64& rng, StrutDamping damping) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  switch (damping) {
    case StrutDamping::none:
      return 0.0;
    case StrutDamping::viscous:
      return 20 + 40 * unit(rng);  // N·s/mm
    case StrutDamping::quadratic:
      return 0.2 + 0.4 * unit(rng);  // N·s²/mm²
    case StrutDamping::coulomb:
      return 20 + 30 * unit(rng);  // N
  }
  return 0.0;
}

/// The same with an elastic element in every strut: stiffness 20…400 N/µm, and `damping` with a coefficient
/// that damps a 10 µm vibration by a few per cent.
inline DynamicsParameters random_elastic_parameters(std::mt19937_64& rng, int struts,
                                                    StrutDamping damping = StrutDamping::none) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  DynamicsParameters p = random_dynamics_parameters(rng, struts, false);
  p.line = 1;  // as if read from a file
  for (int j = 0; j < struts; ++j) {
    StrutDynamics& s = p.struts[j];
    s.stiffness_N_mm = 2e4 + 3.8e5 * unit(rng);
    s.damping = damping;
    s.damping_coefficient = random_damping_coefficient(rng, damping);
  }
  return p;
}

/// A hexapod with joints scattered around two circles, its home 500–800 mm up.
inline Machine random_hexapod_machine(std::mt19937_64& rng, int index) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::string text = "name: random\ntype: hexapod\nangles: krylov\nbase_joints:\n";
  const double base_r = 300 + 300 * unit(rng), platform_r = 100 + 150 * unit(rng);
  for (int j = 0; j < 6; ++j) {
    const double angle = 2 * kPi * j / 6 + 0.3 * (unit(rng) - 0.5);
    text +=
        fmt::format("  - [{}, {}, {}]\n", base_r * std::cos(angle), base_r * std::sin(angle), 20 * unit(rng));
  }
  text += "platform_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const double angle = 2 * kPi * (j / 2) / 3 + (j % 2 == 0 ? -0.3 : 0.3) + 0.2 * (unit(rng) - 0.5);
    text += fmt::format("  - [{}, {}, {}]\n", platform_r * std::cos(angle), platform_r * std::sin(angle),
                        10 * unit(rng));
  }
  text += fmt::format("tool: [0, 0, {}]\nhome: [0, 0, {}, 0, 0, 0]\n", 50 + 150 * unit(rng),
                      500 + 300 * unit(rng));
  return machine_from_text(text, fmt::format("random_hexapod_{}.yaml", index));
}

/// A machine with elastic struts for the elastic model's tests, with its own dynamics parameters.
struct ElasticCase {
  std::string label;
  Machine machine;
  DynamicsParameters parameters;
};

/// Sets every strut's friction to `damping` (coefficients as random_elastic_parameters draws them, the
/// file's own where it has that model).
inline void set_strut_damping(std::mt19937_64& rng, DynamicsParameters& p, StrutDamping damping) {
  for (int j = 0; j < p.strut_count; ++j) {
    StrutDynamics& s = p.struts[j];
    if (s.damping == damping) continue;
    s.damping = damping;
    s.damping_coefficient = random_damping_coefficient(rng, damping);
  }
}

/// The shipped ch5 hexapod and planar biped with their files' parameters, and `random` random hexapods with
/// random inertial and elastic parameters; every strut's friction `damping`. Make models only after the
/// vector is complete (they keep pointers into it).
/// How many random hexapods the elastic tests take: 5, or PKM_RANDOM_GEOMETRIES (the sanitizer run of
/// `make sanitize` takes 1: its simulations are 20× slower, and the shipped machines stay in every run).
inline int random_geometry_count() {
  const char* value = std::getenv("PKM_RANDOM_GEOMETRIES");
  return value != nullptr ? std::max(1, std::atoi(value)) : 5;
}

inline std::vector<ElasticCase> elastic_cases(StrutDamping damping, int random = -1, unsigned seed = 2027) {
  if (random < 0) random = random_geometry_count();
  std::vector<ElasticCase> cases;
  std::mt19937_64 rng(seed);
  for (const char* file : {"hexapod_ch5.yaml", "planar2.yaml"}) {
    ElasticCase c{file, machine_from_example(std::string("examples/machines/") + file), {}};
    c.parameters = c.machine.dynamics;
    set_strut_damping(rng, c.parameters, damping);
    cases.push_back(std::move(c));
  }
  for (int i = 0; i < random; ++i) {
    ElasticCase c{fmt::format("random hexapod {}", i), random_hexapod_machine(rng, i), {}};
    c.parameters = random_elastic_parameters(rng, 6, damping);
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace pkm::test
