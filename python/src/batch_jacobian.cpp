// Machine.jacobian and Machine.conditioning: d(actuators)/d(controlled coordinates) and the measures of
// kinematics/conditioning.hpp (det J, condition number, error amplification δρ) for many poses, in parallel.
#include <pybind11/numpy.h>

#include <array>

#include "array_args.hpp"
#include "batch_bindings.hpp"
#include "batch_support.hpp"
#include "machine/conditioning.hpp"
#include "row_loop.hpp"

namespace pkm::python {
namespace {

// The pose of a row, completed (reduced-DOF mechanisms compute their dependent coordinates) and reachable
// (within the actuator range when check_limits): the Jacobian of a pose the machine cannot take means little.
class ReachablePose {
 public:
  ReachablePose(const Machine& machine, bool check_limits)
      : machine_(machine), range_(machine.limits), check_limits_(check_limits) {}

  Result<Pose> operator()(const double* values) const {
    const Mechanism& mech = *machine_.mechanism;
    auto pose = mech.complete_pose(pose_from_vector(mech.convention(), Eigen::Map<const PoseVector>(values)));
    if (!pose) return pose.error();
    std::array<double, kMaxActuators> q{};
    if (!mech.actuator_values(*pose, q.data()) ||
        (check_limits_ && !range_.contains(q.data(), mech.actuator_count())))
      return unreachable_error(machine_, *pose, check_limits_);
    return pose;
  }
  const Mechanism& mechanism() const { return *machine_.mechanism; }

