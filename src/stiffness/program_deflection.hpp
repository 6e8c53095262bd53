#pragma once
// The tool's deflection at every point of a part program (the outputs per path point; Rusanov et al.'s
// Tools Response: the deflection of the tool at each CL point under the cutting force): quasi-static, so the
// program's geometry is enough, no feed planning. The points are redundancy::sample_program's (each move cut
// into parts no longer than a step, so a CL file's GOTOs are its points), the pose the program's own (its
// spin included), the load the LoadModel's with the direction of travel into the point and the tool axis
// turned with the platform.
#include <functional>

#include "redundancy/program_points.hpp"
#include "statics/load_model.hpp"
#include "stiffness/compliance_model.hpp"
#include "stiffness/tool_deflection.hpp"

namespace pkm::stiffness {

struct PointDeflection {
  long index = 0;  ///< into ProgramPoints::points
  int line = 0;
  bool cutting = false;
  const ToolCompliance* compliance = nullptr;  ///< at the (completed) nominal pose; valid in the callback
  Eigen::Vector3d tool_axis = Eigen::Vector3d::UnitZ();  ///< unit, base frame
  statics::Wrench load;
  ToolDeflection deflection;
};

/// The load case at a program point (statics/load_model.hpp): the direction of travel into the point (out of
/// it at the start), the tool axis of `rotation`.
statics::LoadPoint program_load_point(const redundancy::ProgramPoints& points, std::size_t index,
                                      const Eigen::Matrix3d& rotation);

/// Calls `on_point` for every point in order and returns the statistics. Fails at the first point out of
/// reach or of unbounded compliance, naming the program's source and line.
Result<DeflectionStatistics> deflect_program(const redundancy::ProgramPoints& points,
                                             const std::string& source, const ComplianceModel& model,
                                             const statics::LoadModel& load,
                                             const std::function<Status(const PointDeflection&)>& on_point);

}  // namespace pkm::stiffness
