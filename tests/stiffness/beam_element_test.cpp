// The frame model's beam element (src/stiffness/beam_element.hpp) against a textbook cantilever:
//  - the closed-form tip values QL³/3EJ, QL²/2EJ, ML²/2EJ, ML/EJ, QL/EF, ML/GJ_t (the cantilever of Rusanov
//    et al. with the printed errors corrected: L³ in entry (1,1), couplings of one sign per bending plane and
//    the same in both places) come out of an independent integration of the elastic line (vector statics and
//    small-rotation kinematics, no sign table), to 1e-12;
//  - the finite-element beam clamped at one end, at random lengths, sections, materials and orientations in
//    space, gives the tip those values, to 1e-12 relative;
//  - the element stiffness is symmetric, positive semi-definite with exactly the six rigid-body motions as
//  its
//    null space, and the cantilever compliance symmetric positive definite.
#include "stiffness/beam_element.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <random>

#include "core/rotation.hpp"

namespace pkm {
namespace {

using stiffness::Matrix12;
using stiffness::Matrix6;
using BeamVector6 = Eigen::Matrix<double, 6, 1>;

// Steel or aluminium, sections of real proportions: radii of gyration 20…100 mm about either axis (so slender
// beams, L/r up to 100), a torsion constant near the polar moment.
BeamSection random_beam_section(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BeamSection s;
  s.modulus_N_mm2 = 7e4 + 1.4e5 * unit(rng);
  s.shear_modulus_N_mm2 = s.modulus_N_mm2 / (2.0 * (1.25 + 0.2 * unit(rng)));
  s.area_mm2 = 500.0 + 2e4 * unit(rng);
  const double rx = 20.0 + 80.0 * unit(rng), ry = 20.0 + 80.0 * unit(rng);
  s.second_moment_x_mm4 = s.area_mm2 * rx * rx;
  s.second_moment_y_mm4 = s.area_mm2 * ry * ry;
  s.torsion_constant_mm4 = (0.3 + 0.7 * unit(rng)) * (s.second_moment_x_mm4 + s.second_moment_y_mm4);
  return s;
}

Eigen::Vector3d random_beam_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

// The textbook cantilever, clamped at s = 0 along e_z, tip load (Q, M) at s = L: the moment a section carries
// is M(s) = M + (L − s) e_z × Q (statics of the part beyond it), its curvature κ = (M_x/EJ_x, M_y/EJ_y,
// M_z/GJ_t), the section turns by φ(s) = ∫₀ˢ κ, and the centre line follows du/ds = φ × e_z plus the axial
// strain Q_z/EF. Integrated by Gauss–Legendre rules exact for these polynomials (κ linear, φ quadratic).
BeamVector6 elastic_line_tip(const BeamSection& s, double length, const BeamVector6& load) {
  const Eigen::Vector3d q = load.head<3>(), m = load.tail<3>(), ez = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d flexibility(1.0 / (s.modulus_N_mm2 * s.second_moment_x_mm4),
                                    1.0 / (s.modulus_N_mm2 * s.second_moment_y_mm4),
                                    1.0 / (s.shear_modulus_N_mm2 * s.torsion_constant_mm4));
  const auto curvature = [&](double at) {
    return Eigen::Vector3d((m + (length - at) * ez.cross(q)).cwiseProduct(flexibility));
  };
  // Three-point Gauss–Legendre on [0, b]: exact to degree 5.
  const double nodes[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const auto rotation = [&](double at) {
    Eigen::Vector3d phi = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) phi += 0.5 * at * weights[i] * curvature(0.5 * at * (nodes[i] + 1.0));
    return phi;
  };
  Eigen::Vector3d u = ez * q.z() * length / (s.modulus_N_mm2 * s.area_mm2);
  for (int i = 0; i < 3; ++i)
    u += 0.5 * length * weights[i] * rotation(0.5 * length * (nodes[i] + 1.0)).cross(ez);
  BeamVector6 tip;
  tip << u, rotation(length);
  return tip;
}

TEST(BeamElement, CantileverTipValuesAreTheClosedFormsOfTheElasticLine) {
  std::mt19937_64 rng(1501);
  for (int trial = 0; trial < 20; ++trial) {
    const BeamSection s = random_beam_section(rng);
    const double l = 200.0 + 1800.0 * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const double e = s.modulus_N_mm2, jx = s.second_moment_x_mm4, jy = s.second_moment_y_mm4;
    const Matrix6 c = stiffness::cantilever_compliance(s, l);
    // Column by column: a unit load component, its tip values by the elastic line and by name.
    for (int k = 0; k < 6; ++k) {
      BeamVector6 unit = BeamVector6::Zero();
      unit[k] = 1.0;
      const BeamVector6 textbook = elastic_line_tip(s, l, unit);
      for (int i = 0; i < 6; ++i) {
        EXPECT_NEAR(c(i, k), textbook[i], 1e-12 * textbook.cwiseAbs().maxCoeff()) << i << ", " << k;
      }
    }
    // The closed-form tip values by name, with the signs the elastic line gives.
    EXPECT_NEAR(c(0, 0), l * l * l / (3 * e * jy), 1e-12 * c(0, 0));  // Q L³/3EJ
    EXPECT_NEAR(c(1, 1), l * l * l / (3 * e * jx), 1e-12 * c(1, 1));
    EXPECT_NEAR(c(4, 0), l * l / (2 * e * jy), 1e-12 * c(4, 4) * l);   // Q L²/2EJ: turns about +y
    EXPECT_NEAR(c(3, 1), -l * l / (2 * e * jx), 1e-12 * c(3, 3) * l);  // … and about −x
    EXPECT_NEAR(c(0, 4), l * l / (2 * e * jy), 1e-12 * c(4, 4) * l);   // M L²/2EJ
    EXPECT_NEAR(c(1, 3), -l * l / (2 * e * jx), 1e-12 * c(3, 3) * l);
    EXPECT_NEAR(c(4, 4), l / (e * jy), 1e-12 * c(4, 4));  // M L/EJ
    EXPECT_NEAR(c(3, 3), l / (e * jx), 1e-12 * c(3, 3));
    EXPECT_NEAR(c(2, 2), l / (e * s.area_mm2), 1e-12 * c(2, 2));                                  // Q L/EF
    EXPECT_NEAR(c(5, 5), l / (s.shear_modulus_N_mm2 * s.torsion_constant_mm4), 1e-12 * c(5, 5));  // M L/GJ_t
    // Symmetric positive definite, and cantilever_stiffness is its inverse.
    EXPECT_EQ((c - c.transpose()).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(Eigen::LLT<Matrix6>(c).info(), Eigen::Success);
    const Matrix6 k = stiffness::cantilever_stiffness(s, l);
    // Against the size of the terms that cancel (k and c mix mm and rad).
    const Matrix6 terms = k.cwiseAbs() * c.cwiseAbs();
    EXPECT_LT(((k * c - Matrix6::Identity()).cwiseAbs().array() / (terms.array() + 1e-300)).maxCoeff(),
              1e-14);
  }
}

TEST(BeamElement, ClampedElementInAnyOrientationGivesTheCantileverTip) {
  std::mt19937_64 rng(1502);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const BeamSection s = random_beam_section(rng);
    const double l = 200.0 + 1800.0 * unit(rng);
    const Eigen::Vector3d from(1000 * unit(rng), 1000 * unit(rng), 1000 * unit(rng));
    const Eigen::Vector3d axis = random_beam_unit(rng);
    Eigen::Vector3d section_x = random_beam_unit(rng);
    const Matrix12 k = stiffness::beam_stiffness_global(s, from, from + l * axis, section_x);
    // Node 0 clamped: the tip's stiffness is the lower right block; the compliance in the beam's own axes is
    // γ K₁₁⁻¹ γᵀ per 3 × 3 block.
    const Matrix6 tip_stiffness = k.block<6, 6>(6, 6);
    const Matrix6 global_compliance = tip_stiffness.ldlt().solve(Matrix6::Identity());
    const Eigen::Matrix3d gamma = stiffness::beam_axes(axis, section_x);
    Matrix6 big_gamma = Matrix6::Zero();
    big_gamma.block<3, 3>(0, 0) = big_gamma.block<3, 3>(3, 3) = gamma;
    const Matrix6 local = big_gamma * global_compliance * big_gamma.transpose();
    const Matrix6 closed = stiffness::cantilever_compliance(s, l);
    // The entries that are zero in closed form must be zero relative to their row's and column's scale.
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) {
        const double scale =
            closed(i, j) != 0.0 ? std::abs(closed(i, j)) : std::sqrt(closed(i, i) * closed(j, j));
        EXPECT_LT(std::abs(local(i, j) - closed(i, j)), 1e-12 * scale)
            << i << ", " << j << " trial " << trial;
      }
    }
    // The beam's axes: right-handed, orthonormal, z along the beam, x in the plane of z and section_x.
    EXPECT_LT((gamma * gamma.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-13);
    EXPECT_NEAR(gamma.determinant(), 1.0, 1e-14);
    EXPECT_LT((gamma.row(2).transpose() - axis).norm(), 1e-14);
    EXPECT_GT(gamma.row(0).dot(section_x), 0.0);
    EXPECT_NEAR(gamma.row(1).dot(section_x), 0.0, 1e-14);
  }
}

TEST(BeamElement, StiffnessIsSymmetricWithTheRigidMotionsAsItsNullSpace) {
  std::mt19937_64 rng(1503);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const BeamSection s = random_beam_section(rng);
    const Eigen::Vector3d from(500 * unit(rng), 500 * unit(rng), 500 * unit(rng));
    const Eigen::Vector3d to = from + (100 + 1500 * unit(rng)) * random_beam_unit(rng);
    const Matrix12 k = stiffness::beam_stiffness_global(s, from, to, random_beam_unit(rng));
    EXPECT_LE((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-12 * k.cwiseAbs().maxCoeff());
    // A rigid motion (d, θ) of the whole beam: node i moves by d + θ × x_i, turns by θ; no force.
    for (int motion = 0; motion < 6; ++motion) {
      BeamVector6 twist = BeamVector6::Zero();
      twist[motion] = 1.0;
      Eigen::Matrix<double, 12, 1> q;
      q << stiffness::rigid_transfer(from) * twist, stiffness::rigid_transfer(to) * twist;
      const Eigen::Matrix<double, 12, 1> f = k * q;
      // Against the size of the terms that cancel.
      EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-11 * (k.cwiseAbs() * q.cwiseAbs()).maxCoeff())
          << "motion " << motion;
    }
    // Exactly six zero eigenvalues in consistent units (rotations times the beam's length).
    Eigen::Matrix<double, 12, 1> scale = Eigen::Matrix<double, 12, 1>::Ones();
    const double l = (to - from).norm();
    scale.segment<3>(3).setConstant(1.0 / l);
    scale.segment<3>(9).setConstant(1.0 / l);
    const Matrix12 scaled = scale.asDiagonal() * k * scale.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Matrix12> spectrum(scaled);
    int zero = 0;
    for (int i = 0; i < 12; ++i) {
      EXPECT_GT(spectrum.eigenvalues()[i], -1e-9 * spectrum.eigenvalues().maxCoeff());
      zero += spectrum.eigenvalues()[i] < 1e-9 * spectrum.eigenvalues().maxCoeff() ? 1 : 0;
    }
    EXPECT_EQ(zero, 6);
  }
}

}  // namespace
}  // namespace pkm
