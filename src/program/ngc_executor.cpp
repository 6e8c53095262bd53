// The executor's run loop, the order of execution within a block, and where moves and events go.
#include "program/ngc_executor.hpp"

#include <fmt/format.h>

#include <cmath>

#include "program/ngc_block_reader.hpp"
#include "program/ngc_executor_support.hpp"
#include "program/ngc_work_offsets.hpp"

namespace pkm::program::ngc {

using namespace executor_support;

namespace {

ReaderOptions reader_options(const InterpretOptions& options) {
  ReaderOptions reader;
  reader.subroutine_path = options.subroutine_path;
  reader.block_delete = options.block_delete;
  reader.max_blocks = options.max_blocks;
  reader.max_call_depth = options.max_call_depth;
  return reader;
}

// Where to point at for an error about the block's move: its motion code, else its first axis word.
int block_motion_column(const gcode::Block& b) {
  if (b.g[gcode::g_motion].given()) return b.g[gcode::g_motion].column;
  if (const int axis = b.first_axis_column(); axis > 0) return axis;
  return 1;
}

std::string_view message_prefix(MessageKind kind) {
  switch (kind) {
    case MessageKind::msg:
      return "MSG";
    case MessageKind::debug:
      return "DEBUG";
    case MessageKind::print:
      return "PRINT";
  }
  return "MSG";
}

}  // namespace

Executor::Executor(const std::string& source, const InterpretOptions& options, std::optional<ToolTable> tools)
    : source_(source), options_(options), tools_(std::move(tools)) {}

Status Executor::run(std::string_view text, CanonicalProgram& program) {
  program_ = &program;
  // A UTF-8 byte-order mark (some Windows editors write one) is not part of the first block.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  program.source = source_;
  program.files = {source_};
  program.frames = {WorkFrame{}};
  if (!options_.parameter_file.empty()) {
    if (auto loaded = parameters_.load_var_file(options_.parameter_file); !loaded) return loaded;
  }
  if (parameters_.get(parameter::active_system) < 1.0) parameters_.set(parameter::active_system, 1.0);
  refresh_frame();
  // The tool starts where the caller says it is in the work frame; the program sees it through its offsets.
  state_.position_mm = to_program_mm(state_.frame, options_.start_mm);
  state_.abc_deg = options_.start_abc_deg - state_.frame.g5x_abc_deg - state_.frame.g92_abc_deg;
  compensation_.set_position(state_.position_mm);
  program.start_mm = options_.start_mm;
  program.start_abc_deg = options_.start_abc_deg;
  output_.attach(program, options_.move_sink);
  if (!options_.move_sink) program.moves.reserve(text.size() / 12 + 16);
  write_position_parameters();

  BlockReader reader(text, source_, reader_options(options_), parameters_, *this);
  EvaluatedBlock evaluated;
  gcode::LexedLine lexed;
  gcode::Block block;
  while (!ended_) {
    auto got = reader.next(evaluated);
    if (!got) return got.error();
    if (!*got) break;
    file_name_ = &reader.files()[static_cast<std::size_t>(evaluated.where.file)];
    line_ = evaluated.where.line;
    source_ref_ = evaluated.where;
    for (const Message& message : evaluated.messages)
      add_event(fmt::format("{}: {}", message_prefix(message.kind), message.text));
    if (evaluated.words.empty()) continue;
    lexed.words.swap(evaluated.words);
    if (auto built = gcode::build_block(lexed, where(), block); !built) return built.error();
    motion_column_ = block_motion_column(block);
    lexed.words.swap(evaluated.words);
    if (auto executed = execute(block); !executed) return executed.error();
    write_position_parameters();
  }
  if (auto flushed = flush_compensation(); !flushed) return flushed;
  if (auto handed = output_.flush(); !handed) return handed;
  program.files = reader.files();
  program.end_line = reader.main_line();
  if (options_.write_parameter_file && !options_.parameter_file.empty())
    return parameters_.save_var_file(options_.parameter_file);
  return ok_status();
}

Status Executor::execute(const gcode::Block& b) {
  const gcode::Code& motion_code = b.g[gcode::g_motion];
  const int motion = motion_code.given() ? motion_code.number : state_.motion;
  const bool arc_words = b['I'].given() || b['J'].given() || b['K'].given() || b['R'].given();
  const bool axis_users = codes_take_axis_words(b);
  // A block moves when it names a motion code, or has axis words no G10/G28/G30/G52/G92/G43.1 takes, or
  // gives arc data to a modal G2/G3.
  const bool moves = motion != 800 && (motion_code.given() || (b.first_axis_column() > 0 && !axis_users) ||
                                       ((motion == 20 || motion == 30) && arc_words));
  if (auto checked = check_words(b, motion, moves); !checked) return checked;
  if (auto read = read_feed_and_speed(b); !read) return read;
  if (auto tools = tools_and_spindle(b); !tools) return tools;
  machine_functions(b);
  if (b.g[gcode::g_non_modal].is(40)) {
    const gcode::Value& p = b['P'];
    if (p.value < 0.0) return gcode::error_at(where(), p.column, "negative dwell time P");
    dwell(p.value);
  }
  if (auto planed = set_plane_and_compensation(b); !planed) return planed;
  if (b.g[gcode::g_tool_length].given()) {
    if (auto set = set_tool_length(b); !set) return set;
  }
  if (auto system = set_coordinate_system(b); !system) return system;
  if (auto path = set_path_control(b); !path) return path;
  if (const gcode::Code& distance = b.g[gcode::g_distance]; distance.given())
    state_.incremental = distance.is(910);
  if (const gcode::Code& arc_distance = b.g[gcode::g_arc_distance]; arc_distance.given())
    state_.arc_centre_incremental = arc_distance.is(911);
  if (const gcode::Code& retract = b.g[gcode::g_retract]; retract.given())
    state_.retract_to_r = retract.is(990);
  if (auto other = non_modal(b); !other) return other;
  if (is_cycle(state_.motion) && !is_cycle(motion)) cycle_memory_ = CycleMemory{};
  state_.motion = motion;
  if (moves) {
    if (auto moved = this->motion(b, motion); !moved) return moved;
  }
  return stop(b);
}

CanonicalMove Executor::new_move(MoveKind kind) const {
  CanonicalMove m;
  m.kind = kind;
  m.line = source_ref_.call_line > 0 ? source_ref_.call_line : line_;
  m.source_file = source_ref_.file;
  m.source_line = line_;
  m.frame = state_.frame_index;
  m.plane = state_.plane;
  m.tool_length_mm = state_.tool_length_mm;
  m.path_tolerance_mm = state_.path_tolerance_mm;
  m.exact_stop = state_.exact_stop;
  m.end_mm = state_.position_mm;
  m.end_abc_deg = state_.abc_deg;
  return m;
}

Status Executor::emit(const CanonicalMove& m) {
  compensated_.clear();
  if (auto passed = compensation_.move(m, where(), motion_column_, compensated_); !passed) return passed;
  return append_compensated();
}

Status Executor::flush_compensation() {
  compensated_.clear();
  if (auto flushed = compensation_.flush(compensated_, where(), motion_column_); !flushed) return flushed;
  return append_compensated();
}

// What compensation let out, from program coordinates into the work frame of each move.
Status Executor::append_compensated() {
  for (CanonicalMove& out : compensated_) {
    if (out.frame != 0) move_to_work(program_->frames[static_cast<std::size_t>(out.frame)], out);
    if (Status taken = output_.push(out); !taken) return taken;
  }
  return ok_status();
}

void Executor::add_event(std::string what) {
  ProgramEvent e;
  e.line = source_ref_.call_line > 0 ? source_ref_.call_line : line_;
  e.what = std::move(what);
  e.source_file = source_ref_.file;
  e.source_line = line_;
  program_->events.push_back(std::move(e));
}

// The frame follows the parameters: after G10, G92 and G54… the executor re-reads them. An unchanged frame
// keeps its index, so a program without offsets stays in frame 0 (no transform at all).
void Executor::refresh_frame() {
  const WorkFrame frame = read_work_frame(parameters_);
  auto same = [](const WorkFrame& a, const WorkFrame& b) {
    return a.system == b.system && a.g5x_mm == b.g5x_mm && a.g5x_abc_deg == b.g5x_abc_deg &&
           a.xy_rotation_deg == b.xy_rotation_deg && a.g92_mm == b.g92_mm && a.g92_abc_deg == b.g92_abc_deg;
  };
  if (same(frame, state_.frame)) return;
  state_.frame = frame;
  if (frame.identity() && frame.system == 1) {
    state_.frame_index = 0;
    return;
  }
  if (state_.frame_index != 0 && same(program_->frames[static_cast<std::size_t>(state_.frame_index)], frame))
    return;
  program_->frames.push_back(frame);
  state_.frame_index = static_cast<int>(program_->frames.size()) - 1;
}

// After an offset changes, the tool has not moved: its program coordinates change instead (LinuxCNC moves the
// current point by the change of offset).
void Executor::reframe() {
  const Eigen::Vector3d work_mm = to_work_mm(state_.frame, state_.position_mm);
  const Eigen::Vector3d work_abc_deg = state_.abc_deg + state_.frame.g5x_abc_deg + state_.frame.g92_abc_deg;
  refresh_frame();
  state_.position_mm = to_program_mm(state_.frame, work_mm);
  state_.abc_deg = work_abc_deg - state_.frame.g5x_abc_deg - state_.frame.g92_abc_deg;
  compensation_.set_position(state_.position_mm);
}

void Executor::write_position_parameters() {
  const double unit = state_.mm_per_unit();
  for (int i = 0; i < 3; ++i) {
    parameters_.set(parameter::position + i, state_.position_mm[i] / unit);
    parameters_.set(parameter::position + 3 + i, state_.abc_deg[i]);
  }
}

}  // namespace pkm::program::ngc