 private:
  const Machine& machine_;
  ActuatorRange range_;
  bool check_limits_;
};

Result<JacobianMatrix> row_jacobian(const ReachablePose& reachable, const double* values) {
  auto pose = reachable(values);
  if (!pose) return pose.error();
  return reachable.mechanism().jacobian(*pose);
}

py::array_t<double> jacobian(const Machine& machine, const py::object& poses, const std::string& errors,
                             bool check_limits) {
  const Mechanism& mech = *machine.mechanism;
  const ReachablePose reachable(machine, check_limits);
  const OnError mode = on_error_mode(errors);
  const RowArray in = row_array(poses, 6, "poses");
  const py::ssize_t n = mech.actuator_count();
  const py::ssize_t m = mech.controlled_axes().count();
  auto out = in.single ? new_array({n, m}) : new_array({static_cast<py::ssize_t>(in.rows), n, m});
  double* data = out.mutable_data();
  const auto size = static_cast<std::size_t>(n * m);
  FirstRow invalid, failed;
  {
    const GilRelease release(in.rows >= kRowsToReleaseGil);
    for_each_row(in.rows, [&](std::size_t row) {
      double* j = data + row * size;
      if (!all_finite(in.row(row), 6)) {
        fill_nan(j, size);
        invalid.offer(row);
        return;
      }
      auto result = row_jacobian(reachable, in.row(row));
      if (!result || result->rows() != n || result->cols() != m) {
        fill_nan(j, size);
        failed.offer(row);
        return;
      }
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(j, n, m) = *result;
    });
  }
  if (invalid.any()) raise_non_finite("poses", invalid.get(), in.single);
  if (mode == OnError::raise && failed.any()) {
    auto result = row_jacobian(reachable, in.row(failed.get()));
    const Error error =
        result ? make_error(ErrorCode::unsupported, "the Jacobian has an unexpected shape") : result.error();
    raise_row_error(error, "poses", failed.get(), in.single);
  }
  return out;
}

// The measures' names (and the dict's keys), in the order of MeasureRow.
constexpr std::array<const char*, 7> kMeasureNames = {
    "det", "condition_number", "min_singular_value", "delta_rho", "s_x", "s_y", "s_z"};
using MeasureRow = std::array<double, kMeasureNames.size()>;

Result<MeasureRow> row_measures(const ReachablePose& reachable, const double* values) {
  const Mechanism& mech = reachable.mechanism();
  auto pose = reachable(values);
  if (!pose) return pose.error();
  auto measures = jacobian_measures(mech, *pose);
  if (!measures) return measures.error();
  const JacobianMeasures& j = *measures;
  // det, δρ and S exist for square Jacobians only (jacobian_measures leaves them 0 otherwise).
  const bool square = mech.actuator_count() == mech.controlled_axes().count();
  const double none = std::nan("");
  return MeasureRow{square ? j.determinant : none,
                    j.condition_number,
                    j.min_singular_value,
                    square ? j.error_amplification : none,
                    square ? j.sensitivity_sums[0] : none,
                    square ? j.sensitivity_sums[1] : none,
                    square ? j.sensitivity_sums[2] : none};
}

py::object conditioning(const Machine& machine, const py::object& poses, const std::string& errors,
                        bool check_limits) {
  const ReachablePose reachable(machine, check_limits);
  const OnError mode = on_error_mode(errors);
  const RowArray in = row_array(poses, 6, "poses");
  const std::size_t k = kMeasureNames.size();
  // Filled column by column: one (N,) array per measure.
  std::array<py::array_t<double>, kMeasureNames.size()> columns;
  std::array<double*, kMeasureNames.size()> data{};
  for (std::size_t c = 0; c < k; ++c) {
    columns[c] = new_array({static_cast<py::ssize_t>(in.rows)});
    data[c] = columns[c].mutable_data();
  }
  FirstRow invalid, failed;
  {
    const GilRelease release(in.rows >= kRowsToReleaseGil);
    for_each_row(in.rows, [&](std::size_t row) {
      Result<MeasureRow> measures = make_error(ErrorCode::bad_input, "");
      if (all_finite(in.row(row), 6)) {
        measures = row_measures(reachable, in.row(row));
        if (!measures) failed.offer(row);
      } else {
        invalid.offer(row);
      }
      for (std::size_t c = 0; c < k; ++c) data[c][row] = measures ? (*measures)[c] : std::nan("");
    });
  }
  if (invalid.any()) raise_non_finite("poses", invalid.get(), in.single);
  if (mode == OnError::raise && failed.any()) {
    raise_row_error(row_measures(reachable, in.row(failed.get())).error(), "poses", failed.get(), in.single);
  }
  py::dict out;
  for (std::size_t c = 0; c < k; ++c) {
    out[kMeasureNames[c]] = in.single ? py::object(py::float_(data[c][0])) : py::object(columns[c]);
  }
  return out;
}

}  // namespace

void bind_jacobian(MachineClass& cls) {
  cls.def("jacobian", &jacobian, py::arg("poses"), py::kw_only(), py::arg("errors") = "raise",
          py::arg("check_limits") = true, R"(The Jacobian d(actuators)/d(controlled coordinates) at each pose.

poses: shape (N, 6) or (6,), [x, y, z mm, a, b, c rad] in the machine's angle_convention (as for ik);
    reduced-DOF machines complete the dependent coordinates first.
errors: "raise" (default): the first unreachable or singular row raises (pkm.UnreachableError, ...), with
    "poses[ROW]:" in the message and the attribute `row`; "nan": such rows are NaN.
check_limits: a pose whose actuator values leave actuator_min/actuator_max counts as unreachable (as ik).

Returns shape (N, n, m) (or (n, m)): rows are the n actuators (mm, or rad for angular actuators), columns the
m controlled coordinates (controlled_names) per mm or per rad of the angles, as `pkm jacobian` prints it.)");
  cls.def(
      "conditioning", &conditioning, py::arg("poses"), py::kw_only(), py::arg("errors") = "nan",
      py::arg("check_limits") = true,
      R"(Singularity and accuracy measures at each pose (Smirnov 2019, §5.1, eq. 144–146), as `pkm jacobian`.

poses: shape (N, 6) or (6,), as for jacobian.
errors: "nan" (default): unreachable or singular poses give NaN; "raise": the first such row raises.
check_limits: a pose whose actuator values leave actuator_min/actuator_max counts as unreachable (as ik).

Returns a dict of (N,) float arrays (floats for one pose):
    det                 det J in the controlled coordinates (J in mm, or rad, per mm and per rad)
    condition_number    σ_max/σ_min of J (mixed units as det; inf at a singularity)
    min_singular_value  σ_min of J
    delta_rho           error amplification δρ = sqrt(s_x² + s_y² + s_z²): mm of tool-point error per mm of
                        equal actuator errors
    s_x, s_y, s_z       Σ_j |∂x/∂L_j| (and y, z): mm per mm; 0 for uncontrolled axes
det, delta_rho and s_* are NaN for mechanisms whose J is not square.)");
}

}  // namespace pkm::python
