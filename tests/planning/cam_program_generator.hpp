#pragma once
// Generated CAM-like part programs with the mess real CAM output has: thousands of short G1 moves, point
// noise, near-reversals, micrometre moves and 0.001 mm steps, back-tracking zig-zags, mixed arcs, and 5-axis
// CL data with tool-axis noise. Shapes are drawn in a unit frame and mapped onto the axes a machine controls,
// scaled to the part of its workspace that a probe plan shows it can reach (cam_workspace_scale).
#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "program/part_program.hpp"

namespace pkm::test {

enum class CamShape { noisy_circle, spiral, random_walk, zigzag, mixed_arcs, five_axis_cl };
inline constexpr CamShape kCamShapes[] = {CamShape::noisy_circle, CamShape::spiral,
                                          CamShape::random_walk,  CamShape::zigzag,
                                          CamShape::mixed_arcs,   CamShape::five_axis_cl};

inline const char* cam_shape_name(CamShape shape) {
  switch (shape) {
    case CamShape::noisy_circle:
      return "noisy circle";
    case CamShape::spiral:
      return "spiral";
    case CamShape::random_walk:
      return "random walk";
    case CamShape::zigzag:
      return "zig-zag";
    case CamShape::mixed_arcs:
      return "mixed arcs";
    case CamShape::five_axis_cl:
      return "5-axis CL";
  }
  return "?";
}

/// How the unit-frame shape (u, v, w) lands on a machine's program axes, and how far it may go.
struct CamAxes {
  bool x = false, y = false, z = false;  ///< program X Y Z the machine controls
  bool tilt = false;                     ///< A and B controlled as well as X Y Z (5-axis programs)
  bool tilt_only = false;                ///< A B (and Z) are all it controls: the shape draws in A/B (deg)
  bool phi = false;                      ///< a planar machine's platform angle C
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  ///< the start, program coordinates
  Eigen::Vector3d centre_abc_deg = Eigen::Vector3d::Zero();
  double scale = 1.0;  ///< unit shape → mm (deg for tilt_only)
};

inline CamAxes cam_axes_of(const Machine& machine) {
  const AxisMask mask = machine.mechanism->controlled_axes();
  CamAxes axes;
  axes.x = mask.controlled[0];
  axes.y = mask.controlled[1];
  axes.z = mask.controlled[2];
  axes.tilt = axes.x && axes.y && axes.z && mask.controlled[3] && mask.controlled[4];
  axes.tilt_only = !axes.x && !axes.y && mask.controlled[3] && mask.controlled[4];
  axes.phi = axes.x && axes.y && !axes.z && mask.controlled[5];
  const planning::ProgramStart start = planning::program_start(machine);
  axes.centre_mm = start.start_mm;
  axes.centre_abc_deg = start.start_abc_deg;
  return axes;
}

/// One G-code point: a unit-frame position (|u|, |v|, |w| ≤ 1) and a tilt (unit: the scale's share).
struct CamPoint {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector2d tilt = Eigen::Vector2d::Zero();
};

/// The G-code words of a point on `axes` (only the axes the machine controls).
inline std::string cam_words(const CamAxes& axes, const CamPoint& point) {
  std::string words;
  if (axes.tilt_only) {
    // The shape draws in A/B degrees; w moves Z by a tenth of the scale (mm).
    const Eigen::Vector2d ab = axes.centre_abc_deg.head<2>() + axes.scale * point.p.head<2>();
    return fmt::format("Z{:.4f} A{:.4f} B{:.4f}", axes.centre_mm.z() + 0.1 * axes.scale * point.p.z(), ab.x(),
                       ab.y());
  }
  const Eigen::Vector3d q = axes.centre_mm + axes.scale * point.p;
  if (axes.x) words += fmt::format("X{:.4f} ", q.x());
  if (axes.y) words += fmt::format("Y{:.4f} ", q.y());
  if (axes.z) words += fmt::format("Z{:.4f} ", q.z());
  if (axes.tilt) {
    const Eigen::Vector2d ab = axes.centre_abc_deg.head<2>() + 10.0 * point.tilt;  // ±10° at |tilt| = 1
    words += fmt::format("A{:.4f} B{:.4f} ", ab.x(), ab.y());
  }
  if (axes.phi) words += fmt::format("C{:.4f} ", axes.centre_abc_deg.z() + 10.0 * point.tilt.x());
  if (!words.empty()) words.pop_back();
  return words;
}

inline double cam_uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
inline double cam_normal(std::mt19937_64& rng, double sigma) {
  return std::normal_distribution<double>(0.0, sigma)(rng);
}

/// Points of a polyline shape in the unit frame. `noise` is the point noise in unit lengths.
inline std::vector<CamPoint> cam_polyline(std::mt19937_64& rng, CamShape shape, int count, double noise,
                                          bool tilt) {
  std::vector<CamPoint> points;
  points.reserve(static_cast<std::size_t>(count) * 2);
  auto add = [&](Eigen::Vector3d p, Eigen::Vector2d t = Eigen::Vector2d::Zero()) {
    p += Eigen::Vector3d(cam_normal(rng, noise), cam_normal(rng, noise), 0.0);
    points.push_back({p.cwiseMax(-1.0).cwiseMin(1.0), tilt ? t : Eigen::Vector2d::Zero()});
  };
  const double two_pi = 2.0 * std::numbers::pi;
  double z = 0.0;
  if (shape == CamShape::noisy_circle || shape == CamShape::spiral) {
    const double turns = cam_uniform(rng, 1.0, 3.0);
    const double r0 = cam_uniform(rng, 0.5, 0.9), r1 = shape == CamShape::spiral ? 0.15 : r0;
    for (int k = 0; k < count; ++k) {
      const double f = static_cast<double>(k) / (count - 1), angle = two_pi * turns * f;
      const double r = r0 + (r1 - r0) * f;
      if (cam_uniform(rng, 0, 1) < 0.03) z += cam_uniform(rng, 0, 1) < 0.5 ? 1e-3 / 25 : -1e-3 / 25;
      const Eigen::Vector3d p(r * std::cos(angle), r * std::sin(angle), z);
      const Eigen::Vector2d t(0.5 * std::cos(angle), 0.5 * std::sin(angle));
      if (cam_uniform(rng, 0, 1) < 0.02) {  // a near-reversal: a short step back along the path, then on
        const Eigen::Vector3d back(std::sin(angle), -std::cos(angle), 0.0);
        add(p + cam_uniform(rng, 0.002, 0.02) * back, t);
      }
      add(p, t);
    }
  } else if (shape == CamShape::random_walk) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    double heading = cam_uniform(rng, 0, two_pi);
    for (int k = 0; k < count; ++k) {
      // Step lengths log-uniform from 1 µm to 2 mm (at a 25 mm scale), turns of any size, reversals included.
      const double step = std::pow(10.0, cam_uniform(rng, -4.4, -1.1));
      heading +=
          cam_uniform(rng, 0, 1) < 0.1 ? std::numbers::pi + cam_normal(rng, 0.01) : cam_normal(rng, 0.4);
      Eigen::Vector3d q =
          p + step * Eigen::Vector3d(std::cos(heading), std::sin(heading), cam_normal(rng, 0.1));
      if (q.cwiseAbs().maxCoeff() > 0.9) heading += std::numbers::pi, q = p;  // turn back at the border
      p = q;
      add(p, Eigen::Vector2d(0.5 * p.x(), 0.5 * p.y()));
    }
  } else {  // zig-zag raster along u, with back-tracking steps and stepovers in v
    const int passes = std::max(2, count / 40);
    const double width = cam_uniform(rng, 0.5, 0.9);
    const int per_pass = std::max(4, count / passes);
    for (int pass = 0; pass < passes; ++pass) {
      const double v = -0.8 + 1.6 * pass / (passes - 1);
      for (int k = 0; k < per_pass; ++k) {
        double u = -width + 2.0 * width * k / (per_pass - 1);
        if (pass % 2) u = -u;
        if (cam_uniform(rng, 0, 1) < 0.05) add(Eigen::Vector3d(u - (pass % 2 ? -1 : 1) * 0.004, v, 0.0));
        add(Eigen::Vector3d(u, v, 0.001 * std::sin(7.0 * u)), Eigen::Vector2d(0.4 * u, 0.4 * v));
      }
    }
  }
  return points;
}

