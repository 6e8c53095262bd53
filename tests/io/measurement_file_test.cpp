// Calibration measurement and fixture files (src/io/measurement_file.hpp, fixture_file.hpp,
// docs/calibration.md): what a tracker file and a ballbar file read as (poses grouped by pose_id, the sigma
// default and column, degrees turned into radians), that writing and reading back gives the same set, that
// the fixture a file names is found next to it, and every refusal (units, frame, column
// count, NaN/inf/huge, empty file, repeated target, readings that differ within a pose, unknown target, too
// few poses, readings beyond the travel) named by file, line, column and key, with the same place in
// Error::location.
#include "io/measurement_file.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/units.hpp"
#include "io/fixture_file.hpp"

namespace pkm {
namespace {

using calibration::FixtureTarget;
using calibration::MeasurementKind;
using calibration::MeasurementSet;

const char* kMeasFixtureText = R"(# units: mm
# frame: tool
# note: the dissertation's triangular plate
target,x,y,z
A,100,0,-150
B,-50,86.6,-150
C,-50,-86.6,-150
)";

std::vector<FixtureTarget> meas_fixture() {
  auto fixture = parse_fixture_csv(kMeasFixtureText, "plate.csv");
  EXPECT_TRUE(fixture.ok()) << fixture.error().message;
  return fixture.ok() ? *fixture : std::vector<FixtureTarget>{};
}

MeasurementReadOptions meas_options(int n = 3) {
  MeasurementReadOptions options;
  options.actuator_count = n;
  options.actuator_min = 350.0;
  options.actuator_max = 900.0;
  return options;
}

// Three actuators keep the rows short; the reader takes n from the caller.
const std::string kMeasTracker = R"(# kind: tracker
# units: mm
# frame: base
# sigma_mm: 0.01
pose_id,L1,L2,L3,target,x,y,z
P1,600,610,620,A,100.5,0.25,549.75
P1,600,610,620,B,-49.5,86.5,550
# a free comment between rows
P2,601,611,621.5,C,-50,-86,551

P2,601,611,621.5,A,101,1,551
)";

Result<MeasurementSet> meas_parse(const std::string& text,
                                  const MeasurementReadOptions& options = meas_options()) {
  return parse_measurement_csv(text, "m.csv", options, meas_fixture());
}

// The error of reading `text`, which must fail.
Error meas_error(const std::string& text, const MeasurementReadOptions& options = meas_options()) {
  auto set = meas_parse(text, options);
  EXPECT_FALSE(set.ok()) << "accepted:\n" << text;
  return set.ok() ? Error{ErrorCode::bad_input, "accepted"} : set.error();
}

// kMeasTracker with its first `from` replaced by `to`.
std::string meas_edit(const std::string& text, const std::string& from, const std::string& to) {
  std::string out = text;
  const std::size_t at = out.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) out.replace(at, from.size(), to);
  return out;
}

void meas_expect_place(const Error& error, int line, int column, const std::string& key) {
  EXPECT_EQ(error.code, ErrorCode::bad_input);
  EXPECT_EQ(error.location.file, "m.csv");
  EXPECT_EQ(error.location.line, line) << error.message;
  EXPECT_EQ(error.location.column, column) << error.message;
  EXPECT_EQ(error.location.key, key) << error.message;
  EXPECT_EQ(error.message.rfind(fmt::format("m.csv:{}:{}: {}: ", line, column, key), 0), 0u) << error.message;
}

