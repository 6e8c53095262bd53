// FEDRAT, SPINDL, UNITS, TLAXIS, MULTAX, OPSKIP, END, CUTTER/TLDATA and annotations: the statements that set
// the reader's state without moving the tool.
#include <fmt/format.h>

#include "program/cl_reader_state.hpp"

namespace pkm::program {
namespace {

constexpr double kClMmPerInch = 25.4;

}  // namespace

// FEDRAT/f, FEDRAT/f,MMPM, FEDRAT/MMPM,f, IPM, and per revolution MMPR / IPR.
Status ClReader::fedrat(const ClStatement& s) {
  std::optional<double> value;
  const ClArg* value_arg = nullptr;
  double scale = scale_;  // without a modifier: program units per minute
  bool per_rev = false;
  const ClArg* per_rev_arg = nullptr;
  for (const ClArg& arg : s.args) {
    if (cl_starts_like_word(arg.text)) {
      if (cl_equals_upper(arg.text, "MMPM")) {
        scale = 1.0;
      } else if (cl_equals_upper(arg.text, "IPM")) {
        scale = kClMmPerInch;
      } else if (cl_equals_upper(arg.text, "MMPR") || cl_equals_upper(arg.text, "IPR")) {
        scale = cl_equals_upper(arg.text, "IPR") ? kClMmPerInch : 1.0;
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

Status ClReader::tlaxis(const ClStatement& s) {
  if (s.args.size() != 3) {
    return error_at(s.at, fmt::format("TLAXIS takes 3 values (i,j,k), got {}", s.args.size()));
  }
  return unit_vector(s, 0, axis_);
}

// UNITS/MM|INCHES (UNIT/… as some systems write it).
Status ClReader::units(const ClStatement& s) {
  if (s.args.size() == 1 &&
      (cl_equals_upper(s.args[0].text, "MM") || cl_equals_upper(s.args[0].text, "METRIC"))) {
    scale_ = 1.0;
  } else if (s.args.size() == 1 &&
             (cl_equals_upper(s.args[0].text, "INCHES") || cl_equals_upper(s.args[0].text, "INCH") ||
              cl_equals_upper(s.args[0].text, "IN"))) {
    scale_ = kClMmPerInch;
  } else {
    return error_at(s.args.empty() ? s.at : s.args[0].at, fmt::format("{} takes MM or INCHES", s.word));
  }
  return ok_status();
}

// Five-axis output on or off: decides how multi-point GOTOs split into points.
Status ClReader::multax(const ClStatement& s) {
  if (s.args.empty() || (s.args.size() == 1 && cl_equals_upper(s.args[0].text, "ON"))) {
    multax_ = true;
  } else if (s.args.size() == 1 && cl_equals_upper(s.args[0].text, "OFF")) {
    multax_ = false;
  } else {
    return error_at(s.args[0].at, "MULTAX takes ON or OFF");
  }
  return ok_status();
}

Status ClReader::end(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  for (const ClArg& arg : s.args) {  // END/… with words only (some systems write END/PROGRAM)
    if (!cl_starts_like_word(arg.text)) return error_at(arg.at, fmt::format("{} takes no values", s.word));
  }
  program_.end_line = s.at.line;
  ended_ = true;
  return ok_status();
}

// SPINDL/rpm[,CLW|CCLW], SPINDL/RPM,rpm,CLW (NX), SPINDL/ON, SPINDL/OFF. OFF keeps the last speed, as the
// S word stays set after M5; surface speed (SFM/SMM) would need the cutting diameter and is refused.
Status ClReader::spindl(const ClStatement& s) {
  std::optional<double> rpm;
  for (std::size_t i = 0; i < s.args.size(); ++i) {
    const ClArg& arg = s.args[i];
    if (!cl_starts_like_word(arg.text)) {
      if (rpm) return error_at(arg.at, "SPINDL takes one spindle speed");
      double v = 0.0;
      if (auto status = number(arg, v); !status) return status;
      if (!(v > 0.0)) return error_at(arg.at, "the spindle speed must be positive");
      rpm = v;
    } else if (cl_equals_upper(arg.text, "SFM") || cl_equals_upper(arg.text, "SMM")) {
      return error_at(arg.at, "surface speed (SFM/SMM) is not supported: give the speed in RPM");
    } else if (cl_equals_upper(arg.text, "RANGE") || cl_equals_upper(arg.text, "MAXRPM")) {
      ++i;  // gear range / speed limit: a value for the machine's post-processor, not for the motion
      double ignored = 0.0;
      if (i >= s.args.size()) return error_at(arg.at, fmt::format("{} needs a value", arg.text));
      if (auto status = number(s.args[i], ignored); !status) return status;
    } else if (cl_equals_upper(arg.text, "CLW")) {
      spindle_clockwise_ = true;
    } else if (cl_equals_upper(arg.text, "CCLW")) {
      spindle_clockwise_ = false;
    } else if (cl_equals_upper(arg.text, "OFF")) {
      spindle_on_ = false;
    } else if (!(cl_equals_upper(arg.text, "RPM") || cl_equals_upper(arg.text, "ON"))) {
      return error_at(arg.at, fmt::format("unknown SPINDL modifier '{}'", arg.text));
    }
  }
  if (rpm) {
    spindle_rpm_ = *rpm;
    spindle_rpm_known_ = true;
    spindle_on_ = true;
  } else if (!s.args.empty() && cl_equals_upper(s.args[0].text, "ON")) {
    spindle_on_ = true;
  }
  record_event(s);
  return ok_status();
}

Status ClReader::opskip(const ClStatement& s) {
  if (s.args.size() == 1 && cl_equals_upper(s.args[0].text, "ON")) {
    skipping_ = block_delete_;
  } else if (s.args.size() == 1 && cl_equals_upper(s.args[0].text, "OFF")) {
    skipping_ = false;
  } else {
    return error_at(s.args.empty() ? s.at : s.args[0].at, "OPSKIP takes ON or OFF");
  }
  record_event(s);
  return ok_status();
}

// CUTTER/d[,r,…] (APT: the diameter first) and NX's TLDATA/MILL,d,…: the cutter's diameter, which
// CUTCOM/LEFT|RIGHT offsets the path by half of. Kept as an event too.
Status ClReader::cutter(const ClStatement& s) {
  for (const ClArg& arg : s.args) {
    if (cl_starts_like_word(arg.text)) continue;  // TLDATA/MILL, DRILL …
    double d = 0.0;
    if (auto status = number(arg, d); !status) return status;
    if (!(d >= 0.0)) return error_at(arg.at, "the cutter diameter must not be negative");
    cutter_diameter_mm_ = scale_ * d;
    break;
  }
  record_event(s);
  return ok_status();
}

// Pro/CLfile's "$$-> WORD / …" statements and NX's CSI_SET_… lines: for a post-processor, kept as events;
// the ones that say something about the motion (CSYS, CUTTER) are read by their own handlers.
Status ClReader::annotation(const ClStatement& s) {
  record_event(s);
  return ok_status();
}

}  // namespace pkm::program
