// pkm.inverse_dynamics: the rigid-body drive forces (dynamics/rigid_dynamics.hpp) for many platform motions
// at once, the loop in C++ across TBB's threads with the GIL released. The library takes the platform's
// twist about the tool point (v mm/s, ω rad/s in the base frame) and its rate; rates of the pose coordinates
// (the angles' time derivatives) are converted with the convention's ω = E(θ)·θ̇, α = E·θ̈ + Ė·θ̇.
#include <fmt/format.h>

#include <array>
#include <optional>

#include "analysis_bindings.hpp"
#include "array_args.hpp"
#include "batch_support.hpp"
#include "bindings.hpp"
#include "core/rotation.hpp"
#include "dynamics/rigid_dynamics.hpp"
#include "dynamics/run_dynamics.hpp"
#include "pipeline_support.hpp"
#include "row_loop.hpp"

namespace pkm::python {

namespace {

enum class DynRates { twist, coordinates };

DynRates dyn_rates_mode(const std::string& rates) {
  if (rates == "twist") return DynRates::twist;
  if (rates == "coordinates") return DynRates::coordinates;
  throw py::value_error("rates '" + rates + "': expected 'twist' or 'coordinates'");
}

// The angles' step of the central difference for Ė: small against the angles, large against rounding; fixed
// (not scaled by θ̇) so that Ė·θ̇ stays exactly bilinear in θ̇.
constexpr double kDynAngleStepRad = 1e-6;

/// The platform motion of one row: the pose and, for rates of the coordinates, ω and α from θ̇ and θ̈.
Result<dynamics::PlatformMotion> dyn_row_motion(const Mechanism& mechanism, const double* pose,
                                                const double* velocity, const double* acceleration,
                                                DynRates rates) {
  auto completed =
      mechanism.complete_pose(pose_from_vector(mechanism.convention(), Eigen::Map<const PoseVector>(pose)));
  if (!completed) return completed.error();
  dynamics::PlatformMotion motion;
  motion.pose = *completed;
  motion.velocity_mm_s = Eigen::Map<const Eigen::Vector3d>(velocity);
  motion.acceleration_mm_s2 = Eigen::Map<const Eigen::Vector3d>(acceleration);
  const Eigen::Map<const Eigen::Vector3d> angular_rate(velocity + 3), angular_accel(acceleration + 3);
  if (rates == DynRates::twist) {
    motion.angular_velocity_rad_s = angular_rate;
    motion.angular_acceleration_rad_s2 = angular_accel;
    return motion;
  }
  const AngleConvention convention = mechanism.convention();
  const Eigen::Vector3d angles = Eigen::Map<const Eigen::Vector3d>(pose + 3);
  const Eigen::Matrix3d e = angular_velocity_matrix(convention, angles);
  Eigen::Matrix3d e_rate = Eigen::Matrix3d::Zero();  // Ė = Σ_k ∂E/∂θ_k · θ̇_k
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    step[k] = kDynAngleStepRad;
    e_rate += (angular_velocity_matrix(convention, angles + step) -
               angular_velocity_matrix(convention, angles - step)) *
              (angular_rate[k] / (2.0 * kDynAngleStepRad));
  }
  motion.angular_velocity_rad_s = e * angular_rate;
  motion.angular_acceleration_rad_s2 = e * angular_accel + e_rate * angular_rate;
  return motion;
}

struct DynOutputs {
  double* total;
  double* static_part;
  double* dynamic_part;
  double* rates;
  double* power;
};

py::dict inverse_dynamics_batch(const Machine& machine, const py::object& poses, const py::object& velocities,
                                const py::object& accelerations, const std::string& rates_name,
                                const std::optional<std::array<double, 6>>& load, const std::string& errors,
                                bool check_limits) {
  const Mechanism& mechanism = *machine.mechanism;
  if (Status given = dynamics::require_dynamics_section(machine); !given) raise_error(given.error());
  const DynRates rates = dyn_rates_mode(rates_name);
  const OnError mode = on_error_mode(errors);
  const RowArray p = row_array(poses, 6, "poses");
  const RowArray v = row_array(velocities, 6, "velocities");
  const RowArray a = row_array(accelerations, 6, "accelerations");
  if (v.rows != p.rows || a.rows != p.rows || v.single != p.single || a.single != p.single) {
    throw py::value_error(fmt::format(
        "poses, velocities and accelerations must have the same shape (N, 6) or (6,); got {} poses, {} "
        "velocities, {} accelerations",
        p.rows, v.rows, a.rows));
  }
  statics::Wrench wrench;
  if (load) {
    wrench.force_N = Eigen::Vector3d((*load)[0], (*load)[1], (*load)[2]);
    wrench.moment_Nmm = Eigen::Vector3d((*load)[3], (*load)[4], (*load)[5]);
    if (!all_finite(load->data(), 6)) throw py::value_error("load_N_Nmm contains NaN or infinity");
  }
  const py::ssize_t n = mechanism.actuator_count();
  const std::vector<py::ssize_t> shape =
      p.single ? std::vector<py::ssize_t>{n} : std::vector<py::ssize_t>{static_cast<py::ssize_t>(p.rows), n};
  std::array<py::array_t<double>, 5> arrays{new_array(shape), new_array(shape), new_array(shape),
                                            new_array(shape), new_array(shape)};
  const DynOutputs out{arrays[0].mutable_data(), arrays[1].mutable_data(), arrays[2].mutable_data(),
                       arrays[3].mutable_data(), arrays[4].mutable_data()};
  const auto width = static_cast<std::size_t>(n);
  const ActuatorRange range(machine.limits);
  auto row_forces = [&](std::size_t row) -> Result<dynamics::DriveForces> {
    auto motion = dyn_row_motion(mechanism, p.row(row), v.row(row), a.row(row), rates);
    if (!motion) return motion.error();
    if (check_limits) {
      std::array<double, kMaxActuators> q{};
      if (!mechanism.actuator_values(motion->pose, q.data()) ||
          !range.contains(q.data(), mechanism.actuator_count()))
        return unreachable_error(machine, motion->pose, true);
    }
    return dynamics::inverse_dynamics(mechanism, machine.dynamics, *motion, wrench);
  };
  FirstRow invalid, failed;
  {
    const GilRelease release(p.rows >= kRowsToReleaseGil);
    for_each_row(p.rows, [&](std::size_t row) {
      const std::size_t at = row * width;
      if (!all_finite(p.row(row), 6) || !all_finite(v.row(row), 6) || !all_finite(a.row(row), 6)) {
        for (double* o : {out.total, out.static_part, out.dynamic_part, out.rates, out.power})
          fill_nan(o + at, width);
        invalid.offer(row);
        return;
      }
      auto forces = row_forces(row);
      if (!forces || forces->total.size() != n) {
        for (double* o : {out.total, out.static_part, out.dynamic_part, out.rates, out.power})
          fill_nan(o + at, width);
        failed.offer(row);
        return;
      }
      for (std::size_t j = 0; j < width; ++j) {
        const auto k = static_cast<Eigen::Index>(j);
        out.total[at + j] = forces->total[k];
        out.static_part[at + j] = forces->static_part[k];
        out.dynamic_part[at + j] = forces->dynamic_part[k];
        out.rates[at + j] = forces->actuator_rates[k];
        out.power[at + j] = forces->total[k] * forces->actuator_rates[k] * 1e-3;  // N·mm/s → W
      }
    });
  }
  if (invalid.any()) raise_non_finite("poses, velocities or accelerations", invalid.get(), p.single);
  if (mode == OnError::raise && failed.any()) {
    auto forces = row_forces(failed.get());
    const Error error = forces ? make_error(ErrorCode::singular, "no drive forces") : forces.error();
    raise_row_error(error, "poses", failed.get(), p.single);
  }
  const std::string force_unit = drive_force_unit(mechanism);
  const std::string rate_unit = actuator_unit(mechanism) + "_s";
  py::dict result;
  result[py::str("force_" + force_unit)] = arrays[0];
  result[py::str("static_force_" + force_unit)] = arrays[1];
  result[py::str("dynamic_force_" + force_unit)] = arrays[2];
  result[py::str("actuator_rates_" + rate_unit)] = arrays[3];
  result["power_W"] = arrays[4];
  return result;
}

}  // namespace

