// Dynamics (issue 27, docs/dynamics.md): one whisker, N = 100, 1 s of whisking in air at 8 Hz (30 deg
// amplitude) with 1 kHz output, default tolerance; the model and modes, the integration alone, and the whole.
//   build/bench/bench_dynamics --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "bench_whisker.hpp"

#include <numbers>

#include "vibrissa/dynamics/simulate.hpp"

namespace {
using namespace vibrissa;

using bench::bench_whisker;

dynamics::BaseTrajectory whisk(const Whisker& w) {
  const Pose rest = w.placement().pose();
  return dynamics::trajectory_from_placements([rest](double t) {
    const double d = (30.0 * std::numbers::pi / 180.0) * (1.0 - std::cos(2.0 * std::numbers::pi * 8.0 * t));
    return Placement(rotation_from_angles(rest.theta + d, rest.phi, rest.zeta), rest.p_W_base);
  });
}

void BM_ModelAndModes(benchmark::State& state) {
  const Whisker w = bench_whisker();
  for (auto _ : state) {
    const dynamics::LinearModel m = dynamics::linear_model(w, {});
    benchmark::DoNotOptimize(dynamics::modes(m, w));
  }
}
BENCHMARK(BM_ModelAndModes)->Unit(benchmark::kMillisecond);

void BM_Integrate1sWhisking(benchmark::State& state) {
  const Whisker w = bench_whisker();
  const dynamics::LinearModel m = dynamics::linear_model(w, {});
  const dynamics::Modes all = dynamics::modes(m, w);
  dynamics::SimulationOptions o;
  o.record_nodes = state.range(0) != 0;
  long steps = 0;
  for (auto _ : state) {
    const auto ts = dynamics::simulate(w, m, all, whisk(w), Eigen::Vector3d::Zero(), o);
    steps = ts.steps;
    benchmark::DoNotOptimize(ts.moment_B.data());
  }
  state.counters["steps"] = static_cast<double>(steps);
}
BENCHMARK(BM_Integrate1sWhisking)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_Whole1sWhisking(benchmark::State& state) {
  const Whisker w = bench_whisker();
  dynamics::SimulationOptions o;
  for (auto _ : state) benchmark::DoNotOptimize(dynamics::simulate(w, dynamics::DynamicsProperties{}, whisk(w), o));
}
BENCHMARK(BM_Whole1sWhisking)->Unit(benchmark::kMillisecond);  // model, modes, integration, nodes

}  // namespace

BENCHMARK_MAIN();
