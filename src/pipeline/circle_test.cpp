#include "pipeline/circle_test.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "io/atomic_file.hpp"
#include "io/json_text.hpp"
#include "io/output_set.hpp"
#include "io/version.hpp"
#include "pipeline/circle_plot.hpp"
#include "pipeline/plan_program.hpp"
#include "pipeline/servo_program.hpp"
#include "pipeline/simulate_program.hpp"

namespace pkm::pipeline {

namespace {

constexpr int kTurns = 3;          // per direction; the middle one is measured
constexpr int kAngleBins = 360;    // for the hysteresis: one degree
constexpr int kCounterLine = 4;    // circle_program's G3 line (after its comment, set-up and G0 lines)
constexpr int kClockwiseLine = 5;  // and its G2 line

struct PlaneWords {
  const char* code;   // G17 …
  int first, second;  // the plane's axes (0 X, 1 Y, 2 Z), in the arc's sense
  char first_offset, second_offset;
};

Result<PlaneWords> plane_words(const std::string& plane) {
  if (plane == "XY") return PlaneWords{"G17", 0, 1, 'I', 'J'};
  if (plane == "ZX") return PlaneWords{"G18", 2, 0, 'K', 'I'};
  if (plane == "YZ") return PlaneWords{"G19", 1, 2, 'J', 'K'};
  return make_error(ErrorCode::bad_input,
                    fmt::format("circle plane {}: expected XY, ZX or YZ (G17, G18, G19)", plane));
}

// Three turns counter-clockwise (G3) from the point at +radius along the plane's first axis, then three
// clockwise (G2) back over them.
std::string circle_program(const CircleTestJob& job, const PlaneWords& plane) {
  Eigen::Vector3d start = job.centre_mm;
  start[plane.first] += job.radius_mm;
  const std::string at = fmt::format("X{:.6f} Y{:.6f} Z{:.6f}", start.x(), start.y(), start.z());
  const std::string offsets =
      fmt::format("{}{:.6f} {}0", plane.first_offset, -job.radius_mm, plane.second_offset);
  return fmt::format(
      "(pkm circle: the circular test of ISO 230-4, radius {r} mm at {f} mm/min in the {p} plane)\n"
      "G21 G90 G94 {code}\nG0 {at}\nG3 {at} {off} P{turns} F{f}\nG2 {at} {off} P{turns}\nM2\n",
      fmt::arg("r", job.radius_mm), fmt::arg("f", job.feed_mm_min), fmt::arg("p", job.plane),
      fmt::arg("code", plane.code), fmt::arg("at", at), fmt::arg("off", offsets), fmt::arg("turns", kTurns));
}

// The least-squares circle through planar points (Kåsa: x² + y² + D x + E y + F = 0, linear in D E F).
Eigen::Vector3d fit_circle(const std::vector<Eigen::Vector2d>& points) {
  Eigen::MatrixXd a(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    a(row, 0) = points[i].x();
    a(row, 1) = points[i].y();
    a(row, 2) = 1.0;
    b(row) = -points[i].squaredNorm();
  }
  const Eigen::Vector3d def = a.colPivHouseholderQr().solve(b);
  const Eigen::Vector2d centre(-0.5 * def[0], -0.5 * def[1]);
  return {centre.x(), centre.y(), std::sqrt(std::max(0.0, centre.squaredNorm() - def[2]))};
}

// The tool's commanded and actual positions of every tick (base frame), with its line.
struct Sample {
  double time_s;
  int line;
  Eigen::Vector3d commanded, actual;
};

// The middle turn of one direction's ticks: those of `line` in the middle third of its time.
std::vector<const Sample*> middle_turn(const std::vector<Sample>& samples, int line) {
  double first = 1e300, last = -1e300;
  for (const Sample& s : samples)
    if (s.line == line) first = std::min(first, s.time_s), last = std::max(last, s.time_s);
  std::vector<const Sample*> out;
  const double third = (last - first) / kTurns;
  for (const Sample& s : samples)
    if (s.line == line && s.time_s >= first + third && s.time_s < first + 2.0 * third) out.push_back(&s);
  return out;
}

struct PlaneFrame {
  Eigen::Vector3d origin, u, v;
  Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    return {(p - origin).dot(u), (p - origin).dot(v)};
  }
};

// The plane of the commanded circle (its points' best plane), with the plane's first and second program axes
// (XY: X and Y) projected into it as its axes, so that angles count from the first axis towards the second as
// G3 turns, and the plot is not mirrored.
PlaneFrame commanded_plane(const std::vector<Sample>& samples, const PlaneWords& plane) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Sample& s : samples) mean += s.commanded;
  mean /= static_cast<double>(samples.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Sample& s : samples) scatter += (s.commanded - mean) * (s.commanded - mean).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(scatter, Eigen::ComputeFullU);
  const Eigen::Vector3d normal = svd.matrixU().col(2);
  const Eigen::Vector3d first = Eigen::Vector3d::Unit(plane.first),
                        second = Eigen::Vector3d::Unit(plane.second);
  const Eigen::Vector3d u = (first - first.dot(normal) * normal).normalized();
  const Eigen::Vector3d v = (second - second.dot(normal) * normal - second.dot(u) * u).normalized();
  return {mean, u, v};
}

