#include "pipeline/stiffness_program.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iterator>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "formats/stiffness_csv.hpp"
#include "io/buffered_file.hpp"
#include "io/json_text.hpp"
#include "io/output_set.hpp"
#include "io/version.hpp"
#include "pipeline/load_program.hpp"
#include "pipeline/run_report.hpp"
#include "program/cl_writer.hpp"
#include "program/gcode_writer.hpp"
#include "program/part_program.hpp"
#include "redundancy/program_points.hpp"
#include "report/stiffness_plots.hpp"
#include "stiffness/compliance_bode.hpp"
#include "stiffness/nc_compensation.hpp"
#include "stiffness/program_deflection.hpp"

namespace pkm::pipeline {
namespace {

bool is_cl_path(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".cl" || extension == ".cls" || extension == ".apt";
}

bool states_tool_axes(const program::CanonicalProgram& program) {
  for (const program::CanonicalMove& move : program.moves) {
    if (move.orientation == program::OrientationSource::tool_axis) return true;
  }
  return false;
}

std::string points_header(int struts, bool compensate) {
  std::string header =
      "index,line,cutting,time_s,s_mm,x_mm,y_mm,z_mm,a_abc_deg,b_abc_deg,c_abc_deg,axis_i,axis_j,axis_k,fx_N,"
      "fy_N,fz_N,"
      "mx_Nmm,my_Nmm,mz_Nmm,dx_mm,dy_"
      "mm,"
      "dz_mm,rx_rad,ry_rad,rz_rad,normal_mm,deflected_x_mm,deflected_y_mm,deflected_z_mm";
  for (int j = 1; j <= struts; ++j) header += fmt::format(",F{}_N", j);
  if (compensate) header += ",command_x_mm,command_y_mm,command_z_mm,correction_mm,residual_mm,residual_rad";
  return header + "\n";
}

// The first guess of the commanded pose for the strut-only model of a machine driven by its struts' lengths:
// L_cmd = IK(x_nom) − T/c, x_cmd = FK(L_cmd) (nc_compensation.hpp). Empty where it does not apply.
std::optional<Pose> closed_form_command(const Mechanism& mechanism,
                                        const stiffness::ToolCompliance& compliance,
                                        const stiffness::ToolDeflection& deflection) {
  auto lengths = mechanism.inverse(compliance.pose);
  if (!lengths) return std::nullopt;
  const ActuatorVector commanded =
      *lengths - deflection.strut_force_N.cwiseQuotient(compliance.strut_stiffness_N_mm);
  auto solved = mechanism.forward(commanded, compliance.pose);
  if (!solved) return std::nullopt;
  return solved->pose;
}

// points.csv's row of one point, without the compensation's columns and the newline.
void append_point_row(fmt::memory_buffer& buffer, const stiffness::PointDeflection& p, double time_s,
                      double path_mm) {
  const stiffness::ToolCompliance& c = *p.compliance;
  const stiffness::ToolDeflection& d = p.deflection;
  const Eigen::Vector3d& x = c.pose.position_mm;
  const Eigen::Vector3d deflected = x + d.displacement_mm;
  const Eigen::Vector3d abc_deg =
      deg_from_rad(1.0) * angles_from_rotation(AngleConvention::abc, c.pose.rotation);
  auto out = std::back_inserter(buffer);
  fmt::format_to(out, "{},{},{},{:.6f},{:.6f},{:.9f},{:.9f},{:.9f},{:.6f},{:.6f},{:.6f},", p.index, p.line,
                 p.cutting ? 1 : 0, time_s, path_mm, x.x(), x.y(), x.z(), abc_deg.x(), abc_deg.y(),
                 abc_deg.z());
  fmt::format_to(out, "{:.9f},{:.9f},{:.9f},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},", p.tool_axis.x(),
                 p.tool_axis.y(), p.tool_axis.z(), p.load.force_N.x(), p.load.force_N.y(), p.load.force_N.z(),
                 p.load.moment_Nmm.x(), p.load.moment_Nmm.y(), p.load.moment_Nmm.z());
  fmt::format_to(out, "{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9f},{:.9f},{:.9f}",
                 d.displacement_mm.x(), d.displacement_mm.y(), d.displacement_mm.z(), d.rotation_rad.x(),
                 d.rotation_rad.y(), d.rotation_rad.z(), d.normal_mm, deflected.x(), deflected.y(),
                 deflected.z());
  for (int j = 0; j < d.strut_force_N.size(); ++j) fmt::format_to(out, ",{:.6g}", d.strut_force_N[j]);
}

// The NC pre-compensation point by point: the commanded pose whose deflected tool lands on the nominal one,
// its columns of points.csv, and the largest residual and correction.
struct PointCompensation {
  const stiffness::ComplianceModel& model;
  const Mechanism& mechanism;
  bool closed_form = false;
  const std::string& source;
  CompensationSummary summary;
  std::vector<Pose> commands;

