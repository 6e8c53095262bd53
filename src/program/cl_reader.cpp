// APT CL data reader: statements -> canonical moves and events. See docs/cl-data.md for what each statement
// means here; the syntax is split off in cl_lexer, the CIRCLE geometry in cl_arc.
//
// Rules worth knowing (APT / NX CLSF conventions):
//  - RAPID applies to the next motion only; a CIRCLE record applies to the next GOTO only (its end point).
//  - A GOTO with three values keeps the last tool axis (TLAXIS or the previous GOTO's; (0,0,1) at first).
//  - FROM before any motion sets the start point; a later FROM is a rapid to that point.
//  - UNITS/INCHES scales every following length and per-minute feed to mm.
//  - OPSKIP/ON ... OPSKIP/OFF marks statements for the block-delete switch (InterpretOptions::block_delete).
//  - END or FINI ends the program; what follows is not read.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <optional>

#include "program/cl_arc.hpp"
#include "program/cl_lexer.hpp"
#include "program/cl_number.hpp"
#include "program/part_program.hpp"

namespace pkm::program {
namespace {

constexpr double kClMmPerInch = 25.4;

enum class Word {
  go_to,
  from,
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
  event,  // recorded with its line, no effect on the motion
};

Word const* find_word(std::string_view word) {
  // GOTO first: it is nearly every statement of a real file.
  static constexpr std::array<std::pair<std::string_view, Word>, 31> words = {{
      {"GOTO", Word::go_to},    {"FEDRAT", Word::fedrat},   {"RAPID", Word::rapid},
      {"CIRCLE", Word::circle}, {"TLAXIS", Word::tlaxis},   {"FROM", Word::from},
      {"UNITS", Word::units},   {"MULTAX", Word::multax},   {"END", Word::end},
      {"FINI", Word::end},      {"SPINDL", Word::spindl},   {"DELAY", Word::delay},
      {"CUTCOM", Word::cutcom}, {"OPSKIP", Word::opskip},   {"COOLNT", Word::event},
      {"LOADTL", Word::event},  {"LOAD", Word::event},      {"CUTTER", Word::event},
      {"TLDATA", Word::event},  {"TOOL PATH", Word::event}, {"END-OF-PATH", Word::event},
      {"PARTNO", Word::event},  {"PPRINT", Word::event},    {"INSERT", Word::event},
      {"TPRINT", Word::event},  {"MACHIN", Word::event},    {"SELECT", Word::event},
      {"CLEARP", Word::event},  {"MSYS", Word::event},      {"PAINT", Word::event},
      {"OPSTOP", Word::event},
  }};
  for (const auto& [name, kind] : words) {
    if (name == word) return &kind;
  }
  return nullptr;
}

bool equals_upper(std::string_view text, std::string_view upper_word) {
  return text.size() == upper_word.size() && std::equal(text.begin(), text.end(), upper_word.begin(),
                                                        [](char a, char b) { return ascii_upper(a) == b; });
}

bool starts_like_word(std::string_view text) {
  return !text.empty() &&
         ((text.front() >= 'A' && text.front() <= 'Z') || (text.front() >= 'a' && text.front() <= 'z'));
}

class ClReader {
 public:
  ClReader(const std::string& source, const InterpretOptions& options, int line_count)
      : source_(source), block_delete_(options.block_delete) {
    program_.source = source;
    program_.start_mm = options.start_mm;
    program_.start_abc_deg = options.start_abc_deg;
    program_.moves.reserve(static_cast<std::size_t>(line_count));  // at most one move per statement
    position_ = options.start_mm;
  }

  bool ended() const { return ended_; }

