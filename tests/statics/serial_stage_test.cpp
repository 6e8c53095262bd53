// The serial 2-axis stage of Smirnov 2019, §3.1 (Figs. 60–61): the whole reference table, the
// useful-energy bound (69) and its maximum (71).
#include "statics/serial_stage.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/units.hpp"

namespace pkm::statics {
namespace {

struct V1Row {
  double angle_deg, useful_Nmm, friction_Nmm, total_Nmm;
};

// Smirnov 2019, §3.1: P_τ = P_n = 100 N, dL = 1 mm, f = 0.1 (the values recomputed from (66), (68)).
constexpr V1Row kV1Table[] = {
    {0, 100.000, 11.000, 111.000},     {15, 100.000, 14.343, 114.343},  {30, 100.000, 13.977, 113.977},
    {45, 100.000, 10.000, 110.000},    {60, 136.603, 9.817, 146.420},   {67.5, 141.421, 9.793, 151.214},
    {75, 136.603, 9.817, 146.420},     {90, 100.000, 10.000, 110.000},  {135, 100.000, 11.000, 111.000},
    {157.5, 141.421, 11.207, 152.628}, {180, 100.000, 11.000, 111.000}, {247.5, 141.421, 9.793, 151.214},
    {337.5, 141.421, 11.207, 152.628},
};

TEST(SerialStage, ReproducesTheV1Table) {
  for (const V1Row& row : kV1Table) {
    SCOPED_TRACE(row.angle_deg);
    const SerialStageEnergy e = serial_stage_step_energy(100.0, 100.0, rad_from_deg(row.angle_deg), 1.0, 0.1);
    EXPECT_NEAR(e.useful_Nmm, row.useful_Nmm, 1e-3);
    EXPECT_NEAR(e.friction_Nmm, row.friction_Nmm, 1e-3);
    EXPECT_NEAR(e.total_Nmm(), row.total_Nmm, 1e-3);
    EXPECT_DOUBLE_EQ(e.required_Nmm, 100.0);
  }
}

TEST(SerialStage, DriveForces66) {
  const SerialStageDriveForces p = serial_stage_drive_forces(100.0, 100.0, rad_from_deg(30.0));
  EXPECT_NEAR(p.x_N, 100 * std::cos(kPi / 6) - 100 * std::sin(kPi / 6), 1e-12);
  EXPECT_NEAR(p.y_N, 100 * std::sin(kPi / 6) + 100 * std::cos(kPi / 6), 1e-12);
  // (67): the drives together do the work of P_τ only.
  const double dx = std::cos(kPi / 6), dy = std::sin(kPi / 6);
  EXPECT_NEAR(p.x_N * dx + p.y_N * dy, 100.0, 1e-12);
}

TEST(SerialStage, UsefulEnergyBoundAndItsMaximum) {
  // (69): useful ≥ required, with equality on [0°, arctan(P_τ/P_n)] = [0°, 45°]; (71): the maximum
  // P_ext dL = √2 · 100 N·mm at φ = −½ arctan(P_n/P_τ) ≡ 67.5° (mod 90°).
  double best = 0.0, best_angle = -1.0;
  for (int tenth = 0; tenth <= 900; ++tenth) {
    const double deg = tenth / 10.0;
    const SerialStageEnergy e = serial_stage_step_energy(100.0, 100.0, rad_from_deg(deg), 1.0, 0.0);
    EXPECT_GE(e.useful_Nmm, e.required_Nmm - 1e-9) << deg;
    if (deg <= 45.0) {
      EXPECT_NEAR(e.useful_Nmm, e.required_Nmm, 1e-9) << deg;
    } else if (deg < 89.95) {
      EXPECT_GT(e.useful_Nmm, e.required_Nmm + 1e-9) << deg;
    }
    if (e.useful_Nmm > best) {
      best = e.useful_Nmm;
      best_angle = deg;
    }
    EXPECT_EQ(e.friction_Nmm, 0.0);
  }
  EXPECT_DOUBLE_EQ(best_angle, 67.5);
  EXPECT_NEAR(best, std::sqrt(2.0) * 100.0, 1e-9);
}

TEST(SerialStage, FrictionKeepsTheMaximumAtTheSameAngle) {
  // Fig. 61: the total with f = 0.1 peaks where the useful energy does (on [0°, 90°]).
  double best = 0.0, best_angle = -1.0;
  for (int tenth = 0; tenth <= 900; ++tenth) {
    const double deg = tenth / 10.0;
    const double total = serial_stage_step_energy(100.0, 100.0, rad_from_deg(deg), 1.0, 0.1).total_Nmm();
    if (total > best) {
      best = total;
      best_angle = deg;
    }
  }
  EXPECT_NEAR(best_angle, 67.5, 0.5);
}

}  // namespace
}  // namespace pkm::statics
