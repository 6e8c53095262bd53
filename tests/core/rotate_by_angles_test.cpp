// The elementary rotations in turn (core/rotate_by_angles.hpp): the convention's matrix times the vector to
// rounding, in every convention, and lane by lane the bits of the scalar form.
#include "core/rotate_by_angles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

namespace pkm {
namespace {

using Pair = double __attribute__((vector_size(16)));

TEST(RotateByAngles, IsTheConventionsMatrixTimesTheVector) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const AngleConvention convention :
       {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Vector3d angles(3.2 * u(rng), 3.2 * u(rng), 3.2 * u(rng));
      const Eigen::Vector3d v(300 * u(rng), 300 * u(rng), 300 * u(rng));
      const Eigen::Vector3d expected = rotation_from_angles(convention, angles) * v;
      double x = v.x(), y = v.y(), z = v.z();
      rotate_by_angles(convention, std::sin(angles[0]), std::sin(angles[1]), std::sin(angles[2]),
                       std::cos(angles[0]), std::cos(angles[1]), std::cos(angles[2]), x, y, z);
      worst = std::max(worst, (Eigen::Vector3d(x, y, z) - expected).norm() / v.norm());
    }
    // A few units of the last place; a wrong order or sign of an elementary rotation is off by O(1).
    EXPECT_LT(worst, 1e-15) << to_string(convention);
  }
}

TEST(RotateByAngles, AVectorsLanesHaveTheBitsOfTheScalarForm) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const AngleConvention convention :
       {AngleConvention::abc, AngleConvention::krylov, AngleConvention::euler_zxz}) {
    for (int i = 0; i < 500; ++i) {
      double s[3], c[3];
      for (int k = 0; k < 3; ++k) {
        const double angle = 3.0 * u(rng);
        s[k] = std::sin(angle);
        c[k] = std::cos(angle);
      }
      Pair x = {200 * u(rng), 200 * u(rng)}, y = {200 * u(rng), 200 * u(rng)},
           z = {200 * u(rng), 200 * u(rng)};
      double scalar[2][3] = {{x[0], y[0], z[0]}, {x[1], y[1], z[1]}};
      rotate_by_angles(convention, s[0], s[1], s[2], c[0], c[1], c[2], x, y, z);
      for (int lane = 0; lane < 2; ++lane) {
        double* v = scalar[lane];
        rotate_by_angles(convention, s[0], s[1], s[2], c[0], c[1], c[2], v[0], v[1], v[2]);
        const double lanes[3] = {x[lane], y[lane], z[lane]};
        EXPECT_EQ(std::memcmp(lanes, v, sizeof lanes), 0) << to_string(convention) << " " << i;
      }
    }
  }
}

}  // namespace
}  // namespace pkm
