// In-process cost of the library queries (issue 18: `search`, `show`, `near` under 50 ms at
// 100,000 entries, excluding process start-up), on an index built beforehand:
//   export SANDPAPER_BENCH_INDEX=LIB/.index/library.sqlite SANDPAPER_BENCH_LIBRARY=LIB
//   build/bin/sandpaper_bench_library [--benchmark_min_time=0.2]
// bench/library_scale.sh runs it at each N. Each query is what the CLI does after start-up:
// the staleness check, opening the index, then the query.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/near.hpp"
#include "sandpaper/curation/search.hpp"

namespace {

namespace cur = sandpaper::curation;

std::string env(const char* name, const char* fallback = "") {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

bool ready(benchmark::State& state) {
  if (env("SANDPAPER_BENCH_INDEX").empty() || env("SANDPAPER_BENCH_LIBRARY").empty()) {
    state.SkipWithError("set SANDPAPER_BENCH_INDEX and SANDPAPER_BENCH_LIBRARY (bench/library_scale.sh does)");
    return false;
  }
  return true;
}

void BM_LibraryStalenessCheck(benchmark::State& state) {
  if (!ready(state)) return;
  const auto cal = sandpaper::calibration::default_calibration_dir();
  for (auto _ : state) {
    const auto s = cur::index_state(env("SANDPAPER_BENCH_INDEX"), env("SANDPAPER_BENCH_LIBRARY"), cal);
    if (s != cur::IndexState::Fresh) state.SkipWithError("the index is not fresh: run `sandpaper library index` first");
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_LibraryStalenessCheck)->Unit(benchmark::kMillisecond);

void BM_LibrarySearch(benchmark::State& state) {
  if (!ready(state)) return;
  cur::SearchQuery q;
  q.words = {env("SANDPAPER_BENCH_QUERY", "corduroy")};
  std::size_t hits = 0;
  for (auto _ : state) {
    const cur::Index idx(env("SANDPAPER_BENCH_INDEX"));
    hits = cur::search(idx, q).size();
    benchmark::DoNotOptimize(hits);
  }
  state.counters["hits"] = static_cast<double>(hits);
}
BENCHMARK(BM_LibrarySearch)->Unit(benchmark::kMillisecond);

void BM_LibraryShow(benchmark::State& state) {
  if (!ready(state)) return;
  const std::string name = env("SANDPAPER_BENCH_NAME", "gen-grating-000010");
  for (auto _ : state) {
    const cur::Index idx(env("SANDPAPER_BENCH_INDEX"));
    const auto n = idx.resolve(name);
    if (!n) {
      state.SkipWithError("no such entry");
      break;
    }
    benchmark::DoNotOptimize(idx.entry(*n));
    benchmark::DoNotOptimize(idx.statements(*n));
    benchmark::DoNotOptimize(idx.provenance(*n));
  }
}
BENCHMARK(BM_LibraryShow)->Unit(benchmark::kMillisecond);

void BM_LibraryNear(benchmark::State& state) {
  if (!ready(state)) return;
  const std::string name = env("SANDPAPER_BENCH_NAME", "gen-grating-000010");
  for (auto _ : state) {
    const cur::Index idx(env("SANDPAPER_BENCH_INDEX"));
    benchmark::DoNotOptimize(cur::nearest(idx, name, 20));
  }
}
BENCHMARK(BM_LibraryNear)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
