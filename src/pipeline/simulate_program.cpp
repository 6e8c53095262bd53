#include "pipeline/simulate_program.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "io/atomic_file.hpp"
#include "io/buffered_file.hpp"
#include "io/json_text.hpp"
#include "io/output_manifest.hpp"
#include "io/output_set.hpp"
#include "io/version.hpp"
#include "pipeline/servo_program.hpp"
#include "pipeline/simulate_plot.hpp"
#include "report/report_data.hpp"
#include "report/report_html.hpp"
#include "servo/machine_run.hpp"

namespace pkm::pipeline {

namespace {

constexpr std::size_t kSimulateWorstLines = 10;

// The runs that split the error: each switches one more cause on (servo_program.hpp's order).
constexpr std::array<servo::MachineRunSetup, 4> kSimulateRuns{{
    {false, false, false},  // the loops on the rigid machine, ideal drives, no load
    {true, false, false},   // the elastic machine
    {true, true, false},    // with the process load
    {true, true, true},     // with the drives' imperfections: the machine as the files give it
}};

// The process load at every tick: the load model at the commanded pose, its direction of travel from the
// ticks' central differences (as pkm stiffness takes it), the tool axis the platform's z at home.
std::vector<statics::Wrench> simulate_loads(const Machine& machine, const servo::ServoRunInput& input,
                                            const statics::LoadModel& load) {
  std::vector<statics::Wrench> out(input.time_s.size());
  if (load.empty()) return out;
  const Eigen::Vector3d axis = machine.mechanism->home().rotation.transpose() * Eigen::Vector3d::UnitZ();
  const std::size_t ticks = input.time_s.size();
  for (std::size_t k = 0; k < ticks; ++k) {
    const std::size_t before = k > 0 ? k - 1 : k, after = k + 1 < ticks ? k + 1 : k;
    const double span_s = input.time_s[after] - input.time_s[before];
    const Eigen::Vector3d velocity =
        span_s > 0.0
            ? Eigen::Vector3d((input.pose[after].position_mm - input.pose[before].position_mm) / span_s)
            : Eigen::Vector3d::Zero();
    out[k] = load.wrench_at(statics::travel_load_point(input.pose[k], velocity, axis, input.line[k], true));
  }
  return out;
}

// A part's statistics over the ticks from its error vectors.
struct PartAccumulator {
  double squares = 0.0;
  long count = 0;
  void add(ContourPart& part, const Eigen::Vector3d& error, int line, double time_s) {
    const double e = error.norm();
    if (!std::isfinite(e)) return;
    squares += e * e;
    ++count;
    if (e > part.max_mm) {
      part.max_mm = e;
      part.max_line = line;
      part.max_time_s = time_s;
    }
  }
  void finish(ContourPart& part) const { part.rms_mm = count > 0 ? std::sqrt(squares / count) : 0.0; }
};

nlohmann::json part_json(const ContourPart& p) {
  return {{"max_mm", p.max_mm}, {"rms_mm", p.rms_mm}, {"max_line", p.max_line}, {"max_time_s", p.max_time_s}};
}

nlohmann::json simulate_json(const Machine& machine, const SimulateJob& job, const SimulateResult& r) {
  nlohmann::json parts = nlohmann::json::object();
  for (const ContourPart& p : r.parts) parts[p.name] = part_json(p);
  nlohmann::json worst = nlohmann::json::array();
  for (const auto& [line, error] : r.worst_lines)
    worst.push_back({{"line", line}, {"contour_error_mm", error}});
  return {{"kind", "simulate"},
          {"pkm_version", std::string(pkm_version())},
          {"machine", machine.source},
          {"plan", job.plan_directory},
          {"ticks", r.ticks},
          {"simulated_s", r.simulated_s},
          {"load", !job.load.empty()},
          {"split", job.split},
          {"contour_error", part_json(r.total)},
          {"parts", job.split ? parts : nlohmann::json(nullptr)},
          {"worst_lines", worst},
          {"files", {{"ticks", "simulate.csv"}, {"plot", "simulate.svg"}}}};
}

// The contour error vectors (and, of the full run, the actual tool points) of one run, tick by tick.
struct RunTrace {
  std::vector<Eigen::Vector3d> contour_mm;
  std::vector<Eigen::Vector3d> actual_mm;
};

Status run_traces(const servo::MachineRunInputs& inputs, const SimulateJob& job,
                  std::array<RunTrace, 4>& traces) {
  const std::size_t ticks = inputs.input->time_s.size();
  const double run_s = inputs.input->time_s.back();
  std::array<Status, 4> statuses{ok_status(), ok_status(), ok_status(), ok_status()};
  const int first = job.split ? 0 : 3;
  tbb::parallel_for(first, 4, [&](int run) {
    RunTrace& trace = traces[run];
    trace.contour_mm.resize(ticks);
    if (run == 3) trace.actual_mm.resize(ticks);
    statuses[run] = servo::run_machine(inputs, kSimulateRuns[run], [&](const servo::MachineRunTick& t) {
      trace.contour_mm[t.index] = t.contour_mm;
      if (run != 3) return ok_status();
      trace.actual_mm[t.index] = t.actual_mm;
      if (t.index % 1024 == 0 && run_s > 0.0)
        report_progress(job.progress, "simulating the machine", t.time_s / run_s, t.line);
      return job.listener ? job.listener(t) : ok_status();
    });
  });
  for (const Status& s : statuses)
    if (!s) return s;
  return ok_status();
}

// simulate.csv's rows, and the statistics into `result`.
std::string simulate_csv(const Machine& machine, const servo::ServoRunInput& input,
                         const std::array<RunTrace, 4>& traces, bool split, SimulateResult& result) {
  fmt::memory_buffer b;
  fmt::format_to(std::back_inserter(b),
                 "time_s,line,x_program_mm,y_program_mm,z_program_mm,x_actual_mm,y_actual_mm,z_actual_mm,"
                 "contour_error_mm,servo_mm,elastic_mm,load_mm,drives_mm\n");
  std::array<PartAccumulator, 5> accumulators{};
  std::map<int, double> worst_by_line;
  const Eigen::Vector3d origin = machine.motion.program_origin_mm;
  for (std::size_t k = 0; k < input.time_s.size(); ++k) {
    const Eigen::Vector3d& total = traces[3].contour_mm[k];
    const Eigen::Vector3d commanded = input.pose[k].position_mm - origin;
    const Eigen::Vector3d actual = traces[3].actual_mm[k] - origin;
    accumulators[4].add(result.total, total, input.line[k], input.time_s[k]);
    if (std::isfinite(total.norm())) {
      double& worst = worst_by_line[input.line[k]];
      worst = std::max(worst, total.norm());
    }
    fmt::format_to(std::back_inserter(b), "{:.6f},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.4e}",
                   input.time_s[k], input.line[k], commanded.x(), commanded.y(), commanded.z(), actual.x(),
                   actual.y(), actual.z(), total.norm());
    if (split) {
      const std::array<Eigen::Vector3d, 4> parts{
          traces[0].contour_mm[k], traces[1].contour_mm[k] - traces[0].contour_mm[k],
          traces[2].contour_mm[k] - traces[1].contour_mm[k], total - traces[2].contour_mm[k]};
      for (std::size_t p = 0; p < 4; ++p) {
        accumulators[p].add(result.parts[p], parts[p], input.line[k], input.time_s[k]);
        fmt::format_to(std::back_inserter(b), ",{:.4e}", parts[p].norm());
      }
    } else {
      fmt::format_to(std::back_inserter(b), ",,,,");
    }
    b.push_back('\n');
  }
  for (std::size_t p = 0; p < 4; ++p) accumulators[p].finish(result.parts[p]);
  accumulators[4].finish(result.total);
  std::vector<std::pair<int, double>> lines(worst_by_line.begin(), worst_by_line.end());
  std::sort(lines.begin(), lines.end(), [](const auto& a, const auto& c) { return a.second > c.second; });
  if (lines.size() > kSimulateWorstLines) lines.resize(kSimulateWorstLines);
  result.worst_lines = std::move(lines);
  return fmt::to_string(b);
}

// --report: the plan's report with the simulation's charts, one more member of the output set, the
// simulation's files read back from the staging folder as `pkm report` reads them.
Status stage_simulate_report(OutputSet& outputs, const Machine& machine, const SimulateJob& job) {
  report_progress(job.progress, "writing the report");
  auto staged = outputs.stage_file(job.report_path);
  if (!staged) return staged.error();
  report::ReportOptions options;
  options.machine_file = machine.source;
  options.simulate_directory = outputs.staging_directory();
  auto data = report::report_from_directory(job.plan_directory, options);
  if (!data) return data.error();
  return report::write_report_html(*staged, *data);
}

Status write_simulate_outputs(const Machine& machine, const SimulateJob& job, const std::string& csv,
                              const std::string& svg, const SimulateResult& result) {
  OutputSet outputs{"simulate"};
  if (job.out_directory.empty() || same_folder(job.out_directory, job.plan_directory)) {
    if (Status joined = outputs.join_directory(job.plan_directory, {"plan"}); !joined) return joined;
  } else if (Status used = outputs.use_directory(job.out_directory); !used) {
    return used;
  }
  for (const auto& [name, text] :
       {std::pair<const char*, const std::string*>{"simulate.csv", &csv}, {"simulate.svg", &svg}}) {
    if (Status written = write_file_atomically(outputs.staged_path(name), *text); !written) return written;
  }
  if (Status written =
          write_file_atomically(outputs.staged_path("simulate_summary.json"), json_text(result.json) + "\n");
      !written)
    return written;
  if (!job.report_path.empty()) {
    if (Status written = stage_simulate_report(outputs, machine, job); !written) return written;
  }
  return outputs.commit();
}

}  // namespace

Result<SimulateResult> simulate_program(const Machine& machine, const SimulateJob& job) {
  auto prepared =
      prepare_planned_servo_run(machine, job.plan_directory, job.inertia_stride, true, job.progress);
  if (!prepared) return prepared.error();
  const servo::ServoRunInput* input = &prepared->input;
  const int* steps = &prepared->steps_per_period;
  const servo::ServoPlant* plant = &prepared->plant;
  const servo::LoopDesign* design = &prepared->design;
  const std::vector<statics::Wrench> loads = simulate_loads(machine, *input, job.load);
  const servo::CommandedPath path = servo::commanded_path(*input, machine.mechanism->controlled_axes());
  servo::MachineRunInputs inputs{
      &machine, &*design,   &*plant, &*input, &loads, &path, servo::search_window(*design, *input),
      *steps,   job.coupled};
  std::array<RunTrace, 4> traces;
  if (Status ran = run_traces(inputs, job, traces); !ran) return ran.error();

  SimulateResult result;
  result.ticks = static_cast<long>(input->time_s.size());
  result.simulated_s = input->time_s.back() - input->time_s.front();
  report_progress(job.progress, "writing simulate.csv");
  const std::string csv = simulate_csv(machine, *input, traces, job.split, result);
  result.json = simulate_json(machine, job, result);
  const std::string svg = simulate_plot_svg(*input, traces[3].contour_mm, result);
  if (Status written = write_simulate_outputs(machine, job, csv, svg, result); !written)
    return written.error();
  return result;
}

}  // namespace pkm::pipeline
