// APT CL data reader: statements -> canonical moves and events. See docs/cl-data.md for what each statement
// means here; the syntax is split off in cl_lexer, the CIRCLE geometry in cl_arc, the handlers in the
// cl_reader_*.cpp files (cl_reader_state.hpp lists them).
//
// Rules worth knowing (APT conventions, as the CAM systems write them):
//  - RAPID applies to the next motion only; a CIRCLE record applies to the next GOTO only (its end point).
//  - A GOTO with three values keeps the last tool axis (TLAXIS or the previous GOTO's; (0,0,1) at first).
//  - Points are written in the CL frame; MSYS/CSYS/TRNTYP give the frame, and the moves are turned into the
//    part frame unless the user keeps the CL frame (InterpretOptions::apply_cl_transforms).
//  - END or FINI ends the program; what follows is not read.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <utility>

#include "program/cl_number.hpp"
#include "program/cl_reader_cutcom.hpp"
#include "program/cl_reader_cycle.hpp"
#include "program/cl_reader_nurbs.hpp"
#include "program/cl_reader_state.hpp"

namespace pkm::program {
namespace {

enum class ClWord {
  go_to,
  from,
  gohome,
  rapid,
  fedrat,
  tlaxis,
  units,
  multax,
  circle,
  end,
  spindl,
  delay,
  cutcom,
  opskip,
  cycle,
  cutter,
  msys,
  csys,
  trntyp,
  rotabl,
  nurbs,
  event,  // recorded with its line, no effect on the motion
};

const ClWord* find_cl_word(std::string_view word) {
  // GOTO first: it is nearly every statement of a real file.
  static constexpr std::array<std::pair<std::string_view, ClWord>, 54> words = {{
      {"GOTO", ClWord::go_to},        {"FEDRAT", ClWord::fedrat},     {"RAPID", ClWord::rapid},
      {"CIRCLE", ClWord::circle},     {"TLAXIS", ClWord::tlaxis},     {"FROM", ClWord::from},
      {"GOHOME", ClWord::gohome},     {"UNITS", ClWord::units},       {"UNIT", ClWord::units},
      {"MULTAX", ClWord::multax},     {"END", ClWord::end},           {"FINI", ClWord::end},
      {"SPINDL", ClWord::spindl},     {"DELAY", ClWord::delay},       {"CUTCOM", ClWord::cutcom},
      {"OPSKIP", ClWord::opskip},     {"CYCLE", ClWord::cycle},       {"CUTTER", ClWord::cutter},
      {"TLDATA", ClWord::cutter},     {"MSYS", ClWord::msys},         {"CSYS", ClWord::csys},
      {"TRNTYP", ClWord::trntyp},     {"ROTABL", ClWord::rotabl},     {"NURBS", ClWord::nurbs},
      {"COOLNT", ClWord::event},      {"LOADTL", ClWord::event},      {"LOAD", ClWord::event},
      {"TOOL PATH", ClWord::event},   {"END-OF-PATH", ClWord::event}, {"PARTNO", ClWord::event},
      {"PPRINT", ClWord::event},      {"INSERT", ClWord::event},      {"TPRINT", ClWord::event},
      {"MACHIN", ClWord::event},      {"SELECT", ClWord::event},      {"CLEARP", ClWord::event},
      {"PAINT", ClWord::event},       {"OPSTOP", ClWord::event},      {"STOP", ClWord::event},
      {"SETUP", ClWord::event},       {"OPFEATSTART", ClWord::event}, {"OPFEATEND", ClWord::event},
      {"MOVE_ATTRIB", ClWord::event}, {"BOX", ClWord::event},         {"TOOLNO", ClWord::event},
      {"AUTOPS", ClWord::event},      {"MODE", ClWord::event},        {"OPERATION", ClWord::event},
      {"TLON", ClWord::event},        {"INDIRV", ClWord::event},      {"SEQNO", ClWord::event},
      {"ORIGIN", ClWord::event},      {"HEAD", ClWord::event},        {"FINISH", ClWord::event},
  }};
  for (const auto& [name, kind] : words) {
    if (name == word) return &kind;
  }
  return nullptr;
}

// APT source statements that move the tool along surfaces (CATIA writes some into its "APT" output):
// TLON,GOFWD/(CIRCLE/…),ON,(LINE/…) and the like need the geometry engine of an APT processor.
bool is_part_surface_motion(std::string_view word) {
  for (const std::string_view w :
       {"TLON", "TLLFT", "TLRGT", "GOFWD", "GOLFT", "GORGT", "GOBACK", "GOUP", "GODOWN", "PSIS", "GO"}) {
    if (word.starts_with(w) && (word.size() == w.size() || word[w.size()] == ',')) return true;
  }
  return false;
}

// NX writes its own annotations as CSI_SET_… statements; pkm keeps them as events.
bool is_nx_annotation(std::string_view word) {
  return word.starts_with("CSI_");
}

}  // namespace

bool cl_equals_upper(std::string_view text, std::string_view upper_word) {
  return text.size() == upper_word.size() && std::equal(text.begin(), text.end(), upper_word.begin(),
                                                        [](char a, char b) { return ascii_upper(a) == b; });
}

bool cl_starts_like_word(std::string_view text) {
  return !text.empty() &&
         ((text.front() >= 'A' && text.front() <= 'Z') || (text.front() >= 'a' && text.front() <= 'z'));
}

ClReader::ClReader(const std::string& source, const InterpretOptions& options, ProgramFormat dialect,
                   int line_count)
    : source_(source),
      block_delete_(options.block_delete),
      apply_transforms_(options.apply_cl_transforms),
      dialect_(dialect) {
  program_.source = source;
  program_.format = std::string(program_format_name(dialect));
  program_.start_mm = options.start_mm;
  program_.start_abc_deg = options.start_abc_deg;
  output_.attach(program_, options.move_sink);
  if (!options.move_sink)
    program_.moves.reserve(static_cast<std::size_t>(line_count));  // about one move per statement
  position_ = options.start_mm;
  initial_mm_ = options.start_mm;
  emitted_end_mm_ = options.start_mm;
}

ClReader::~ClReader() = default;

Status ClReader::apply(const ClStatement& s) {
  if (!output_.status()) return output_.status();  // whoever takes the moves gave up
  if (s.is_comment) {
    if (!skipping_ && !s.text.empty()) program_.events.push_back({s.at.line, "$$ " + std::string(s.text)});
    return ok_status();
  }
  if (s.word.empty() && !s.has_slash) return ok_status();  // a lone '$'
  if (nurbs_collecting()) {
    bool consumed = false;
    if (auto status = nurbs_continue(s, consumed); !status || consumed) return status;
  }
  const ClWord* kind = find_cl_word(s.word);
  // Of Pro/CLfile's "$$->" statements only the frame and the cutter concern the motion ("$$-> END /" ends
  // a feature, not the program).
  const bool read_annotation = kind != nullptr && (*kind == ClWord::csys || *kind == ClWord::cutter);
  if (s.is_annotation && !read_annotation) return annotation(s);
  if (kind == nullptr && is_nx_annotation(s.word)) return annotation(s);
  if (kind == nullptr && is_part_surface_motion(s.word)) {
    return error_at(s.at, fmt::format("'{}' is APT part-program motion (drive and check surfaces), not CL "
                                      "data: output the CAM program as CL records (GOTO, CIRCLE)",
                                      std::string_view(s.word).substr(0, 40)));
  }
  if (kind == nullptr) {
    const std::string_view shown = std::string_view(s.word).substr(0, 40);
    return error_at(s.at, fmt::format("unknown statement '{}'", shown));
  }
  if (skipping_ && *kind != ClWord::opskip && *kind != ClWord::end) return ok_status();
  switch (*kind) {
    case ClWord::go_to:
      return go_to(s);
    case ClWord::from:
      return from(s);
    case ClWord::gohome:
      return gohome(s);
    case ClWord::rapid:
      return rapid(s);
    case ClWord::fedrat:
      return fedrat(s);
    case ClWord::tlaxis:
      return tlaxis(s);
    case ClWord::units:
      return units(s);
    case ClWord::multax:
      return multax(s);
    case ClWord::circle:
      return circle(s);
    case ClWord::end:
      return end(s);
    case ClWord::spindl:
      return spindl(s);
    case ClWord::delay:
      return delay(s);
    case ClWord::cutcom:
      return cutcom(s);
    case ClWord::opskip:
      return opskip(s);
    case ClWord::cycle:
      return cycle(s);
    case ClWord::cutter:
      return cutter(s);
    case ClWord::msys:
      return msys(s);
    case ClWord::csys:
      return csys(s);
    case ClWord::trntyp:
      return trntyp(s);
    case ClWord::rotabl:
      return rotabl(s);
    case ClWord::nurbs:
      return nurbs(s);
    case ClWord::event:
      record_event(s);
      return ok_status();
  }
  return ok_status();
}

Result<CanonicalProgram> ClReader::finish(int line_count) {
  if (circle_) return error_at(circle_at_, "CIRCLE is not followed by the GOTO to its end point");
  const ClPosition last{ended_ ? program_.end_line : line_count, 1};
  if (nurbs_collecting()) {
    if (auto status = nurbs_finish(last); !status) return status.error();
  }
  if (auto status = flush_compensation(last); !status) return status.error();
  if (!ended_) program_.end_line = line_count;
  note_arc_directions();
  if (Status handed = output_.flush(); !handed) return handed.error();
  return std::move(program_);
}

// What the arc checks found, for the user (pkm interpret prints notes; plan adds them to its warnings).
void ClReader::note_arc_directions() {
  if (longer_arcs_ > 0) {
    add_note(
        fmt::format("{} arc(s) of more than 180° taken the long way round: SolidWorks CAM writes the "
                    "axis of the shorter arc, and the longer one continues the move before it",
                    longer_arcs_));
  }
  if (reversed_arc_lines_.empty()) return;
  std::string lines;
  for (std::size_t i = 0; i < reversed_arc_lines_.size() && i < 10; ++i)
    lines += fmt::format("{}{}", i == 0 ? "" : ", ", reversed_arc_lines_[i]);
  if (reversed_arc_lines_.size() > 10) lines += fmt::format(" and {} more", reversed_arc_lines_.size() - 10);
  add_note(
      fmt::format("warning: {} arc(s) start against the direction of the move before them (lines {}): "
                  "read as {}, whose CIRCLE turns {} about its axis; if that is not the CAM system "
                  "that wrote the file, give --format",
                  reversed_arc_lines_.size(), lines, program_format_name(dialect_),
                  dialect_ == ProgramFormat::nx ? "clockwise" : "counter-clockwise"));
}

Error ClReader::error_at(ClPosition at, std::string_view message) const {
  return Error{ErrorCode::bad_input, fmt::format("{}:{}:{}: {}", source_, at.line, at.column, message),
               ErrorLocation{source_, at.line, at.column, ""}};
}

Status ClReader::number(const ClArg& arg, double& out) const {
  if (const auto value = parse_cl_number(arg.text)) {
    out = *value;
    return ok_status();
  }
  if (arg.text.empty()) return error_at(arg.at, "missing value");
  return error_at(arg.at, fmt::format("bad number '{}'", arg.text));
}

Status ClReader::numbers(const ClStatement& s, std::size_t first, std::size_t count, double* out) const {
  for (std::size_t i = 0; i < count; ++i) {
    if (auto status = number(s.args[first + i], out[i]); !status) return status;
  }
  return ok_status();
}

Status ClReader::unit_vector(const ClStatement& s, std::size_t first, Eigen::Vector3d& out) const {
  std::array<double, 3> v{};
  if (auto status = numbers(s, first, 3, v.data()); !status) return status;
  const Eigen::Vector3d axis(v[0], v[1], v[2]);
  const double norm = axis.norm();
  if (!(norm > 1e-9)) return error_at(s.args[first].at, "the axis vector (i,j,k) has zero length");
  out = axis / norm;
  return ok_status();
}

Status ClReader::no_values(const ClStatement& s) const {
  if (s.args.empty()) return ok_status();
  return error_at(s.args.front().at, fmt::format("{} takes no values", s.word));
}

Status ClReader::not_after_circle(const ClStatement& s) const {
  if (!circle_) return ok_status();
  return error_at(s.at, fmt::format("{} between CIRCLE (line {}) and the GOTO to its end point", s.word,
                                    circle_at_.line));
}

// "LOADTL/1", "COOLNT/ON", "PPRINT free text": word and values in upper case, free text as written.
void ClReader::record_event(const ClStatement& s) {
  std::string what = s.word;
  if (s.is_text) {
    if (!s.text.empty()) {
      what += ' ';
      what += s.text;
    }
  } else if (s.has_slash) {
    what += '/';
    for (std::size_t i = 0; i < s.args.size(); ++i) {
      if (i > 0) what += ',';
      for (const char c : s.args[i].text) what += ascii_upper(c);
    }
  }
  program_.events.push_back({s.at.line, std::move(what)});
}

void ClReader::add_note(std::string note) {
  if (std::find(program_.notes.begin(), program_.notes.end(), note) == program_.notes.end())
    program_.notes.push_back(std::move(note));
}

CanonicalMove ClReader::move_to(const ClStatement& s, MoveKind kind, const Eigen::Vector3d& end_mm) const {
  CanonicalMove move;
  move.line = s.at.line;
  move.source_line = s.at.line;
  move.kind = kind;
  move.end_mm = end_mm;
  move.orientation = OrientationSource::tool_axis;
  move.tool_axis = axis_;
  return move;
}

Status ClReader::set_feed(const ClStatement& s, CanonicalMove& move) const {
  if (!feed_) return error_at(s.at, "cutting move before any feed rate (FEDRAT)");
  move.feed_mm_min = feed_per_rev_ ? *feed_ * spindle_rpm_ : *feed_;
  if (feed_per_rev_) move.feed_per_revolution_mm = *feed_;
  return ok_status();
}

Status ClReader::emit(const CanonicalMove& move, ClPosition at) {
  remember_direction(move, emitted_end_mm_);
  emitted_end_mm_ = move.end_mm;
  if (!cutcom_active()) {
    output(move);
    return ok_status();
  }
  scratch_.clear();
  if (auto status = compensated(move, at, scratch_); !status) return status;
  for (const CanonicalMove& m : scratch_) output(m);
  return ok_status();
}

// Into the part frame: points by the whole transform, directions by its rotation only.
void ClReader::output(CanonicalMove move) {
  if (apply_transforms_) {
    const Eigen::Matrix3d r = transform_.linear();
    move.end_mm = transform_ * move.end_mm;
    move.center_mm = transform_ * move.center_mm;
    move.normal = r * move.normal;
    move.tool_axis = r * move.tool_axis;
    if (move.kind == MoveKind::arc) move.plane = cl_nearest_plane(move.normal);
  }
  (void)output_.push(move);  // a sink's error stops the reading at the next statement
}

}  // namespace pkm::program

namespace pkm::program {

Result<CanonicalProgram> read_cl_data(std::string_view text, const std::string& source_name,
                                      const InterpretOptions& options) {
  ProgramFormat dialect = options.format;
  if (!is_cl_format(dialect)) {  // automatic, or G-code asked of the CL reader: the CAM system from the text
    dialect = detect_program_format(text);
    if (!is_cl_format(dialect)) dialect = ProgramFormat::apt;
  }
  ClLexer lexer(text);
  const int line_count = lexer.line_count();
  ClReader reader(source_name, options, dialect, line_count);
  ClStatement statement;
  statement.args.reserve(16);
  while (!reader.ended() && lexer.next(statement)) {
    if (auto status = reader.apply(statement); !status) return status.error();
  }
  return reader.finish(line_count);
}

}  // namespace pkm::program
