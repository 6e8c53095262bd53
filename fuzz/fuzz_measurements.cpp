// libFuzzer harness: calibration measurement files (`pkm calibrate identify --measurements F.csv`,
// io/measurement_file.hpp) and fixture files (io/fixture_file.hpp). The first byte picks what the reader
// checks the file against (actuator count 1…6, lengths or angles, a travel or none), so that mutations reach
// every column layout; the rest is the file's text. A file the reader accepts must be written back by the
// writer and read again to the same poses (for lengths, whose numbers round-trip exactly): a failure there
// ends the run as a crash. An exception escaping the library is a crash too: bad input must come back as an
// error.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/fixture_file.hpp"
#include "io/measurement_file.hpp"

namespace {

// The fixture every harness input's tracker rows refer to (the plate of Smirnov 2019, §5.2.4).
std::vector<pkm::calibration::FixtureTarget> fuzz_meas_fixture() {
  return {{"A", {100, 0, -150}}, {"B", {-50, 86.6, -150}}, {"C", {-50, -86.6, -150}}};
}

bool fuzz_meas_same(const pkm::calibration::MeasurementSet& a, const pkm::calibration::MeasurementSet& b) {
  if (a.poses.size() != b.poses.size() || a.kind != b.kind || a.ballbar_centre_mm != b.ballbar_centre_mm)
    return false;
  for (std::size_t p = 0; p < a.poses.size(); ++p) {
    const auto& x = a.poses[p];
    const auto& y = b.poses[p];
    if (x.id != y.id || x.readings != y.readings || x.targets.size() != y.targets.size() ||
        x.distances.size() != y.distances.size())
      return false;
    for (std::size_t t = 0; t < x.targets.size(); ++t) {
      if (x.targets[t].target != y.targets[t].target ||
          x.targets[t].position_mm != y.targets[t].position_mm ||
          x.targets[t].sigma_mm != y.targets[t].sigma_mm)
        return false;
    }
    for (std::size_t d = 0; d < x.distances.size(); ++d) {
      if (x.distances[d].distance_mm != y.distances[d].distance_mm ||
          x.distances[d].sigma_mm != y.distances[d].sigma_mm)
        return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  (void)pkm::parse_fixture_csv(text, "fuzz_fixture.csv");
  pkm::MeasurementReadOptions options;
  options.actuator_count = 1 + mode % 6;
  options.actuators_are_angles = (mode & 0x40) != 0;
  if ((mode & 0x80) != 0 && !options.actuators_are_angles) {
    options.actuator_min = 350.0;
    options.actuator_max = 900.0;
  }
  options.min_poses = 1 + (mode >> 3) % 4;
  const auto fixture = fuzz_meas_fixture();
  auto set = pkm::parse_measurement_csv(text, "fuzz.csv", options, fixture);
  if (!set || options.actuators_are_angles) return 0;
  auto written = pkm::measurement_file_text(*set, {});
  if (!written) __builtin_trap();
  auto back = pkm::parse_measurement_csv(*written, "fuzz_back.csv", options, fixture);
  if (!back || !fuzz_meas_same(*set, *back)) __builtin_trap();
  return 0;
}