/// A whole generated G-code program (every shape but five_axis_cl), `count` points.
inline std::string cam_gcode(std::mt19937_64& rng, CamShape shape, const CamAxes& axes, int count) {
  const double noise = std::pow(10.0, cam_uniform(rng, -4.5, -3.0));  // 0.03…1 µm per mm of scale
  std::string text = "G21 G90 G17 G94\n";
  const double feed = cam_uniform(rng, 300.0, 3000.0);
  if (shape == CamShape::mixed_arcs) {
    // Arcs of random radius and sweep in the XY plane, joined by short lines, tangent or not.
    text += fmt::format("G0 {}\nF{:.1f}\n", cam_words(axes, {}), feed);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    double heading = 0.0;
    for (int k = 0; k < count; ++k) {
      const double r = std::pow(10.0, cam_uniform(rng, -3.0, -1.0));  // 1 µm…0.1 of the scale, ×25 mm
      if (!(axes.x && axes.y) || cam_uniform(rng, 0, 1) < 0.4) {
        heading += cam_normal(rng, 1.0);
        Eigen::Vector3d q = p + r * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0.0);
        if (q.cwiseAbs().maxCoeff() > 0.8) q = 0.5 * q, heading += std::numbers::pi;
        text += fmt::format("G1 {}\n", cam_words(axes, {q}));
        p = q;
        continue;
      }
      const bool ccw = cam_uniform(rng, 0, 1) < 0.5;
      const double side = ccw ? 1.0 : -1.0;
      // The centre to the left (ccw) or right of the heading, so that the arc starts tangent to it.
      const Eigen::Vector3d centre =
          p + r * side * Eigen::Vector3d(-std::sin(heading), std::cos(heading), 0.0);
      if ((centre.head<2>().cwiseAbs().array() + r > 0.85).any()) {
        heading += std::numbers::pi;
        continue;
      }
      const double sweep = cam_uniform(rng, 0.1, 3.0);
      const double start = std::atan2(p.y() - centre.y(), p.x() - centre.x());
      const double end = start + side * sweep;
      const Eigen::Vector3d q = centre + r * Eigen::Vector3d(std::cos(end), std::sin(end), 0.0);
      const Eigen::Vector3d offset = axes.scale * (centre - p);
      text +=
          fmt::format("G{} {} I{:.6f} J{:.6f}\n", ccw ? 3 : 2, cam_words(axes, {q}), offset.x(), offset.y());
      p = q;
      heading = end + side * 0.5 * std::numbers::pi + cam_normal(rng, 0.3);  // tangent, with a kink
    }
    return text + "M2\n";
  }
  const std::vector<CamPoint> points = cam_polyline(rng, shape, count, noise, axes.tilt || axes.phi);
  text += fmt::format("G0 {}\nG1 F{:.1f}\n", cam_words(axes, points.front()), feed);
  for (const CamPoint& point : points) text += fmt::format("G1 {}\n", cam_words(axes, point));
  return text + "M2\n";
}

