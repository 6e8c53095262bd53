// Machine.ik: inverse kinematics of many poses, the loop in C++ across TBB's threads with the GIL released;
// pkm.set_threads; and the timing helper the benchmark compares against (the same loop, one thread).
#include <pybind11/numpy.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <memory>
#include <vector>

#include "array_args.hpp"
#include "batch_bindings.hpp"
#include "batch_support.hpp"
#include "row_loop.hpp"

namespace pkm::python {
namespace {

enum class RowResult { ok, invalid_input, failed };

// One row of IK, as the batch loop and the timing helper run it: the hot, non-allocating form.
class IkRow {
 public:
  IkRow(const Machine& machine, bool check_limits)
      : mechanism_(*machine.mechanism),
        convention_(mechanism_.convention()),
        range_(machine.limits),
        check_limits_(check_limits) {}

  RowResult operator()(const PoseVector& pose, double* out) const noexcept {
    if (!all_finite(pose.data(), 6)) return RowResult::invalid_input;
    if (mechanism_.actuator_values_at(convention_, pose, out) &&
        (!check_limits_ || range_.contains(out, count())))
      return RowResult::ok;
    return RowResult::failed;
  }
  int count() const noexcept { return mechanism_.actuator_count(); }

 private:
  const Mechanism& mechanism_;
  AngleConvention convention_;
  ActuatorRange range_;
  bool check_limits_;
};

// IK of rows [begin, end) of `poses` into `values`. The rows are first copied, a block at a time, into
// PoseVectors of their own: measured on the ch5 hexapod (bench/python/bench_batch.py), handing the library a
// PoseVector made from the numpy row just before each call (an Eigen::Map bound to `const PoseVector&`) cost
// 15 % more per pose (87 against 100 ns), most likely the fresh copy's loads waiting on its stores.
void solve_ik_range(const IkRow& ik_row, const RowArray& poses, double* values, std::size_t begin,
                    std::size_t end, FirstRow& invalid, FirstRow& failed) {
  constexpr std::size_t kBlockRows = 64;
  static_assert(sizeof(PoseVector) == 6 * sizeof(double), "a PoseVector is its six numbers");
  const auto n = static_cast<std::size_t>(ik_row.count());
  std::array<PoseVector, kBlockRows> block;
  for (std::size_t first = begin; first < end; first += kBlockRows) {
    const std::size_t count = std::min(kBlockRows, end - first);
    for (std::size_t k = 0; k < count; ++k)
      std::memcpy(block[k].data(), poses.row(first + k), sizeof(PoseVector));
    for (std::size_t k = 0; k < count; ++k) {
      double* q = values + (first + k) * n;
      const RowResult result = ik_row(block[k], q);
      if (result == RowResult::ok) continue;
      fill_nan(q, n);
      (result == RowResult::invalid_input ? invalid : failed).offer(first + k);
    }
  }
}

Error ik_row_error(const Machine& machine, const double* values, bool check_limits) {
  const Pose pose = pose_from_vector(machine.mechanism->convention(), Eigen::Map<const PoseVector>(values));
  return unreachable_error(machine, pose, check_limits);
}

py::array_t<double> ik(const Machine& machine, const py::object& poses, const std::string& errors,
                       bool check_limits, const py::object& out_argument) {
  const OnError mode = on_error_mode(errors);
  const RowArray in = row_array(poses, 6, "poses");
  const IkRow ik_row(machine, check_limits);
  const auto n = static_cast<std::size_t>(ik_row.count());
  const auto shape =
      in.single ? std::vector<py::ssize_t>{static_cast<py::ssize_t>(n)}
                : std::vector<py::ssize_t>{static_cast<py::ssize_t>(in.rows), static_cast<py::ssize_t>(n)};
  auto out = output_array(out_argument, shape, in, "out");
  double* values = out.mutable_data();
  FirstRow invalid, failed;
  {
    const GilRelease release(in.rows >= kRowsToReleaseGil);
    for_each_range(in.rows, [&](std::size_t begin, std::size_t end) {
      solve_ik_range(ik_row, in, values, begin, end, invalid, failed);
    });
  }
  if (invalid.any()) raise_non_finite("poses", invalid.get(), in.single);
  if (mode == OnError::raise && failed.any()) {
    raise_row_error(ik_row_error(machine, in.row(failed.get()), check_limits), "poses", failed.get(),
                    in.single);
  }
  return out;
}

// The C++ loop alone, one thread: what `ik` costs without Python and without TBB.
double ik_loop_seconds(const Machine& machine, const py::object& poses, bool check_limits) {
  const RowArray in = row_array(poses, 6, "poses");
  const IkRow ik_row(machine, check_limits);
  const auto n = static_cast<std::size_t>(ik_row.count());
  std::vector<double> values(in.rows * n);
  FirstRow invalid, failed;
  const GilRelease release(true);
  const auto start = std::chrono::steady_clock::now();
  solve_ik_range(ik_row, in, values.data(), 0, in.rows, invalid, failed);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The thread limit set by set_threads; never destroyed (a TBB object torn down among static destructors at
// exit could outlive the scheduler).
std::unique_ptr<tbb::global_control>& thread_limit() {
  static auto* limit = new std::unique_ptr<tbb::global_control>();
  return *limit;
}

constexpr const char* kIkDoc = R"(Inverse kinematics: the actuator values of each pose.

poses: shape (N, 6), or (6,) for one pose. Each row is [x, y, z, a, b, c]: the tool point in mm (base frame)
    and the platform orientation in rad, in the machine's angle_convention (krylov, abc or euler_zxz; planar
    machines: x, y and c = phi). Reduced-DOF machines use only their controlled coordinates
    (controlled_axes). Any real dtype numpy converts to float64 (lists, float32, integers) is accepted.
errors: "raise" (default): the first unreachable row (lowest index) raises pkm.UnreachableError, whose
    message starts "poses[ROW]:" and whose attribute `row` is that index. "nan": unreachable rows are NaN.
check_limits: when True (default, as `pkm ik`), a pose whose actuator values leave the machine's
    actuator_min/actuator_max counts as unreachable.
out: None, or a float64 C-contiguous array of the result's shape to write into and return (reusing one
    saves a new array's page faults: about 10 ns per pose of a large batch).

Returns shape (N, n) (or (n,)) actuator values: mm for struts and carriages, rad for angular actuators
(actuator_unit). NaN or infinity in `poses` raises ValueError naming the row. Results do not depend on the
number of threads and equal a Python loop of single-pose calls bit for bit. From 64 rows on the GIL is
released; from 1024 rows the rows run in blocks on TBB's threads (pkm.set_threads).)";

}  // namespace

void bind_ik(MachineClass& cls, py::module_& m) {
  cls.def("ik", &ik, py::arg("poses"), py::kw_only(), py::arg("errors") = "raise",
          py::arg("check_limits") = true, py::arg("out") = py::none(), kIkDoc);
  m.def(
      "_ik_loop_seconds", &ik_loop_seconds, py::arg("machine"), py::arg("poses"),
      py::arg("check_limits") = true,
      "Seconds the C++ IK loop of Machine.ik takes over `poses` on one thread, without Python (benchmarks).");
  m.def(
      "set_threads",
      [](std::optional<int> threads) {
        if (threads && *threads < 0) throw py::value_error("threads must be ≥ 1, or 0/None for all cores");
        thread_limit().reset();
        if (threads && *threads > 0) {
          thread_limit() = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                 static_cast<std::size_t>(*threads));
        }
      },
      py::arg("threads"),
      "Limits the threads of pkm's batch calls and analyses to `threads` (TBB); 0 or None: all cores. "
      "Results "
      "do not depend on it.");
  m.def(
      "get_threads",
      [] { return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism); },
      "The number of threads pkm's batch calls may use (TBB's current limit).");
}

}  // namespace pkm::python
