// write_gcode: canonical moves → RS274/NGC. The writer keeps the state the reading interpreter will have
// (position as rounded and written, plane, feed mode, feed, path control) so that it writes a modal word
// only when it changes, computes arc centres from the position the reader will start the arc at, and can
// check each arc the way the reader will check it.
#include "program/gcode_writer.hpp"

#include <fmt/format.h>

#include <climits>
#include <cmath>
#include <numbers>
#include <optional>
#include <string_view>

#include "program/gcode_arc.hpp"
#include "program/gcode_format.hpp"

namespace pkm::program {

namespace {

// More digits than this describe a double's noise, not a position.
constexpr int kWriterMaxDecimals = 12;
// An arc normal computed elsewhere (CL data) may be off its axis by rounding; more is an oblique arc.
constexpr double kWriterAxisTolerance = 1e-9;
// Rounding moves an arc's ends and centre by half a unit of the last digit, which changes its swept angle a
// little; a change near a full turn means the end crossed the start (a tiny arc became a full circle).
constexpr double kWriterSweepChangeRad = std::numbers::pi;

const char* writer_plane_code(Plane plane) {
  switch (plane) {
    case Plane::xy:
      return "G17";
    case Plane::zx:
      return "G18";
    case Plane::yz:
      return "G19";
  }
  return "G17";
}

class GcodeProgramWriter {
 public:
  GcodeProgramWriter(const CanonicalProgram& program, const GcodeWriteOptions& options)
      : program_(program),
        options_(options),
        position_mm_(program.start_mm),
        canonical_position_mm_(program.start_mm) {}

  Result<std::string> run();

 private:
  std::string where(int line) const {
    return program_.source.empty() ? fmt::format("line {}", line)
                                   : fmt::format("{}:{}", program_.source, line);
  }
  Error error(ErrorCode code, const CanonicalMove& m, std::string_view what) const {
    return make_error(code, fmt::format("{}: {}", where(m.line), what));
  }
  void end_line(int source_line);
  void write_events_through(int line);
  void write_path_control(const CanonicalMove& m);
  std::string plane_change(Plane plane);
  Status check(const CanonicalMove& m) const;
  Status write_dwell(const CanonicalMove& m);
  Status write_motion(const CanonicalMove& m);
  Status write_arc_words(const CanonicalMove& m, const Eigen::Vector3d& end_mm, Plane& plane,
                         const char*& motion, std::string& words) const;
  Status write_feed_words(const CanonicalMove& m, std::string& codes, std::string& words);
  std::string positive_mm_number(double value) const;

