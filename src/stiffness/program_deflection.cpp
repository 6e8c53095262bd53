#include "stiffness/program_deflection.hpp"

#include <fmt/format.h>

namespace pkm::stiffness {

statics::LoadPoint program_load_point(const redundancy::ProgramPoints& points, std::size_t index,
                                      const Eigen::Matrix3d& rotation) {
  const redundancy::PathPoint& point = points.points[index];
  statics::LoadPoint out;
  out.tangent = point.tangent;
  // The start has no travel into it: the first step's direction out of it.
  if (out.tangent.isZero(0.0) && index + 1 < points.points.size())
    out.tangent = points.points[index + 1].tangent;
  const Eigen::Vector3d tool_axis_platform =
      points.frame.reference_rotation.conjugate() * Eigen::Vector3d::UnitZ();
  out.tool_axis = rotation * tool_axis_platform;
  out.line = point.line;
  out.cutting = point.cutting;
  return out;
}

Result<DeflectionStatistics> deflect_program(const redundancy::ProgramPoints& points,
                                             const std::string& source, const ComplianceModel& model,
                                             const statics::LoadModel& load,
                                             const std::function<Status(const PointDeflection&)>& on_point) {
  DeflectionStatistics statistics;
  for (std::size_t k = 0; k < points.points.size(); ++k) {
    const redundancy::PathPoint& point = points.points[k];
    auto compliance = model.at(Pose{point.position_mm, point.rotation});
    if (!compliance) {
      return Error{compliance.error().code,
                   fmt::format("{}:{}: {}", source, point.line, compliance.error().message),
                   ErrorLocation{source, point.line, 0, ""}};
    }
    const statics::LoadPoint load_point = program_load_point(points, k, compliance->pose.rotation);
    PointDeflection out;
    out.index = static_cast<long>(k);
    out.line = point.line;
    out.cutting = point.cutting;
    out.compliance = &*compliance;
    out.tool_axis = load_point.tool_axis;
    out.load = load.wrench_at(load_point);
    out.deflection = deflect(*compliance, out.load, out.tool_axis);
    // An overflow must not reach the summary as "inf µm": say where the answer stopped being a number.
    if (!out.deflection.displacement_mm.allFinite() || !out.deflection.rotation_rad.allFinite()) {
      return Error{ErrorCode::bad_input,
                   fmt::format("{}:{}: the tool's deflection under the load is not a finite number (a load "
                               "too large for the machine's compliance)",
                               source, point.line),
                   ErrorLocation{source, point.line, 0, ""}};
    }
    statistics.add(out.index, out.line, out.cutting, out.deflection);
    if (on_point) {
      if (Status written = on_point(out); !written) return written.error();
    }
  }
  statistics.finish();
  return statistics;
}

}  // namespace pkm::stiffness