  Status apply(const ClStatement& s) {
    if (s.word.empty() && !s.has_slash) return ok_status();  // a lone '$'
    const Word* kind = find_word(s.word);
    if (kind == nullptr) {
      const std::string_view shown = std::string_view(s.word).substr(0, 40);
      return error_at(s.at, fmt::format("unknown statement '{}'", shown));
    }
    if (skipping_ && *kind != Word::opskip && *kind != Word::end) return ok_status();
    switch (*kind) {
      case Word::go_to:
        return go_to(s);
      case Word::from:
        return from(s);
      case Word::rapid:
        return rapid(s);
      case Word::fedrat:
        return fedrat(s);
      case Word::tlaxis:
        return tlaxis(s);
      case Word::units:
        return units(s);
      case Word::multax:
        return multax(s);
      case Word::circle:
        return circle(s);
      case Word::end:
        return end(s);
      case Word::spindl:
        return spindl(s);
      case Word::delay:
        return delay(s);
      case Word::cutcom:
        return cutcom(s);
      case Word::opskip:
        return opskip(s);
      case Word::event:
        record_event(s);
        return ok_status();
    }
    return ok_status();
  }

  Result<CanonicalProgram> finish(int line_count) {
    if (circle_) return error_at(circle_at_, "CIRCLE is not followed by the GOTO to its end point");
    if (!ended_) program_.end_line = line_count;
    return std::move(program_);
  }

 private:
  Error error_at(ClPosition at, std::string_view message) const {
    return Error{ErrorCode::bad_input, fmt::format("{}:{}:{}: {}", source_, at.line, at.column, message),
                 ErrorLocation{source_, at.line, at.column, ""}};
  }

  Status number(const ClArg& arg, double& out) const {
    if (const auto value = parse_cl_number(arg.text)) {
      out = *value;
      return ok_status();
    }
    if (arg.text.empty()) return error_at(arg.at, "missing value");
    return error_at(arg.at, fmt::format("bad number '{}'", arg.text));
  }

  Status numbers(const ClStatement& s, std::size_t first, std::size_t count, double* out) const {
    for (std::size_t i = 0; i < count; ++i) {
      if (auto status = number(s.args[first + i], out[i]); !status) return status;
    }
    return ok_status();
  }

  // A tool axis or circle axis from three numbers starting at args[first], normalised.
  Status unit_vector(const ClStatement& s, std::size_t first, Eigen::Vector3d& out) const {
    std::array<double, 3> v{};
    if (auto status = numbers(s, first, 3, v.data()); !status) return status;
    const Eigen::Vector3d axis(v[0], v[1], v[2]);
    const double norm = axis.norm();
    if (!(norm > 1e-9)) return error_at(s.args[first].at, "the axis vector (i,j,k) has zero length");
    out = axis / norm;
    return ok_status();
  }

  // GOTO/FROM: x,y,z in program units, optionally i,j,k.
  Status point(const ClStatement& s, Eigen::Vector3d& out) {
    const std::size_t n = s.args.size();
    if (n != 3 && n != 6) {
      return error_at(s.at, fmt::format("{} takes 3 values (x,y,z) or 6 (x,y,z,i,j,k), got {}", s.word, n));
    }
    std::array<double, 3> v{};
    if (auto status = numbers(s, 0, 3, v.data()); !status) return status;
    if (n == 6) {
      if (auto status = unit_vector(s, 3, axis_); !status) return status;
    }
    out = scale_ * Eigen::Vector3d(v[0], v[1], v[2]);
    return ok_status();
  }

  CanonicalMove move_to(const ClStatement& s, MoveKind kind, const Eigen::Vector3d& end_mm) const {
    CanonicalMove move;
    move.line = s.at.line;
    move.kind = kind;
    move.end_mm = end_mm;
    move.orientation = OrientationSource::tool_axis;
    move.tool_axis = axis_;
    return move;
  }

  Status set_feed(const ClStatement& s, CanonicalMove& move) const {
    if (!feed_) return error_at(s.at, "cutting move before any feed rate (FEDRAT)");
    move.feed_mm_min = feed_per_rev_ ? *feed_ * spindle_rpm_ : *feed_;
    return ok_status();
  }