TEST(MeasurementFile, ReadsATrackerFileGroupedByPose) {
  auto set = meas_parse(kMeasTracker);
  ASSERT_TRUE(set.ok()) << set.error().message;
  EXPECT_EQ(set->kind, MeasurementKind::targets);
  EXPECT_EQ(set->source, "m.csv");
  ASSERT_EQ(set->fixture.size(), 3u);
  ASSERT_EQ(set->poses.size(), 2u);
  const calibration::MeasuredPose& p1 = set->poses[0];
  EXPECT_EQ(p1.id, "P1");
  EXPECT_EQ(p1.line, 6);
  ASSERT_EQ(p1.readings.size(), 3);
  EXPECT_EQ(p1.readings[2], 620.0);
  ASSERT_EQ(p1.targets.size(), 2u);
  EXPECT_EQ(p1.targets[1].target, 1);
  EXPECT_EQ(p1.targets[1].position_mm, Eigen::Vector3d(-49.5, 86.5, 550));
  EXPECT_EQ(p1.targets[1].sigma_mm, 0.01);
  EXPECT_EQ(p1.targets[1].line, 7);
  const calibration::MeasuredPose& p2 = set->poses[1];
  EXPECT_EQ(p2.readings[2], 621.5);
  ASSERT_EQ(p2.targets.size(), 2u);
  EXPECT_EQ(p2.targets[0].target, 2);
  EXPECT_EQ(p2.targets[1].target, 0);
  EXPECT_EQ(p2.targets[1].line, 11);
  EXPECT_TRUE(p2.distances.empty());
}

TEST(MeasurementFile, ReadsABallbarFileWithItsSigmaColumnAndCentre) {
  const std::string text = R"(# kind: ballbar
# units: mm
# frame: base
# ballbar_centre_mm: 10 -20.5 300
# sigma_mm: 0.002
pose_id,L1,L2,L3,distance,sigma
Q1,500,500,500,150.25,
Q1,500,500,500,150.5,0.004
Q2,510,500,500,149,
)";
  auto set = meas_parse(text);
  ASSERT_TRUE(set.ok()) << set.error().message;
  EXPECT_EQ(set->kind, MeasurementKind::ballbar);
  EXPECT_EQ(set->ballbar_centre_mm, Eigen::Vector3d(10, -20.5, 300));
  EXPECT_TRUE(set->fixture.empty());
  ASSERT_EQ(set->poses.size(), 2u);
  ASSERT_EQ(set->poses[0].distances.size(), 2u);
  EXPECT_EQ(set->poses[0].distances[0].sigma_mm, 0.002);  // empty field: the header's
  EXPECT_EQ(set->poses[0].distances[1].sigma_mm, 0.004);
  EXPECT_EQ(set->poses[0].distances[1].distance_mm, 150.5);
  EXPECT_EQ(set->poses[1].distances[0].line, 9);
}

TEST(MeasurementFile, AngularActuatorsAreReadInTheUnitTheFileStates) {
  MeasurementReadOptions options = meas_options();
  options.actuators_are_angles = true;
  options.actuator_min = rad_from_deg(-90.0);
  options.actuator_max = rad_from_deg(90.0);
  const std::string degrees =
      meas_edit(meas_edit(meas_edit(kMeasTracker, "# frame", "# actuator_units: deg\n# frame"),
                          "600,610,620,A", "10,20,30,A"),
                "600,610,620,B", "10,20,30,B");
  const std::string text =
      meas_edit(meas_edit(degrees, "601,611,621.5,C", "11,21,31,C"), "601,611,621.5,A", "11,21,31,A");
  auto set = meas_parse(text, options);
  ASSERT_TRUE(set.ok()) << set.error().message;
  EXPECT_DOUBLE_EQ(set->poses[0].readings[1], rad_from_deg(20.0));
  // The unit must be said for turning actuators, and lengths are refused for them.
  meas_expect_place(meas_error(meas_edit(text, "# actuator_units: deg\n", ""), options), 5, 1,
                    "actuator_units");
  meas_expect_place(meas_error(meas_edit(text, "actuator_units: deg", "actuator_units: mm"), options), 3, 1,
                    "actuator_units");
  // Beyond the travel, in the file's unit.
  const Error beyond = meas_error(meas_edit(text, "11,21,31,C", "11,21,95,C"), options);
  meas_expect_place(beyond, 10, 10, "L3");
  EXPECT_NE(beyond.message.find("max 90 deg"), std::string::npos) << beyond.message;
}

