#include "core/pose.hpp"

namespace pkm {

Pose pose_from_vector(AngleConvention convention, const PoseVector& c) {
  // Built in place, not default-made and overwritten: this is on the IK hot path.
  return Pose{c.head<3>(), rotation_from_angles(convention, c.tail<3>())};
}

PoseVector vector_from_pose(AngleConvention convention, const Pose& pose) {
  PoseVector c;
  c.head<3>() = pose.position_mm;
  c.tail<3>() = angles_from_rotation(convention, pose.rotation);
  return c;
}

PoseDistance pose_distance(const Pose& a, const Pose& b) {
  return {(a.position_mm - b.position_mm).norm(),
          rotation_vector_from_rotation(a.rotation.transpose() * b.rotation).norm()};
}

}  // namespace pkm
