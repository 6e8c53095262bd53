// CYCLE/DRILL|DEEP|TAP|BORE|… … CYCLE/OFF: every GOTO in between is a hole, drilled along the tool axis the
// way the G-code canned cycles drill along Z.
//
// Each hole goes through the G-code canned-cycle engine (ngc_canned_cycle.hpp) in G17/G90, in a frame whose
// +Z is the tool axis and whose origin is the top of the first hole of the series (the holes drilled with one
// tool axis); the engine's points come back into the CL frame. So a CL cycle makes the rapids, feeds, dwells
// and spindle events of the G-code cycle it names, on a tilted axis too.
//
// The forms (all lengths measured along the tool axis from the GOTO point, the hole top; docs/cl-data.md):
//   NX          CYCLE/DRILL[,DEEP],RAPTO,r,FEDTO,d,MMPM,f[,STEP,s][,RTRCTO,q|AUTO]
//   Pro/CLfile  CYCLE / DEEP, DEPTH, d, STEP, s, MMPM, f, CLEAR, c
//   SolidWorks  CYCLE/DRILL,FEDTO,d,MMPM,f,RAPTO,r,RTRCTO,q,DWELL,t   DEEP2,…,1STPECK,p1,SUBPECK,p2,…
//               DEEP,…,INCR,p,…   CYCLE/INIT, CYCLE/CLEAR (events)
//   CAMWorks    CYCLE/ DRILL,G98,d,PECKING,p1,p2,MMPM,f,r,q q DWELL,t (blanks separate values too)
//   APT         CYCLE/DRILL|FACE|DEEP|BRKCHP|TAP|BORE|REAM,d,IPM|MMPM|IPR|MMPR,f,c
// Decisions where the data leave a choice:
//   - FEDTO/DEPTH is the depth below the hole top; a negative value is read as the same depth (drilling
//     upwards from the top makes no sense) and a note says so.
//   - DEEP or BRKCHP without a peck (NX writes DRILL,DEEP with no STEP) drills in one feed (G81), with a
//   note.
//   - Between holes the tool goes back to RTRCTO (above each hole top) when given, to the level the series
//     started from after G98 or RTRCTO,AUTO, else to the R plane (G99: APT's clearance plane).
//   - 1STPECK/SUBPECK (and PECKING,p1,p2) peck as G83 does, the first peck p1 below R, the next ones p2.
//   - Without a feed in the CYCLE statement the FEDRAT in effect is the cycle's feed.
#include "program/cl_reader_cycle.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "program/cl_reader_cutcom.hpp"