TEST(MeasurementFile, WritingAndReadingBackGivesTheSameSet) {
  auto set = meas_parse(kMeasTracker);
  ASSERT_TRUE(set.ok()) << set.error().message;
  // Unequal sigmas make the writer add a sigma column; awkward numbers must survive exactly.
  set->poses[1].targets[0].sigma_mm = 0.0123456789012345;
  set->poses[0].targets[0].position_mm.x() = 0.1 + 0.2;
  set->poses[0].readings[0] = 600.0000000000001;
  MeasurementWriteOptions write;
  write.fixture_file = "plate.csv";
  write.notes = {"simulated"};
  auto text = measurement_file_text(*set, write);
  ASSERT_TRUE(text.ok()) << text.error().message;
  EXPECT_NE(text->find("# fixture: plate.csv\n"), std::string::npos);
  EXPECT_NE(text->find(",sigma\n"), std::string::npos);
  auto back = meas_parse(*text);
  ASSERT_TRUE(back.ok()) << back.error().message << "\n" << *text;
  ASSERT_EQ(back->poses.size(), set->poses.size());
  for (std::size_t p = 0; p < set->poses.size(); ++p) {
    EXPECT_EQ(back->poses[p].id, set->poses[p].id);
    EXPECT_EQ(back->poses[p].readings, set->poses[p].readings);
    ASSERT_EQ(back->poses[p].targets.size(), set->poses[p].targets.size());
    for (std::size_t t = 0; t < set->poses[p].targets.size(); ++t) {
      EXPECT_EQ(back->poses[p].targets[t].target, set->poses[p].targets[t].target);
      EXPECT_EQ(back->poses[p].targets[t].position_mm, set->poses[p].targets[t].position_mm);
      EXPECT_EQ(back->poses[p].targets[t].sigma_mm, set->poses[p].targets[t].sigma_mm);
    }
  }
  // A ballbar set with one sigma: a header line, no column; angles in degrees come back within rounding.
  MeasurementSet ballbar;
  ballbar.kind = MeasurementKind::ballbar;
  ballbar.ballbar_centre_mm = Eigen::Vector3d(1.5, -2.25, 3);
  for (int p = 0; p < 3; ++p) {
    calibration::MeasuredPose pose;
    pose.id = fmt::format("B{}", p);
    pose.readings = ActuatorVector::Constant(3, rad_from_deg(10.0 + p) / 3.0);
    pose.distances.push_back({100.0 + p / 7.0, 0.001, 0});
    ballbar.poses.push_back(pose);
  }
  MeasurementWriteOptions angles;
  angles.actuators_are_angles = true;
  auto ballbar_text = measurement_file_text(ballbar, angles);
  ASSERT_TRUE(ballbar_text.ok()) << ballbar_text.error().message;
  EXPECT_NE(ballbar_text->find("# sigma_mm: 0.001\n"), std::string::npos) << *ballbar_text;
  MeasurementReadOptions options = meas_options();
  options.actuators_are_angles = true;
  options.actuator_min.reset();
  options.actuator_max.reset();
  auto ballbar_back = parse_measurement_csv(*ballbar_text, "b.csv", options, std::vector<FixtureTarget>{});
  ASSERT_TRUE(ballbar_back.ok()) << ballbar_back.error().message;
  EXPECT_EQ(ballbar_back->ballbar_centre_mm, ballbar.ballbar_centre_mm);
  for (int p = 0; p < 3; ++p) {
    const auto& q = ballbar_back->poses[static_cast<std::size_t>(p)];
    EXPECT_EQ(q.distances[0].distance_mm,
              ballbar.poses[static_cast<std::size_t>(p)].distances[0].distance_mm);
    EXPECT_NEAR(q.readings[0], ballbar.poses[static_cast<std::size_t>(p)].readings[0], 1e-15);
  }
}

