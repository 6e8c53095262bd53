#include "pipeline/optimize_job.hpp"

#include <fmt/format.h>

#include "formats/optimize_summary.hpp"
#include "io/atomic_file.hpp"
#include "io/output_set.hpp"
#include "program/gcode_writer.hpp"
#include "report/optimize_report.hpp"
#include "report/report_html.hpp"
#include "statics/load_model.hpp"

namespace pkm::pipeline {

namespace {

/// The rewritten program as G-code, its header saying how it was made.
Result<std::string> rewritten_gcode(const Machine& machine, const OptimizeJob& job,
                                    const OptimizeJobResult& r) {
  const redundancy::OptimizeOptions& o = job.options;
  program::GcodeWriteOptions write;
  write.header_comments = {
      fmt::format("pkm optimize: {} law ({} solver), free {} on {}", redundancy::to_string(o.law.law),
                  o.solver == redundancy::Solver::global ? "global" : "greedy", redundancy::to_string(o.free),
                  machine.name),
      fmt::format("from {}; sum of max strut increments {:.3f} mm (held constant: {:.3f} mm)",
                  job.program_path, r.summary["opt_sum_mm"].get<double>(),
                  r.summary["const_sum_mm"].get<double>())};
  return program::write_gcode(r.result.program, write);
}

/// The program and the report replace the previous ones together or not at all.
Status write_optimized(const Machine& machine, const OptimizeJob& job, const OptimizeJobResult& r) {
  auto text = rewritten_gcode(machine, job, r);
  if (!text) return text.error();
  OutputSet outputs{"optimize"};
  auto staged_program = outputs.stage_file(job.out_path);
  if (!staged_program) return staged_program.error();
  if (Status written = write_file_atomically(*staged_program, *text); !written) return written;
  if (!job.report_path.empty()) {
    report_progress(job.progress, "writing the report");
    auto staged_report = outputs.stage_file(job.report_path);
    if (!staged_report) return staged_report.error();
    auto data = report::optimize_report(machine, r.program, r.result, job.options, r.summary, job.out_path);
    if (!data) return data.error();
    if (Status written = report::write_report_html(*staged_report, *data); !written) return written;
  }
  return outputs.commit();
}

}  // namespace

Result<OptimizeJobResult> run_optimize_job(const Machine& machine, const OptimizeJob& job) {
  if (Status lines = statics::check_load_lines(job.options.loads, job.program_path); !lines)
    return make_error(lines.error().code, "--load: " + lines.error().message);
  report_progress(job.progress, "reading the program");
  auto program = load_program_for(machine, job.program_path, job.program_options);
  if (!program) return program.error();
  report_progress(job.progress, "choosing the free coordinates");
  auto result = redundancy::optimize_program(*program, machine, job.options);
  if (!result) return result.error();
  OptimizeJobResult r{std::move(*program), std::move(*result), {}};
  r.summary = formats::optimize_summary_json(r.result, job.options);
  r.summary["machine"] = machine.source;
  if (!job.out_path.empty()) {
    r.summary["out"] = job.out_path;
    if (Status written = write_optimized(machine, job, r); !written) return written.error();
  }
  return r;
}

}  // namespace pkm::pipeline
