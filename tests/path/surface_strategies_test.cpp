// The five machining strategies over an ellipsoid cap (path/surface_strategies.hpp) on random caps: every
// point on the ellipsoid with its unit normal, the step-over and point spacing kept on the surface, the cap
// covered, each strategy's own shape, and the CL text read back point for point.
#include "path/surface_strategies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "path/surface_program.hpp"
#include "program/cl_writer.hpp"
#include "program/part_program.hpp"

namespace pkm::path {
namespace {

struct SurfaceStrategyCase {
  EllipsoidCap cap;
  StrategyOptions options;
};

// Random caps of moderate size (a few thousand points each), tilts up to about 50°.
std::vector<SurfaceStrategyCase> surface_strategy_cases(int count) {
  std::mt19937_64 rng(20240615);
  auto draw = [&rng](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  std::vector<SurfaceStrategyCase> cases;
  for (int i = 0; i < count; ++i) {
    SurfaceStrategyCase c;
    c.cap.semi_axes_mm = Eigen::Vector3d(draw(30, 90), draw(30, 90), draw(20, 80));
    c.cap.centre_mm = Eigen::Vector3d(draw(-50, 50), draw(-50, 50), draw(-100, 0));
    c.cap.depth_mm = draw(0.1, 0.5) * c.cap.semi_axes_mm.z();
    c.options.step_over_mm = draw(4, 10);
    c.options.spacing_mm = draw(2, c.options.step_over_mm);
    cases.push_back(c);
  }
  return cases;
}

SurfaceToolPath generated_strategy(SurfaceStrategy strategy, const SurfaceStrategyCase& c) {
  auto path = generate_strategy(strategy, c.cap, c.options);
  EXPECT_TRUE(path.ok()) << (path.ok() ? "" : path.error().message);
  return path.ok() ? std::move(*path) : SurfaceToolPath{};
}

double strategy_distance_to_polyline_mm(const Eigen::Vector3d& p, const std::vector<SurfacePoint>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < line.size(); ++i) {
    const Eigen::Vector3d& a = line[i].position_mm;
    best = std::min(best, (p - a).norm());
    if (i + 1 == line.size()) break;
    const Eigen::Vector3d ab = line[i + 1].position_mm - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (a + t * ab)).norm());
  }
  return best;
}

std::vector<const SurfacePass*> strategy_machining_passes(const SurfaceToolPath& path) {
  std::vector<const SurfacePass*> passes;
  for (const SurfacePass& piece : path.pieces)
    if (!piece.link) passes.push_back(&piece);
  return passes;
}

TEST(SurfaceStrategies, EveryPointLiesOnTheCapWithItsUnitNormal) {
  for (const SurfaceStrategyCase& c : surface_strategy_cases(6)) {
    const Eigen::Vector3d& s = c.cap.semi_axes_mm;
    const double rim_z = c.cap.centre_mm.z() + s.z() - c.cap.depth_mm;
    for (const SurfaceStrategy strategy : kSurfaceStrategies) {
      const SurfaceToolPath path = generated_strategy(strategy, c);
      ASSERT_GT(path.point_count(), 10u) << strategy_name(strategy);
      for (const SurfacePass& piece : path.pieces) {
        for (const SurfacePoint& p : piece.points) {
          const Eigen::Vector3d r = p.position_mm - c.cap.centre_mm;
          ASSERT_NEAR(r.cwiseQuotient(s).squaredNorm(), 1.0, 1e-9) << strategy_name(strategy);
          ASSERT_GE(p.position_mm.z(), rim_z - 1e-9) << strategy_name(strategy);
          ASSERT_NEAR(p.normal.norm(), 1.0, 1e-12);
          ASSERT_GT(p.normal.z(), 0.0);
          // The tangents of the parametrisation (a sinθ cosφ, b sinθ sinφ, c cosθ) at the point.
          const double theta = std::atan2(std::hypot(r.x() / s.x(), r.y() / s.y()), r.z() / s.z());
          const double phi = std::atan2(r.y() / s.y(), r.x() / s.x());
          const Eigen::Vector3d along_theta(s.x() * std::cos(theta) * std::cos(phi),
                                            s.y() * std::cos(theta) * std::sin(phi),
                                            -s.z() * std::sin(theta));
          const Eigen::Vector3d along_phi(-s.x() * std::sin(theta) * std::sin(phi),
                                          s.y() * std::sin(theta) * std::cos(phi), 0.0);
          ASSERT_NEAR(p.normal.dot(along_theta), 0.0, 1e-9 * along_theta.norm()) << strategy_name(strategy);
          ASSERT_NEAR(p.normal.dot(along_phi), 0.0, 1e-9 * std::max(1.0, along_phi.norm()));
        }
      }
    }
  }
}

