// Errors about an input file carry their place as fields as well as in the message (core/result.hpp): the
// machine-file and load-file reader (file, line, column, key), the G-code interpreter and the CL-data reader
// (file, line, column), and errors located at a program line. The message and the fields must agree.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "io/machine_file.hpp"
#include "program/part_program.hpp"

namespace pkm {
namespace {

// "FILE:LINE:COLUMN: …" as the fields say.
void expect_message_starts_with_location(const Error& error) {
  // A stream, not string concatenation: GCC 12 reports a false -Wstringop-overflow for `s += ":" + …`.
  std::ostringstream prefix;
  prefix << error.location.file;
  if (error.location.line > 0) prefix << ':' << error.location.line;
  if (error.location.column > 0) prefix << ':' << error.location.column;
  prefix << ": ";
  EXPECT_EQ(error.message.rfind(prefix.str(), 0), 0u) << error.message << " vs " << prefix.str();
  if (!error.location.key.empty()) {
    EXPECT_NE(error.message.find(": " + error.location.key + ": "), std::string::npos) << error.message;
  }
}

TEST(ErrorLocation, MachineFileValueHasFileLineColumnAndKey) {
  const auto machine =
      parse_machine_text("type: planar2\nbase_joints:\n  - [0.0, 0.0]\n  - [300.0, x]\n", "m.yaml");
  ASSERT_FALSE(machine);
  const Error& error = machine.error();
  EXPECT_EQ(error.location.file, "m.yaml");
  EXPECT_EQ(error.location.line, 4);
  EXPECT_EQ(error.location.column, 13);  // the x of "  - [300.0, x]"
  EXPECT_EQ(error.location.key, "base_joints[1][1]");
  expect_message_starts_with_location(error);
}

TEST(ErrorLocation, DuplicateKeyAndBrokenYamlAreLocatedToo) {
  const auto twice = parse_machine_text("type: planar2\ntype: planar3\n", "d.yaml");
  ASSERT_FALSE(twice);
  EXPECT_EQ(twice.error().location.line, 2);
  EXPECT_EQ(twice.error().location.key, "type");
  expect_message_starts_with_location(twice.error());
  const auto broken = parse_machine_text("type: [planar2\n", "b.yaml");
  ASSERT_FALSE(broken);
  EXPECT_EQ(broken.error().location.file, "b.yaml");
  EXPECT_GT(broken.error().location.line, 0);
  expect_message_starts_with_location(broken.error());
}

TEST(ErrorLocation, GcodeAndClErrorsHaveFileLineAndColumn) {
  const auto gcode = program::interpret_gcode("G21 G90\nG1 X1 Q\n", "p.ngc");
  ASSERT_FALSE(gcode);
  EXPECT_EQ(gcode.error().location.file, "p.ngc");
  EXPECT_EQ(gcode.error().location.line, 2);
  EXPECT_GT(gcode.error().location.column, 0);
  EXPECT_TRUE(gcode.error().location.key.empty());
  expect_message_starts_with_location(gcode.error());

  const auto cl = program::read_cl_data("UNITS/MM\nGOTO/1,2,bad\n", "p.cl");
  ASSERT_FALSE(cl);
  EXPECT_EQ(cl.error().location.file, "p.cl");
  EXPECT_EQ(cl.error().location.line, 2);
  EXPECT_GT(cl.error().location.column, 0);
  expect_message_starts_with_location(cl.error());
}

TEST(ErrorLocation, ErrorsNotAboutAFileHaveNoLocation) {
  const Error error = make_error(ErrorCode::singular, "the Jacobian is singular");
  EXPECT_TRUE(error.location.file.empty());
  EXPECT_EQ(error.location.line, 0);
}

}  // namespace
}  // namespace pkm
