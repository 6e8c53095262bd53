#pragma once
// Named rotation conventions. An angle triple never travels without its convention.
//
// All matrices are *active* rotations R that map platform-frame vectors into the base frame:
//   r_base = R · r_platform + r_pole                                   (dissertation eq. 16/17)
//
//  abc       R = Rz(C)·Ry(B)·Rx(A)       angles (A, B, C): fixed-axis X, Y, Z rotations, as G-code A B C and
//                                         LinuxCNC's hexapod kinematics (dissertation eq. 12, verified)
//  krylov    R = Rz(-ψ)·Rx(-ϑ)·Ry(-γ)    angles (ψ yaw, ϑ pitch, γ roll): the matrix the dissertation
//  actually
//                                         uses in eq. 15/22 (every angle sign reversed w.r.t. the words; ch2
//                                         §3.3)
//  euler_zxz R = Rz(ψ)·Rx(ϑ)·Rz(φ)       angles (ψ precession, ϑ nutation, φ proper rotation) (eq. 13)
//
// Singularities: abc at B = ±90°, krylov at ϑ = ±90°, euler_zxz at ϑ = 0 or 180°.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string_view>

namespace pkm {

enum class AngleConvention { abc, krylov, euler_zxz };

std::string_view to_string(AngleConvention convention);
std::optional<AngleConvention> angle_convention_from_string(std::string_view name);

/// Elementary active rotations about the base axes.
Eigen::Matrix3d rot_x(double angle_rad);
Eigen::Matrix3d rot_y(double angle_rad);
Eigen::Matrix3d rot_z(double angle_rad);

/// R from an angle triple (radians) in the named convention.
Eigen::Matrix3d rotation_from_angles(AngleConvention convention, const Eigen::Vector3d& angles_rad);

/// The same R as the literal product of the convention's elementary rotations (slower; the definition).
Eigen::Matrix3d rotation_from_elementary_product(AngleConvention convention,
                                                 const Eigen::Vector3d& angles_rad);

/// The angle triple (radians) of R in the named convention. Of the two triples that give the same R, the one
/// with the middle angle in [-90°, 90°] (abc, krylov) or [0°, 180°] (euler_zxz) is returned. At the singular
/// middle angle the first angle is set to 0 and the last one carries the whole rotation about that axis.
Eigen::Vector3d angles_from_rotation(AngleConvention convention, const Eigen::Matrix3d& rotation);

/// E(angles): the base-frame angular velocity ω = E · d(angles)/dt for the convention.
Eigen::Matrix3d angular_velocity_matrix(AngleConvention convention, const Eigen::Vector3d& angles_rad);

/// Distance of the middle angle from the convention's singular value, radians (0 = singular).
double distance_from_angle_singularity(AngleConvention convention, const Eigen::Vector3d& angles_rad);

/// Quaternions follow Hamilton's rule (dissertation eq. 40–46); Eigen::Quaterniond is that algebra.
Eigen::Quaterniond quaternion_from_angles(AngleConvention convention, const Eigen::Vector3d& angles_rad);
Eigen::Vector3d angles_from_quaternion(AngleConvention convention, const Eigen::Quaterniond& q);

/// sin(θ)/θ and (1 − cos θ)/θ², by series for small θ (no sin/cos on the solver's hot path).
struct RodriguesCoefficients {
  double a;
  double b;
};
RodriguesCoefficients rodrigues_coefficients(double angle_rad);

/// Rotation by |ω| about ω/|ω| (Rodrigues), exact for any size; used for on-manifold solver updates.
Eigen::Matrix3d rotation_from_rotation_vector(const Eigen::Vector3d& omega_rad);
/// Inverse of rotation_from_rotation_vector, angle in [0, π].
Eigen::Vector3d rotation_vector_from_rotation(const Eigen::Matrix3d& rotation);

/// Skew matrix [v]× with [v]× w = v × w.
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

}  // namespace pkm
