// The tool's dynamic compliance W(iω) = B (K − ω²M + iωC)⁻¹ Bᵀ (src/stiffness/dynamic_compliance.hpp)
// against what it must equal, on the ch5 hexapod, the planar biped and random hexapods with random masses
// and springs (tests/dynamics/dynamics_test_support.hpp), at home and at random poses near it:
//  - W(0) is the static strut-only compliance of the same springs (strut_compliance.hpp, an independent
//    computation from the struts' Plücker lines) when the gravity preload is left out, and K⁻¹ of
//    natural_modes when it is in; the natural frequencies are natural_modes';
//  - a 1-DOF model is 1/(k − ω²m + iωc), and modal damping gives it c = 2ζ√(km);
//  - lightly damped, |W| peaks where K − ω²M is singular (the roots of det(K − ω²M) = 0);
//  - W = Wᵀ; at high frequency ω²W → −B M⁻¹ Bᵀ (|W| → 1/(ω²m));
//  - Rayleigh damping equals modal damping with the ratios it implies, ζ_i = α/(2ω_i) + βω_i/2;
//  - the Bode data: log-spaced frequencies, magnitudes and phases of W's entries, the CSV.
#include "stiffness/dynamic_compliance.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <tuple>
#include <vector>

#include "core/units.hpp"
#include "dynamics/dynamics_test_support.hpp"
#include "formats/stiffness_csv.hpp"
#include "stiffness/compliance_bode.hpp"

namespace pkm {
namespace {

using dynamics::CoordinateMatrix;
using dynamics::CoordinateVector;
using Complex = std::complex<double>;

/// The springs of the elastic model as strut-only stiffness parameters (the same c_j).
StiffnessParameters dynamic_compliance_springs(const DynamicsParameters& p) {
  StiffnessParameters s;
  s.strut_count = p.strut_count;
  s.line = 1;
  for (int j = 0; j < p.strut_count; ++j) s.struts[j].stiffness_N_mm = p.struts[j].stiffness_N_mm;
  return s;
}

/// Home, and the platform moved up to 30 mm (and, for spatial machines, turned up to 5°) from it.
Pose dynamic_compliance_pose(const Mechanism& mech, std::mt19937_64& rng, bool at_home) {
  const Pose home = *mech.complete_pose(mech.home());
  if (at_home) return home;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Pose p = home;
  if (mech.is_planar()) {
    p.position_mm += Eigen::Vector3d(30 * unit(rng), 30 * unit(rng), 0);
    return *mech.complete_pose(p);
  }
  p.position_mm += Eigen::Vector3d(30 * unit(rng), 30 * unit(rng), 30 * unit(rng));
  const Eigen::Vector3d axis = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
  p.rotation = Eigen::AngleAxisd(rad_from_deg(5 * unit(rng)), axis).matrix() * p.rotation;
  return p;
}

/// Rotations weighed by the platform's size, so that one norm fits mm and rad entries.
Eigen::Matrix<double, 6, 1> dynamic_compliance_unit_scale(const Mechanism& mech) {
  Eigen::Matrix<double, 6, 1> s;
  s << 1, 1, 1, mech.platform_size_mm(), mech.platform_size_mm(), mech.platform_size_mm();
  return s;
}

double largest_singular_value(const stiffness::ComplexMatrix6& w, const Eigen::Matrix<double, 6, 1>& scale) {
  const stiffness::ComplexMatrix6 scaled =
      scale.cast<Complex>().asDiagonal() * w * scale.cast<Complex>().asDiagonal();
  return Eigen::JacobiSVD<stiffness::ComplexMatrix6>(scaled).singularValues()[0];
}

/// Random symmetric positive definite n × n, eigenvalues around `scale`.
CoordinateMatrix dynamic_compliance_spd(std::mt19937_64& rng, int n, double scale) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  CoordinateMatrix a(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) a(r, c) = unit(rng);
  return scale * (a * a.transpose() + 0.5 * CoordinateMatrix::Identity(n, n));
}

TEST(DynamicCompliance, AtZeroFrequencyIsTheStaticStrutCompliance) {
  std::mt19937_64 rng(1501);
  for (const auto& c : test::elastic_cases(StrutDamping::none)) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    auto model = dynamics::make_elastic_model(mech, c.parameters);
    ASSERT_TRUE(model.ok()) << model.error().message;
    for (bool at_home : {true, false}) {
      const Pose pose = dynamic_compliance_pose(mech, rng, at_home);
      stiffness::DynamicComplianceOptions options;
      options.gravity_preload = false;
      auto linear = stiffness::tool_dynamics(*model, pose, options);
      ASSERT_TRUE(linear.ok()) << linear.error().message;
      auto w0 = stiffness::dynamic_compliance(*linear, 0.0);
      ASSERT_TRUE(w0.ok()) << w0.error().message;
      auto statics = stiffness::strut_compliance(mech, dynamic_compliance_springs(c.parameters), pose);
      ASSERT_TRUE(statics.ok()) << statics.error().message;
      const double scale = statics->compliance.cwiseAbs().maxCoeff();
      EXPECT_LE((w0->real() - statics->compliance).cwiseAbs().maxCoeff(), 1e-10 * scale);
      EXPECT_EQ(w0->imag().cwiseAbs().maxCoeff(), 0.0);

      // With the gravity preload: K⁻¹ of natural_modes (its K and its frequencies), about the sagged
      // equilibrium and with the preload's geometric stiffness.
      auto preloaded = stiffness::tool_dynamics(*model, pose);
      ASSERT_TRUE(preloaded.ok()) << preloaded.error().message;
      auto modes = dynamics::natural_modes(*model, pose);
      ASSERT_TRUE(modes.ok()) << modes.error().message;
      EXPECT_LE((preloaded->frequency_Hz - modes->frequency_Hz).cwiseAbs().maxCoeff(),
                1e-9 * modes->frequency_Hz.maxCoeff());
      auto w0_preloaded = stiffness::dynamic_compliance(*preloaded, 0.0);
      ASSERT_TRUE(w0_preloaded.ok());
      const stiffness::Matrix6 expected =
          1e3 * model->basis * modes->stiffness.inverse() * model->basis.transpose();
      EXPECT_LE((w0_preloaded->real() - expected).cwiseAbs().maxCoeff(), 1e-9 * scale);
      // On the shipped machines the preload's share is ~10⁻⁵ (random ones may sit nearer to buckling).
      if (c.label.find("random") == std::string::npos) {
        EXPECT_LE((w0_preloaded->real() - statics->compliance).cwiseAbs().maxCoeff(), 1e-4 * scale);
      }
    }
  }
}

