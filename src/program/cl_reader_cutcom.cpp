// CUTCOM/LEFT|RIGHT|OFF: the path offset by the cutter radius, as the G-code interpreter's G41/G42/G40.
//
// Forms: CUTCOM/LEFT|RIGHT[,XYPLAN|YZPLAN|ZXPLAN], CUTCOM/OFF, and CAMWorks' separate CUTCOM/ON (an event).
// No CAM system writes the radius: it is half the diameter of CUTTER/d or TLDATA/MILL,d.
//
// Whether the GOTOs under CUTCOM are the part contour (offset them) or already the tool centre (do not offset
// again) depends on the CAM system. The real files (docs/cl-data.md) say centre for every one seen:
//   - NX CLSF heads its data "$$ centerline data", and its CUTCOM paths run lead-in arcs whose radius is the
//     tool radius (12.5 mm with TLDATA 25): as a contour the offset arc would have no radius at all;
//   - Pro/CLfile says so itself: "$$-> CUTCOM_GEOMETRY_TYPE / OUTPUT_ON_CENTER";
//   - SolidWorks CAM and CAMWorks circle holes of radius 2.5 mm and lead in on 0.1–1.4 mm arcs with 12 and
//     14 mm cutters, which no contour reading allows.
// So NX, Pro/CLfile (unless its last CUTCOM_GEOMETRY_TYPE says otherwise) and SolidWorks/CAMWorks keep the
// path as written (an event and a note); generic APT and CATIA data follow APT, where CUTCOM means the CL
// points are the part contour, and are offset by the radius.
#include "program/cl_reader_cutcom.hpp"

#include <fmt/format.h>

#include <string>

#include "program/gcode_arc.hpp"

