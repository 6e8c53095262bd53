#include "pipeline_program_arrays.hpp"

#include <limits>

#include "pipeline_support.hpp"
#include "program/move_kind_name.hpp"

namespace pkm::python {

namespace {

void append(std::vector<double>& out, const Eigen::Vector3d& v) {
  out.insert(out.end(), v.data(), v.data() + 3);
}

// The work offsets a move's `frame` index names (program/canonical_program.hpp WorkFrame).
py::list frames_list(const program::CanonicalProgram& program) {
  const auto vector = [](const Eigen::Vector3d& v) {
    return numpy_from(std::vector<double>(v.data(), v.data() + 3));
  };
  py::list frames;
  for (const program::WorkFrame& f : program.frames) {
    py::dict frame;
    frame["system"] = f.system;
    frame["g5x_mm"] = vector(f.g5x_mm);
    frame["g5x_abc_deg"] = vector(f.g5x_abc_deg);
    frame["xy_rotation_deg"] = f.xy_rotation_deg;
    frame["g92_mm"] = vector(f.g92_mm);
    frame["g92_abc_deg"] = vector(f.g92_abc_deg);
    frames.append(frame);
  }
  return frames;
}

}  // namespace

py::dict program_arrays(const program::CanonicalProgram& program) {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  const auto count = static_cast<py::ssize_t>(program.moves.size());
  std::vector<std::int32_t> line, turns, source_file, source_line, frame;
  std::vector<std::string> kind;
  std::vector<double> end_mm, program_end_mm, end_abc_deg, tool_axis, center_mm, normal, feed, inverse_time,
      dwell, tool_length, tolerance;
  std::vector<bool> exact_stop, axis_given;
  for (const program::CanonicalMove& m : program.moves) {
    line.push_back(m.line);
    source_file.push_back(m.source_file);
    source_line.push_back(m.source_line);
    frame.push_back(m.frame);
    append(program_end_mm, program::program_coordinates(program, m).end_mm);
    kind.emplace_back(program::move_kind_name(m.kind));
    append(end_mm, m.end_mm);
    append(end_abc_deg, m.end_abc_deg);
    const bool arc = m.kind == program::MoveKind::arc;
    append(center_mm, arc ? m.center_mm : Eigen::Vector3d::Constant(kNone));
    append(normal, arc ? m.normal : Eigen::Vector3d::Constant(kNone));
    turns.push_back(arc ? m.turns : 0);
    const bool by_axis = m.orientation == program::OrientationSource::tool_axis;
    axis_given.push_back(by_axis);
    append(tool_axis, by_axis ? m.tool_axis : Eigen::Vector3d::Constant(kNone));
    feed.push_back(m.feed_mm_min);
    inverse_time.push_back(m.inverse_time ? m.inverse_time_per_min : kNone);
    dwell.push_back(m.kind == program::MoveKind::dwell ? m.dwell_s : 0.0);
    tool_length.push_back(m.tool_length_mm);
    tolerance.push_back(m.path_tolerance_mm >= 0.0 ? m.path_tolerance_mm : kNone);
    exact_stop.push_back(m.exact_stop);
  }
  const auto booleans = [count](const std::vector<bool>& values) {
    py::array_t<bool> out(count);
    for (py::ssize_t i = 0; i < count; ++i) out.mutable_at(i) = values[static_cast<std::size_t>(i)];
    return out;
  };
  py::list events;
  for (const program::ProgramEvent& e : program.events) events.append(py::make_tuple(e.line, e.what));
  py::list files;
  for (const std::string& file : program.files) files.append(file);
  if (program.files.empty()) files.append(program.source);  // [0] is the program itself, as in the CLI's JSON
  py::dict out;
  out["source"] = program.source;
  out["format"] = program.format;
  out["files"] = files;
  out["line"] = numpy_from(std::move(line));
  out["source_file"] = numpy_from(std::move(source_file));
  out["source_line"] = numpy_from(std::move(source_line));
  out["frame"] = numpy_from(std::move(frame));
  out["frames"] = frames_list(program);
  out["kind"] = numpy_strings(kind);
  out["end_mm"] = numpy_from(std::move(end_mm), {count, 3});
  out["program_end_mm"] = numpy_from(std::move(program_end_mm), {count, 3});
  out["end_abc_deg"] = numpy_from(std::move(end_abc_deg), {count, 3});
  out["tool_axis_given"] = booleans(axis_given);
  out["tool_axis"] = numpy_from(std::move(tool_axis), {count, 3});
  out["center_mm"] = numpy_from(std::move(center_mm), {count, 3});
  out["normal"] = numpy_from(std::move(normal), {count, 3});
  out["turns"] = numpy_from(std::move(turns));
  out["feed_mm_min"] = numpy_from(std::move(feed));
  out["inverse_time_per_min"] = numpy_from(std::move(inverse_time));
  out["dwell_s"] = numpy_from(std::move(dwell));
  out["tool_length_mm"] = numpy_from(std::move(tool_length));
  out["path_tolerance_mm"] = numpy_from(std::move(tolerance));
  out["exact_stop"] = booleans(exact_stop);
  out["events"] = events;
  out["start_mm"] = numpy_from(std::vector<double>(program.start_mm.data(), program.start_mm.data() + 3));
  out["start_abc_deg"] =
      numpy_from(std::vector<double>(program.start_abc_deg.data(), program.start_abc_deg.data() + 3));
  out["end_line"] = program.end_line;
  return out;
}

}  // namespace pkm::python