TEST(DynamicCompliance, OneDegreeOfFreedomIsItsClosedForm) {
  std::mt19937_64 rng(1502);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const double m = 1 + 99 * unit(rng), k = 1e5 + 1e8 * unit(rng), c = 1e3 * unit(rng);
    const CoordinateMatrix mm = CoordinateMatrix::Constant(1, 1, m), kk = CoordinateMatrix::Constant(1, 1, k),
                           cc = CoordinateMatrix::Constant(1, 1, c);
    const double omega_n = std::sqrt(k / m);
    for (double ratio : {0.0, 0.1, 0.5, 0.999, 1.001, 2.0, 1e3}) {
      const double omega = ratio * omega_n;
      auto h = stiffness::receptance(mm, kk, cc, omega);
      ASSERT_TRUE(h.ok()) << h.error().message;
      const Complex expected = 1.0 / Complex(k - omega * omega * m, omega * c);
      EXPECT_LE(std::abs((*h)(0, 0) - expected), 1e-13 * std::abs(expected)) << ratio;
    }
    // Modal damping of ratio ζ is c = 2ζ√(km); Rayleigh fitted at any two frequencies gives ζ at ω_n only
    // where one of them is ω_n.
    const double zeta = 0.2 * unit(rng);
    stiffness::DampingAssumption modal;
    modal.modal_ratio = zeta;
    auto modal_c = stiffness::damping_matrix(mm, kk, modal);
    ASSERT_TRUE(modal_c.ok());
    EXPECT_NEAR((*modal_c)(0, 0), 2 * zeta * std::sqrt(k * m), 1e-12 * 2 * zeta * std::sqrt(k * m) + 1e-300);
    const double f_n = omega_n / (2 * kPi);
    auto rayleigh_c = stiffness::damping_matrix(mm, kk, stiffness::rayleigh_for_ratio(zeta, f_n, 3 * f_n));
    ASSERT_TRUE(rayleigh_c.ok());
    EXPECT_NEAR((*rayleigh_c)(0, 0), (*modal_c)(0, 0), 1e-12 * (*modal_c)(0, 0) + 1e-300);
  }
  // Undamped, exactly at the natural frequency: unbounded, said so.
  const CoordinateMatrix one = CoordinateMatrix::Constant(1, 1, 4.0), zero = CoordinateMatrix::Zero(1, 1);
  auto at_resonance = stiffness::receptance(one, CoordinateMatrix::Constant(1, 1, 16.0), zero, 2.0);
  ASSERT_FALSE(at_resonance.ok());
  EXPECT_EQ(at_resonance.error().code, ErrorCode::singular);
}