namespace pkm::program {
namespace cl_cutcom_detail {

constexpr double kCutcomAxisTolerance = 1e-6;  // |sin| of the angle between tool axis and plane normal

// Pro/CLfile names its geometry type; the other CAM systems are known by their dialect.
bool cl_writes_centre_path(const ClReader& r) {
  for (auto it = r.program_.events.rbegin(); it != r.program_.events.rend(); ++it) {
    static constexpr std::string_view kKey = "CUTCOM_GEOMETRY_TYPE/";
    if (it->what.starts_with(kKey)) return it->what.substr(kKey.size()) == "OUTPUT_ON_CENTER";
  }
  return r.dialect_ == ProgramFormat::nx || r.dialect_ == ProgramFormat::creo ||
         r.dialect_ == ProgramFormat::solidworks;
}

/// The words of a CUTCOM statement.
struct CutcomWords {
  const ClArg* side = nullptr;  // LEFT, RIGHT, OFF, ON
  std::optional<Plane> plane;
};

Status read_cutcom_words(const ClReader& r, const ClStatement& s, CutcomWords& w) {
  for (const ClArg& arg : s.args) {
    if (cl_equals_upper(arg.text, "XYPLAN")) {
      w.plane = Plane::xy;
    } else if (cl_equals_upper(arg.text, "YZPLAN")) {
      w.plane = Plane::yz;
    } else if (cl_equals_upper(arg.text, "ZXPLAN")) {
      w.plane = Plane::zx;
    } else if (cl_equals_upper(arg.text, "LEFT") || cl_equals_upper(arg.text, "RIGHT") ||
               cl_equals_upper(arg.text, "OFF") || cl_equals_upper(arg.text, "ON")) {
      if (w.side != nullptr) return r.error_at(arg.at, "CUTCOM takes one of LEFT, RIGHT, OFF, ON");
      w.side = &arg;
    } else {
      return r.error_at(arg.at, fmt::format("unknown CUTCOM word '{}'", arg.text));
    }
  }
  if (w.side == nullptr) return r.error_at(s.at, "CUTCOM needs LEFT, RIGHT or OFF");
  return ok_status();
}

/// The plane normal to the tool axis (XY for ±Z …), when the axis is a coordinate axis.
std::optional<Plane> cl_plane_of_axis(const Eigen::Vector3d& axis) {
  for (const Plane p : {Plane::xy, Plane::zx, Plane::yz}) {
    if (axis.cross(gcode::plane_normal(p)).norm() < kCutcomAxisTolerance) return p;
  }
  return std::nullopt;
}

}  // namespace cl_cutcom_detail

bool ClReader::cutcom_active() const {
  return cutcom_ && cutcom_->engaged;
}

Status ClReader::cutcom(const ClStatement& s) {
  using namespace cl_cutcom_detail;
  if (auto status = not_after_circle(s); !status) return status;
  if (cycle_active()) return error_at(s.at, "CUTCOM inside a CYCLE (CYCLE/OFF first)");
  CutcomWords w;
  if (auto status = read_cutcom_words(*this, s, w); !status) return status;
  if (!cutcom_) cutcom_ = std::make_unique<ClCutcomState>();
  ClCutcomState& c = *cutcom_;
  record_event(s);
  const gcode::LineRef where{source_, s.at.line};
  if (cl_equals_upper(w.side->text, "ON")) return ok_status();  // CAMWorks: LEFT or RIGHT follows
  if (cl_equals_upper(w.side->text, "OFF")) {
    c.centre_path = false;
    if (c.compensation.active()) return c.compensation.stop(where, w.side->at.column);
    return ok_status();
  }
  const bool left = cl_equals_upper(w.side->text, "LEFT");
  if (cl_writes_centre_path(*this)) {
    c.centre_path = true;
    // One note for the file (add_note keeps one of each text): the statements are events with their lines.
    add_note(fmt::format("CUTCOM/LEFT and RIGHT: {} writes the tool-centre path, which is not offset again",
                         program_format_name(dialect_)));
    return ok_status();
  }
  if (!(cutter_diameter_mm_ > 0.0))
    return error_at(w.side->at, fmt::format("CUTCOM/{} needs the cutter's diameter (CUTTER/d or TLDATA)",
                                            left ? "LEFT" : "RIGHT"));
  const std::optional<Plane> plane = w.plane ? w.plane : cl_plane_of_axis(axis_);
  if (!plane) return error_at(w.side->at, "CUTCOM with a tool axis that is not a coordinate axis");
  const Eigen::Vector3d normal = gcode::plane_normal(*plane);
  if (axis_.cross(normal).norm() > kCutcomAxisTolerance)
    return error_at(w.side->at, "CUTCOM in a plane the tool axis is not normal to");
  // LEFT is seen from the tool, looking along -axis at the part: a tool axis against the plane's normal
  // (machining from below) mirrors the sides.
  const bool mirrored = axis_.dot(normal) < 0.0;
  const auto side = (left != mirrored) ? ngc::CompensationSide::left : ngc::CompensationSide::right;
  if (!c.engaged) {
    c.compensation.set_position(position_);
    c.compensation.set_inch(scale_ > 1.0);
    c.engaged = true;
  }
  c.plane = *plane;
  return c.compensation.start(side, cutter_diameter_mm_ / 2.0, *plane, where, w.side->at.column);
}

Status ClReader::compensated(const CanonicalMove& move, ClPosition at, std::vector<CanonicalMove>& out) {
  using namespace cl_cutcom_detail;
  ClCutcomState& c = *cutcom_;
  if (c.compensation.active() && move.kind != MoveKind::dwell &&
      move.tool_axis.cross(gcode::plane_normal(c.plane)).norm() > kCutcomAxisTolerance)
    return error_at(at, "a move with the tool axis tilted from the CUTCOM plane's normal under compensation");
  return c.compensation.move(move, gcode::LineRef{source_, at.line}, at.column, out);
}

Status ClReader::flush_compensation(ClPosition at) {
  if (!cutcom_active()) return ok_status();
  scratch_.clear();
  if (auto status = cutcom_->compensation.flush(scratch_, gcode::LineRef{source_, at.line}, at.column);
      !status)
    return status;
  for (const CanonicalMove& m : scratch_) output(m);
  return ok_status();
}

}  // namespace pkm::program
