// The measurement file writer (measurement_file.hpp): the simulation's measurements as the file a tracker or
// a ballbar run would give, so that `pkm calibrate identify` reads simulated and real data the same way.
#include <fmt/format.h>

#include <iterator>

#include "core/units.hpp"
#include "io/fixture_file.hpp"
#include "io/measurement_file.hpp"

namespace pkm {
namespace {

using calibration::MeasurementKind;
using calibration::MeasurementSet;

// One sigma for the whole set (then a `# sigma_mm` line and no column), or none when they differ.
std::optional<double> meas_common_sigma(const MeasurementSet& set) {
  std::optional<double> common;
  for (const calibration::MeasuredPose& pose : set.poses) {
    const auto same = [&](double sigma) {
      if (!common) common = sigma;
      return *common == sigma;
    };
    for (const auto& t : pose.targets)
      if (!same(t.sigma_mm)) return std::nullopt;
    for (const auto& d : pose.distances)
      if (!same(d.sigma_mm)) return std::nullopt;
  }
  return common;
}

bool meas_one_line(const std::string& text) {
  return text.find_first_of("\r\n") == std::string::npos;
}

}  // namespace

Result<std::string> measurement_file_text(const MeasurementSet& set, const MeasurementWriteOptions& options) {
  if (set.poses.empty()) return make_error(ErrorCode::bad_input, "measurement file: no poses to write");
  const bool ballbar = set.kind == MeasurementKind::ballbar;
  const long n = set.poses.front().readings.size();
  for (const std::string* text : {&options.fixture_file, &options.machine_file}) {
    if (!meas_one_line(*text))
      return make_error(ErrorCode::bad_input, "measurement file: a header value holds a line break");
  }
  for (const std::string& note : options.notes) {
    if (!meas_one_line(note))
      return make_error(ErrorCode::bad_input, "measurement file: a note holds a line break");
  }
  for (const calibration::FixtureTarget& target : set.fixture) {
    if (!is_calibration_name(target.name))
      return make_error(ErrorCode::bad_input,
                        fmt::format("measurement file: '{}' is not a target name", target.name));
  }
  const std::optional<double> sigma = meas_common_sigma(set);
  std::string text;
  auto out = std::back_inserter(text);
  for (const std::string& note : options.notes) fmt::format_to(out, "# note: {}\n", note);
  fmt::format_to(out, "# kind: {}\n# units: mm\n", ballbar ? "ballbar" : "tracker");
  if (options.actuators_are_angles) fmt::format_to(out, "# actuator_units: deg\n");
  fmt::format_to(out, "# frame: base\n");
  if (sigma) fmt::format_to(out, "# sigma_mm: {}\n", *sigma);
  if (ballbar) {
    const Eigen::Vector3d& c = set.ballbar_centre_mm;
    fmt::format_to(out, "# ballbar_centre_mm: {} {} {}\n", c.x(), c.y(), c.z());
  }
  if (!ballbar && !options.fixture_file.empty()) fmt::format_to(out, "# fixture: {}\n", options.fixture_file);
  if (!options.machine_file.empty()) fmt::format_to(out, "# machine: {}\n", options.machine_file);
  fmt::format_to(out, "pose_id");
  for (long j = 1; j <= n; ++j) fmt::format_to(out, ",L{}", j);
  fmt::format_to(out, "{}{}\n", ballbar ? ",distance" : ",target,x,y,z", sigma ? "" : ",sigma");
  for (const calibration::MeasuredPose& pose : set.poses) {
    if (!is_calibration_name(pose.id))
      return make_error(ErrorCode::bad_input,
                        fmt::format("measurement file: '{}' is not a pose name", pose.id));
    if (pose.readings.size() != n)
      return make_error(ErrorCode::bad_input, fmt::format("measurement file: pose {} has {} readings, not {}",
                                                          pose.id, pose.readings.size(), n));
    if (ballbar ? pose.distances.empty() || !pose.targets.empty()
                : pose.targets.empty() || !pose.distances.empty()) {
      return make_error(
          ErrorCode::bad_input,
          fmt::format("measurement file: pose {} has no {} measurement, or one of the other kind", pose.id,
                      ballbar ? "ballbar" : "target"));
    }
    std::string readings = pose.id;
    for (long j = 0; j < n; ++j)
      fmt::format_to(std::back_inserter(readings), ",{}",
                     options.actuators_are_angles ? deg_from_rad(pose.readings[j]) : pose.readings[j]);
    for (const calibration::DistanceObservation& d : pose.distances) {
      fmt::format_to(out, "{},{}", readings, d.distance_mm);
      if (!sigma) fmt::format_to(out, ",{}", d.sigma_mm);
      text += '\n';
    }
    for (const calibration::TargetObservation& t : pose.targets) {
      if (t.target < 0 || t.target >= static_cast<int>(set.fixture.size()))
        return make_error(ErrorCode::bad_input, fmt::format("measurement file: pose {} names target {} of {}",
                                                            pose.id, t.target, set.fixture.size()));
      const Eigen::Vector3d& p = t.position_mm;
      fmt::format_to(out, "{},{},{},{},{}", readings, set.fixture[static_cast<std::size_t>(t.target)].name,
                     p.x(), p.y(), p.z());
      if (!sigma) fmt::format_to(out, ",{}", t.sigma_mm);
      text += '\n';
    }
  }
  return text;
}

}  // namespace pkm
