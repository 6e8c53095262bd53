// A program may move only what its machine controls: the tripod's X, Y and C, the tricept's orientation and
// a planar machine's Z follow from the rest or stay put, and a program that moves them is refused at its line
// with the coordinate named; restating them unchanged, and everything on a six-axis machine, plans.
#include "planning/commanded_coordinates.hpp"

#include <gtest/gtest.h>

#include <string>

#include "plan_test_support.hpp"
#include "program/part_program.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

Status commanded(const Machine& machine, const std::string& text) {
  return planning::check_commanded_coordinates(machine, test::gcode_for(machine, text, "prog.ngc"));
}

void expect_refused(const Machine& machine, const std::string& text, int line,
                    const std::string& coordinate) {
  const Status status = commanded(machine, text);
  ASSERT_FALSE(status.ok()) << text;
  EXPECT_EQ(status.error().code, ErrorCode::bad_input);
  EXPECT_EQ(status.error().location.line, line) << status.error().message;
  EXPECT_EQ(status.error().location.key, coordinate) << status.error().message;
  EXPECT_NE(status.error().message.find("prog.ngc:" + std::to_string(line) + ": " + coordinate +
                                        " is not a controlled coordinate"),
            std::string::npos)
      << status.error().message;
}

TEST(CommandedCoordinates, ATripodRefusesXYAndCAndTakesZAB) {
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  EXPECT_TRUE(commanded(tripod, "G21 G90\nG0 X0 Y0 Z-10 A0 B0 C0\nG1 Z-20 A4 B-3 F600\nM2\n").ok());
  expect_refused(tripod, "G21 G90\nG0 Z-10\nG1 X10 F600\nM2\n", 3, "X");
  expect_refused(tripod, "G21 G90\nG1 Z-5 F600\nG1 Y-0.01\nM2\n", 3, "Y");
  expect_refused(tripod, "G21 G90\nG1 Z-5 F600\nG1 A2 C3\nM2\n", 3, "C");
  // An arc in the XY plane moves X and Y even where it ends where it began.
  expect_refused(tripod, "G21 G90\nG1 Z-5 F600\nG2 X0 Y0 I5 J0\nM2\n", 3, "X");
  const Status status = commanded(tripod, "G21 G90\nG0 Z-10\nG1 X10 F600\nM2\n");
  EXPECT_NE(status.error().message.find("it follows from Z, A, B"), std::string::npos)
      << status.error().message;
}

TEST(CommandedCoordinates, ATriceptRefusesOrientationButNotAConstantToolAxis) {
  const Machine tricept = test::machine_from_example("examples/machines/tricept.yaml");
  EXPECT_TRUE(commanded(tricept, "G21 G90\nG1 X10 Y-5 Z-3 F600\nG2 X20 Y-5 I5 J0\nM2\n").ok());
  expect_refused(tricept, "G21 G90\nG1 X10 F600\nG1 A-360\nM2\n", 3, "A");
  program::InterpretOptions start;
  const planning::ProgramStart home = planning::program_start(tricept);
  start.start_mm = home.start_mm;
  start.start_abc_deg = home.start_abc_deg;
  const std::string fixed_axis = "UNITS/MM\nFEDRAT/600\nGOTO/0,0,0,0,0,1\nGOTO/10,0,0,0,0,1\nFINI\n";
  auto straight = program::read_cl_data(fixed_axis, "prog.cl", start);
  ASSERT_TRUE(straight.ok()) << straight.error().message;
  EXPECT_TRUE(planning::check_commanded_coordinates(tricept, *straight).ok());
  const std::string tilted = "UNITS/MM\nFEDRAT/600\nGOTO/0,0,0,0,0,1\nGOTO/10,0,0,0.5,0,0.8660254\nFINI\n";
  auto tilting = program::read_cl_data(tilted, "prog.cl", start);
  ASSERT_TRUE(tilting.ok()) << tilting.error().message;
  const Status refused = planning::check_commanded_coordinates(tricept, *tilting);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().location.line, 4);
  EXPECT_NE(refused.error().message.find("the tool axis is not a controlled coordinate"), std::string::npos)
      << refused.error().message;
  // Tilted from its first point on and never changing: still a tool axis the tricept cannot set.
  const std::string tilted_throughout =
      "UNITS/MM\nFEDRAT/600\nGOTO/0,0,0,0.5,0,0.8660254\nGOTO/10,0,0\nFINI\n";
  auto constant_tilt = program::read_cl_data(tilted_throughout, "prog.cl", start);
  ASSERT_TRUE(constant_tilt.ok()) << constant_tilt.error().message;
  const Status refused_first = planning::check_commanded_coordinates(tricept, *constant_tilt);
  ASSERT_FALSE(refused_first.ok());
  EXPECT_EQ(refused_first.error().location.line, 3);
  EXPECT_NE(refused_first.error().message.find("by 30.0000 deg"), std::string::npos)
      << refused_first.error().message;
}

TEST(CommandedCoordinates, APlanarMachineRefusesZ) {
  const Machine planar = test::machine_from_example("examples/machines/planar2.yaml");
  EXPECT_TRUE(commanded(planar, "G21 G90\nG1 X5 Y5 Z0 F600\nM2\n").ok());
  expect_refused(planar, "G21 G90\nG1 X5 Y5 F600\nG1 Z-1\nM2\n", 3, "Z");
  expect_refused(planar, "G21 G90\nG1 X5 Y5 F600\nG1 C10\nM2\n", 3, "C");  // two struts to a point: no φ
  const Machine planar3 = test::machine_from_example("examples/machines/planar3.yaml");
  EXPECT_TRUE(commanded(planar3, "G21 G90\nG1 X5 Y5 C10 F600\nM2\n").ok());
}

TEST(CommandedCoordinates, ASixAxisMachineTakesEverything) {
  const Machine hexapod = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  EXPECT_TRUE(commanded(hexapod, "G21 G90\nG1 X10 Y-5 Z-3 A4 B-2 C30 F600\nG2 X10 Y-5 I5 J0\nM2\n").ok());
}

// The tolerance, at half and one and a half times: a change below it is the rounding of a four-decimal post.
TEST(CommandedCoordinates, TheToleranceIsAFourDecimalProgramsResolution) {
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  const double t = planning::kUncontrolledChangeTolerance;
  EXPECT_TRUE(commanded(tripod, fmt::format("G21 G90\nG1 Z-5 F600\nG1 X{:.8f}\nM2\n", 0.5 * t)).ok());
  EXPECT_FALSE(commanded(tripod, fmt::format("G21 G90\nG1 Z-5 F600\nG1 X{:.8f}\nM2\n", 1.5 * t)).ok());
}

}  // namespace
}  // namespace pkm
