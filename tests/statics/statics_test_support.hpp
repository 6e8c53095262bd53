#pragma once
// For the statics tests: the virtual-work balance of actuator forces under small motions the mechanism
// allows.
#include <Eigen/Core>
#include <random>

#include "core/rotation.hpp"
#include "machine/mechanism.hpp"
#include "statics/wrench.hpp"
#include "test_support.hpp"

namespace pkm::test {

/// One small motion ±dq of the controlled coordinates about `pose`, through complete_pose, measured by
/// central differences (so the balance below holds to second order in dq).
struct SmallMotion {
  ActuatorVector dl;                                 ///< actuator changes (mm or rad)
  Eigen::Vector3d dp = Eigen::Vector3d::Zero();      ///< tool-point displacement, mm
  Eigen::Vector3d dtheta = Eigen::Vector3d::Zero();  ///< rotation vector, rad
};

/// Random dq: translations up to `step_mm`, angles up to `step_rad`, on the controlled coordinates only.
inline SmallMotion random_small_motion(const Mechanism& mechanism, const Pose& pose, std::mt19937_64& rng,
                                       double step_mm = 1e-2, double step_rad = 1e-5) {
  const AngleConvention convention = mechanism.convention();
  const PoseVector centre = vector_from_pose(convention, pose);
  PoseVector dq = PoseVector::Zero();
  const AxisMask mask = mechanism.controlled_axes();
  for (int axis = 0; axis < 6; ++axis) {
    if (mask.controlled[axis]) dq[axis] = uniform(rng, -1.0, 1.0) * (axis < 3 ? step_mm : step_rad);
  }
  auto plus = mechanism.complete_pose(pose_from_vector(convention, centre + dq));
  auto minus = mechanism.complete_pose(pose_from_vector(convention, centre - dq));
  EXPECT_TRUE(plus.ok() && minus.ok());
  auto l_plus = mechanism.inverse(*plus);
  auto l_minus = mechanism.inverse(*minus);
  EXPECT_TRUE(l_plus.ok() && l_minus.ok());
  SmallMotion m;
  m.dl = (*l_plus - *l_minus) / 2.0;
  m.dp = (plus->position_mm - minus->position_mm) / 2.0;
  m.dtheta = rotation_vector_from_rotation(plus->rotation * minus->rotation.transpose()) / 2.0;
  return m;
}

/// Checks Σ P_j dL_j = −(F · dp + M · dθ) for one motion, relative to the size of the terms.
inline void expect_virtual_work_balance(const ActuatorVector& forces, const SmallMotion& m,
                                        const statics::Wrench& load, double relative_tolerance = 1e-6) {
  const double actuator_work = forces.dot(m.dl);
  const double load_work = load.force_N.dot(m.dp) + load.moment_Nmm.dot(m.dtheta);
  const double scale = forces.cwiseProduct(m.dl).cwiseAbs().sum() + load.force_N.norm() * m.dp.norm() +
                       load.moment_Nmm.norm() * m.dtheta.norm();
  EXPECT_NEAR(actuator_work, -load_work, relative_tolerance * scale)
      << "actuator work " << actuator_work << ", load work " << load_work;
}

inline statics::Wrench random_wrench(std::mt19937_64& rng, double force_N = 1000.0, double moment_Nmm = 1e5) {
  statics::Wrench w;
  for (int i = 0; i < 3; ++i) {
    w.force_N[i] = uniform(rng, -force_N, force_N);
    w.moment_Nmm[i] = uniform(rng, -moment_Nmm, moment_Nmm);
  }
  return w;
}

}  // namespace pkm::test