TEST(DynamicCompliance, LightlyDampedPeaksSitAtTheRootsOfTheFrequencyDeterminant) {
  std::mt19937_64 rng(1503);
  for (const auto& c : test::elastic_cases(StrutDamping::none, 3)) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    auto model = dynamics::make_elastic_model(mech, c.parameters);
    ASSERT_TRUE(model.ok());
    stiffness::DynamicComplianceOptions options;
    options.gravity_preload = false;
    options.damping.modal_ratio = 1e-4;
    auto linear = stiffness::tool_dynamics(*model, dynamic_compliance_pose(mech, rng, false), options);
    ASSERT_TRUE(linear.ok()) << linear.error().message;
    const auto scale = dynamic_compliance_unit_scale(mech);
    const auto size = [&](double f) {
      return largest_singular_value(*stiffness::dynamic_compliance(*linear, f), scale);
    };
    const CoordinateVector& f = linear->frequency_Hz;
    for (int i = 0; i < f.size(); ++i) {
      if (i > 0 && f[i] - f[i - 1] < 1e-6 * f[i]) continue;  // a double root: found once
      // The bracket reaches half way to the neighbouring distinct roots.
      double below = 0.05, above = 0.05;
      for (int k = 0; k < f.size(); ++k) {
        if (f[k] < f[i] * (1 - 1e-6)) below = std::min(below, 0.5 * (f[i] - f[k]) / f[i]);
        if (f[k] > f[i] * (1 + 1e-6)) above = std::min(above, 0.5 * (f[k] - f[i]) / f[i]);
      }
      // Golden-section search for the largest |W| in the bracket.
      double a = f[i] * (1 - below), b = f[i] * (1 + above);
      const double g = 0.5 * (std::sqrt(5.0) - 1);
      double x1 = b - g * (b - a), x2 = a + g * (b - a), s1 = size(x1), s2 = size(x2);
      for (int step = 0; step < 200 && b - a > 1e-13 * f[i]; ++step) {
        if (s1 > s2) {
          b = x2, x2 = x1, s2 = s1, x1 = b - g * (b - a), s1 = size(x1);
        } else {
          a = x1, x1 = x2, s1 = s2, x2 = a + g * (b - a), s2 = size(x2);
        }
      }
      const double peak_Hz = 0.5 * (a + b);
      EXPECT_NEAR(peak_Hz, f[i], 1e-6 * f[i]) << "mode " << i + 1;
      // det(K − ω²M) = 0 there: K − ω²M is singular to the peak's precision (equilibrated by K's diagonal).
      const double omega = 2 * kPi * peak_Hz;
      const CoordinateVector d = linear->stiffness.diagonal().cwiseSqrt().cwiseInverse();
      const CoordinateMatrix a_matrix =
          d.asDiagonal() * (linear->stiffness - omega * omega * linear->mass) * d.asDiagonal();
      const auto singular = Eigen::JacobiSVD<CoordinateMatrix>(a_matrix).singularValues();
      EXPECT_LT(singular[singular.size() - 1], 1e-5 * singular[0]) << "mode " << i + 1;
    }
  }
}