  const CanonicalProgram& program_;
  const GcodeWriteOptions& options_;
  std::string out_;
  Eigen::Vector3d position_mm_;            ///< where the reader will be: the numbers as written
  Eigen::Vector3d canonical_position_mm_;  ///< the previous move's end as the program states it
  Plane plane_ = Plane::xy;
  bool inverse_time_ = false;
  std::string feed_;                  ///< G94 F word in effect; empty: none (G93 and G94 clear it)
  std::string path_control_ = "G64";  ///< G61 / G64 / G64 P… in effect
  std::size_t next_event_ = 0;
};

Result<std::string> GcodeProgramWriter::run() {
  for (const int decimals : {options_.decimals_mm, options_.decimals_deg}) {
    if (decimals < 0 || decimals > kWriterMaxDecimals)
      return make_error(ErrorCode::bad_input, fmt::format("G-code decimals must be from 0 to {}, not {}",
                                                          kWriterMaxDecimals, decimals));
  }
  out_.reserve(128 + program_.moves.size() * 96);
  for (const std::string& text : options_.header_comments) {
    std::string_view rest = text;
    while (true) {
      const std::size_t newline = rest.find('\n');
      const std::string_view line = rest.substr(0, newline);
      if (!line.empty()) out_ += gcode::comment(line) + '\n';
      if (newline == std::string_view::npos) break;
      rest.remove_prefix(newline + 1);
    }
  }
  // Every modal group the moves rely on, stated rather than assumed from the controller's start-up state.
  out_ += "G17 G21 G90 G94 G91.1 G40 G49 G64\n";
  for (const CanonicalMove& m : program_.moves) {
    if (auto checked = check(m); !checked) return checked.error();
    write_events_through(m.line);
    write_path_control(m);
    const Status written = m.kind == MoveKind::dwell ? write_dwell(m) : write_motion(m);
    if (!written) return written.error();
  }
  write_events_through(INT_MAX);
  out_ += "M2\n";
  return std::move(out_);
}

void GcodeProgramWriter::end_line(int source_line) {
  if (options_.write_source_lines) fmt::format_to(std::back_inserter(out_), " (src {})", source_line);
  out_ += '\n';
}

// In a block, LinuxCNC acts on S, T, M6 and M3–M9 before the dwell and the motion, so an event goes before
// the moves of its own line too.
void GcodeProgramWriter::write_events_through(int line) {
  for (; next_event_ < program_.events.size() && program_.events[next_event_].line <= line; ++next_event_) {
    const ProgramEvent& event = program_.events[next_event_];
    const std::string text = gcode::event_text(event.what);
    if (text.front() == '(' && options_.write_source_lines) {
      // LinuxCNC acts on the last comment of a line only: the source note goes first, the message last.
      fmt::format_to(std::back_inserter(out_), "(src {}) {}\n", event.line, text);
      continue;
    }
    out_ += text;
    end_line(event.line);
  }
}

// On a line of its own: G64 P in a block with G2/G3 P (turns) would claim the P word twice.
void GcodeProgramWriter::write_path_control(const CanonicalMove& m) {
  std::string words = "G64";
  if (m.exact_stop) {
    words = "G61";
  } else if (m.path_tolerance_mm > 0.0 && std::isfinite(m.path_tolerance_mm)) {
    words += " P" + positive_mm_number(m.path_tolerance_mm);
  }
  if (words == path_control_) return;
  path_control_ = std::move(words);
  out_ += path_control_;
  out_ += '\n';
}

std::string GcodeProgramWriter::plane_change(Plane plane) {
  if (plane == plane_) return {};
  plane_ = plane;
  return std::string(writer_plane_code(plane)) + ' ';
}

// A value for which 0 means something else (F0 is no feed, G64 P0 no limit) keeps its digits when the
// requested decimals would round it to zero.
std::string GcodeProgramWriter::positive_mm_number(double value) const {
  std::string text = gcode::fixed_number(value, options_.decimals_mm);
  if (gcode::number_value(text) > 0.0) return text;
  return gcode::exact_number(value).value_or(text);
}

Status GcodeProgramWriter::check(const CanonicalMove& m) const {
  if (m.orientation == OrientationSource::tool_axis)
    return error(ErrorCode::unsupported, m,
                 "the tool orientation is a tool-axis vector; G-code needs A B C angles (not supported)");
  if (m.tool_length_mm != 0.0)
    return error(ErrorCode::unsupported, m,
                 fmt::format("tool length offset {} mm (G43): writing G-code with tool length offsets is "
                             "not supported",
                             m.tool_length_mm));
  if (!m.end_mm.allFinite() || !m.end_abc_deg.allFinite() ||
      (m.kind == MoveKind::arc && (!m.center_mm.allFinite() || !m.normal.allFinite())))
    return error(ErrorCode::bad_input, m, "a coordinate is not a finite number");
  return ok_status();
}

Status GcodeProgramWriter::write_dwell(const CanonicalMove& m) {
  const std::optional<std::string> seconds =
      m.dwell_s >= 0.0 ? gcode::exact_number(m.dwell_s) : std::optional<std::string>();
  if (!seconds)
    return error(ErrorCode::bad_input, m, fmt::format("dwell of {} s cannot be written", m.dwell_s));
  out_ += plane_change(m.plane);
  out_ += "G4 P";
  out_ += *seconds;
  end_line(m.line);
  return ok_status();
}

Status GcodeProgramWriter::write_motion(const CanonicalMove& m) {
  static constexpr char kLinearAxes[3] = {'X', 'Y', 'Z'};
  static constexpr char kRotaryAxes[3] = {'A', 'B', 'C'};
  std::string words;
  Eigen::Vector3d end_mm;  // as the reader will read it
  for (int i = 0; i < 3; ++i) {
    const std::string text = gcode::fixed_number(m.end_mm[i], options_.decimals_mm);
    fmt::format_to(std::back_inserter(words), " {}{}", kLinearAxes[i], text);
    end_mm[i] = gcode::number_value(text);
  }
  for (int i = 0; i < 3; ++i)
    fmt::format_to(std::back_inserter(words), " {}{}", kRotaryAxes[i],
                   gcode::fixed_number(m.end_abc_deg[i], options_.decimals_deg));

  Plane plane = m.plane;
  const char* motion = m.kind == MoveKind::rapid ? "G0" : "G1";
  if (m.kind == MoveKind::arc) {
    if (auto arc = write_arc_words(m, end_mm, plane, motion, words); !arc) return arc;
  }
  std::string codes = plane_change(plane);
  if (auto fed = write_feed_words(m, codes, words); !fed) return fed;
  out_ += codes;
  out_ += motion;
  out_ += words;
  end_line(m.line);
  position_mm_ = end_mm;
  canonical_position_mm_ = m.end_mm;
  return ok_status();
}

Status GcodeProgramWriter::write_arc_words(const CanonicalMove& m, const Eigen::Vector3d& end_mm,
                                           Plane& plane, const char*& motion, std::string& words) const {
  static constexpr char kOffsetLetters[3] = {'I', 'J', 'K'};
  const double length = m.normal.norm();
  int axis = 2;
  if (length > 0.0) m.normal.cwiseAbs().maxCoeff(&axis);
  const Eigen::Vector3d unit = length > 0.0 ? Eigen::Vector3d(m.normal / length) : Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (length == 0.0 || (i != axis && std::abs(unit[i]) > kWriterAxisTolerance))
      return error(
          ErrorCode::unsupported, m,
          fmt::format("arc about the axis ({:.6f}, {:.6f}, {:.6f}) is not in the XY, XZ or YZ plane; "
                      "G2/G3 cannot describe it",
                      m.normal.x(), m.normal.y(), m.normal.z()));
  }
  if (m.turns < 1) return error(ErrorCode::bad_input, m, fmt::format("arc with {} turns", m.turns));
  plane = axis == 2 ? Plane::xy : (axis == 1 ? Plane::zx : Plane::yz);
  const bool counter_clockwise = unit[axis] > 0.0;
  motion = counter_clockwise ? "G3" : "G2";