CircleTrace measure(const std::vector<const Sample*>& turn, const PlaneFrame& plane,
                    const Eigen::Vector2d& common_centre, double common_radius) {
  std::vector<Eigen::Vector2d> points;
  for (const Sample* s : turn) points.push_back(plane.project(s->actual));
  const Eigen::Vector3d own = fit_circle(points);
  CircleTrace trace;
  trace.radius_mm = own[2];
  double low = 1e300, high = -1e300;
  for (const Eigen::Vector2d& p : points) {
    const double r = (p - own.head<2>()).norm();
    low = std::min(low, r), high = std::max(high, r);
    const Eigen::Vector2d d = p - common_centre;
    double angle = std::atan2(d.y(), d.x()) * 180.0 / std::numbers::pi;
    if (angle < 0.0) angle += 360.0;
    trace.angle_deg.push_back(angle);
    trace.deviation_mm.push_back(d.norm() - common_radius);
  }
  trace.circular_deviation_mm = points.empty() ? 0.0 : high - low;
  return trace;
}

// H: the largest difference between the two directions' mean deviations in a one-degree bin.
double hysteresis(const CircleTrace& a, const CircleTrace& b) {
  std::vector<double> sum_a(kAngleBins, 0.0), sum_b(kAngleBins, 0.0);
  std::vector<int> count_a(kAngleBins, 0), count_b(kAngleBins, 0);
  auto bin = [](double angle) { return std::clamp(static_cast<int>(angle), 0, kAngleBins - 1); };
  for (std::size_t i = 0; i < a.angle_deg.size(); ++i)
    sum_a[bin(a.angle_deg[i])] += a.deviation_mm[i], ++count_a[bin(a.angle_deg[i])];
  for (std::size_t i = 0; i < b.angle_deg.size(); ++i)
    sum_b[bin(b.angle_deg[i])] += b.deviation_mm[i], ++count_b[bin(b.angle_deg[i])];
  double largest = 0.0;
  for (int k = 0; k < kAngleBins; ++k) {
    if (count_a[k] == 0 || count_b[k] == 0) continue;
    largest = std::max(largest, std::abs(sum_a[k] / count_a[k] - sum_b[k] / count_b[k]));
  }
  return largest;
}

std::string circle_csv(const CircleTestResult& r) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "direction,angle_deg,radial_deviation_um\n");
  for (const auto& [name, trace] : {std::pair{"ccw", &r.counter_clockwise}, std::pair{"cw", &r.clockwise}}) {
    for (std::size_t i = 0; i < trace->angle_deg.size(); ++i)
      fmt::format_to(std::back_inserter(out), "{},{:.4f},{:.5f}\n", name, trace->angle_deg[i],
                     trace->deviation_mm[i] * 1e3);
  }
  return fmt::to_string(out);
}

nlohmann::json circle_json(const Machine& machine, const CircleTestJob& job, const CircleTestResult& r) {
  return {{"kind", "circle"},
          {"pkm_version", std::string(pkm_version())},
          {"machine", machine.source},
          {"radius_mm", job.radius_mm},
          {"feed_mm_min", job.feed_mm_min},
          {"plane", job.plane},
          {"centre_mm", {job.centre_mm.x(), job.centre_mm.y(), job.centre_mm.z()}},
          {"circular_deviation_ccw_um", r.counter_clockwise.circular_deviation_mm * 1e3},
          {"circular_deviation_cw_um", r.clockwise.circular_deviation_mm * 1e3},
          {"hysteresis_um", r.hysteresis_mm * 1e3},
          {"radius_ccw_mm", r.counter_clockwise.radius_mm},
          {"radius_cw_mm", r.clockwise.radius_mm},
          {"max_contour_error_mm", r.max_contour_error_mm},
          {"files",
           {{"program", "circle.ngc"},
            {"deviations", "circle.csv"},
            {"plot", "circle.svg"},
            {job.elastic ? "simulate" : "servo", job.elastic ? "simulate.csv" : "servo.csv"}}},
          {"machine_in_the_loop", job.elastic}};
}

Status check_job(const Machine& machine, const CircleTestJob& job) {
  if (!machine.servo.given()) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{}: the circle test runs the drives' loops: the machine file has no servo: "
                    "section (docs/machine-file.md)",
                    machine.source));
  }
  if (!(job.radius_mm > 0.0) || !std::isfinite(job.radius_mm))
    return make_error(ErrorCode::bad_input,
                      fmt::format("circle radius {} mm must be positive", job.radius_mm));
  if (!(job.feed_mm_min > 0.0) || !std::isfinite(job.feed_mm_min))
    return make_error(ErrorCode::bad_input,
                      fmt::format("circle feed {} mm/min must be positive", job.feed_mm_min));
  if (job.out_directory.empty()) return make_error(ErrorCode::bad_input, "the circle test needs --out DIR");
  return ok_status();
}

