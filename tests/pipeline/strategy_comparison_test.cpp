// The strategy comparison (pipeline/strategy_comparison.hpp) on the ch5 hexapod over a small cap: the ranking
// follows its criterion, the table's numbers are those of the runs' files, the errors are linear in the load
// and zero without one, and a bad input writes nothing.
#include "pipeline/strategy_comparison.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "report/csv_table.hpp"
#include "test_support.hpp"

namespace pkm::pipeline {
namespace {

namespace fs = std::filesystem;

// A small cap at the ch5 hexapod's program zero, coarse passes and a low servo rate: a few thousand ticks a
// strategy.
StrategyComparisonJob small_comparison_job(const std::string& out, double tangential_N) {
  StrategyComparisonJob job;
  path::EllipsoidCap cap;
  cap.semi_axes_mm = Eigen::Vector3d(60, 50, 30);
  cap.centre_mm = Eigen::Vector3d(0, 0, -30);
  cap.depth_mm = 2.0;
  job.surface = cap;
  job.strategy.step_over_mm = 8.0;
  job.strategy.spacing_mm = 4.0;
  job.feed_mm_min = 2400.0;
  job.load.default_load.tangential_N = tangential_N;
  job.load.default_load.normal_N = 0.3 * tangential_N;
  job.plan.rate_hz = 100.0;
  job.out_directory = out;
  return job;
}

std::string comparison_test_directory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_strategy_comparison_" + name);
  fs::remove_all(dir);
  return dir.string();
}

// Σ x² of a column and the number of rows of a CSV.
std::pair<double, long> comparison_squares(const std::string& csv, const std::string& column,
                                           double& largest) {
  report::CsvReader in;
  EXPECT_TRUE(in.open(csv).ok()) << csv;
  const int k = in.column(column);
  EXPECT_GE(k, 0) << csv << " " << column;
  std::vector<double> row;
  double squares = 0.0;
  long rows = 0;
  while (in.next(row)) {
    squares += row[k] * row[k];
    largest = std::max(largest, std::abs(row[k]));
    ++rows;
  }
  return {squares, rows};
}

TEST(StrategyComparison, RanksByRmsAndTheTableIsTheRunsFiles) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const std::string out = comparison_test_directory("ranking");
  auto compared = compare_strategies(machine, small_comparison_job(out, 500.0));
  ASSERT_TRUE(compared.ok()) << compared.error().message;
  const auto& ranking = compared->ranking;
  ASSERT_EQ(ranking.size(), 5u);
  for (std::size_t i = 0; i < ranking.size(); ++i) {
    EXPECT_EQ(ranking[i].rank, static_cast<int>(i) + 1);
    EXPECT_GT(ranking[i].rms_normal_mm, 0.0);
    EXPECT_GE(ranking[i].max_normal_mm, ranking[i].rms_normal_mm);
    if (i > 0) {
      EXPECT_TRUE(ranking[i - 1].rms_normal_mm < ranking[i].rms_normal_mm ||
                  (ranking[i - 1].rms_normal_mm == ranking[i].rms_normal_mm &&
                   ranking[i - 1].max_normal_mm <= ranking[i].max_normal_mm));
    }
  }
  // strategies.csv holds a row per strategy. Each strategy's rms is the one recomputed from its
  // deflection.csv (rapids carry no load: their rows add nothing) over its cutting ticks, the rows of its
  // surface error map; the map holds the same errors, and the largest is the largest of deflection.csv (to
  // the CSVs' five significant digits).
  const auto rows = report::count_csv_rows(out + "/strategies.csv");
  ASSERT_TRUE(rows.ok());
  EXPECT_EQ(*rows, 5);
  for (const StrategyScore& s : ranking) {
    const std::string run = out + "/" + s.name;
    ASSERT_TRUE(fs::exists(run + "/program.cl")) << run;
    double largest = 0.0, largest_on_map = 0.0;
    const auto [squares, ticks] = comparison_squares(run + "/deflection.csv", "normal_mm", largest);
    const auto [map_squares_um, cutting] =
        comparison_squares(run + "/surface_error.csv", "normal_um", largest_on_map);
    ASSERT_GT(cutting, 100);
    EXPECT_LT(cutting, ticks);  // the approach and retract are not on the map
    EXPECT_EQ(static_cast<double>(cutting), std::round(s.cutting_time_s * 100.0)) << s.name;
    EXPECT_NEAR(std::sqrt(squares / cutting), s.rms_normal_mm, 1e-4 * s.rms_normal_mm) << s.name;
    EXPECT_NEAR(std::sqrt(map_squares_um / cutting) * 1e-3, s.rms_normal_mm, 1e-4 * s.rms_normal_mm)
        << s.name;
    EXPECT_NEAR(largest, s.max_normal_mm, 1e-4 * s.max_normal_mm) << s.name;
    EXPECT_NEAR(largest_on_map * 1e-3, s.max_normal_mm, 1e-4 * s.max_normal_mm) << s.name;
  }
  EXPECT_TRUE(fs::exists(out + "/strategies.svg"));
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().rfind(".pkm-staging", 0), std::string::npos) << entry.path();
  fs::remove_all(out);
}