TEST(DynamicCompliance, IsSymmetricAndFallsAsOneOverOmegaSquaredTimesTheMass) {
  std::mt19937_64 rng(1504);
  for (const auto& c : test::elastic_cases(StrutDamping::none)) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    auto model = dynamics::make_elastic_model(mech, c.parameters);
    ASSERT_TRUE(model.ok());
    for (stiffness::DampingModel damping :
         {stiffness::DampingModel::modal, stiffness::DampingModel::rayleigh}) {
      stiffness::DynamicComplianceOptions options;
      options.damping.model = damping;
      options.damping.modal_ratio = 0.05;
      options.damping.rayleigh_mass_per_s = 50.0;
      options.damping.rayleigh_stiffness_s = 2e-5;
      auto linear = stiffness::tool_dynamics(*model, dynamic_compliance_pose(mech, rng, false), options);
      ASSERT_TRUE(linear.ok()) << linear.error().message;
      const double f_top = linear->frequency_Hz.maxCoeff();
      for (double f :
           {0.0, 0.3 * linear->frequency_Hz[0], linear->frequency_Hz[0], 0.7 * f_top, f_top, 3 * f_top}) {
        auto w = stiffness::dynamic_compliance(*linear, f);
        ASSERT_TRUE(w.ok());
        EXPECT_LE((*w - w->transpose()).cwiseAbs().maxCoeff(), 1e-12 * w->cwiseAbs().maxCoeff()) << f;
      }
      // ω²W → −B M⁻¹ Bᵀ (per N: × 10³); the error falls as the frequency rises.
      const stiffness::Matrix6 inertia =
          -1e3 * model->basis * linear->mass.inverse() * model->basis.transpose();
      double previous = std::numeric_limits<double>::infinity();
      for (double ratio : {1e2, 1e3, 1e4}) {
        const double f = ratio * f_top, omega = 2 * kPi * f;
        auto w = stiffness::dynamic_compliance(*linear, f);
        ASSERT_TRUE(w.ok());
        const double error = (omega * omega * *w - inertia.cast<Complex>()).cwiseAbs().maxCoeff() /
                             inertia.cwiseAbs().maxCoeff();
        EXPECT_LT(error, previous);
        previous = error;
      }
      EXPECT_LT(previous, 1e-4);
    }
  }
  // One degree of freedom: |W| ω² m → 1.
  const CoordinateMatrix m = CoordinateMatrix::Constant(1, 1, 30.0),
                         k = CoordinateMatrix::Constant(1, 1, 3e7),
                         c = CoordinateMatrix::Constant(1, 1, 600.0);
  const double omega = 1e4 * std::sqrt(3e7 / 30.0);
  EXPECT_NEAR(std::abs((*stiffness::receptance(m, k, c, omega))(0, 0)) * omega * omega * 30.0, 1.0, 1e-6);
}

TEST(DynamicCompliance, RayleighDampingEqualsModalDampingWithTheRatiosItImplies) {
  std::mt19937_64 rng(1505);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Two degrees of freedom, Rayleigh fitted to ζ at both natural frequencies: the same C, the same W.
  for (int trial = 0; trial < 10; ++trial) {
    const CoordinateMatrix m = dynamic_compliance_spd(rng, 2, 50.0), k = dynamic_compliance_spd(rng, 2, 1e8);
    const Eigen::GeneralizedSelfAdjointEigenSolver<CoordinateMatrix> modes(k, m);
    const double f1 = std::sqrt(modes.eigenvalues()[0]) / (2 * kPi),
                 f2 = std::sqrt(modes.eigenvalues()[1]) / (2 * kPi);
    const double zeta = 0.1 * unit(rng);
    stiffness::DampingAssumption modal;
    modal.modal_ratio = zeta;
    auto c_modal = stiffness::damping_matrix(m, k, modal);
    auto c_rayleigh = stiffness::damping_matrix(m, k, stiffness::rayleigh_for_ratio(zeta, f1, f2));
    ASSERT_TRUE(c_modal.ok() && c_rayleigh.ok());
    EXPECT_LE((*c_modal - *c_rayleigh).cwiseAbs().maxCoeff(), 1e-10 * c_modal->cwiseAbs().maxCoeff());
    for (double f : {0.5 * f1, f1, 0.5 * (f1 + f2), f2, 2 * f2}) {
      const auto a = *stiffness::receptance(m, k, *c_modal, 2 * kPi * f);
      const auto b = *stiffness::receptance(m, k, *c_rayleigh, 2 * kPi * f);
      EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-9 * a.cwiseAbs().maxCoeff()) << f;
    }
  }
  // The machines: αM + βK equals modal damping with ζ_i = α/(2ω_i) + βω_i/2, which tool_dynamics reports.
  for (const auto& c : test::elastic_cases(StrutDamping::none, 3)) {
    SCOPED_TRACE(c.label);
    auto model = dynamics::make_elastic_model(*c.machine.mechanism, c.parameters);
    ASSERT_TRUE(model.ok());
    stiffness::DynamicComplianceOptions options;
    options.damping.model = stiffness::DampingModel::rayleigh;
    options.damping.rayleigh_mass_per_s = 100 * unit(rng);
    options.damping.rayleigh_stiffness_s = 1e-4 * unit(rng);
    auto rayleigh = stiffness::tool_dynamics(*model, c.machine.mechanism->home(), options);
    ASSERT_TRUE(rayleigh.ok()) << rayleigh.error().message;
    const CoordinateVector omega = 2 * kPi * rayleigh->frequency_Hz;
    const CoordinateVector ratios = (options.damping.rayleigh_mass_per_s * 0.5 * omega.cwiseInverse() +
                                     options.damping.rayleigh_stiffness_s * 0.5 * omega)
                                        .eval();
    EXPECT_LE((rayleigh->damping_ratio - ratios).cwiseAbs().maxCoeff(), 1e-12 * ratios.maxCoeff());
    auto modal_c = stiffness::modal_damping_matrix(rayleigh->mass, rayleigh->stiffness, ratios);
    ASSERT_TRUE(modal_c.ok());
    EXPECT_LE((*modal_c - rayleigh->damping).cwiseAbs().maxCoeff(),
              1e-9 * rayleigh->damping.cwiseAbs().maxCoeff());
    stiffness::ToolDynamics modal = *rayleigh;
    modal.damping = *modal_c;
    for (int i = 0; i < omega.size(); ++i) {
      const double f = rayleigh->frequency_Hz[i] * (1 + 0.01 * i);
      const auto a = *stiffness::dynamic_compliance(*rayleigh, f);
      const auto b = *stiffness::dynamic_compliance(modal, f);
      EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-8 * a.cwiseAbs().maxCoeff()) << f;
    }
  }
}