  // Centre offsets from the start as the reader has it (G91.1), so that its centre is start + offset.
  const gcode::PlaneAxes axes = gcode::axes_of(plane);
  Eigen::Vector3d centre_mm = position_mm_;
  for (int i = 0; i < 3; ++i) {
    if (i == axes.normal) continue;  // in I J K order, not the plane's (K before I in G18)
    const std::string text = gcode::fixed_number(m.center_mm[i] - position_mm_[i], options_.decimals_mm);
    fmt::format_to(std::back_inserter(words), " {}{}", kOffsetLetters[i], text);
    centre_mm[i] = position_mm_[i] + gcode::number_value(text);
  }
  if (m.turns > 1) fmt::format_to(std::back_inserter(words), " P{}", m.turns);

  // The arc as the reader will see it: a spiral must stay within its radius tolerance (always G21's, as the
  // program is in mm), and rounding must not move the end across the start.
  CanonicalMove written = m;
  written.end_mm = end_mm;
  written.center_mm = centre_mm;
  written.plane = plane;
  written.normal = gcode::plane_normal(plane) * (counter_clockwise ? 1.0 : -1.0);
  const gcode::ArcProblem problem =
      gcode::check_centre_arc(position_mm_, end_mm, centre_mm, plane, gcode::arc_tolerances(false));
  if (!problem.message.empty())
    return error(ErrorCode::bad_input, m,
                 fmt::format("the arc written with {} decimals would not be read back: {}",
                             options_.decimals_mm, problem.message));
  CanonicalMove stated = m;
  stated.plane = plane;
  const double sweep_rad = gcode::arc_sweep_rad(canonical_position_mm_, stated);
  const double written_sweep_rad = gcode::arc_sweep_rad(position_mm_, written);
  if (std::abs(written_sweep_rad - sweep_rad) > kWriterSweepChangeRad)
    return error(
        ErrorCode::bad_input, m,
        fmt::format("the arc sweeps {:.6f}°, but written with {} decimals it would sweep {:.6f}° (its end "
                    "is too close to its start); write more decimals",
                    sweep_rad * 180.0 / std::numbers::pi, options_.decimals_mm,
                    written_sweep_rad * 180.0 / std::numbers::pi));
  return ok_status();
}

Status GcodeProgramWriter::write_feed_words(const CanonicalMove& m, std::string& codes, std::string& words) {
  if (m.kind == MoveKind::rapid) return ok_status();  // rapids move at the machine's speed in G93 and G94
  if (m.inverse_time) {
    const std::optional<std::string> rate = m.inverse_time_per_min > 0.0
                                                ? gcode::exact_number(m.inverse_time_per_min)
                                                : std::optional<std::string>();
    if (!rate)
      return error(ErrorCode::bad_input, m,
                   fmt::format("inverse-time feed {} /min cannot be written", m.inverse_time_per_min));
    if (!inverse_time_) {
      codes += "G93 ";
      inverse_time_ = true;
      feed_.clear();
    }
    // G93 needs F in every feed block.
    words += " F";
    words += *rate;
    return ok_status();
  }
  if (!(m.feed_mm_min > 0.0) || !std::isfinite(m.feed_mm_min))
    return error(ErrorCode::bad_input, m, fmt::format("feed move with feed {} mm/min", m.feed_mm_min));
  if (inverse_time_) {
    codes += "G94 ";  // which clears the feed: F follows
    inverse_time_ = false;
    feed_.clear();
  }
  std::string feed = positive_mm_number(m.feed_mm_min);
  if (feed != feed_) {
    words += " F";
    words += feed;
    feed_ = std::move(feed);
  }
  return ok_status();
}

}  // namespace

Result<std::string> write_gcode(const CanonicalProgram& program, const GcodeWriteOptions& options) {
  GcodeProgramWriter writer(program, options);
  return writer.run();
}

}  // namespace pkm::program