namespace pkm::program {
namespace cl_cycle_detail {

constexpr double kCycleMmPerInch = 25.4;
constexpr double kPeckClearanceMm = 0.254;  // G83's back-off above the last depth (LinuxCNC's 0.010 in)
constexpr double kMaxVariablePecks = 1'000'000;
constexpr double kSameAxisTolerance = 1e-9;

/// The values of a CYCLE definition as written, before they become a cycle.
struct CycleWords {
  ClArg name;
  bool deep = false;  // DRILL,DEEP (NX)
  std::optional<bool> g98;
  bool retract_auto = false;
  ClCycleValue depth, r, retract, dwell, peck, sub_peck, feed;
  std::string feed_unit = "MMPM";
  ClPosition feed_unit_at;
  int positional = 0;
};

std::string upper_text(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = ascii_upper(c);
  return out;
}

// CAMWorks separates some values by blanks instead of commas: inside CYCLE both separate.
std::vector<ClArg> cycle_tokens(const ClStatement& s) {
  std::vector<ClArg> out;
  for (const ClArg& arg : s.args) {
    std::size_t i = 0;
    const std::string_view t = arg.text;
    if (t.empty()) out.push_back(arg);
    while (i < t.size()) {
      while (i < t.size() && (t[i] == ' ' || t[i] == '\t')) ++i;
      std::size_t j = i;
      while (j < t.size() && t[j] != ' ' && t[j] != '\t') ++j;
      if (j > i) out.push_back({t.substr(i, j - i), {arg.at.line, arg.at.column + static_cast<int>(i)}});
      i = j;
    }
  }
  return out;
}

// A cycle keyword: a word, or SolidWorks' 1STPECK, which starts with a digit.
bool cycle_keyword(std::string_view text) {
  return cl_starts_like_word(text) || cl_equals_upper(text, "1STPECK");
}

ClCycleValue* value_slot(const std::string& word, CycleWords& w) {
  if (word == "RAPTO" || word == "CLEAR") return &w.r;
  if (word == "FEDTO" || word == "DEPTH") return &w.depth;
  if (word == "RTRCTO") return &w.retract;
  if (word == "DWELL") return &w.dwell;
  if (word == "STEP" || word == "INCR" || word == "1STPECK" || word == "PECKING") return &w.peck;
  if (word == "SUBPECK") return &w.sub_peck;
  if (word == "MMPM" || word == "IPM" || word == "MMPR" || word == "IPR") return &w.feed;
  return nullptr;
}

// A word the CYCLE forms know: after a keyword that needs a value, anything else is a bad number.
bool known_cycle_word(std::string_view text) {
  static constexpr std::string_view kWords[] = {"RAPTO", "CLEAR", "FEDTO",   "DEPTH",   "RTRCTO",  "DWELL",
                                                "STEP",  "INCR",  "1STPECK", "PECKING", "SUBPECK", "MMPM",
                                                "IPM",   "MMPR",  "IPR",     "DEEP",    "G98",     "G99"};
  for (const std::string_view w : kWords)
    if (cl_equals_upper(text, w)) return true;
  return false;
}

Status store_cycle_value(const ClReader& r, const ClArg& arg, ClCycleValue& slot, std::string_view what) {
  if (slot.value) return r.error_at(arg.at, fmt::format("CYCLE gives the {} twice", what));
  double v = 0.0;
  if (auto status = r.number(arg, v); !status) return status;
  slot = {v, arg.at};
  return ok_status();
}

// Unnamed numbers (APT's CYCLE/DRILL,d,IPM,f,c; CAMWorks' depth, clearance, retract printed twice): the
// depth, the R clearance, the retract height in that order.
Status store_positional(const ClReader& r, const ClArg& arg, CycleWords& w) {
  const int k = w.positional++;
  if (k == 0) return store_cycle_value(r, arg, w.depth, "depth");
  if (k == 1) return store_cycle_value(r, arg, w.r, "clearance");
  if (k == 2) return store_cycle_value(r, arg, w.retract, "retract height");
  double v = 0.0;
  if (auto status = r.number(arg, v); !status) return status;
  if (k == 3 && w.retract.value && v == *w.retract.value) return ok_status();  // CAMWorks repeats it
  return r.error_at(arg.at, fmt::format("unexpected value '{}' in CYCLE", arg.text));
}

Status read_words(const ClReader& r, const std::vector<ClArg>& t, CycleWords& w) {
  w.name = t[0];
  for (std::size_t i = 1; i < t.size(); ++i) {
    const ClArg& a = t[i];
    if (!cycle_keyword(a.text)) {
      if (auto status = store_positional(r, a, w); !status) return status;
      continue;
    }
    const std::string word = upper_text(a.text);
    if (word == "DEEP") {
      w.deep = true;
      continue;
    }
    if (word == "G98" || word == "G99") {
      w.g98 = word == "G98";
      continue;
    }
    if (word == "RTRCTO" && i + 1 < t.size() && cl_equals_upper(t[i + 1].text, "AUTO")) {
      w.retract_auto = true;
      ++i;
      continue;
    }
    ClCycleValue* slot = value_slot(word, w);
    if (slot == nullptr) return r.error_at(a.at, fmt::format("unknown CYCLE word '{}'", a.text));
    if (i + 1 >= t.size() || known_cycle_word(t[i + 1].text))
      return r.error_at(a.at, fmt::format("{} needs a value", word));
    if (slot == &w.feed) {
      w.feed_unit = word;
      w.feed_unit_at = a.at;
    }
    if (auto status = store_cycle_value(r, t[++i], *slot, word); !status) return status;
    // PECKING,first,later (CAMWorks): the later pecks follow the first.
    if (word == "PECKING" && i + 1 < t.size() && !cycle_keyword(t[i + 1].text)) {
      if (auto status = store_cycle_value(r, t[++i], w.sub_peck, "later peck"); !status) return status;
    }
  }
  return ok_status();
}

/// The G-code cycle (×10) that drills the holes of the named CL cycle.
Status choose_code(const ClReader& r, const CycleWords& w, int& code) {
  const std::string name = upper_text(w.name.text);
  const bool pecks = w.peck.value.has_value();
  if (name == "DRILL") {
    code = (w.deep || pecks) ? 830 : (w.dwell.value.value_or(0.0) > 0.0 ? 820 : 810);
  } else if (name == "DEEP" || name == "DEEP2") {
    code = 830;
  } else if (name == "BRKCHP") {
    code = 730;
  } else if (name == "FACE") {
    code = 820;
  } else if (name == "TAP") {
    code = 840;
  } else if (name == "BORE" || name == "REAM") {
    code = 850;
  } else {
    return r.error_at(w.name.at,
                      fmt::format("unknown cycle '{}' (DRILL, FACE, DEEP, DEEP2, BRKCHP, TAP, BORE, "
                                  "REAM, OFF)",
                                  w.name.text));
  }
  if (pecks && code != 830 && code != 730)
    return r.error_at(w.peck.at, fmt::format("a peck with CYCLE/{}: only the drilling cycles peck", name));
  if (w.sub_peck.value && code != 830)
    return r.error_at(w.sub_peck.at, "later pecks (SUBPECK) only with the deep-hole cycles");
  if (w.dwell.value.value_or(0.0) > 0.0 && code != 820 && code != 840)
    return r.error_at(w.dwell.at, fmt::format("CYCLE/{} takes no dwell at the bottom here", name));
  return ok_status();
}

/// The cycle's feed in mm/min (and mm/rev when given per revolution).
Status cycle_feed(const ClReader& r, const ClStatement& s, const CycleWords& w, ClCycleState& c) {
  if (!w.feed.value) {  // the FEDRAT in effect
    if (!r.feed_)
      return r.error_at(s.at,
                        fmt::format("CYCLE/{} without a feed (MMPM,f) and no FEDRAT before", w.name.text));
    c.feed_per_rev_mm = r.feed_per_rev_ ? *r.feed_ : 0.0;
    c.feed_mm_min = r.feed_per_rev_ ? *r.feed_ * r.spindle_rpm_ : *r.feed_;
    return ok_status();
  }
  const double f = *w.feed.value;
  if (!(f > 0.0)) return r.error_at(w.feed.at, "the feed rate must be positive");
  const bool inch = w.feed_unit == "IPM" || w.feed_unit == "IPR";
  const double per_unit = f * (inch ? kCycleMmPerInch : 1.0);
  if (w.feed_unit == "MMPR" || w.feed_unit == "IPR") {
    if (!r.spindle_rpm_known_)
      return r.error_at(w.feed_unit_at, "feed per revolution needs a spindle speed (SPINDL/rpm)");
    c.feed_per_rev_mm = per_unit;
    c.feed_mm_min = per_unit * r.spindle_rpm_;
  } else {
    c.feed_per_rev_mm = 0.0;
    c.feed_mm_min = per_unit;
  }
  return ok_status();
}

/// The lengths of the definition, in mm; notes where the data leave a reading open.
Status cycle_lengths(ClReader& r, const CycleWords& w, ClCycleState& c) {
  const std::string name = upper_text(w.name.text);
  if (!w.depth.value)
    return r.error_at(w.name.at,
                      fmt::format("CYCLE/{} needs the depth (FEDTO, DEPTH or the first value)", name));
  if (!w.r.value)
    return r.error_at(w.name.at, fmt::format("CYCLE/{} needs the R clearance (RAPTO, CLEAR)", name));
  if (*w.depth.value < 0.0)
    r.add_note("a negative CYCLE depth (FEDTO, DEPTH) is read as that depth below the hole top");
  c.depth_mm = std::abs(*w.depth.value) * r.scale_;
  c.depth_at = w.depth.at;
  c.r_mm = *w.r.value * r.scale_;
  c.r_at = w.r.at;
  c.retract_mm = w.retract;
  if (c.retract_mm.value) *c.retract_mm.value *= r.scale_;
  c.retract_initial = w.retract_auto || w.g98.value_or(false);
  c.dwell_s = w.dwell.value.value_or(0.0);
  c.dwell_at = w.dwell.at;
  if (c.dwell_s < 0.0) return r.error_at(w.dwell.at, "the dwell time must not be negative");
  c.peck_mm = w.peck.value.value_or(0.0) * r.scale_;
  c.sub_peck_mm = w.sub_peck.value.value_or(0.0) * r.scale_;
  c.peck_at = w.peck.at;
  if (w.peck.value && !(c.peck_mm > 0.0)) return r.error_at(w.peck.at, "the peck must be positive");
  if (w.sub_peck.value && !(c.sub_peck_mm > 0.0))
    return r.error_at(w.sub_peck.at, "the peck must be positive");
  if ((c.code == 830 || c.code == 730) && !w.peck.value) {
    r.add_note(fmt::format("CYCLE/{} with no peck (STEP): each hole is drilled in one feed (G81)", name));
    c.code = 810;
  }
  if (c.r_mm < -c.depth_mm) return r.error_at(c.r_at, "the R clearance is below the hole bottom (the depth)");
  if (c.code == 820 && !w.dwell.value)
    r.add_note(fmt::format("CYCLE/{} with no dwell: 0 s at the bottom", name));
  return ok_status();
}

/// A frame whose +Z is `axis` (its X is the CL X, or Y, made perpendicular): the holes' G17 frame.
Eigen::Matrix3d axis_frame(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d z = axis.normalized();
  const Eigen::Vector3d ref = std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x = (ref - z * z.dot(ref)).normalized();
  Eigen::Matrix3d m;
  m.col(0) = x;
  m.col(1) = z.cross(x);
  m.col(2) = z;
  return m;
}

/// The engine's moves back in the CL frame, as canonical moves of the hole's GOTO. With variable pecks the
/// one feed of G81 to the bottom becomes the pecks of G83 with the first and the later peck.
class ClCycleSink final : public ngc::CycleSink {
 public:
  ClCycleSink(ClReader& reader, const ClStatement& s, const ClCycleState& c)
      : reader_(reader), s_(s), c_(c), last_(reader.position_) {}
  Status status = ok_status();
  /// The hole's R level in the series frame (variable pecks only).
  double r_level = 0.0;

