#include "core/rotation.hpp"
#include "core/units.hpp"
#include "planning/motion_plan.hpp"
#include "planning/plan_producer.hpp"

namespace pkm::planning {

ProgramStart program_start(const Machine& machine) {
  const Pose& home = machine.mechanism->home();
  ProgramStart start;
  start.start_mm = home.position_mm - machine.motion.program_origin_mm;
  start.start_abc_deg = angles_from_rotation(AngleConvention::abc, home.rotation) * (180.0 / kPi);
  if (machine.mechanism->is_planar()) start.start_abc_deg.head<2>().setZero();
  return start;
}

path::PathFrame program_frame(const Machine& machine) {
  path::PathFrame frame;
  frame.program_origin_mm = machine.motion.program_origin_mm;
  frame.reference_rotation = Eigen::Quaterniond(machine.mechanism->home().rotation);
  frame.planar = machine.mechanism->is_planar();
  return frame;
}

Result<MotionPlan> plan_motion(const Machine& machine, const program::CanonicalProgram& program,
                               const PlanOptions& options) {
  MotionPlan plan;
  {
    auto producer = PlanProducer::start(machine, program, options, plan);
    if (!producer) return producer.error();
    if (Status planned = (*producer)->run_to_end(true); !planned) return planned.error();
  }
  return plan;
}

}  // namespace pkm::planning
