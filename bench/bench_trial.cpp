// The whole trial pipeline (pre-processing, contact-point + edge mode with warm starts, all analyses;
// figures excluded) on a 3,300-frame synthetic trial (the length of the paper's trial, §2.3 / Fig. 2).
#include <benchmark/benchmark.h>

#include "vibrissa/trial/analysis.hpp"
#include "vibrissa/trial/synth.hpp"

namespace {

const vibrissa::trial::Trial& trial_3300() {
  static const vibrissa::trial::Trial t = [] {
    vibrissa::trial::SynthOptions o;
    o.duration = 3.3;
    o.shapes = true;
    return vibrissa::trial::synthesize_trial(o);
  }();
  return t;
}

void BM_TrialPipeline_BothModes(benchmark::State& state) {
  const auto& t = trial_3300();
  for (auto _ : state) {
    const auto r = vibrissa::trial::run_pipeline(t);
    const auto a = vibrissa::trial::analyse_trial(r);
    benchmark::DoNotOptimize(a.friction->median);
  }
  state.counters["frames"] = static_cast<double>(t.frames());
}
BENCHMARK(BM_TrialPipeline_BothModes)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_TrialPipeline_ThreeModes(benchmark::State& state) {
  const auto& t = trial_3300();
  vibrissa::trial::PipelineOptions po;
  po.mu = 0.48;
  for (auto _ : state) {
    const auto r = vibrissa::trial::run_pipeline(t, po);
    const auto a = vibrissa::trial::analyse_trial(r);
    benchmark::DoNotOptimize(a.friction->median);
  }
}
BENCHMARK(BM_TrialPipeline_ThreeModes)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SynthesizeTrial(benchmark::State& state) {
  vibrissa::trial::SynthOptions o;
  o.duration = 3.3;
  for (auto _ : state) benchmark::DoNotOptimize(vibrissa::trial::synthesize_trial(o).frames());
}
BENCHMARK(BM_SynthesizeTrial)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