void bind_dynamics(py::module_& m) {
  m.def("inverse_dynamics", &inverse_dynamics_batch, py::arg("machine"), py::arg("poses"),
        py::arg("velocities"), py::arg("accelerations"), py::kw_only(), py::arg("rates") = "twist",
        py::arg("load_N_Nmm") = py::none(), py::arg("errors") = "raise", py::arg("check_limits") = true,
        R"doc(The drive forces that move the platform as given: rigid-body inverse dynamics (Newton–Euler with
virtual power over the platform, the struts and moving base joints; the machine file's dynamics: section),
for many motions at once (the loop in C++, in parallel, the GIL released).

poses: (N, 6) or (6,) [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the machine's angle convention (planar: x,
y and c = φ). velocities, accelerations: the same shape. With rates='twist' (default) they are the
platform's twist about the tool point and its rate: [vx, vy, vz] mm/s (mm/s²) of the tool point and
[ωx, ωy, ωz] rad/s (rad/s²), base frame. With rates='coordinates' they are the time derivatives of the pose's
6 coordinates (mm/s and rad/s of the convention's angles; ω = E(θ)·θ̇, α = E·θ̈ + Ė·θ̇).
load_N_Nmm: an external wrench on the platform at every row, [fx, fy, fz] N and [mx, my, mz] N·mm about the
tool point, base frame (default: none; gravity always acts). errors: 'raise' (the first failing row raises,
e.g. pkm.UnreachableError, with its row) or 'nan' (failing rows are NaN); check_limits: a pose whose
actuators leave the machine's actuator range fails as unreachable (as Machine.ik).

Returns a dict of (N, n) arrays (n actuators; (n,) for a single row), positive where the drive pushes its
coordinate up: force_N = static_force_N + dynamic_force_N (gravity and the load; the rates of momentum),
actuator_rates_mm_s (q̇), power_W (force · q̇). Angular drives: force_Nmm ..., actuator_rates_rad_s.
Raises pkm.InputError (key 'dynamics') for a machine file without a dynamics: section.)doc");
}

}  // namespace pkm::python