TEST(MeasurementFile, FindsTheFixtureItNamesNextToIt) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "pkm_meas_fixture_next_to_it";
  fs::remove_all(dir);
  fs::create_directories(dir / "fixtures");
  std::ofstream(dir / "fixtures" / "plate.csv") << kMeasFixtureText;
  const std::string text = meas_edit(kMeasTracker, "pose_id", "# fixture: fixtures/plate.csv\npose_id");
  std::ofstream(dir / "m.csv") << text;
  auto set = read_measurement_file((dir / "m.csv").string(), meas_options());
  ASSERT_TRUE(set.ok()) << set.error().message;
  EXPECT_EQ(set->fixture.size(), 3u);
  // A fixture given by the caller wins; a missing one is named at the line that names it.
  std::ofstream(dir / "m2.csv") << meas_edit(text, "fixtures/plate.csv", "nowhere.csv");
  const auto missing = read_measurement_file((dir / "m2.csv").string(), meas_options());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().location.line, 5);
  EXPECT_EQ(missing.error().location.key, "fixture");
  EXPECT_NE(missing.error().message.find("nowhere.csv"), std::string::npos) << missing.error().message;
  MeasurementReadOptions given = meas_options();
  given.fixture_path = (dir / "fixtures" / "plate.csv").string();
  EXPECT_TRUE(read_measurement_file((dir / "m2.csv").string(), given).ok());
  // A tracker file with no fixture at all.
  const auto none = parse_measurement_csv(kMeasTracker, "m.csv", meas_options(),
                                          [](const std::string&) -> Result<std::vector<FixtureTarget>> {
                                            return make_error(ErrorCode::io, "not asked");
                                          });
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().location.key, "fixture");
  fs::remove_all(dir);
}

TEST(MeasurementFile, RefusesUnitsFrameAndHeaderMistakesAtTheirLine) {
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "units: mm", "units: in")), 2, 10, "units");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "# units: mm\n", "")), 4, 1, "units");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "frame: base", "frame: platform")), 3, 10, "frame");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "# frame: base\n", "")), 4, 1, "frame");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "# kind: tracker\n", "")), 4, 1, "kind");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "kind: tracker", "kind: laser")), 1, 9, "kind");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "# frame: base", "# frame: base\n# units: mm")), 4, 3,
                    "units");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "# frame: base", "# frame: base\n# Units: mm")), 4, 3,
                    "Units");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "sigma_mm: 0.01", "sigma_mm: -1")), 4, 13, "sigma_mm");
  meas_expect_place(
      meas_error(meas_edit(kMeasTracker, "P2,601,611,621.5,C", "# units: in\nP2,601,611,621.5,C")), 9, 3,
      "units");
  // Without a sigma anywhere the file cannot weigh its rows.
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "# sigma_mm: 0.01\n", "")), 5, 1, "sigma");
}

TEST(MeasurementFile, RefusesColumnsThatDoNotFitTheMachineOrTheKind) {
  const Error fewer = meas_error(kMeasTracker, meas_options(4));
  meas_expect_place(fewer, 5, 18, "L4");
  EXPECT_NE(fewer.message.find("the machine has 4 actuators"), std::string::npos) << fewer.message;
  meas_expect_place(meas_error(kMeasTracker, meas_options(2)), 5, 15, "target");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "pose_id,", "pose,")), 5, 1, "pose_id");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, ",x,y,z", ",x,y,z,extra")), 5, 31, "extra");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "target,x,y,z", "distance")), 5, 18, "target");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, "P1,600,610,620,A,100.5,0.25,549.75",
                                         "P1,600,610,620,A,100.5,0.25")),
                    6, 28, "(missing)");
}

TEST(MeasurementFile, RefusesBadNumbersWithTheirPlace) {
  const std::string row = "P1,600,610,620,B,-49.5,86.5,550";
  meas_expect_place(meas_error(meas_edit(kMeasTracker, row, "P1,600,610,620,B,nan,86.5,550")), 7, 18, "x");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, row, "P1,600,610,620,B,-49.5,inf,550")), 7, 24, "y");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, row, "P1,600,610,620,B,-49.5,86.5,1e300")), 7, 29,
                    "z");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, row, "P1,600,610,620,B,-49.5,86.5,5 50")), 7, 29, "z");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, row, "P1,600,610,,B,-49.5,86.5,550")), 7, 12, "L3");
  meas_expect_place(meas_error(meas_edit(kMeasTracker, row, "P1,600,610,620,B,-49.5,86.5,550\n,1,2")), 8, 5,
                    "(missing)");
  // Beyond the machine's travel (350…900 mm here).
  const Error beyond = meas_error(meas_edit(kMeasTracker, "P2,601,611,621.5,C", "P2,601,300,621.5,C"));
  meas_expect_place(beyond, 9, 8, "L2");
  EXPECT_NE(beyond.message.find("min 350 mm"), std::string::npos) << beyond.message;
}

