// The workspace map (a 200 × 200 δρ map, goal under 1 s on 2 cores), for docs/PERFORMANCE.md: the
// ch5 hexapod's xy section through its home (0, 0, 700) ± 200 mm by 2 mm, 201 × 201 = 40 401 cells, each with
// its status under every limit of the machine file and its Jacobian measures (det J, condition number, δρ and
// S_x, S_y, S_z). One iteration is one whole map, wall time (the worker threads' time is not the caller's);
// the argument is the number of threads: 0 = every core (TBB's default), 1 = serial, for the ratio.
#include <benchmark/benchmark.h>

#include "bench_support.hpp"
#include "workspace/workspace_map.hpp"

namespace pkm {
namespace {

void BM_WorkspaceMap201x201(benchmark::State& state) {
  const Machine& machine = bench::ch5_hexapod();
  const workspace::WorkspaceGrid grid =
      workspace::plane_section(machine.mechanism->home(), dynamics::GridPlane::xy, 200.0, 2.0);
  workspace::WorkspaceMapOptions options;
  options.threads = static_cast<int>(state.range(0));
  long cells = 0;
  for (auto _ : state) {
    auto map = workspace::workspace_map(machine, grid, options);
    if (!map) {
      state.SkipWithError(map.error().message.c_str());
      break;
    }
    cells = static_cast<long>(map->cells.size());
    benchmark::DoNotOptimize(map->cells.data());
  }
  state.counters["cells"] = static_cast<double>(cells);
}
BENCHMARK(BM_WorkspaceMap201x201)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