TEST(SurfaceStrategies, KeepTheStepOverBetweenPassesAndTheSpacingAlongThem) {
  for (const SurfaceStrategyCase& c : surface_strategy_cases(6)) {
    for (const SurfaceStrategy strategy : kSurfaceStrategies) {
      const SurfaceToolPath path = generated_strategy(strategy, c);
      // Along the fed path (passes, links, and the joins between them) no step is longer than the spacing.
      const Eigen::Vector3d* previous = nullptr;
      for (const SurfacePass& piece : path.pieces) {
        for (const SurfacePoint& p : piece.points) {
          if (previous != nullptr && (piece.joined || &p != &piece.points.front())) {
            ASSERT_LE((p.position_mm - *previous).norm(), c.options.spacing_mm + 1e-9)
                << strategy_name(strategy);
          }
          previous = &p.position_mm;
        }
      }
      // Every point of a pass lies within the step-over of a neighbouring piece: the passes before and after
      // it and the links between (a zigzag line near the rim reaches past the ends of the shorter line
      // outside it, not past the longer one inside).
      for (std::size_t k = 0; k < path.pieces.size() && path.pieces.size() > 1; ++k) {
        if (path.pieces[k].link) continue;
        for (const SurfacePoint& p : path.pieces[k].points) {
          double nearest = std::numeric_limits<double>::infinity();
          for (std::size_t j = k >= 3 ? k - 3 : 0; j < std::min(path.pieces.size(), k + 4); ++j) {
            if (j != k)
              nearest =
                  std::min(nearest, strategy_distance_to_polyline_mm(p.position_mm, path.pieces[j].points));
          }
          ASSERT_LE(nearest, c.options.step_over_mm + 1e-9) << strategy_name(strategy) << " piece " << k;
        }
      }
    }
  }
}

TEST(SurfaceStrategies, EachStrategyCoversTheCap) {
  for (const SurfaceStrategyCase& c : surface_strategy_cases(4)) {
    const Eigen::Vector2d outline = cap_outline_semi_axes_mm(c.cap);
    // Surface points over a grid of the outline, its rim included.
    std::vector<Eigen::Vector3d> probes;
    constexpr int kCells = 24;
    for (int i = 0; i <= kCells; ++i) {
      for (int j = 0; j <= kCells; ++j) {
        Eigen::Vector2d xy(outline.x() * (2.0 * i / kCells - 1.0), outline.y() * (2.0 * j / kCells - 1.0));
        const double r = std::hypot(xy.x() / outline.x(), xy.y() / outline.y());
        if (r > 1.0) xy /= r;  // onto the rim
        probes.push_back(cap_point_mm(c.cap, xy));
      }
    }
    for (const SurfaceStrategy strategy : kSurfaceStrategies) {
      const SurfaceToolPath path = generated_strategy(strategy, c);
      for (const Eigen::Vector3d& probe : probes) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const SurfacePass& piece : path.pieces)
          for (const SurfacePoint& p : piece.points)
            nearest = std::min(nearest, (p.position_mm - probe).norm());
        ASSERT_LE(nearest, c.options.step_over_mm) << strategy_name(strategy) << " at " << probe.transpose();
      }
    }
  }
}