/// A 5-axis CL-data program (GOTO/x,y,z,i,j,k) along a noisy shape, with tool-axis noise, for machines that
/// control all six coordinates.
inline std::string cam_cl_data(std::mt19937_64& rng, const CamAxes& axes, int count) {
  const double noise = std::pow(10.0, cam_uniform(rng, -4.5, -3.0));
  const CamShape shape = cam_uniform(rng, 0, 1) < 0.5 ? CamShape::zigzag : CamShape::noisy_circle;
  const std::vector<CamPoint> points = cam_polyline(rng, shape, count, noise, true);
  std::string text = "UNITS/MM\nMULTAX/ON\n";
  const double axis_noise = std::pow(10.0, cam_uniform(rng, -4.0, -2.5));  // rad
  auto goto_line = [&](const CamPoint& point) {
    const Eigen::Vector3d q = axes.centre_mm + axes.scale * point.p;
    const double a = 0.15 * point.tilt.x() + cam_normal(rng, axis_noise);
    const double b = 0.15 * point.tilt.y() + cam_normal(rng, axis_noise);
    const Eigen::Vector3d axis =
        Eigen::Vector3d(std::sin(b), -std::sin(a), std::cos(a) * std::cos(b)).normalized();
    return fmt::format("GOTO/{:.4f},{:.4f},{:.4f},{:.7f},{:.7f},{:.7f}\n", q.x(), q.y(), q.z(), axis.x(),
                       axis.y(), axis.z());
  };
  text += "RAPID\n" + goto_line(points.front());
  text += fmt::format("FEDRAT/MMPM,{:.1f}\n", cam_uniform(rng, 300.0, 3000.0));
  for (const CamPoint& point : points) text += goto_line(point);
  return text + "FINI\n";
}

/// The largest scale (mm, or deg for machines that only tilt) from `candidates` at which a probe program to
/// the corners of the unit cube (and the tilt extremes) plans on `machine`: the generated shapes stay inside
/// it.
inline double cam_workspace_scale(const Machine& machine, CamAxes axes) {
  for (double scale : {25.0, 15.0, 10.0, 6.0, 4.0, 2.5, 1.5, 1.0}) {
    axes.scale = scale;
    std::string text = "G21 G90 G17\nG1 F1000\n";
    for (int corner = 0; corner < 8; ++corner) {
      CamPoint point;
      point.p = Eigen::Vector3d(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
      if (axes.tilt || axes.phi)
        point.tilt = Eigen::Vector2d(corner & 1 ? 0.6 : -0.6, corner & 2 ? 0.6 : -0.6);
      text += fmt::format("G1 {}\n", cam_words(axes, point));
    }
    text += "M2\n";
    program::InterpretOptions options;
    options.start_mm = axes.centre_mm;
    options.start_abc_deg = axes.centre_abc_deg;
    auto program = program::interpret_gcode(text, "probe.ngc", options);
    if (program && planning::plan_motion(machine, program.value(), {}).ok()) return scale;
  }
  return 0.0;
}

/// A CAM-like G-code program of `points` short moves for `machine`, its body `repeats` times over (a program
/// `repeats` times as long, the same motion again and again).
inline std::string cam_program(const Machine& machine, CamShape shape, int points, std::uint64_t seed,
                               int repeats = 1) {
  CamAxes axes = cam_axes_of(machine);
  axes.scale = cam_workspace_scale(machine, axes);
  std::mt19937_64 rng(seed);
  const std::string once = cam_gcode(rng, shape, axes, points);
  const std::string body = once.substr(0, once.rfind("M2"));
  std::string text;
  for (int r = 0; r < repeats; ++r) text += body;
  return text + "M2\n";
}

}  // namespace pkm::test
