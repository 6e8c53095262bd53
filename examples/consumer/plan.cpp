// A part program planned by an outside project, linked against the installed pkm::motion (which brings
// pkm::io and pkm::kinematics): a machine file read with the shared reader, a few G-code lines interpreted
// from the machine's start pose, the motion planned within the machine's limits. Usage: pkm_plan_consumer
// MACHINE.yaml Exits non-zero when any step fails or the plan has no motion.
#include <cstdio>
#include <string>

#include "io/machine_file.hpp"
#include "planning/motion_plan.hpp"
#include "program/part_program.hpp"

int main(int argc, char** argv) {
  using namespace pkm;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s MACHINE.yaml\n", argv[0]);
    return 2;
  }
  const auto machine = load_machine_file(argv[1]);
  if (!machine.ok()) {
    std::fprintf(stderr, "%s\n", machine.error().message.c_str());
    return 1;
  }
  const planning::ProgramStart start = planning::program_start(*machine);
  program::InterpretOptions interpret;
  interpret.start_mm = start.start_mm;
  interpret.start_abc_deg = start.start_abc_deg;
  const std::string text = "G21 G90 G17\nG1 X10 F1200\nG1 Y10\nG2 X20 Y0 I0 J-10\nM2\n";
  const auto program = program::interpret_gcode(text, "square.ngc", interpret);
  if (!program.ok()) {
    std::fprintf(stderr, "%s\n", program.error().message.c_str());
    return 1;
  }
  const auto plan = planning::plan_motion(*machine, *program, planning::PlanOptions{});
  if (!plan.ok()) {
    std::fprintf(stderr, "%s\n", plan.error().message.c_str());
    return 1;
  }
  std::printf("%zu moves planned on %s: %.3f s of motion\n", program->moves.size(), argv[1],
              plan->duration_s);
  if (!(plan->duration_s > 0.0)) return 1;
  std::printf("ok\n");
  return 0;
}
