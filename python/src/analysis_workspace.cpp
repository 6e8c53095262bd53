// pkm.workspace: a workspace map over a plane section or a 3-D grid of poses, as `pkm workspace`
// (pipeline/workspace_job.hpp, the same job): per cell whether the machine can stand there or which limit
// stops it, the sign of det J, the condition number, δρ and S_x, S_y, S_z, and on request the lowest
// stiffness and natural frequency.
#include <fmt/format.h>

#include "analysis_bindings.hpp"
#include "bindings.hpp"
#include "formats/workspace_output.hpp"
#include "json_to_python.hpp"
#include "pipeline/workspace_job.hpp"
#include "pipeline_support.hpp"

namespace pkm::python {

namespace {

workspace::WorkspaceGrid grid_of(const std::string& plane, const Pose& centre, double range_mm,
                                 double step_mm, const py::object& axes) {
  if (!axes.is_none()) {
    workspace::WorkspaceGrid grid{centre, {}};
    for (const py::handle axis : axes) {
      const auto t = axis.cast<std::tuple<int, double, double>>();
      grid.axes.push_back({std::get<0>(t), std::get<1>(t), std::get<2>(t)});
    }
    return grid;
  }
  if (plane == "3d") return workspace::position_grid(centre, range_mm, step_mm);
  auto parsed = dynamics::grid_plane_from_string(plane);
  if (!parsed) {
    throw py::value_error(fmt::format("plane '{}': expected xy, xz, yz or 3d (or give axes)", plane));
  }
  return workspace::plane_section(centre, *parsed, range_mm, step_mm);
}

}  // namespace

void bind_workspace(py::module_& m) {
  m.def(
      "workspace",
      [](const Machine& machine, const std::string& plane, const py::object& centre_value, double range_mm,
         double step_mm, const py::object& axes, bool stiffness, bool frequencies, int threads,
         const py::object& out_dir) {
        const Mechanism& mechanism = *machine.mechanism;
        const Pose centre =
            centre_value.is_none() ? mechanism.home() : pose_from_python(mechanism, centre_value, "centre");
        pipeline::WorkspaceJob job;
        job.grid = grid_of(plane, centre, range_mm, step_mm, axes);
        job.options.stiffness = stiffness;
        job.options.frequencies = frequencies;
        job.options.threads = threads;
        job.out_directory = optional_path(out_dir);
        const pipeline::WorkspaceJobResult r =
            unwrap_released([&] { return pipeline::run_workspace_job(machine, job); });
        const workspace::WorkspaceMap& map = r.map;
        const workspace::GridCells cells(map.grid, mechanism.convention());
        const auto count = static_cast<py::ssize_t>(map.cells.size());
        std::vector<double> pose, condition, delta_rho, sensitivity, stiffness_N_um, frequency_Hz;
        std::vector<std::string> status, limit;
        std::vector<std::int8_t> det_sign;
        std::vector<std::int32_t> index;
        for (long i = 0; i < static_cast<long>(map.cells.size()); ++i) {
          const workspace::WorkspaceCell& c = map.cells[static_cast<std::size_t>(i)];
          const PoseVector v = pose_vector(mechanism, cells.pose(i));
          pose.insert(pose.end(), v.data(), v.data() + 6);
          const auto at = cells.indices(i);
          index.insert(index.end(), at.begin(), at.begin() + cells.axis_count());
          status.emplace_back(workspace::to_string(c.status));
          limit.push_back(formats::limit_text(c));
          det_sign.push_back(c.determinant_sign);
          condition.push_back(c.condition_number);
          delta_rho.push_back(c.error_amplification);
          sensitivity.insert(sensitivity.end(), c.sensitivity_sums.data(), c.sensitivity_sums.data() + 3);
          stiffness_N_um.push_back(c.lowest_stiffness_N_um);
          frequency_Hz.push_back(c.lowest_frequency_Hz);
        }
        std::vector<int> coordinates;
        for (const workspace::GridAxis& axis : map.grid.axes) coordinates.push_back(axis.coordinate);
        py::dict out;
        out["summary"] = python_from_json(r.summary_json);
        out["points_per_axis"] = py::cast(map.points_per_axis);
        out["axes"] = py::cast(coordinates);
        out["pose"] = numpy_from(std::move(pose), {count, 6});
        out["index"] = numpy_from(std::move(index), {count, static_cast<py::ssize_t>(cells.axis_count())});
        out["status"] = numpy_strings(status);
        out["limit"] = numpy_strings(limit);
        out["det_sign"] = numpy_from(std::move(det_sign));
        out["condition_number"] = numpy_from(std::move(condition));
        out["delta_rho"] = numpy_from(std::move(delta_rho));
        out["sensitivity"] = numpy_from(std::move(sensitivity), {count, 3});
        if (map.has_stiffness) out["lowest_stiffness_N_um"] = numpy_from(std::move(stiffness_N_um));
        if (map.has_frequencies) out["lowest_frequency_Hz"] = numpy_from(std::move(frequency_Hz));
        return out;
      },
      py::arg("machine"), py::kw_only(), py::arg("plane") = "xy", py::arg("centre") = py::none(),
      py::arg("range_mm") = 200.0, py::arg("step_mm") = 20.0, py::arg("axes") = py::none(),
      py::arg("stiffness") = false, py::arg("frequencies") = false, py::arg("threads") = 0,
      py::arg("out_dir") = py::none(),
      R"doc(The workspace map over a grid of poses, as `pkm workspace` (same cells, same summary).

The grid: plane 'xy' | 'xz' | 'yz' (a section of the tool positions through `centre`) or '3d' (x, y and z),
each centre ± range_mm by step_mm; or axes: a list of 2 or 3 (coordinate, half_range, step) with coordinate
0 … 5 of the pose vector (x, y, z in mm; the three angles in rad), the first running fastest. centre:
[x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] (default: the machine's home). stiffness / frequencies: also the
lowest translational stiffness (N/µm) and natural frequency (Hz) where the machine can stand. threads: 0 =
every core. out_dir: also write the CLI's workspace.csv and summary.json there.

Returns a dict: summary (the summary.json of `pkm workspace`, as a dict), points_per_axis, axes (the
coordinates varied), and per cell (C cells, in the grid's order): pose (C, 6); index (C, 2 or 3) along each
axis; status (C,) str: ok | unreachable | actuator_range | joint_angle | singular | conditioning; limit (C,)
str (e.g. 'q3_max', '' for none); det_sign (C,) int8; condition_number (C,); delta_rho (C,) the error
amplification δρ; sensitivity (C, 3) S_x, S_y, S_z; with the options lowest_stiffness_N_um (C,),
lowest_frequency_Hz (C,). NaN where a cell has no value.)doc");
}

}  // namespace pkm::python
