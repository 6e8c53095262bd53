// Machine.fk and Machine.fk_all: forward kinematics of many actuator rows, warm along the rows as along a
// path (serial: each row starts from the previous solution) or cold from one guess (independent rows, in
// parallel).
#include <pybind11/numpy.h>

#include <memory>
#include <optional>

#include "array_args.hpp"
#include "batch_bindings.hpp"
#include "batch_support.hpp"
#include "row_loop.hpp"

namespace pkm::python {
namespace {

struct FkArguments {
  FkOptions options;
  bool check_limits = true;
  bool extrapolate = false;  ///< warm rows: start from the path extrapolated from earlier solutions
  OnError mode = OnError::raise;
};

// Where a failed row is recorded: the first failure, by row, with its error when already known.
struct FkFailure {
  std::size_t row = FirstRow::kNone;
  std::optional<Error> error;
};

Pose guess_pose(const Mechanism& mech, const py::object& guess) {
  if (guess.is_none()) return mech.home();
  const RowArray g = row_array(guess, 6, "guess");
  if (!g.single) throw py::value_error("guess must be one pose of shape (6,)");
  if (!all_finite(g.row(0), 6)) raise_non_finite("guess", 0, true);
  auto completed =
      mech.complete_pose(pose_from_vector(mech.convention(), Eigen::Map<const PoseVector>(g.row(0))));
  if (!completed) raise_row_error(completed.error(), "guess", 0, true);
  return *completed;
}

// Outputs of fk: poses, and per row the solver's iterations, residual and assembly-mode label.
class FkOutputs {
 public:
  FkOutputs(std::size_t rows, bool single, bool with_info)
      : poses_(single ? new_array({6}) : new_array({static_cast<py::ssize_t>(rows), 6})),
        info_(with_info),
        iterations_(static_cast<py::ssize_t>(rows)),
        residual_mm_(static_cast<py::ssize_t>(rows)),
        branch_(static_cast<py::ssize_t>(rows)),
        pose_data_(poses_.mutable_data()),
        iteration_data_(iterations_.mutable_data()),
        residual_data_(residual_mm_.mutable_data()),
        branch_data_(branch_.mutable_data()) {}

  void set(std::size_t row, AngleConvention convention, const FkSolution& s) noexcept {
    Eigen::Map<PoseVector>(pose_data_ + 6 * row) = vector_from_pose(convention, s.pose);
    iteration_data_[row] = s.iterations;
    residual_data_[row] = s.residual_mm;
    branch_data_[row] = s.branch;
  }
  void set_failed(std::size_t row) noexcept {
    fill_nan(pose_data_ + 6 * row, 6);
    iteration_data_[row] = -1;
    residual_data_[row] = std::nan("");
    branch_data_[row] = -1;
  }
  py::object result(bool single) const {
    if (!info_) return poses_;
    py::dict info;
    if (single) {
      info["iterations"] = iteration_data_[0];
      info["residual_mm"] = residual_data_[0];
      info["branch"] = branch_data_[0];
    } else {
      info["iterations"] = iterations_;
      info["residual_mm"] = residual_mm_;
      info["branch"] = branch_;
    }
    return py::make_tuple(poses_, info);
  }

