// In-process time of the five side-by-side cases against the published model (docs/performance.md, "Side by
// side with the published model"; cases in tests/data/elastica3d/side_by_side/). Two timings per case: the
// solve alone (Case parsed once, as `vibrissa solve` runs it: find_other_roots on, shape computed) and the
// whole `vibrissa solve` callback (parse the JSON text, build the whisker, solve, write the result JSON).
// Run: build/bench/bench_side_by_side --benchmark_min_time=0.3
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>
#include <string>

#include "vibrissa/io/case_json.hpp"
#include "vibrissa/io/json_input.hpp"

namespace {
using namespace vibrissa;

std::string case_text(int k) {
  std::ifstream in(std::string(VIBRISSA_SOURCE_DIR) + "/tests/data/elastica3d/side_by_side/case_" +
                   std::to_string(k) + ".json");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void BM_Solve(benchmark::State& state) {
  const Case c = case_from_json(io::parse_json_text(case_text(static_cast<int>(state.range(0))), "case"));
  for (auto _ : state) {
    Solution s = solve_case(c);
    benchmark::DoNotOptimize(s);
  }
}

void BM_CaseTextToResultText(benchmark::State& state) {
  const std::string text = case_text(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    std::string out = solve_case_to_json(case_from_json(io::parse_json_text(text, "case"))).dump(2);
    benchmark::DoNotOptimize(out);
  }
}

}  // namespace

BENCHMARK(BM_Solve)->DenseRange(1, 5)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CaseTextToResultText)->DenseRange(1, 5)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