  Status add(const stiffness::PointDeflection& p, fmt::memory_buffer& buffer) {
    const stiffness::ToolCompliance& c = *p.compliance;
    stiffness::Vector6 wrench;
    wrench << p.load.force_N, p.load.moment_Nmm;
    const stiffness::DeflectionAt deflection_at = [&](const Pose& command) -> Result<stiffness::Vector6> {
      auto at = model.at(command);
      if (!at) return at.error();
      return stiffness::Vector6(at->compliance * wrench);
    };
    const std::optional<Pose> start =
        closed_form ? closed_form_command(mechanism, c, p.deflection) : std::nullopt;
    auto command = stiffness::compensate_pose(c.pose, deflection_at, {}, start ? &*start : nullptr);
    if (!command) {
      return Error{command.error().code,
                   fmt::format("{}:{}: NC pre-compensation: {}", source, p.line, command.error().message),
                   ErrorLocation{source, p.line, 0, ""}};
    }
    const Eigen::Vector3d& xc = command->command.position_mm;
    const double correction = (xc - c.pose.position_mm).norm();
    fmt::format_to(std::back_inserter(buffer), ",{:.6f},{:.6f},{:.6f},{:.9g},{:.3g},{:.3g}", xc.x(), xc.y(),
                   xc.z(), correction, command->residual_mm, command->residual_rad);
    summary.max_residual_mm = std::max(summary.max_residual_mm, command->residual_mm);
    summary.max_residual_rad = std::max(summary.max_residual_rad, command->residual_rad);
    summary.max_iterations = std::max(summary.max_iterations, command->iterations);
    if (correction > summary.max_correction_mm) {
      summary.max_correction_mm = correction;
      summary.max_correction_line = p.line;
    }
    commands.push_back(command->command);
    return ok_status();
  }
};

// compliance.csv's row: the 6 × 6 compliance at the point.
void append_compliance_row(fmt::memory_buffer& buffer, const stiffness::PointDeflection& p) {
  auto row = std::back_inserter(buffer);
  fmt::format_to(row, "{},{}", p.index, p.line);
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) fmt::format_to(row, ",{:.9g}", p.compliance->compliance(r, k));
  buffer.push_back('\n');
}

// The program through the commanded poses, as CL data when the output is CL data or the program states tool
// axes, else as G-code with A B C.
Result<std::string> compensated_program_text(const program::CanonicalProgram& program,
                                             const redundancy::ProgramPoints& points,
                                             const std::vector<Pose>& commands, const std::string& path,
                                             const std::string& note) {
  const bool as_cl = is_cl_path(path) || states_tool_axes(program);
  const program::CanonicalProgram corrected =
      redundancy::program_through_poses(program, points, commands, as_cl, true);
  if (as_cl) {
    program::ClWriteOptions write;
    write.header_comments = {note};
    write.decimals_mm = 6;
    return program::write_cl_data(corrected, write);
  }
  program::GcodeWriteOptions write;
  write.header_comments = {note};
  write.decimals_mm = 6;
  write.decimals_deg = 6;
  return program::write_gcode(corrected, write);
}

// The dynamic compliance where the error along the tool axis is largest (the report's Bode plot): its CSV
// staged, and its summary block.
Result<nlohmann::json> stage_frequency_response(const Machine& machine,
                                                const redundancy::ProgramPoints& points,
                                                long max_normal_index, OutputSet& outputs) {
  const std::size_t at = static_cast<std::size_t>(std::max(0L, max_normal_index));
  const redundancy::PathPoint& point = points.points[at];
  auto bode = stiffness::machine_bode(machine, Pose{point.position_mm, point.rotation}, {});
  if (!bode) return bode.error();
  if (Status written = formats::write_bode_csv(outputs.staged_path(report::kBodeCsv), *bode); !written)
    return written.error();
  return nlohmann::json{{"file", report::kBodeCsv},
                        {"index", at},
                        {"line", point.line},
                        {"natural_frequency_Hz", std::vector<double>(bode->natural_frequency_Hz.data(),
                                                                     bode->natural_frequency_Hz.data() +
                                                                         bode->natural_frequency_Hz.size())}};
}

nlohmann::json stiffness_summary_json(const Machine& machine, const StiffnessJob& job,
                                      const StiffnessProgramResult& result, double time_s, double path_mm,
                                      bool closed_form) {
  const stiffness::DeflectionStatistics& s = result.statistics;
  nlohmann::json summary = {{"program", job.program_path},
                            {"pkm_version", std::string(pkm_version())},
                            {"machine", machine.source},
                            {"model", std::string(stiffness::to_string(result.model))},
                            {"step_mm", job.step_mm},
                            {"duration_at_feed_s", time_s},
                            {"path_length_mm", path_mm},
                            {"points", s.points},
                            {"cutting_points", s.cutting_points},
                            {"max_normal_deflection_mm", s.max_normal_mm},
                            {"max_normal_deflection_line", s.max_normal_line},
                            {"max_normal_deflection_index", s.max_normal_index},
                            {"rms_normal_deflection_mm", s.rms_normal_mm},
                            {"max_deflection_mm", s.max_deflection_mm},
                            {"max_deflection_line", s.max_deflection_line},
                            {"max_strut_force_N", s.max_strut_force_N},
                            {"max_strut_force_strut", s.max_strut_force_strut},
                            {"max_strut_force_line", s.max_strut_force_line}};
  if (result.compensation) {
    const CompensationSummary& k = *result.compensation;
    summary["compensation"] = {{"program", job.compensated_path},
                               {"method", closed_form ? "closed form L = IK(x) - T/c, then fixed point"
                                                      : "fixed point x_cmd = x_nom - delta(x_cmd)"},
                               {"max_residual_mm", k.max_residual_mm},
                               {"max_residual_rad", k.max_residual_rad},
                               {"max_iterations", k.max_iterations},
                               {"max_correction_mm", k.max_correction_mm},
                               {"max_correction_line", k.max_correction_line}};
  }
  return summary;
}

}  // namespace

