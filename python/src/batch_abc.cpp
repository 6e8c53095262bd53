// Machine.pose_from_abc and Machine.abc_from_pose: poses whose angles are G-code's A B C (R =
// Rz(C)·Ry(B)·Rx(A), as a part program, `pkm plan`'s path.csv and LinuxCNC read them) to and from the
// machine's own convention, which Machine.ik, fk and the other batch calls take. Positions pass through
// unchanged (both in the base frame).
#include <pybind11/numpy.h>

#include "array_args.hpp"
#include "batch_bindings.hpp"
#include "core/pose.hpp"

namespace pkm::python {
namespace {

py::array_t<double> convert_poses(const py::object& poses, AngleConvention from, AngleConvention to) {
  const RowArray in = row_array(poses, 6, "poses");
  py::array_t<double> result = in.single ? new_array({6}) : new_array({static_cast<py::ssize_t>(in.rows), 6});
  double* out = result.mutable_data();
  for (std::size_t r = 0; r < in.rows; ++r) {
    if (!all_finite(in.row(r), 6)) raise_non_finite("poses", r, in.single);
    const PoseVector v =
        vector_from_pose(to, pose_from_vector(from, Eigen::Map<const PoseVector>(in.row(r))));
    for (int i = 0; i < 6; ++i) out[r * 6 + static_cast<std::size_t>(i)] = v[i];
  }
  return result;
}

}  // namespace

void bind_abc(MachineClass& cls) {
  cls.def(
         "pose_from_abc",
         [](const Machine& machine, const py::object& poses) {
           return convert_poses(poses, AngleConvention::abc, machine.mechanism->convention());
         },
         py::arg("poses"),
         "Poses (N, 6) [x, y, z mm, A, B, C rad] with G-code's angles, R = Rz(C)·Ry(B)·Rx(A) (a program's,\n"
         "path.csv's, LinuxCNC's), as the machine's own poses (Machine.angle_convention), which ik takes;\n"
         "(6,) for one pose. Of the angle triples of one rotation, the one with the middle angle in\n"
         "[-90°, 90°] (abc, krylov) or [0°, 180°] (euler_zxz).")
      .def(
          "abc_from_pose",
          [](const Machine& machine, const py::object& poses) {
            return convert_poses(poses, machine.mechanism->convention(), AngleConvention::abc);
          },
          py::arg("poses"),
          "The machine's own poses (N, 6) (Machine.angle_convention, as fk returns them) with G-code's\n"
          "angles A, B, C (rad), R = Rz(C)·Ry(B)·Rx(A), B in [-90°, 90°]; (6,) for one pose.");
}

}  // namespace pkm::python