 private:
  py::array_t<double> poses_;
  bool info_;
  py::array_t<int> iterations_;
  py::array_t<double> residual_mm_;
  py::array_t<int> branch_;
  double* pose_data_;
  int* iteration_data_;
  double* residual_data_;
  int* branch_data_;
};

ActuatorVector actuator_vector(const double* values, int count) {
  ActuatorVector q(count);
  for (int j = 0; j < count; ++j) q[j] = values[j];
  return q;
}

// Each row from the same guess: independent, so in parallel; equals `pkm fk --guess` row by row.
void fk_cold(const Machine& machine, const RowArray& in, const Pose& guess, const FkArguments& a,
             FkOutputs& out, FirstRow& invalid, FirstRow& failed) {
  const Mechanism& mech = *machine.mechanism;
  const int n = mech.actuator_count();
  const ActuatorRange range(machine.limits);
  for_each_row(in.rows, [&](std::size_t row) {
    const double* values = in.row(row);
    if (!all_finite(values, static_cast<std::size_t>(n))) {
      out.set_failed(row);
      invalid.offer(row);
      return;
    }
    if (a.check_limits && !range.contains(values, n)) {
      out.set_failed(row);
      failed.offer(row);
      return;
    }
    auto solution = mech.forward(actuator_vector(values, n), guess, a.options);
    if (solution) {
      out.set(row, mech.convention(), *solution);
    } else {
      out.set_failed(row);
      failed.offer(row);
    }
  });
}

// Along the rows as along a path: each row starts from the previous row's solution with the mechanism's FK
// workspace (a hexapod keeps its factorisation and extrapolates), so it runs serially. A row whose
// extrapolated start fails is solved again from the previous solution with a fresh workspace; after a failed
// row the next starts again from the last solution found.
void fk_warm(const Machine& machine, const RowArray& in, const Pose& guess, const FkArguments& a,
             FkOutputs& out, FirstRow& invalid, FkFailure& failure) {
  const Mechanism& mech = *machine.mechanism;
  const int n = mech.actuator_count();
  const ActuatorRange range(machine.limits);
  const std::unique_ptr<FkWorkspace> workspace = mech.make_fk_workspace();
  Pose start = guess;
  for (std::size_t row = 0; row < in.rows; ++row) {
    const double* values = in.row(row);
    if (!all_finite(values, static_cast<std::size_t>(n))) {
      invalid.offer(row);
      return;
    }
    const ActuatorVector q = actuator_vector(values, n);
    std::optional<Error> error;
    if (a.check_limits && !range.contains(values, n)) {
      error = check_actuator_range(machine, q).error();
    } else {
      // Without extrapolation the start is the previous solution itself; the kept factorisation still serves
      // chord steps where it contracts (platform_newton.hpp).
      if (!a.extrapolate) workspace->forget_path();
      auto solution = mech.forward_warm(q, start, a.options, *workspace);
      if (!solution) {
        // The start extrapolated from earlier rows can be far off when rows are no smooth path: again from
        // the previous solution alone.
        workspace->reset();
        solution = mech.forward_warm(q, start, a.options, *workspace);
      }
      if (solution) {
        out.set(row, mech.convention(), *solution);
        start = solution->pose;
        continue;
      }
      error = solution.error();
    }
    out.set_failed(row);
    workspace->reset();
    if (a.mode == OnError::raise) {
      failure = {row, std::move(error)};
      return;
    }
  }
}

// Why a cold row failed, in the library's words, as `pkm fk` reports it: the range first, then the solver.
Error fk_row_error(const Machine& machine, const double* values, const Pose& guess, const FkArguments& a) {
  const Mechanism& mech = *machine.mechanism;
  const ActuatorVector q = actuator_vector(values, mech.actuator_count());
  if (a.check_limits) {
    if (auto range = check_actuator_range(machine, q); !range) return range.error();
  }
  auto solution = mech.forward(q, guess, a.options);
  if (!solution) return solution.error();
  return make_error(ErrorCode::not_converged, "forward kinematics failed");
}

FkArguments fk_arguments(const std::string& errors, bool check_limits, double tolerance_mm,
                         int max_iterations, bool same_branch) {
  FkArguments a;
  a.mode = on_error_mode(errors);
  a.check_limits = check_limits;
  if (!(tolerance_mm > 0)) throw py::value_error("tolerance_mm must be > 0");
  if (max_iterations < 1) throw py::value_error("max_iterations must be ≥ 1");
  a.options.tolerance_mm = tolerance_mm;
  a.options.max_iterations = max_iterations;
  a.options.require_same_branch = same_branch;
  return a;
}

py::object fk(const Machine& machine, const py::object& actuators, const py::object& guess, bool warm,
              bool extrapolate, const std::string& errors, bool check_limits, double tolerance_mm,
              int max_iterations, bool same_branch, bool info) {
  const Mechanism& mech = *machine.mechanism;
  FkArguments a = fk_arguments(errors, check_limits, tolerance_mm, max_iterations, same_branch);
  a.extrapolate = extrapolate;
  const RowArray in = row_array(actuators, static_cast<std::size_t>(mech.actuator_count()), "actuators");
  const Pose start = guess_pose(mech, guess);
  FkOutputs out(in.rows, in.single, info);
  FirstRow invalid, failed;
  FkFailure warm_failure;
  {
    const GilRelease release(in.rows >= kRowsToReleaseGil);
    if (warm) {
      fk_warm(machine, in, start, a, out, invalid, warm_failure);
    } else {
      fk_cold(machine, in, start, a, out, invalid, failed);
    }
  }
  if (invalid.any()) raise_non_finite("actuators", invalid.get(), in.single);
  if (warm_failure.error) raise_row_error(*warm_failure.error, "actuators", warm_failure.row, in.single);
  if (a.mode == OnError::raise && failed.any()) {
    raise_row_error(fk_row_error(machine, in.row(failed.get()), start, a), "actuators", failed.get(),
                    in.single);
  }
  return out.result(in.single);
}

py::list fk_all(const Machine& machine, const py::object& actuators, bool check_limits, double tolerance_mm,
                int max_iterations) {
  const Mechanism& mech = *machine.mechanism;
  const FkArguments a = fk_arguments("raise", check_limits, tolerance_mm, max_iterations, false);
  const RowArray in = row_array(actuators, static_cast<std::size_t>(mech.actuator_count()), "actuators");
  if (!in.single) throw py::value_error("fk_all takes one row of actuator values, shape (n,)");
  if (!all_finite(in.row(0), in.width)) raise_non_finite("actuators", 0, true);
  const ActuatorVector q = actuator_vector(in.row(0), mech.actuator_count());
  if (check_limits) {
    if (auto range = check_actuator_range(machine, q); !range)
      raise_row_error(range.error(), "actuators", 0, true);
  }
  auto solutions = mech.forward_all(q, a.options);
  if (!solutions) raise_row_error(solutions.error(), "actuators", 0, true);
  py::list out;
  for (const FkSolution& s : *solutions) {
    const PoseVector pose = vector_from_pose(mech.convention(), s.pose);
    py::array_t<double> pose_array(6);
    std::copy(pose.data(), pose.data() + 6, pose_array.mutable_data());
    py::dict d;
    d["pose"] = pose_array;
    d["branch"] = s.branch;
    d["iterations"] = s.iterations;
    d["residual_mm"] = s.residual_mm;
    out.append(d);
  }
  return out;
}

constexpr const char* kFkDoc = R"(Forward kinematics: the pose of each row of actuator values.

actuators: shape (N, n), or (n,) for one row: mm for struts and carriages, rad for angular actuators
    (actuator_unit); n = actuator_count.
guess: the start pose, shape (6,) [x, y, z mm, a, b, c rad in angle_convention]; None: the home pose.
warm: True (default): rows are a sequence, e.g. a path. Row 0 starts from `guess`, every later row from
    the previous row's solution (keeping the mechanism's FK workspace: a hexapod reuses its factorisation
    where it still contracts), serially, in the previous row's assembly mode. After a failed row
    (errors="nan") the next starts again from the last solution found. False: every row starts from `guess`,
    independently, in parallel on TBB's threads; each row then equals `pkm fk --actuators ROW --guess GUESS`.
extrapolate: with warm, start each row from the path extrapolated through the last four solutions, as the
    servo loop does (about one iteration per row along a smooth path of small steps). Only for such paths:
    for rows far apart the extrapolated start can land in another assembly mode of the same label and give a
    wrong pose silently. A row whose extrapolated start fails is solved again from the previous solution.
errors: "raise" (default): the first failing row raises (pkm.NotConvergedError, pkm.WrongBranchError when the
    solution is in another assembly mode than the guess's, pkm.LimitExceededError for actuator values outside
    the machine's range) with "actuators[ROW]:" in the message and the attribute `row`. "nan": failing rows
    are NaN.
check_limits: refuse actuator values outside actuator_min/actuator_max (as `pkm fk`).
tolerance_mm, max_iterations: the solver's stopping rule (largest actuator residual, mm or rad).
same_branch: require the solution in the guess's assembly mode.
info: also return a dict of (N,) arrays: iterations (int), residual_mm, branch (assembly-mode label, 0 = the
    home pose's), -1/NaN for failed rows.

Returns shape (N, 6) (or (6,)) poses, [x, y, z mm, a, b, c rad] in the machine's angle_convention; with
info=True the tuple (poses, info).)";

}  // namespace

void bind_fk(MachineClass& cls) {
  const FkOptions defaults;
  cls.def("fk", &fk, py::arg("actuators"), py::arg("guess") = py::none(), py::kw_only(),
          py::arg("warm") = true, py::arg("extrapolate") = false, py::arg("errors") = "raise",
          py::arg("check_limits") = true, py::arg("tolerance_mm") = defaults.tolerance_mm,
          py::arg("max_iterations") = defaults.max_iterations,
          py::arg("same_branch") = defaults.require_same_branch, py::arg("info") = false, kFkDoc);
  cls.def("fk_all", &fk_all, py::arg("actuators"), py::kw_only(), py::arg("check_limits") = true,
          py::arg("tolerance_mm") = defaults.tolerance_mm,
          py::arg("max_iterations") = defaults.max_iterations,
          R"(Every assembly mode of one row of actuator values (shape (n,); mm, or rad), as `pkm fk --all`.

Returns a list of dicts, nearest to home first: pose ((6,) array, [x, y, z mm, a, b, c rad] in
angle_convention), branch (assembly-mode label, 0 = the home pose's), iterations, residual_mm. Raises
pkm.UnsupportedError for mechanisms that cannot enumerate their modes (glides, rotopod, ...).)");
}

}  // namespace pkm::python