TEST(StrategyComparison, ErrorsAreLinearInTheLoadAndZeroWithout) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const std::string out = comparison_test_directory("linear");
  std::map<std::string, StrategyScore> single, twice, none;
  for (auto [load_N, into] : {std::pair{400.0, &single}, std::pair{800.0, &twice}, std::pair{0.0, &none}}) {
    auto compared = compare_strategies(machine, small_comparison_job(out, load_N));
    ASSERT_TRUE(compared.ok()) << compared.error().message;
    for (const StrategyScore& s : compared->ranking) (*into)[s.name] = s;
  }
  for (const auto& [name, s] : single) {
    EXPECT_NEAR(twice[name].rms_normal_mm, 2.0 * s.rms_normal_mm, 1e-9 * s.rms_normal_mm) << name;
    EXPECT_NEAR(twice[name].max_normal_mm, 2.0 * s.max_normal_mm, 1e-9 * s.max_normal_mm) << name;
    EXPECT_EQ(twice[name].rank, s.rank) << name;
    EXPECT_EQ(none[name].rms_normal_mm, 0.0) << name;
    EXPECT_EQ(none[name].max_normal_mm, 0.0) << name;
    EXPECT_EQ(none[name].points, s.points);
  }
  fs::remove_all(out);
}

TEST(StrategyComparison, FullTiesKeepTheirOrderAndRmsTiesGoByTheLargest) {
  std::vector<StrategyScore> scores(4);
  const double rms[] = {2e-3, 1e-3, 1e-3, 1e-3}, largest[] = {3e-3, 5e-3, 4e-3, 4e-3};
  for (int i = 0; i < 4; ++i) {
    scores[i].name = std::string(1, static_cast<char>('a' + i));
    scores[i].rms_normal_mm = rms[i];
    scores[i].max_normal_mm = largest[i];
  }
  rank_strategies(scores);
  std::string order;
  for (const StrategyScore& s : scores) order += s.name;
  EXPECT_EQ(order, "cdba");
  EXPECT_EQ(scores.back().rank, 4);
}

TEST(StrategyComparison, ABadInputWritesNothing) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const std::string out = comparison_test_directory("refused");
  StrategyComparisonJob job = small_comparison_job(out, 500.0);
  job.strategy.step_over_mm = 0.0;
  auto refused = compare_strategies(machine, job);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("step-over"), std::string::npos) << refused.error().message;
  EXPECT_FALSE(fs::exists(out));
  // A cap out of the machine's reach: the first strategy's plan fails, naming it and its program line in the
  // output directory, and the staged runs are removed.
  StrategyComparisonJob high = small_comparison_job(out, 500.0);
  high.surface->centre_mm.z() = 300.0;
  auto unreachable = compare_strategies(machine, high);
  ASSERT_FALSE(unreachable.ok());
  EXPECT_NE(unreachable.error().message.find("strategy zigzag: " + out + "/zigzag/program.cl:"),
            std::string::npos)
      << unreachable.error().message;
  EXPECT_FALSE(fs::exists(out));
  // A machine without strut stiffness: refused before anything is written.
  const Machine bare = test::machine_from_example("examples/machines/hexapod_genhexkins.yaml");
  auto no_stiffness = compare_strategies(bare, small_comparison_job(out, 500.0));
  ASSERT_FALSE(no_stiffness.ok());
  EXPECT_NE(no_stiffness.error().message.find("stiffness.struts"), std::string::npos)
      << no_stiffness.error().message;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace pkm::pipeline