TEST(DynamicCompliance, RefusesABadAssumptionAFrequencyAndASingularPose) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto model = dynamics::make_elastic_model(machine);
  ASSERT_TRUE(model.ok());
  for (double ratio :
       {-0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    stiffness::DynamicComplianceOptions options;
    options.damping.modal_ratio = ratio;
    auto linear = stiffness::tool_dynamics(*model, machine.mechanism->home(), options);
    ASSERT_FALSE(linear.ok()) << ratio;
    EXPECT_EQ(linear.error().code, ErrorCode::bad_input);
    EXPECT_NE(linear.error().message.find("damping ratio"), std::string::npos) << linear.error().message;
  }
  stiffness::DynamicComplianceOptions rayleigh;
  rayleigh.damping.model = stiffness::DampingModel::rayleigh;
  rayleigh.damping.rayleigh_stiffness_s = -1e-5;
  auto negative = stiffness::tool_dynamics(*model, machine.mechanism->home(), rayleigh);
  ASSERT_FALSE(negative.ok());
  EXPECT_EQ(negative.error().code, ErrorCode::bad_input);
  // Turned by 90° about z, Fichter's singularity: nothing holds a turn about z, K is singular.
  stiffness::DynamicComplianceOptions springs_only;
  springs_only.gravity_preload = false;
  auto singular = stiffness::tool_dynamics(*model, test::abc_pose(0, 0, 700, 0, 0, 90), springs_only);
  ASSERT_FALSE(singular.ok());
  EXPECT_EQ(singular.error().code, ErrorCode::singular);
  auto linear = stiffness::tool_dynamics(*model, machine.mechanism->home());
  ASSERT_TRUE(linear.ok());
  for (double f : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    auto w = stiffness::dynamic_compliance(*linear, f);
    ASSERT_FALSE(w.ok());
    EXPECT_EQ(w.error().code, ErrorCode::bad_input);
  }
  // A machine without a dynamics: section: the file and the key.
  const Machine bare = test::machine_from_example("examples/machines/hexapod_genhexkins.yaml");
  stiffness::BodeRequest request;
  auto bode = stiffness::machine_bode(bare, bare.mechanism->home(), request);
  ASSERT_FALSE(bode.ok());
  EXPECT_EQ(bode.error().code, ErrorCode::bad_input);
  EXPECT_EQ(bode.error().location.key, "dynamics");
  EXPECT_NE(bode.error().message.find("hexapod_genhexkins.yaml"), std::string::npos) << bode.error().message;
}

