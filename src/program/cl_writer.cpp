#include "program/cl_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <numbers>

#include "core/rotation.hpp"

namespace pkm::program {
namespace {

Error cl_write_error(const CanonicalProgram& program, int line, std::string_view what) {
  return Error{ErrorCode::bad_input,
               fmt::format("{}:{}: cannot write as CL data: {}", program.source, line, what),
               ErrorLocation{program.source, line, 0, ""}};
}

// The unit tool axis a move states (from the tip towards the spindle, program frame).
Eigen::Vector3d move_tool_axis(const CanonicalMove& move) {
  if (move.orientation == OrientationSource::tool_axis) return move.tool_axis.normalized();
  const Eigen::Vector3d abc_rad = move.end_abc_deg * (std::numbers::pi / 180.0);
  return rotation_from_angles(AngleConvention::abc, abc_rad) * Eigen::Vector3d::UnitZ();
}

// A comment's text on one line ("$$" runs to the end of the line).
std::string comment_text(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return out;
}

}  // namespace

Result<std::string> write_cl_data(const CanonicalProgram& program, const ClWriteOptions& options) {
  if (options.decimals_mm < 0 || options.decimals_mm > 12 || options.decimals_axis < 0 ||
      options.decimals_axis > 12) {
    return make_error(ErrorCode::bad_input, "CL decimals must be 0 to 12");
  }
  std::string out;
  auto put = std::back_inserter(out);
  for (const std::string& comment : options.header_comments)
    fmt::format_to(put, "$$ {}\n", comment_text(comment));
  fmt::format_to(put, "UNITS/MM\nMULTAX/ON\n");
  const int d = options.decimals_mm;
  const int a = options.decimals_axis;
  std::size_t event = 0;
  double feed = -1.0;
  Eigen::Vector3d start = program.start_mm;
  for (const CanonicalMove& move : program.moves) {
    for (; event < program.events.size() && program.events[event].line <= move.line; ++event)
      fmt::format_to(put, "$$ {}\n", comment_text(program.events[event].what));
    const Eigen::Vector3d axis = move_tool_axis(move);
    if (!move.end_mm.allFinite() || !axis.allFinite() || !std::isfinite(move.feed_mm_min))
      return cl_write_error(program, move.line, "a value is not finite");
    if (move.tool_length_mm != 0.0)
      return cl_write_error(program, move.line, "a tool length offset (CL data is the tool tip's path)");
    if (move.kind == MoveKind::dwell) {
      fmt::format_to(put, "DELAY/{}\n", move.dwell_s);
      continue;
    }
    if (move.kind == MoveKind::rapid) {
      fmt::format_to(put, "RAPID\n");
    } else {
      if (move.inverse_time) return cl_write_error(program, move.line, "inverse-time feed (G93)");
      if (!(move.feed_mm_min > 0.0)) return cl_write_error(program, move.line, "a feed move without a feed");
      if (move.feed_mm_min != feed) {
        fmt::format_to(put, "FEDRAT/MMPM,{:.{}f}\n", move.feed_mm_min, d);
        feed = move.feed_mm_min;
      }
    }
    if (move.kind == MoveKind::arc) {
      if (move.turns != 1) return cl_write_error(program, move.line, "an arc of more than one turn");
      const Eigen::Vector3d n = move.normal.normalized();
      const Eigen::Vector3d radial = (start - move.center_mm) - n * n.dot(start - move.center_mm);
      fmt::format_to(put, "CIRCLE/{:.{}f},{:.{}f},{:.{}f},{:.{}f},{:.{}f},{:.{}f},{:.{}f}\n",
                     move.center_mm.x(), d, move.center_mm.y(), d, move.center_mm.z(), d, n.x(), a, n.y(), a,
                     n.z(), a, radial.norm(), d);
    }
    fmt::format_to(put, "GOTO/{:.{}f},{:.{}f},{:.{}f},{:.{}f},{:.{}f},{:.{}f}\n", move.end_mm.x(), d,
                   move.end_mm.y(), d, move.end_mm.z(), d, axis.x(), a, axis.y(), a, axis.z(), a);
    start = move.end_mm;
  }
  for (; event < program.events.size(); ++event)
    fmt::format_to(put, "$$ {}\n", comment_text(program.events[event].what));
  fmt::format_to(put, "FINI\n");
  return out;
}

}  // namespace pkm::program
