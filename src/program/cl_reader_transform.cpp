// MSYS (NX), CSYS (Pro/CLfile, CATIA), TRNTYP and ROTABL: the frame the CL points are written in. The reader
// keeps the CL frame → part frame transform; the output stage applies it to every point and direction unless
// the user keeps the CL frame (--no-transform).
#include <fmt/format.h>

#include <array>
#include <numbers>

#include "program/cl_reader_state.hpp"

namespace pkm::program {
namespace {

// A rotation from two written axes (x, then y made orthogonal to it): CAM systems print 7–10 decimals.
bool frame_from_axes(const Eigen::Vector3d& x_axis, const Eigen::Vector3d& y_axis, Eigen::Matrix3d& r) {
  if (!(x_axis.norm() > 1e-9) || !(y_axis.norm() > 1e-9)) return false;
  const Eigen::Vector3d x = x_axis.normalized();
  const Eigen::Vector3d y_raw = y_axis - x * x.dot(y_axis);
  if (!(y_raw.norm() > 1e-6 * y_axis.norm())) return false;
  const Eigen::Vector3d y = y_raw.normalized();
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = x.cross(y);
  return true;
}

}  // namespace

void ClReader::update_transform() {
  transform_ = frame_;
  transform_.linear() = frame_.linear() * table_rotation_.transpose();
}

// MSYS/x0,y0,z0,xi,xj,xk,yi,yj,yk: the machine coordinate system the GOTOs are written in, given in the part
// (absolute) frame by its origin and its X and Y axes. A point p of the CL data is origin + [X Y Z]·p.
Status ClReader::msys(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  if (s.args.size() != 9) {
    return error_at(s.at, fmt::format("MSYS takes 9 values (origin, X axis, Y axis), got {}", s.args.size()));
  }
  std::array<double, 9> v{};
  if (auto status = numbers(s, 0, 9, v.data()); !status) return status;
  Eigen::Matrix3d r;
  if (!frame_from_axes({v[3], v[4], v[5]}, {v[6], v[7], v[8]}, r))
    return error_at(s.args[3].at, "MSYS: the X and Y axes are zero or parallel");
  frame_.linear() = r;
  frame_.translation() = scale_ * Eigen::Vector3d(v[0], v[1], v[2]);
  update_transform();
  record_event(s);
  return ok_status();
}

// CSYS/m11,m12,m13,m14, m21,…,m24, m31,…,m34: a 3×4 matrix [R | t], row by row. Pro/CLfile (and generic
// APT) write the points in that frame: a point p is R·p + t in the part frame. SolidWorks CAM writes one
// per operation, but its GOTOs are already in the common (world) frame: R's third column is the tool axis
// of the setup, which its 6-value GOTOs state again; the record is kept as an event only.
Status ClReader::csys(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  if (s.args.size() != 12) {
    return error_at(s.at,
                    fmt::format("CSYS takes 12 values (a 3×4 matrix, row by row), got {}", s.args.size()));
  }
  std::array<double, 12> v{};
  if (auto status = numbers(s, 0, 12, v.data()); !status) return status;
  Eigen::Matrix3d r;
  if (!frame_from_axes({v[0], v[4], v[8]}, {v[1], v[5], v[9]}, r))
    return error_at(s.args[0].at, "CSYS: the matrix's first two columns are zero or parallel");
  if (dialect_ != ProgramFormat::solidworks) {
    frame_.linear() = r;
    frame_.translation() = scale_ * Eigen::Vector3d(v[3], v[7], v[11]);
    update_transform();
  }
  record_event(s);
  return ok_status();
}

// TRNTYP/WORLD,0,0,0 (SolidWorks CAM, before every CSYS): the points are in the world frame, offset by
// nothing. No file shows another offset, so another one is refused rather than guessed.
Status ClReader::trntyp(const ClStatement& s) {
  if (s.args.size() != 4 || !cl_equals_upper(s.args[0].text, "WORLD")) {
    return error_at(s.args.empty() ? s.at : s.args[0].at, "TRNTYP takes WORLD,x,y,z");
  }
  std::array<double, 3> v{};
  if (auto status = numbers(s, 1, 3, v.data()); !status) return status;
  if (v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0) {
    return error_at(s.args[1].at, "TRNTYP/WORLD with an offset is not supported (only WORLD,0,0,0)");
  }
  record_event(s);
  return ok_status();
}

// ROTABL/angle,AAXIS|BAXIS|CAXIS[,TABLE][,CLW|CCLW][,INCR]: the rotary table turns the part by the angle
// about a machine axis, and the points that follow are written on the turned part. pkm's machines have no
// table: the turn is undone, so the tool reaches the same places of the part standing still (tilted where
// the turn tilts it). The angle adds to the turn so far (CAMWorks turns A, B, C at an operation's start and
// back C, B, A at its end); CAMWorks writes radians, APT degrees.
Status ClReader::rotabl(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  if (s.args.empty()) return error_at(s.at, "ROTABL takes an angle and an axis (AAXIS, BAXIS or CAXIS)");
  double angle = 0.0;
  if (auto status = number(s.args[0], angle); !status) return status;
  std::optional<Eigen::Vector3d> axis;
  double sense = 1.0;
  for (std::size_t i = 1; i < s.args.size(); ++i) {
    const ClArg& arg = s.args[i];
    if (cl_equals_upper(arg.text, "AAXIS")) {
      axis = Eigen::Vector3d::UnitX();
    } else if (cl_equals_upper(arg.text, "BAXIS")) {
      axis = Eigen::Vector3d::UnitY();
    } else if (cl_equals_upper(arg.text, "CAXIS")) {
      axis = Eigen::Vector3d::UnitZ();
    } else if (cl_equals_upper(arg.text, "CLW")) {
      sense = -1.0;
    } else if (cl_equals_upper(arg.text, "CCLW")) {
      sense = 1.0;
    } else if (!(cl_equals_upper(arg.text, "TABLE") || cl_equals_upper(arg.text, "INCR"))) {
      return error_at(arg.at, fmt::format("unknown ROTABL modifier '{}' (ABSOL is not supported)", arg.text));
    }
  }
  if (!axis) return error_at(s.at, "ROTABL needs the axis it turns about (AAXIS, BAXIS or CAXIS)");
  const double angle_rad = dialect_ == ProgramFormat::solidworks ? angle : angle * std::numbers::pi / 180.0;
  table_rotation_ = Eigen::AngleAxisd(sense * angle_rad, *axis).toRotationMatrix() * table_rotation_;
  update_transform();
  record_event(s);
  return ok_status();
}

}  // namespace pkm::program