TEST(SurfaceStrategies, EachStrategyHasItsOwnShape) {
  for (const SurfaceStrategyCase& c : surface_strategy_cases(4)) {
    const Eigen::Vector3d& centre = c.cap.centre_mm;
    // Zigzag: each pass at one y, alternating in x.
    const SurfaceToolPath zigzag_path = generated_strategy(SurfaceStrategy::zigzag, c);
    const auto zigzag = strategy_machining_passes(zigzag_path);
    for (std::size_t k = 0; k < zigzag.size(); ++k) {
      const auto& pts = zigzag[k]->points;
      for (const SurfacePoint& p : pts) ASSERT_NEAR(p.position_mm.y(), pts.front().position_mm.y(), 1e-9);
      const double dx = pts.back().position_mm.x() - pts.front().position_mm.x();
      EXPECT_EQ(dx > 0, k % 2 == 0) << "zigzag pass " << k;
    }
    // Meridians: every pass through the pole, straight in the projection.
    const Eigen::Vector3d pole = centre + Eigen::Vector3d(0, 0, c.cap.semi_axes_mm.z());
    const SurfaceToolPath meridians = generated_strategy(SurfaceStrategy::meridians, c);
    for (const SurfacePass* pass : strategy_machining_passes(meridians)) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const SurfacePoint& p : pass->points) nearest = std::min(nearest, (p.position_mm - pole).norm());
      EXPECT_LT(nearest, 1e-9);
    }
    // Parallels: each loop at one height, closed.
    const SurfaceToolPath parallels = generated_strategy(SurfaceStrategy::parallels, c);
    for (const SurfacePass* pass : strategy_machining_passes(parallels)) {
      for (const SurfacePoint& p : pass->points)
        ASSERT_NEAR(p.position_mm.z(), pass->points.front().position_mm.z(), 1e-9);
      EXPECT_LT((pass->points.back().position_mm - pass->points.front().position_mm).norm(), 1e-9);
    }
    // Contour: each loop at one distance from the outline (projected; the outline sampled densely), the
    // loops one step apart, closed.
    const Eigen::Vector2d outline = cap_outline_semi_axes_mm(c.cap);
    std::vector<Eigen::Vector2d> rim;
    for (int i = 0; i < 20000; ++i) {
      const double phi = 2.0 * std::numbers::pi * i / 20000;
      rim.emplace_back(outline.x() * std::cos(phi), outline.y() * std::sin(phi));
    }
    auto inset = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d xy = (p - centre).head<2>();
      double best = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& q : rim) best = std::min(best, (q - xy).norm());
      return best;
    };
    const SurfaceToolPath contour_path = generated_strategy(SurfaceStrategy::contour, c);
    const auto contour = strategy_machining_passes(contour_path);
    double previous_inset = 0.0;
    for (std::size_t k = 0; k < contour.size(); ++k) {
      const auto& pts = contour[k]->points;
      const double first = inset(pts.front().position_mm);
      for (std::size_t i = 0; i < pts.size(); i += 7)
        ASSERT_NEAR(inset(pts[i].position_mm), first, 2e-3) << k;
      EXPECT_LT((pts.back().position_mm - pts.front().position_mm).norm(), 1e-9);
      if (k > 0) {
        EXPECT_GT(first, previous_inset);
      }
      previous_inset = first;
    }
    // Contour loop: no links and no lifts, one continuous spiral inwards.
    const SurfaceToolPath spiral = generated_strategy(SurfaceStrategy::contour_loop, c);
    for (std::size_t k = 0; k < spiral.pieces.size(); ++k) {
      EXPECT_FALSE(spiral.pieces[k].link);
      EXPECT_EQ(spiral.pieces[k].joined, k > 0);
    }
  }
}

