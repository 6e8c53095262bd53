#include "core/rotation.hpp"

#include <cmath>
#include <cstring>

#include "core/rotation_from_sines.hpp"
#include "core/rotation_kernels.hpp"
#include "core/sincos3.hpp"
#include "core/units.hpp"

namespace pkm {
namespace {

// A convention as a product of three elementary rotations R = E0 · E1 · E2, each about a base axis
// with a sign applied to one of the angles. This one description gives R and the angular-velocity matrix.
struct Elementary {
  int axis;         // 0 = x, 1 = y, 2 = z
  double sign;      // +1 or -1
  int angle_index;  // which entry of the angle triple drives it
};
struct Sequence {
  Elementary factors[3];
};

Sequence sequence_of(AngleConvention convention) {
  switch (convention) {
    case AngleConvention::abc:
      return {{{2, 1.0, 2}, {1, 1.0, 1}, {0, 1.0, 0}}};
    case AngleConvention::krylov:
      return {{{2, -1.0, 0}, {0, -1.0, 1}, {1, -1.0, 2}}};
    case AngleConvention::euler_zxz:
      return {{{2, 1.0, 0}, {0, 1.0, 1}, {2, 1.0, 2}}};
  }
  return {};
}

Eigen::Matrix3d elementary(int axis, double angle_rad) {
  switch (axis) {
    case 0:
      return rot_x(angle_rad);
    case 1:
      return rot_y(angle_rad);
    default:
      return rot_z(angle_rad);
  }
}

}  // namespace

std::string_view to_string(AngleConvention convention) {
  switch (convention) {
    case AngleConvention::abc:
      return "abc";
    case AngleConvention::krylov:
      return "krylov";
    case AngleConvention::euler_zxz:
      return "euler_zxz";
  }
  return "?";
}

std::optional<AngleConvention> angle_convention_from_string(std::string_view name) {
  if (name == "abc") return AngleConvention::abc;
  if (name == "krylov") return AngleConvention::krylov;
  if (name == "euler_zxz") return AngleConvention::euler_zxz;
  return std::nullopt;
}

Eigen::Matrix3d rot_x(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return r;
}
Eigen::Matrix3d rot_y(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d r;
  r << c, 0, s, 0, 1, 0, -s, 0, c;
  return r;
}
Eigen::Matrix3d rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

namespace {

#if PKM_HAS_WIDE_KERNELS
// abc's matrix from the sine and cosine lanes (s1 s2 s3 ·), (c1 c2 c3 ·), each column's first two entries as
// one pair: with v = (c3, s3), column 1 = c2·v, column 2 = s1s2·v + c1·(−s3, c3), column 3 = c1s2·v +
// s1·(s3, −c3). Entry by entry the same products and sums as rotation_from_sines (a − b is a + (−b)), so the
// same bits.
[[gnu::target("avx2")]] inline void abc_rotation_from_lanes(const sincos3_detail::Quad& s,
                                                            const sincos3_detail::Quad& c,
                                                            Eigen::Matrix3d& r) {
#if defined(__clang__)
#pragma clang fp contract(off)
#endif
  using Pair = sincos3_detail::Pair;
  const double s1 = s[0], s2 = s[1], s3 = s[2], c1 = c[0], c2 = c[1], c3 = c[2];
  const Pair v = {c3, s3}, w = {-s3, c3}, u = {s3, -c3};
  const Pair column0 = c2 * v;
  const Pair column1 = (s1 * s2) * v + c1 * w;
  const Pair column2 = (c1 * s2) * v + s1 * u;
  double* d = r.data();  // column-major
  std::memcpy(d, &column0, sizeof column0);
  d[2] = -s2;
  std::memcpy(d + 3, &column1, sizeof column1);
  d[5] = s1 * c2;
  std::memcpy(d + 6, &column2, sizeof column2);
  d[8] = c1 * c2;
}

// The AVX2 copy: the three angles' sines and cosines in one vector, abc's matrix from the lanes (no fused
// multiply–add: the same bits as the baseline).
[[gnu::target("avx2"), gnu::flatten]] Eigen::Matrix3d rotation_from_angles_avx2(
    AngleConvention convention, const Eigen::Vector3d& angles_rad) {
  sincos3_detail::Quad s, c;
  if (!sincos3_avx2_lanes(angles_rad.data(), s, c))
    return rotation_from_angles_baseline(convention, angles_rad);
  if (convention == AngleConvention::abc) {
    Eigen::Matrix3d r;
    abc_rotation_from_lanes(s, c, r);
    return r;
  }
  const double sines[3] = {s[0], s[1], s[2]}, cosines[3] = {c[0], c[1], c[2]};
  return rotation_from_sines(convention, sines, cosines);
}

// Decided once, when the library is loaded.
const bool rotation_kernels_wide = wide_kernels_available();
#endif

}  // namespace

// Out of line (also where the AVX2 copy falls back to it): that copy stays a lean leaf function.
[[gnu::noinline]] Eigen::Matrix3d rotation_from_angles_baseline(AngleConvention convention,
                                                                const Eigen::Vector3d& angles_rad) {
  double sines[3], cosines[3];
  sincos3_baseline(angles_rad.data(), sines, cosines);
  return rotation_from_sines(convention, sines, cosines);
}

Eigen::Matrix3d rotation_from_angles(AngleConvention convention, const Eigen::Vector3d& angles_rad) {
  // The sines and cosines of the three angles in one pass (core/sincos3.hpp): this is on the IK hot path.
#if PKM_HAS_WIDE_KERNELS
  if (rotation_kernels_wide) return rotation_from_angles_avx2(convention, angles_rad);
#endif
  return rotation_from_angles_baseline(convention, angles_rad);
}

Eigen::Matrix3d rotation_from_elementary_product(AngleConvention convention,
                                                 const Eigen::Vector3d& angles_rad) {
  const Sequence seq = sequence_of(convention);
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  for (const Elementary& f : seq.factors) r = r * elementary(f.axis, f.sign * angles_rad[f.angle_index]);
  return r;
}

Eigen::Vector3d angles_from_rotation(AngleConvention convention, const Eigen::Matrix3d& r) {
  auto clamp_unit = [](double v) { return std::fmax(-1.0, std::fmin(1.0, v)); };
  switch (convention) {
    case AngleConvention::abc: {
      // R = Rz(C)Ry(B)Rx(A): R(2,0) = -sin B, R(2,1) = cos B sin A, R(2,2) = cos B cos A,
      // R(0,0) = cos B cos C, R(1,0) = cos B sin C.
      const double b = std::asin(clamp_unit(-r(2, 0)));
      if (std::abs(r(2, 0)) > 1.0 - 1e-12) {  // gimbal lock: only C ± A is defined; set A = 0
        return {0.0, b, std::atan2(-r(0, 1), r(1, 1))};
      }
      return {std::atan2(r(2, 1), r(2, 2)), b, std::atan2(r(1, 0), r(0, 0))};
    }
    case AngleConvention::krylov: {
      // R = Rz(-ψ)Rx(-ϑ)Ry(-γ): row 2 = (cosϑ sinγ, -sinϑ, cosϑ cosγ); column 1 = (sinψ cosϑ, cosψ cosϑ,
      // -sinϑ).
      const double theta = std::asin(clamp_unit(-r(2, 1)));
      if (std::abs(r(2, 1)) > 1.0 - 1e-12) {  // singular pitch: set ψ = 0
        return {0.0, theta, std::atan2(-r(0, 2), r(0, 0))};
      }
      return {std::atan2(r(0, 1), r(1, 1)), theta, std::atan2(r(2, 0), r(2, 2))};
    }
    case AngleConvention::euler_zxz: {
      // R = Rz(ψ)Rx(ϑ)Rz(φ): column 2 = (sinψ sinϑ, -cosψ sinϑ, cosϑ); row 2 = (sinϑ sinφ, sinϑ cosφ, cosϑ).
      const double theta = std::acos(clamp_unit(r(2, 2)));
      if (std::abs(r(2, 2)) > 1.0 - 1e-12) {  // ϑ = 0 or π: set ψ = 0
        return {0.0, theta, std::atan2(r(1, 0), r(0, 0)) * (r(2, 2) > 0 ? 1.0 : -1.0)};
      }
      return {std::atan2(r(0, 2), -r(1, 2)), theta, std::atan2(r(2, 0), r(2, 1))};
    }
  }
  return Eigen::Vector3d::Zero();
}

Eigen::Matrix3d angular_velocity_matrix(AngleConvention convention, const Eigen::Vector3d& angles_rad) {
  // For R = E0 E1 E2 with Ek about axis a_k by s_k·θ_k: ω = Σ_k s_k θ̇_k · (E0 … E(k-1)) a_k.
  const Sequence seq = sequence_of(convention);
  Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d prefix = Eigen::Matrix3d::Identity();
  for (const Elementary& f : seq.factors) {
    e.col(f.angle_index) += f.sign * prefix.col(f.axis);
    prefix = prefix * elementary(f.axis, f.sign * angles_rad[f.angle_index]);
  }
  return e;
}

double distance_from_angle_singularity(AngleConvention convention, const Eigen::Vector3d& angles_rad) {
  const double middle = angles_rad[1];
  if (convention == AngleConvention::euler_zxz) return std::abs(std::sin(middle));
  return std::abs(std::cos(middle));
}

Eigen::Quaterniond quaternion_from_angles(AngleConvention convention, const Eigen::Vector3d& angles_rad) {
  return Eigen::Quaterniond(rotation_from_angles(convention, angles_rad)).normalized();
}

Eigen::Vector3d angles_from_quaternion(AngleConvention convention, const Eigen::Quaterniond& q) {
  return angles_from_rotation(convention, q.normalized().toRotationMatrix());
}

RodriguesCoefficients rodrigues_coefficients(double angle) {
  if (angle < 1e-2) {
    // Series; the first neglected terms are below 3e-17.
    const double t2 = angle * angle;
    return {1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0)),
            0.5 - t2 / 24.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0))};
  }
  return {std::sin(angle) / angle, (1.0 - std::cos(angle)) / (angle * angle)};
}

Eigen::Matrix3d rotation_from_rotation_vector(const Eigen::Vector3d& omega) {
  const Eigen::Matrix3d k = skew(omega);
  const auto [a, b] = rodrigues_coefficients(omega.norm());
  return Eigen::Matrix3d::Identity() + a * k + b * k * k;
}

Eigen::Vector3d rotation_vector_from_rotation(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd aa(rotation);
  return aa.axis() * aa.angle();
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

}  // namespace pkm