  Status not_after_circle(const ClStatement& s) const {
    if (!circle_) return ok_status();
    return error_at(s.at, fmt::format("{} between CIRCLE (line {}) and the GOTO to its end point", s.word,
                                      circle_at_.line));
  }

  Status go_to(const ClStatement& s) {
    Eigen::Vector3d end_mm;
    if (auto status = point(s, end_mm); !status) return status;
    CanonicalMove move = move_to(s, rapid_next_ ? MoveKind::rapid : MoveKind::line, end_mm);
    if (circle_) {
      if (rapid_next_) return error_at(s.at, "RAPID cannot apply to a circular move (CIRCLE)");
      if (const std::string why = make_cl_arc(*circle_, position_, move); !why.empty())
        return error_at(s.at, why);
      circle_.reset();
    }
    if (move.kind != MoveKind::rapid) {
      if (auto status = set_feed(s, move); !status) return status;
    }
    rapid_next_ = false;
    program_.moves.push_back(move);
    position_ = end_mm;
    return ok_status();
  }

  Status from(const ClStatement& s) {
    if (auto status = not_after_circle(s); !status) return status;
    Eigen::Vector3d p;
    if (auto status = point(s, p); !status) return status;
    if (program_.moves.empty()) {
      program_.start_mm = p;
    } else {  // the tool is said to be elsewhere: get it there the way a post-processor would, by a rapid
      program_.moves.push_back(move_to(s, MoveKind::rapid, p));
      rapid_next_ = false;
    }
    position_ = p;
    return ok_status();
  }

  Status no_values(const ClStatement& s) const {
    if (s.args.empty()) return ok_status();
    return error_at(s.args.front().at, fmt::format("{} takes no values", s.word));
  }

  Status rapid(const ClStatement& s) {
    if (auto status = no_values(s); !status) return status;
    rapid_next_ = true;
    return ok_status();
  }

  // FEDRAT/f, FEDRAT/f,MMPM, FEDRAT/MMPM,f, IPM, and per revolution MMPR / IPR.
  Status fedrat(const ClStatement& s) {
    std::optional<double> value;
    const ClArg* value_arg = nullptr;
    double scale = scale_;  // without a modifier: program units per minute
    bool per_rev = false;
    const ClArg* per_rev_arg = nullptr;
    for (const ClArg& arg : s.args) {
      if (starts_like_word(arg.text)) {
        if (equals_upper(arg.text, "MMPM")) {
          scale = 1.0;
        } else if (equals_upper(arg.text, "IPM")) {
          scale = kClMmPerInch;
        } else if (equals_upper(arg.text, "MMPR") || equals_upper(arg.text, "IPR")) {
          scale = equals_upper(arg.text, "IPR") ? kClMmPerInch : 1.0;
          per_rev = true;
          per_rev_arg = &arg;
        } else {
          return error_at(arg.at, fmt::format("unknown FEDRAT modifier '{}'", arg.text));
        }
        continue;
      }
      if (value) return error_at(arg.at, "FEDRAT takes one feed value");
      double v = 0.0;
      if (auto status = number(arg, v); !status) return status;
      value = v;
      value_arg = &arg;
    }
    if (!value) return error_at(s.at, "FEDRAT without a feed value");
    if (!(*value > 0.0)) return error_at(value_arg->at, "the feed rate must be positive");
    if (per_rev && !spindle_rpm_known_) {
      return error_at(per_rev_arg->at,
                      "feed per revolution is not supported before a spindle speed is known (SPINDL/rpm)");
    }
    feed_ = *value * scale;
    feed_per_rev_ = per_rev;
    return ok_status();
  }

  Status tlaxis(const ClStatement& s) {
    if (s.args.size() != 3) {
      return error_at(s.at, fmt::format("TLAXIS takes 3 values (i,j,k), got {}", s.args.size()));
    }
    return unit_vector(s, 0, axis_);
  }