TEST(ComplianceBode, FrequenciesAreLogSpacedWithBothEnds) {
  auto f = stiffness::log_spaced_frequencies(10.0, 2000.0, 37);
  ASSERT_TRUE(f.ok());
  ASSERT_EQ(f->size(), 37u);
  EXPECT_EQ(f->front(), 10.0);
  EXPECT_EQ(f->back(), 2000.0);
  const double ratio = (*f)[1] / (*f)[0];
  for (std::size_t k = 1; k < f->size(); ++k) EXPECT_NEAR((*f)[k] / (*f)[k - 1], ratio, 1e-12 * ratio);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::tuple<double, double, int>> refused = {
      {0.0, 100.0, 10},    {-1.0, 100.0, 10},
      {100.0, 100.0, 10},  {100.0, 10.0, 10},
      {1.0, 10.0, 1},      {nan, 10.0, 10},
      {1.0, nan, 10},      {1.0, std::numeric_limits<double>::infinity(), 10},
      {1.0, 10.0, 1000000}};
  for (const auto& [lo, hi, n] : refused) {
    auto bad = stiffness::log_spaced_frequencies(lo, hi, n);
    ASSERT_FALSE(bad.ok()) << lo << " " << hi << " " << n;
    EXPECT_EQ(bad.error().code, ErrorCode::bad_input);
  }
}

TEST(ComplianceBode, EntriesAreTheCompliancesMagnitudesAndPhasesAndTheCsvHoldsThem) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  stiffness::BodeRequest request;
  request.f_min_Hz = 0.01;
  request.f_max_Hz = 1e6;
  request.points = 81;  // ten per decade
  auto data = stiffness::machine_bode(machine, machine.mechanism->home(), request);
  ASSERT_TRUE(data.ok()) << data.error().message;
  ASSERT_EQ(data->entries.size(), 4u);
  EXPECT_EQ(data->entries[3].name, "tool_axis");
  EXPECT_NEAR(data->entries[3].displacement_direction.z(), 1.0, 1e-6);  // home: the tool axis is base z
  auto model = dynamics::make_elastic_model(machine);
  auto linear = stiffness::tool_dynamics(*model, machine.mechanism->home(), request.options);
  ASSERT_TRUE(linear.ok());
  EXPECT_EQ(data->natural_frequency_Hz, linear->frequency_Hz);
  for (std::size_t e = 0; e < data->entries.size(); ++e) {
    const Eigen::Vector3d r = data->entries[e].displacement_direction;
    for (std::size_t k = 0; k < data->frequency_Hz.size(); k += 7) {
      const auto w = *stiffness::dynamic_compliance(*linear, data->frequency_Hz[k]);
      const Complex value =
          (r.cast<Complex>().transpose() * w.topLeftCorner<3, 3>() * r.cast<Complex>())(0, 0);
      EXPECT_NEAR(data->magnitude_um_N[e][k], 1e3 * std::abs(value), 1e-12 * 1e3 * std::abs(value));
      EXPECT_NEAR(data->phase_deg[e][k], deg_from_rad(std::arg(value)), 1e-9);
      // A direct compliance lags: the phase is in [−180°, 0°].
      EXPECT_LE(data->phase_deg[e][k], 1e-9);
      EXPECT_GE(data->phase_deg[e][k], -180.0 - 1e-9);
    }
    // Far below the first mode the magnitude is the static one, the phase ~0; far above, it falls as 1/f².
    const auto w0 = *stiffness::dynamic_compliance(*linear, 0.0);
    EXPECT_NEAR(data->magnitude_um_N[e].front(),
                1e3 * (r.transpose() * w0.real().topLeftCorner<3, 3>() * r)(0, 0),
                1e-6 * data->magnitude_um_N[e].front());
    EXPECT_GT(data->phase_deg[e].front(), -0.01);
    const std::size_t n = data->frequency_Hz.size();
    // The last decade (10⁵…10⁶ Hz) is 180 times above the highest mode.
    const double decade = data->magnitude_um_N[e][n - 1] / data->magnitude_um_N[e][n - 11];
    EXPECT_NEAR(decade, 0.01, 1e-5);
    EXPECT_LT(data->phase_deg[e].back(), -179.0);
  }
  const std::string csv = formats::bode_csv(*data);
  std::istringstream lines(csv);
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header,
            "frequency_Hz,xx_magnitude_um_N,xx_phase_deg,yy_magnitude_um_N,yy_phase_deg,zz_magnitude_um_N,"
            "zz_phase_deg,tool_axis_magnitude_um_N,tool_axis_phase_deg");
  int rows = 0;
  for (std::string line; std::getline(lines, line);) ++rows;
  EXPECT_EQ(rows, request.points);
  // Written whole or not at all.
  const auto dir = std::filesystem::temp_directory_path() / "pkm_bode_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "bode.csv").string();
  ASSERT_TRUE(formats::write_bode_csv(path, *data).ok());
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), csv);
  auto refused = formats::write_bode_csv((dir / "missing" / "bode.csv").string(), *data);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::io);
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
}

}  // namespace
}  // namespace pkm
