// pkm.stiffness, pkm.servo, pkm.simulate and pkm.circle: the library runs that write an output set
// (pipeline/stiffness_program.hpp, pipeline/servo_program.hpp, pipeline/simulate_program.hpp,
// pipeline/circle_test.hpp), run into `out_dir`
// or a temporary directory; their summary comes back as a dict and their per-point / per-tick CSV as a dict
// of numpy columns (numpy.genfromtxt; empty fields are NaN).
#include <array>
#include <utility>

#include "analysis_bindings.hpp"
#include "bindings.hpp"
#include "json_to_python.hpp"
#include "pipeline/circle_test.hpp"
#include "pipeline/servo_program.hpp"
#include "pipeline/simulate_program.hpp"
#include "pipeline/stiffness_program.hpp"
#include "pipeline_law_options.hpp"
#include "pipeline_support.hpp"
#include "run_directory.hpp"
#include "stiffness/compliance_model.hpp"

namespace pkm::python {

namespace {

/// The CSV's columns by their header names.
py::dict csv_columns(const std::string& path) {
  const py::object numpy = py::module_::import("numpy");
  const py::object table = numpy.attr("genfromtxt")(path, py::arg("delimiter") = ",", py::arg("names") = true,
                                                    py::arg("dtype") = "f8", py::arg("ndmin") = 1);
  py::dict columns;
  for (const py::handle name : table.attr("dtype").attr("names")) columns[name] = table[name];
  return columns;
}

// pkm.circle: the circular test (pipeline/circle_test.hpp).
void bind_circle(py::module_& m) {
  m.def(
      "circle",
      [](const Machine& machine, double radius_mm, double feed_mm_min, const std::string& plane,
         std::array<double, 3> centre_mm, bool elastic, const std::string& load, const py::object& out_dir) {
        if (plane != "XY" && plane != "ZX" && plane != "YZ")
          throw py::value_error("plane: expected XY, ZX or YZ");
        pipeline::CircleTestJob job;
        job.radius_mm = radius_mm;
        job.feed_mm_min = feed_mm_min;
        job.plane = plane;
        job.centre_mm = Eigen::Vector3d(centre_mm[0], centre_mm[1], centre_mm[2]);
        job.elastic = elastic;
        if (!load.empty()) {
          if (!elastic) throw py::value_error("load needs elastic=True: the rigid machine takes no load");
          job.load = unwrap(load_model(load));
        }
        const RunDirectory directory(out_dir);
        job.out_directory = directory.path();
        const pipeline::CircleTestResult r =
            unwrap_released([&] { return pipeline::circle_test(machine, job); });
        py::dict out;
        out["summary"] = python_from_json(r.json);
        py::dict deviations;
        const py::object numpy = py::module_::import("numpy");
        for (const auto& [name, trace] :
             {std::pair{"ccw", &r.counter_clockwise}, std::pair{"cw", &r.clockwise}}) {
          py::dict one;
          one["angle_deg"] = numpy.attr("array")(trace->angle_deg);
          one["radial_deviation_mm"] = numpy.attr("array")(trace->deviation_mm);
          deviations[name] = one;
        }
        out["deviations"] = deviations;
        return out;
      },
      py::arg("machine"), py::kw_only(), py::arg("radius_mm") = 30.0, py::arg("feed_mm_min") = 3000.0,
      py::arg("plane") = "XY", py::arg("centre_mm") = std::array<double, 3>{0.0, 0.0, 0.0},
      py::arg("elastic") = false, py::arg("load") = "", py::arg("out_dir") = py::none(),
      R"doc(The circular test of ISO 230-4 through the drives' servo loops and their imperfections, as
`pkm circle`.

radius_mm, feed_mm_min: the circle; plane: 'XY', 'ZX' or 'YZ'; centre_mm: its centre in program coordinates;
elastic: the machine in the loop (`pkm circle --elastic`: the loops on the elastic machine), under `load` (the
CLI's --load text); out_dir: keep the plan, the servo run, circle.svg, circle.csv and circle_summary.json there (default: a
temporary directory).

Returns a dict: summary (circle_summary.json: circular_deviation_ccw_um, circular_deviation_cw_um,
hysteresis_um, ...) and deviations: for 'ccw' and 'cw' the measured turn's angle_deg and radial_deviation_mm
(about the common least-squares centre) as float64 arrays.)doc");
}

// pkm.simulate: the machine in the loop (pipeline/simulate_program.hpp).
void bind_simulate(py::module_& m) {
  m.def(
      "simulate",
      [](const Machine& machine, const py::object& plan_dir, const std::string& load, bool split,
         const py::object& out_dir) {
        pipeline::SimulateJob job;
        job.plan_directory = optional_path(plan_dir);
        if (!load.empty()) job.load = unwrap(load_model(load));
        job.split = split;
        const RunDirectory directory(out_dir);
        job.out_directory = directory.path();
        const pipeline::SimulateResult r =
            unwrap_released([&] { return pipeline::simulate_program(machine, job); });
        py::dict out;
        out["summary"] = python_from_json(r.json);
        out["ticks"] = csv_columns(directory.file("simulate.csv"));
        return out;
      },
      py::arg("machine"), py::arg("plan_dir"), py::kw_only(), py::arg("load") = "", py::arg("split") = true,
      py::arg("out_dir") = py::none(),
      R"doc(A planned run on the machine in simulation, as `pkm simulate PLAN_DIR`: the drives' servo loops
closed on the elastic machine under the process load, with the drives' imperfections.

plan_dir: the directory pkm.plan(..., out_dir=...) or `pkm plan --out` wrote; load: the CLI's --load text
(e.g. 'tangential=300,normal=100', or '@FILE'; '' for none); split: also the runs that split the contour error
into its servo, elastic, load and drives parts; out_dir: keep simulate.csv, simulate_summary.json and
simulate.svg there (default: a temporary directory).

Returns a dict: summary (simulate_summary.json as a dict) and ticks: the columns of simulate.csv by name
(time_s, line, x_program_mm ... commanded, x_actual_mm ... the tool's actual point, contour_error_mm,
servo_mm, elastic_mm, load_mm, drives_mm), float64 arrays.)doc");
}
}  // namespace

void bind_file_runs(py::module_& m) {
  m.def(
      "stiffness",
      [](const Machine& machine, const py::object& program_path, const std::string& load,
         std::optional<std::string> model, double step_mm, const py::object& compensate_path,
         const py::object& out_dir) {
        pipeline::StiffnessJob job;
        job.program_path = optional_path(program_path);
        job.load = unwrap(load_model(load));
        if (model) {
          job.model = stiffness::stiffness_model_from_string(*model);
          if (!job.model)
            throw py::value_error("model '" + *model + "': expected struts, struts_joints or frame");
        }
        if (!(step_mm > 0.0 && step_mm <= 1000.0))
          throw py::value_error("step_mm: expected a length in (0, 1000] mm");
        job.step_mm = step_mm;
        job.compensated_path = optional_path(compensate_path);
        const RunDirectory directory(out_dir);
        job.out_directory = directory.path();
        const pipeline::StiffnessProgramResult r =
            unwrap_released([&] { return pipeline::stiffness_program(machine, job); });
        py::dict out;
        out["summary"] = python_from_json(r.summary);
        out["points"] = csv_columns(directory.file("points.csv"));
        return out;
      },
      py::arg("machine"), py::arg("program_path"), py::arg("load"), py::kw_only(),
      py::arg("model") = py::none(), py::arg("step_mm") = 1.0, py::arg("compensate_path") = py::none(),
      py::arg("out_dir") = py::none(),
      R"doc(The tool's deflection under a cutting load along a part program, as `pkm stiffness`.

load: the CLI's --load text (e.g. 'tangential=200,normal=50', or '@FILE'); model: 'struts', 'struts_joints'
or 'frame' (default: the fullest the machine file describes); step_mm: points at most this far apart;
compensate_path: also write the pre-compensated program there; out_dir: keep the CLI's points.csv and
summary.json there (default: a temporary directory, removed).

Returns a dict: summary (the summary.json of `pkm stiffness`) and points: the columns of points.csv by name
(index, line, time_s, x_mm ... (base frame), a_abc_deg ... (G-code's A B C), fx_N ..., dx_mm, dy_mm, dz_mm, rx_rad ..., normal_mm, F1_N ...),
each a float64 array with one value per path point.)doc");

  m.def(
      "servo",
      [](const Machine& machine, const py::object& plan_dir, bool coupled, int inertia_stride,
         int bode_points, const py::object& out_dir) {
        if (inertia_stride < 1) throw py::value_error("inertia_stride must be at least 1");
        if (bode_points < 2) throw py::value_error("bode_points must be at least 2");
        pipeline::ServoJob job;
        job.plan_directory = optional_path(plan_dir);
        job.coupled = coupled;
        job.inertia_stride = inertia_stride;
        job.bode_points = bode_points;
        const RunDirectory directory(out_dir);
        job.out_directory = directory.path();
        const pipeline::ServoProgramResult r =
            unwrap_released([&] { return pipeline::servo_program(machine, job); });
        py::dict out;
        out["summary"] = python_from_json(r.json);
        out["ticks"] = csv_columns(directory.file("servo.csv"));
        return out;
      },
      py::arg("machine"), py::arg("plan_dir"), py::kw_only(), py::arg("coupled") = true,
      py::arg("inertia_stride") = 10, py::arg("bode_points") = 120, py::arg("out_dir") = py::none(),
      R"doc(A planned run through the drives' cascaded servo loops (the machine file's servo: section), as
`pkm servo PLAN_DIR`.

plan_dir: the directory pkm.plan(..., out_dir=...) or `pkm plan --out` wrote; coupled: the drives on the
coupled plant (False: each on its own inertia); inertia_stride: the plant's inertia every this many ticks;
out_dir: keep servo.csv, servo_bode.csv and servo_summary.json there (default: a temporary directory).

Returns a dict: summary (servo_summary.json as a dict) and ticks: the columns of servo.csv by name (time_s,
line, e1_mm ... following errors, f1_N ... forces, u1 ... commands, contour_error_mm, lag_ms, ...).)doc");
  bind_circle(m);
  bind_simulate(m);
}

}  // namespace pkm::python