  Status units(const ClStatement& s) {
    if (s.args.size() == 1 && equals_upper(s.args[0].text, "MM")) {
      scale_ = 1.0;
    } else if (s.args.size() == 1 &&
               (equals_upper(s.args[0].text, "INCHES") || equals_upper(s.args[0].text, "INCH"))) {
      scale_ = kClMmPerInch;
    } else {
      return error_at(s.args.empty() ? s.at : s.args[0].at, "UNITS takes MM or INCHES");
    }
    return ok_status();
  }

  // Five-axis output on or off; GOTOs with 3 or 6 values are read the same either way.
  Status multax(const ClStatement& s) {
    if (s.args.empty() ||
        (s.args.size() == 1 && (equals_upper(s.args[0].text, "ON") || equals_upper(s.args[0].text, "OFF")))) {
      return ok_status();
    }
    return error_at(s.args[0].at, "MULTAX takes ON or OFF");
  }

  // CIRCLE/xc,yc,zc,i,j,k,r[,...]: NX appends tolerance and tool values, which are checked as numbers and
  // otherwise not used.
  Status circle(const ClStatement& s) {
    if (auto status = not_after_circle(s); !status) return status;
    if (s.args.size() < 7) {
      return error_at(
          s.at, fmt::format("CIRCLE takes at least 7 values (xc,yc,zc,i,j,k,r), got {}", s.args.size()));
    }
    std::array<double, 4> v{};  // xc, yc, zc, r
    if (auto status = numbers(s, 0, 3, v.data()); !status) return status;
    if (auto status = number(s.args[6], v[3]); !status) return status;
    for (std::size_t i = 7; i < s.args.size(); ++i) {
      double extra = 0.0;
      if (auto status = number(s.args[i], extra); !status) return status;
    }
    ClCircle c;
    if (auto status = unit_vector(s, 3, c.axis); !status) return status;
    if (!(v[3] > 0.0)) return error_at(s.args[6].at, "the CIRCLE radius must be positive");
    c.center_mm = scale_ * Eigen::Vector3d(v[0], v[1], v[2]);
    c.radius_mm = scale_ * v[3];
    circle_ = c;
    circle_at_ = s.at;
    return ok_status();
  }

  Status end(const ClStatement& s) {
    if (auto status = no_values(s); !status) return status;
    if (auto status = not_after_circle(s); !status) return status;
    program_.end_line = s.at.line;
    ended_ = true;
    return ok_status();
  }

  // SPINDL/rpm[,CLW|CCLW], SPINDL/RPM,rpm,CLW (NX), SPINDL/ON, SPINDL/OFF. OFF keeps the last speed, as the
  // S word stays set after M5; surface speed (SFM/SMM) would need the cutting diameter and is refused.
  Status spindl(const ClStatement& s) {
    std::optional<double> rpm;
    for (std::size_t i = 0; i < s.args.size(); ++i) {
      const ClArg& arg = s.args[i];
      if (!starts_like_word(arg.text)) {
        if (rpm) return error_at(arg.at, "SPINDL takes one spindle speed");
        double v = 0.0;
        if (auto status = number(arg, v); !status) return status;
        if (!(v > 0.0)) return error_at(arg.at, "the spindle speed must be positive");
        rpm = v;
      } else if (equals_upper(arg.text, "SFM") || equals_upper(arg.text, "SMM")) {
        return error_at(arg.at, "surface speed (SFM/SMM) is not supported: give the speed in RPM");
      } else if (equals_upper(arg.text, "RANGE") || equals_upper(arg.text, "MAXRPM")) {
        ++i;  // gear range / speed limit: a value for the machine's post-processor, not for the motion
        double ignored = 0.0;
        if (i >= s.args.size()) return error_at(arg.at, fmt::format("{} needs a value", arg.text));
        if (auto status = number(s.args[i], ignored); !status) return status;
      } else if (!(equals_upper(arg.text, "RPM") || equals_upper(arg.text, "CLW") ||
                   equals_upper(arg.text, "CCLW") || equals_upper(arg.text, "ON") ||
                   equals_upper(arg.text, "OFF"))) {
        return error_at(arg.at, fmt::format("unknown SPINDL modifier '{}'", arg.text));
      }
    }
    if (rpm) {
      spindle_rpm_ = *rpm;
      spindle_rpm_known_ = true;
    }
    record_event(s);
    return ok_status();
  }