// The circle's ticks through the drives' loops on the rigid machine (pkm servo): the commanded and the actual
// tool point by forward kinematics of the set points and of the drives' positions. Returns the run's largest
// contour error.
Result<double> circle_on_rigid(const Machine& machine, const CircleTestJob& job,
                               std::vector<Sample>& samples) {
  const Mechanism& m = *machine.mechanism;
  const int drives = m.actuator_count();
  Pose commanded_guess = m.home(), actual_guess = m.home();
  ServoJob servo;
  servo.plan_directory = job.out_directory;
  servo.progress = job.progress;
  servo.listener = [&](const servo::ServoTick& t) -> Status {
    if (t.line != kCounterLine && t.line != kClockwiseLine) return ok_status();
    auto commanded = m.forward(ActuatorVector(t.setpoint->head(drives)), commanded_guess);
    auto actual = m.forward(ActuatorVector(t.position->head(drives)), actual_guess);
    if (!commanded || !actual) return ok_status();  // counted by the servo run's own contour error
    commanded_guess = commanded->pose, actual_guess = actual->pose;
    samples.push_back({t.time_s, t.line, commanded->pose.position_mm, actual->pose.position_mm});
    return ok_status();
  };
  auto ran = servo_program(machine, servo);
  if (!ran) return ran.error();
  return ran->summary.max_contour_error_mm;
}

// The same on the machine in the loop (pkm simulate): the actual tool point is the elastic platform's.
Result<double> circle_in_the_loop(const Machine& machine, const CircleTestJob& job,
                                  std::vector<Sample>& samples) {
  SimulateJob simulate;
  simulate.plan_directory = job.out_directory;
  simulate.load = job.load;
  simulate.split = false;
  simulate.progress = job.progress;
  simulate.listener = [&](const servo::MachineRunTick& t) -> Status {
    if ((t.line == kCounterLine || t.line == kClockwiseLine) && t.actual_mm.allFinite())
      samples.push_back({t.time_s, t.line, t.commanded_mm, t.actual_mm});
    return ok_status();
  };
  auto ran = simulate_program(machine, simulate);
  if (!ran) return ran.error();
  return ran->total.max_mm;
}

}  // namespace

Result<CircleTestResult> circle_test(const Machine& machine, const CircleTestJob& job) {
  if (Status checked = check_job(machine, job); !checked) return checked.error();
  auto plane = plane_words(job.plane);
  if (!plane) return plane.error();
  const std::string program = circle_program(job, *plane);
  // The program is planned from a file of its own; the set keeps a copy as circle.ngc.
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() /
      fmt::format("pkm-circle-{}-{}.ngc", ::getpid(), static_cast<const void*>(&job));
  if (Status written = write_file_atomically(scratch.string(), program); !written) return written.error();
  struct Remove {
    std::filesystem::path path;
    ~Remove() {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
  } remove_scratch{scratch};

  PlanJob plan;
  plan.program_path = scratch.string();
  plan.out_directory = job.out_directory;
  plan.progress = job.progress;
  if (auto planned = plan_program(machine, plan); !planned) {
    // Named as the program the user sees (circle.ngc, as the set would keep it), not the scratch file.
    Error error = planned.error();
    for (std::size_t at; (at = error.message.find(scratch.string())) != std::string::npos;)
      error.message.replace(at, scratch.string().size(), "circle.ngc");
    if (error.location.file == scratch.string()) error.location.file = "circle.ngc";
    return error;
  }

  std::vector<Sample> samples;
  auto largest =
      job.elastic ? circle_in_the_loop(machine, job, samples) : circle_on_rigid(machine, job, samples);
  if (!largest) return largest.error();

  CircleTestResult result;
  result.max_contour_error_mm = *largest;
  const std::vector<const Sample*> ccw = middle_turn(samples, kCounterLine),
                                   cw = middle_turn(samples, kClockwiseLine);
  if (ccw.size() < 8 || cw.size() < 8)
    return make_error(ErrorCode::bad_input, "the circle is too short for the servo period: raise its radius");
  const PlaneFrame frame = commanded_plane(samples, *plane);
  std::vector<Eigen::Vector2d> both;
  for (const Sample* s : ccw) both.push_back(frame.project(s->actual));
  for (const Sample* s : cw) both.push_back(frame.project(s->actual));
  const Eigen::Vector3d common = fit_circle(both);
  result.counter_clockwise = measure(ccw, frame, common.head<2>(), common[2]);
  result.clockwise = measure(cw, frame, common.head<2>(), common[2]);
  result.hysteresis_mm = hysteresis(result.counter_clockwise, result.clockwise);
  result.json = circle_json(machine, job, result);

  OutputSet outputs{"circle"};
  if (Status joined = outputs.join_directory(job.out_directory, {"plan"}); !joined) return joined.error();
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"circle.ngc", program},
                                   {"circle.csv", circle_csv(result)},
                                   {"circle.svg", circle_plot_svg(result, job.radius_mm, job.plane)},
                                   {"circle_summary.json", json_text(result.json) + "\n"}}) {
    if (Status written = write_file_atomically(outputs.staged_path(name), text); !written)
      return written.error();
  }
  if (Status committed = outputs.commit(); !committed) return committed.error();
  return result;
}

}  // namespace pkm::pipeline