Result<StiffnessProgramResult> stiffness_program(const Machine& machine, const StiffnessJob& job) {
  report_progress(job.progress, "reading the program");
  auto program = load_program_for(machine, job.program_path, job.program_options);
  if (!program) return program.error();
  auto points = redundancy::sample_program(*program, machine, job.step_mm);
  if (!points) return points.error();
  auto model = stiffness::ComplianceModel::make(machine, job.model);
  if (!model) return model.error();
  const Mechanism& mechanism = *machine.mechanism;
  const bool compensate = !job.compensated_path.empty();
  const bool closed_form = model->model() == StiffnessModel::struts && mechanism.has_distance_actuators();

  OutputSet outputs{"stiffness"};
  if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
  BufferedStagedFile points_csv, compliance_csv;
  if (Status opened = points_csv.open(outputs.staged_path("points.csv")); !opened) return opened.error();
  const int struts = model->parameters().strut_count;
  fmt::format_to(std::back_inserter(points_csv.buffer), "{}", points_header(struts, compensate));
  if (job.compliance_matrices) {
    if (Status opened = compliance_csv.open(outputs.staged_path("compliance.csv")); !opened)
      return opened.error();
    std::string header = "index,line";
    for (int r = 1; r <= 6; ++r)
      for (int c = 1; c <= 6; ++c) header += fmt::format(",c{}{}", r, c);
    fmt::format_to(std::back_inserter(compliance_csv.buffer), "{}\n", header);
  }

  StiffnessProgramResult result;
  result.model = model->model();
  PointCompensation compensation{*model, mechanism, closed_form, program->source, {}, {}};
  if (compensate) compensation.commands.reserve(points->points.size());
  // The time at the programmed feeds (rapids at the machine's rapid speed; no acceleration: the analysis is
  // quasi-static) and the path length, for the report's charts.
  double time_s = 0.0, path_mm = 0.0;
  const double rapid_mm_s = machine.motion.rapid_mm_min / 60.0;
  const auto on_point = [&](const stiffness::PointDeflection& p) -> Status {
    const redundancy::PathPoint& point = points->points[static_cast<std::size_t>(p.index)];
    if (p.index % 1024 == 0)
      report_progress(job.progress, "deflection along the path",
                      static_cast<double>(p.index) / static_cast<double>(points->points.size()), point.line);
    const double speed = point.cutting && point.feed_mm_s > 0.0 ? point.feed_mm_s : rapid_mm_s;
    path_mm += point.step_mm;
    if (speed > 0.0) time_s += point.step_mm / speed;
    append_point_row(points_csv.buffer, p, time_s, path_mm);
    if (compensate) {
      if (Status added = compensation.add(p, points_csv.buffer); !added) return added;
    }
    points_csv.buffer.push_back('\n');
    if (job.compliance_matrices) {
      append_compliance_row(compliance_csv.buffer, p);
      if (Status flushed = compliance_csv.flush_if_large(); !flushed) return flushed;
    }
    return points_csv.flush_if_large();
  };
  auto statistics = stiffness::deflect_program(*points, program->source, *model, job.load, on_point);
  if (!statistics) return statistics.error();
  result.statistics = *statistics;

  if (compensate) {
    const std::string note = fmt::format(
        "pkm stiffness: {} pre-compensated for the deflection on {} ({} model); residual {:.3g} mm",
        job.program_path, machine.name, stiffness::to_string(result.model),
        compensation.summary.max_residual_mm);
    auto text =
        compensated_program_text(*program, *points, compensation.commands, job.compensated_path, note);
    if (!text) return text.error();
    auto staged = outputs.stage_file(job.compensated_path);
    if (!staged) return staged.error();
    if (Status written = write_file_atomically(*staged, *text); !written) return written.error();
    result.compensation = compensation.summary;
  }

  nlohmann::json summary = stiffness_summary_json(machine, job, result, time_s, path_mm, closed_form);
  if (job.frequency_response) {
    auto frequency_response =
        stage_frequency_response(machine, *points, result.statistics.max_normal_index, outputs);
    if (!frequency_response) return frequency_response.error();
    summary["frequency_response"] = std::move(*frequency_response);
  }
  if (Status written = write_file_atomically(outputs.staged_path("summary.json"), json_text(summary) + "\n");
      !written)
    return written.error();
  if (Status committed = points_csv.commit(); !committed) return committed.error();
  if (job.compliance_matrices) {
    if (Status committed = compliance_csv.commit(); !committed) return committed.error();
  }
  if (!job.report_path.empty()) report_progress(job.progress, "writing the report");
  if (Status written = stage_run_report(outputs, job.report_path); !written) return written.error();
  if (Status committed = outputs.commit(); !committed) return committed.error();
  result.summary = std::move(summary);
  return result;
}

}  // namespace pkm::pipeline