  // DELAY/s (seconds) or DELAY/REV,n (spindle revolutions): a dwell where the tool is.
  Status delay(const ClStatement& s) {
    if (auto status = not_after_circle(s); !status) return status;
    double seconds = 0.0;
    if (s.args.size() == 1) {
      if (auto status = number(s.args[0], seconds); !status) return status;
    } else if (s.args.size() == 2 && equals_upper(s.args[0].text, "REV")) {
      double revolutions = 0.0;
      if (auto status = number(s.args[1], revolutions); !status) return status;
      if (!spindle_rpm_known_) {
        return error_at(s.args[0].at, "DELAY/REV needs a spindle speed (SPINDL/rpm)");
      }
      seconds = revolutions / spindle_rpm_ * 60.0;
    } else {
      return error_at(s.at, "DELAY takes seconds (DELAY/s) or revolutions (DELAY/REV,n)");
    }
    if (!(seconds >= 0.0)) return error_at(s.args.back().at, "the dwell time must not be negative");
    CanonicalMove move = move_to(s, MoveKind::dwell, position_);
    move.dwell_s = seconds;
    program_.moves.push_back(move);
    return ok_status();
  }

  // CL data is the path of the tool tip: compensation left or right of it would move the tool elsewhere.
  Status cutcom(const ClStatement& s) {
    if (!s.args.empty() && equals_upper(s.args[0].text, "OFF")) {
      record_event(s);
      return ok_status();
    }
    return error_at(
        s.args.empty() ? s.at : s.args[0].at,
        "cutter compensation is not supported (only CUTCOM/OFF): write tool-tip (centre-line) CL data");
  }

  Status opskip(const ClStatement& s) {
    if (s.args.size() == 1 && equals_upper(s.args[0].text, "ON")) {
      skipping_ = block_delete_;
    } else if (s.args.size() == 1 && equals_upper(s.args[0].text, "OFF")) {
      skipping_ = false;
    } else {
      return error_at(s.args.empty() ? s.at : s.args[0].at, "OPSKIP takes ON or OFF");
    }
    record_event(s);
    return ok_status();
  }

  // "LOADTL/1", "COOLNT/ON", "PPRINT free text": word and values in upper case, free text as written.
  void record_event(const ClStatement& s) {
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

  const std::string& source_;
  const bool block_delete_;
  CanonicalProgram program_;
  double scale_ = 1.0;  // mm per program length unit (UNITS)
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ();
  std::optional<double> feed_;  // mm/min, or mm/rev when feed_per_rev_
  bool feed_per_rev_ = false;
  double spindle_rpm_ = 0.0;
  bool spindle_rpm_known_ = false;
  bool rapid_next_ = false;
  std::optional<ClCircle> circle_;
  ClPosition circle_at_;
  bool skipping_ = false;
  bool ended_ = false;
};

}  // namespace

Result<CanonicalProgram> read_cl_data(std::string_view text, const std::string& source_name,
                                      const InterpretOptions& options) {
  ClLexer lexer(text);
  const int line_count = lexer.line_count();
  ClReader reader(source_name, options, line_count);
  ClStatement statement;
  statement.args.reserve(16);
  while (!reader.ended() && lexer.next(statement)) {
    if (auto status = reader.apply(statement); !status) return status.error();
  }
  return reader.finish(line_count);
}

}  // namespace pkm::program