  void rapid(const Eigen::Vector3d& to) override { put(MoveKind::rapid, to); }
  void feed(const Eigen::Vector3d& to) override {
    if (c_.sub_peck_mm > 0.0) {
      double depth = r_level - c_.peck_mm;
      for (double n = 0; depth > to.z() && n < kMaxVariablePecks; depth -= c_.sub_peck_mm, n += 1) {
        put(MoveKind::line, {to.x(), to.y(), depth});
        put(MoveKind::rapid, {to.x(), to.y(), r_level});
        put(MoveKind::rapid, {to.x(), to.y(), depth + kPeckClearanceMm});
      }
    }
    put(MoveKind::line, to);
  }
  void dwell(double seconds) override {
    CanonicalMove m = reader_.move_to(s_, MoveKind::dwell, last_);
    m.dwell_s = seconds;
    send(m);
  }
  void event(const std::string& what) override { reader_.program_.events.push_back({s_.at.line, what}); }

 private:
  void put(MoveKind kind, const Eigen::Vector3d& local) {
    last_ = c_.frame * local;
    CanonicalMove m = reader_.move_to(s_, kind, last_);
    if (kind == MoveKind::line) {
      m.feed_mm_min = c_.feed_mm_min;
      m.feed_per_revolution_mm = c_.feed_per_rev_mm;
    }
    send(m);
  }
  void send(const CanonicalMove& m) {
    if (status) status = reader_.emit(m, s_.at);
  }
  ClReader& reader_;
  const ClStatement& s_;
  const ClCycleState& c_;
  Eigen::Vector3d last_;
};

void set_word(gcode::Block& b, char letter, double value, int column) {
  b.letters[static_cast<std::size_t>(letter - 'A')] = {value, column};
}

/// The G-code block that drills the hole at `top` (series frame). Its words all point at the GOTO: the
/// engine reports its errors on the GOTO's line.
gcode::Block hole_block(const ClCycleState& c, int code, const Eigen::Vector3d& top, ClPosition at) {
  const int column = at.column > 0 ? at.column : 1;
  gcode::Block b;
  b.g[gcode::g_motion] = {code, column};
  set_word(b, 'X', top.x(), column);
  set_word(b, 'Y', top.y(), column);
  set_word(b, 'Z', top.z() - c.depth_mm, column);
  set_word(b, 'R', top.z() + c.r_mm, column);
  if (code == 830 || code == 730) set_word(b, 'Q', c.peck_mm, column);
  if (code == 820 || code == 840) set_word(b, 'P', c.dwell_s, column);
  return b;
}

// Too many pecks would make the variable-peck loop (not bounded by the engine) run for ever.
Status check_variable_pecks(const ClReader& r, const ClCycleState& c) {
  if (c.sub_peck_mm <= 0.0) return ok_status();
  if ((c.r_mm + c.depth_mm) / c.sub_peck_mm > kMaxVariablePecks)
    return r.error_at(c.peck_at, fmt::format("more than {} pecks a hole (pkm's bound)", kMaxVariablePecks));
  return ok_status();
}

}  // namespace cl_cycle_detail

bool ClReader::cycle_active() const {
  return cycle_ && cycle_->active;
}

Status ClReader::cycle(const ClStatement& s) {
  using namespace cl_cycle_detail;
  if (auto status = not_after_circle(s); !status) return status;
  const std::vector<ClArg> tokens = cycle_tokens(s);
  if (tokens.empty() || tokens[0].text.empty())
    return error_at(tokens.empty() ? s.at : tokens[0].at, "CYCLE needs a cycle (DRILL, DEEP …) or OFF");
  if (!cycle_) cycle_ = std::make_unique<ClCycleState>();
  const std::string name = upper_text(tokens[0].text);
  if (name == "ON" || name == "INIT" || name == "CLEAR" || name == "OFF") {
    if (tokens.size() > 1) return error_at(tokens[1].at, fmt::format("CYCLE/{} takes no values", name));
    if (name == "OFF") cycle_->active = false;
    record_event(s);
    return ok_status();
  }
  if (cutcom_ && cutcom_->compensation.active())
    return error_at(s.at, "CYCLE with cutter compensation on (CUTCOM/OFF first)");
  if (auto status = flush_compensation(s.at); !status) return status;
  CycleWords words;
  if (auto status = read_words(*this, tokens, words); !status) return status;
  ClCycleState c;
  c.at = s.at;
  if (auto status = choose_code(*this, words, c.code); !status) return status;
  if (auto status = cycle_lengths(*this, words, c); !status) return status;
  if (auto status = cycle_feed(*this, s, words, c); !status) return status;
  if (auto status = check_variable_pecks(*this, c); !status) return status;
  if (c.sub_peck_mm > 0.0 && c.sub_peck_mm == c.peck_mm) c.sub_peck_mm = 0.0;  // plain G83
  c.active = true;
  *cycle_ = std::move(c);
  record_event(s);
  return ok_status();
}

Status ClReader::cycle_point(const ClStatement& s, const ClPoint& point) {
  using namespace cl_cycle_detail;
  if (circle_) return error_at(s.at, "a GOTO after CIRCLE inside a CYCLE (CYCLE/OFF first)");
  if (rapid_next_)
    return error_at(s.at, "RAPID inside a CYCLE: the cycle makes the holes' moves (CYCLE/OFF missing?)");
  if (cutcom_ && cutcom_->compensation.active())
    return error_at(s.at, "CYCLE hole with cutter compensation on (CUTCOM/OFF first)");
  ClCycleState& c = *cycle_;
  if (!c.series || (c.frame_axis - axis_).norm() > kSameAxisTolerance) {
    c.series = true;
    c.frame_axis = axis_;
    c.frame = Eigen::Isometry3d::Identity();
    c.frame.linear() = axis_frame(axis_);
    c.frame.translation() = point.p_mm;
    c.memory = ngc::CycleMemory{};
  }
  const Eigen::Isometry3d to_local = c.frame.inverse();
  const Eigen::Vector3d top = to_local * point.p_mm;
  // G98's level is where the tool goes between holes: RTRCTO above this hole, or where the series began.
  ngc::CycleContext context;
  context.code = c.sub_peck_mm > 0.0 ? 810 : c.code;
  context.retract_to_r = !c.retract_initial && !c.retract_mm.value;
  context.position_mm = to_local * position_;
  context.spindle_speed = spindle_rpm_;
  context.spindle_clockwise = spindle_clockwise_;
  context.spindle_turning = spindle_on_;
  if (c.retract_mm.value) {
    c.memory.started = true;
    c.memory.code = context.code;
    c.memory.old_z_mm = top.z() + *c.retract_mm.value;
  }
  const gcode::Block block = hole_block(c, context.code, top, s.at);
  ClCycleSink sink(*this, s, c);
  sink.r_level = top.z() + c.r_mm;
  const gcode::LineRef where{source_, s.at.line};
  if (auto status = ngc::run_canned_cycle(block, where, context, c.memory, sink); !status) return status;
  if (!sink.status) return sink.status;
  position_ = c.frame * c.memory.end_mm;
  return ok_status();
}

}  // namespace pkm::program
