// Full-array throughput (issue 5 item 8): whiskers x frames x head pitches of the default whisk against a
// world-fixed peg, both sides of the Towal array. Arguments: frames, pitches, sides (1 right, 2 both).
#include <benchmark/benchmark.h>

#include "vibrissa/io/array_config.hpp"

namespace {

vibrissa::array::SimulationConfig make_config(int frames, int pitches, int sides) {
  nlohmann::json j = vibrissa::io::default_array_config_json();
  j["morphology"]["sides"] = sides == 2 ? "both" : "right";
  j["time"]["frames"] = frames;
  j["output"]["render_count"] = 0;
  nlohmann::json list = nlohmann::json::array();
  for (int p = 0; p < pitches; ++p) list.push_back(pitches == 1 ? 0.0 : -20.0 + 40.0 * p / (pitches - 1));
  j["head"]["pitches_deg"] = list;
  return vibrissa::io::array_config_from_json(j);
}

void BM_ArraySimulation(benchmark::State& state) {
  const auto config = make_config(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                                  static_cast<int>(state.range(2)));
  std::size_t solves = 0, whisker_frames = 0;
  for (auto _ : state) {
    const auto r = vibrissa::array::simulate_array(config);
    solves = r.solves;
    whisker_frames = r.n_pitches * r.n_whiskers * r.n_frames;
    benchmark::DoNotOptimize(r.MB.data());
  }
  state.counters["whisker_frames"] = static_cast<double>(whisker_frames);
  state.counters["edge_solves"] = static_cast<double>(solves);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(whisker_frames));
}

}  // namespace

// frames, pitches, sides
BENCHMARK(BM_ArraySimulation)
    ->Args({250, 1, 1})
    ->Args({1000, 1, 1})
    ->Args({1000, 1, 2})
    ->Args({250, 9, 2})
    ->Args({1000, 3, 2})
    ->Args({1000, 9, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

BENCHMARK_MAIN();
