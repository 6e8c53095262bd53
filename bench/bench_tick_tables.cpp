// What writing a planned run's servo-rate tables costs per tick, against what computing the tick costs: the
// ch5 hexapod's pocket.ngc (examples/), planned once, then streamed (planning::stream_plan: path point, IK,
// the run monitor's checks and the path error's forward kinematics) with
//   BM_StreamTicks/none   no observer: the tick's own work;
//   BM_StreamTicks/csv    formats::PlanFiles writing actuators.csv and path.csv (TickTables::csv);
//   BM_StreamTicks/hdf5   formats::PlanFiles writing ticks.h5 (TickTables::hdf5).
// Each iteration stages its files in a scratch output folder and discards them (no commit): the writing is
// timed, the renaming is not. Counters: ticks, ns_per_tick (wall time: the HDF5 chunks are deflated on a
// thread of their own); the row's cost is a row's time less none's.
#include <filesystem>
#include <stdexcept>

#include "bench_support.hpp"
#include "formats/plan_files.hpp"
#include "io/output_set.hpp"
#include "planning/plan_stream.hpp"

namespace pkm {
namespace {

const planning::MotionPlan& pocket_plan() {
  static const planning::MotionPlan plan = bench::ch5_plan("pocket.ngc");
  return plan;
}

// tables: -1 no observer, 0 CSV, 1 HDF5.
void BM_StreamTicks(benchmark::State& state, int tables) {
  const Machine& machine = bench::ch5_hexapod();
  const planning::MotionPlan& plan = pocket_plan();
  const std::string folder = (std::filesystem::temp_directory_path() / "pkm-bench-tick-tables").string();
  long ticks = 0;
  for (auto _ : state) {
    OutputSet outputs{"plan"};
    std::vector<planning::TickObserver*> observers;
    std::optional<formats::PlanFiles> files;
    if (tables >= 0) {
      if (Status used = outputs.use_directory(folder); !used) throw std::runtime_error(used.error().message);
      files.emplace(machine, analyses::PlanAnalysisOptions{},
                    tables == 0 ? formats::TickTables::csv : formats::TickTables::hdf5);
      if (Status opened = files->open(outputs); !opened) throw std::runtime_error(opened.error().message);
      observers.push_back(&*files);
    }
    auto run = planning::stream_plan(plan, machine, planning::StreamOptions{}, observers);
    if (!run) throw std::runtime_error(run.error().message);
    if (files) {
      if (Status finished = files->finish(nlohmann::json::object()); !finished)
        throw std::runtime_error(finished.error().message);
    }
    ticks = run->ticks;
    benchmark::DoNotOptimize(run->max_path_error_mm);
  }
  state.counters["ticks"] = static_cast<double>(ticks);
  state.counters["ns_per_tick"] =
      benchmark::Counter(static_cast<double>(ticks) * 1e-9,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK_CAPTURE(BM_StreamTicks, none, -1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_StreamTicks, csv, 0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_StreamTicks, hdf5, 1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