TEST(SurfaceStrategies, TheProgramReadsBackWithTheSamePoints) {
  for (const SurfaceStrategyCase& c : surface_strategy_cases(3)) {
    for (const SurfaceStrategy strategy : kSurfaceStrategies) {
      const SurfaceToolPath path = generated_strategy(strategy, c);
      SurfaceProgramOptions options;
      const program::CanonicalProgram written = surface_program(path, options);
      program::ClWriteOptions text_options;
      text_options.header_comments = {"a test"};
      text_options.decimals_mm = 9;
      text_options.decimals_axis = 12;
      auto text = program::write_cl_data(written, text_options);
      ASSERT_TRUE(text.ok()) << text.error().message;
      auto program = program::read_cl_data(*text, "strategy.cl");
      ASSERT_TRUE(program.ok()) << program.error().message;
      ASSERT_EQ(program->moves.size(), written.moves.size());
      // Rapid above the first point and down onto it, a stop there (a dwell of 0 s), the rest fed, a stop
      // and a rapid retract at the end.
      const auto& moves = program->moves;
      ASSERT_EQ(moves.size(), path.point_count() + 4) << strategy_name(strategy);
      using program::MoveKind;
      EXPECT_EQ(moves[0].kind, MoveKind::rapid);
      EXPECT_EQ(moves[1].kind, MoveKind::rapid);
      EXPECT_EQ(moves[2].kind, MoveKind::dwell);
      EXPECT_EQ(moves[moves.size() - 2].kind, MoveKind::dwell);
      EXPECT_EQ(moves.back().kind, MoveKind::rapid);
      std::size_t m = 1;
      for (const SurfacePass& piece : path.pieces) {
        for (const SurfacePoint& p : piece.points) {
          if (m == 2) ++m;  // the stop
          const program::CanonicalMove& move = moves[m];
          if (m > 2) {
            EXPECT_EQ(move.kind, MoveKind::line);
            EXPECT_EQ(move.feed_mm_min, options.feed_mm_min);
          }
          ASSERT_LT((move.end_mm - p.position_mm).norm(), 1e-9) << strategy_name(strategy) << " move " << m;
          ASSERT_LT((move.tool_axis - p.normal).norm(), 1e-9);
          ++m;
        }
      }
    }
  }
}

TEST(SurfaceStrategies, RefusesBadCapsStepOversAndSpacings) {
  EllipsoidCap cap;
  StrategyOptions options;
  EXPECT_TRUE(validate_strategy_options(cap, options).ok());
  auto refused = [&](EllipsoidCap c, StrategyOptions o, const std::string& words) {
    const Status status = validate_strategy_options(c, o);
    ASSERT_FALSE(status.ok()) << words;
    EXPECT_EQ(status.error().code, ErrorCode::bad_input);
    EXPECT_NE(status.error().message.find(words), std::string::npos) << status.error().message;
    EXPECT_FALSE(generate_strategy(SurfaceStrategy::zigzag, c, o).ok());
  };
  for (const double bad : {0.0, -3.0, std::nan("")}) {
    EllipsoidCap c = cap;
    c.semi_axes_mm.y() = bad;
    refused(c, options, "semi-axis b must be a positive length");
    StrategyOptions o = options;
    o.step_over_mm = bad;
    refused(cap, o, "step-over must be a positive length");
    o = options;
    o.spacing_mm = bad;
    refused(cap, o, "point spacing must be a positive length");
  }
  EllipsoidCap deep = cap;
  deep.depth_mm = cap.semi_axes_mm.z();
  refused(deep, options, "cap depth must be > 0 and < the semi-axis c");
  StrategyOptions tiny = options;
  tiny.step_over_mm = 1e-4;
  refused(cap, tiny, "choose a larger step-over or spacing");
}

}  // namespace
}  // namespace pkm::path