TEST(MeasurementFile, RefusesRowsThatContradictTheirPose) {
  // Readings that differ within a pose: both lines named.
  const Error differ = meas_error(meas_edit(kMeasTracker, "P1,600,610,620,B", "P1,600,610,620.001,B"));
  meas_expect_place(differ, 7, 12, "L3");
  EXPECT_NE(differ.message.find("line 6"), std::string::npos) << differ.message;
  // A target twice in one pose, and one the fixture does not have.
  const Error twice = meas_error(meas_edit(kMeasTracker, "P1,600,610,620,B", "P1,600,610,620,A"));
  meas_expect_place(twice, 7, 16, "target");
  EXPECT_NE(twice.message.find("line 6"), std::string::npos) << twice.message;
  const Error unknown = meas_error(meas_edit(kMeasTracker, "P1,600,610,620,B", "P1,600,610,620,D"));
  meas_expect_place(unknown, 7, 16, "target");
  EXPECT_NE(unknown.message.find("A, B, C"), std::string::npos) << unknown.message;
}

TEST(MeasurementFile, RefusesEmptyFilesAndTooFewPoses) {
  meas_expect_place(meas_error(""), 1, 1, "pose_id");
  meas_expect_place(meas_error("# kind: tracker\n# units: mm\n"), 2, 1, "pose_id");
  meas_expect_place(meas_error(kMeasTracker.substr(0, kMeasTracker.find("P1,"))), 5, 1, "pose_id");
  MeasurementReadOptions options = meas_options();
  options.min_poses = 3;
  const Error few = meas_error(kMeasTracker, options);
  meas_expect_place(few, 11, 1, "pose_id");
  EXPECT_NE(few.message.find("2 poses, at least 3"), std::string::npos) << few.message;
}

TEST(FixtureFile, ReadsTargetsAndRefusesWhatItCannotTrust) {
  auto fixture = parse_fixture_csv(kMeasFixtureText, "plate.csv");
  ASSERT_TRUE(fixture.ok()) << fixture.error().message;
  ASSERT_EQ(fixture->size(), 3u);
  EXPECT_EQ((*fixture)[1].name, "B");
  EXPECT_EQ((*fixture)[1].position_mm, Eigen::Vector3d(-50, 86.6, -150));
  auto back = parse_fixture_csv(fixture_file_text(*fixture), "back.csv");
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ((*back)[2].position_mm, (*fixture)[2].position_mm);

  const std::string text = kMeasFixtureText;
  const auto refused = [&](const std::string& bad, int line, int column, const std::string& key) {
    auto result = parse_fixture_csv(bad, "plate.csv");
    ASSERT_FALSE(result.ok()) << bad;
    EXPECT_EQ(result.error().location.line, line) << result.error().message;
    EXPECT_EQ(result.error().location.column, column) << result.error().message;
    EXPECT_EQ(result.error().location.key, key) << result.error().message;
  };
  refused(meas_edit(text, "units: mm", "units: inch"), 1, 10, "units");
  refused(meas_edit(text, "# units: mm\n", ""), 3, 1, "units");
  refused(meas_edit(text, "frame: tool", "frame: platform"), 2, 10, "frame");
  refused(meas_edit(text, "B,-50", "A,-50"), 6, 1, "target");
  refused(meas_edit(text, "C,-50,-86.6", "C,-50,nan"), 7, 7, "y");
  refused(meas_edit(text, "target,x,y,z", "name,x,y,z"), 4, 1, "target");
  refused(text.substr(0, text.find("A,")), 4, 1, "target");
  refused("", 1, 1, "target");
}

}  // namespace
}  // namespace pkm
