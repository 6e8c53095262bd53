// MSYS (NX), CSYS (Pro/CLfile, CATIA), TRNTYP and ROTABL: the frame the CL points are written in. The reader
// keeps the CL frame → part frame transform; the output stage applies it to every point and direction unless
// the user keeps the CL frame (--no-transform).
#include <fmt/format.h>

#include <array>

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
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  t.translation() = scale_ * Eigen::Vector3d(v[0], v[1], v[2]);
  transform_ = t;
  record_event(s);
  return ok_status();
}

// CSYS/m11,m12,m13,m14, m21,…,m24, m31,…,m34: the 3×4 matrix [R | t] of the frame the points are written in,
// row by row; a point p is R·p + t.
Status ClReader::csys(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  if (s.args.size() != 12) {
    return error_at(s.at, fmt::format("CSYS takes 12 values (a 3×4 matrix, row by row), got {}", s.args.size()));
  }
  std::array<double, 12> v{};
  if (auto status = numbers(s, 0, 12, v.data()); !status) return status;
  Eigen::Matrix3d r;
  if (!frame_from_axes({v[0], v[4], v[8]}, {v[1], v[5], v[9]}, r))
    return error_at(s.args[0].at, "CSYS: the matrix's first two columns are zero or parallel");
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  t.translation() = scale_ * Eigen::Vector3d(v[3], v[7], v[11]);
  transform_ = t;
  record_event(s);
  return ok_status();
}

Status ClReader::trntyp(const ClStatement& s) {
  return error_at(s.at, "TRNTYP is not supported yet");
}

Status ClReader::rotabl(const ClStatement& s) {
  return error_at(s.at, "ROTABL is not supported yet");
}

}  // namespace pkm::program
