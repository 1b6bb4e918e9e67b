// Speed of the engine at N = 100 (issue 2, item 11; issue 13): forward evaluation, its Jacobian (Dual<3>
// reference and analytic), contact-point and edge solves, cold and warm; "iterations" counts accepted LM steps.
// Issue 13's targets are ratios to BM_Forward from one run (docs/performance.md, "Engine"):
//   build/bench/bench_solve --benchmark_format=json --benchmark_repetitions=5 | bench/ratios.py
#include <benchmark/benchmark.h>

#include "bench_whisker.hpp"

#include <numbers>

#include "vibrissa/core/chain_jacobian.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace {
using namespace vibrissa;

using bench::bench_whisker;
Edge bench_peg() {
  Edge e;
  e.point = {0.020, 0.0, 0.0};
  e.direction = {0.0, 0.0, 1.0};
  return e;
}
SolveOptions fast() {
  SolveOptions o;
  o.compute_shape = false;
  return o;
}

void BM_Forward(benchmark::State& state) {
  const Whisker w = bench_whisker();
  double f = 1e-4;
  for (auto _ : state) {
    auto c = deflect<double>(w, V3<double>(0.0, f, 0.3 * f), V3<double>(0, 0, 0), 0.025);
    benchmark::DoNotOptimize(c);
    f += 1e-12;
  }
}
BENCHMARK(BM_Forward);

void BM_ForwardWithJacobian(benchmark::State& state) {
  const Whisker w = bench_whisker();
  using D = Dual<3>;
  for (auto _ : state) {
    auto c = deflect<D>(w, V3<D>(D(0.0), D::variable(1e-4, 0), D::variable(3e-5, 1)), V3<D>(D(0.0), D(0.0), D(0.0)),
                        D::variable(0.025, 2));
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_ForwardWithJacobian);

void BM_ForwardAnalyticJacobian(benchmark::State& state) {
  const Whisker w = bench_whisker();
  using D = Dual<3>;
  for (auto _ : state) {
    auto c = deflect_analytic(w, V3<D>(D(0.0), D::variable(1e-4, 0), D::variable(3e-5, 1)),
                              V3<D>(D(0.0), D(0.0), D(0.0)), D::variable(0.025, 2));
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_ForwardAnalyticJacobian);

void BM_EdgeCold(benchmark::State& state) {
  const Whisker w = bench_whisker();
  const Edge peg = bench_peg();
  for (auto _ : state) benchmark::DoNotOptimize(solve_edge(w, peg, std::nullopt, fast()));
  state.counters["iterations"] = solve_edge(w, peg, std::nullopt, fast()).iterations;
}
BENCHMARK(BM_EdgeCold);

void BM_EdgeWarm(benchmark::State& state) {
  // Warm start from the previous frame of a 1 kHz whisk (0.05 deg of protraction earlier).
  const Whisker w = bench_whisker();
  Pose prev = w.placement().pose();
  prev.theta -= 0.05 * std::numbers::pi / 180.0;
  const Solution before = solve_edge(w, prev, bench_peg(), std::nullopt, fast());
  for (auto _ : state) benchmark::DoNotOptimize(solve_edge(w, bench_peg(), std::nullopt, fast(), &before.state));
  state.counters["iterations"] = solve_edge(w, bench_peg(), std::nullopt, fast(), &before.state).iterations;
}
BENCHMARK(BM_EdgeWarm);

void BM_PointCold(benchmark::State& state) {
  const Whisker w = bench_whisker();
  const Eigen::Vector3d target = solve_edge(w, bench_peg()).contact_point_W + Eigen::Vector3d(0, 0, 1e-3);
  for (auto _ : state) benchmark::DoNotOptimize(solve_point(w, target, std::nullopt, fast()));
  state.counters["iterations"] = solve_point(w, target, std::nullopt, fast()).iterations;
}
BENCHMARK(BM_PointCold);

void BM_PointWarm(benchmark::State& state) {
  const Whisker w = bench_whisker();
  const Eigen::Vector3d target = solve_edge(w, bench_peg()).contact_point_W + Eigen::Vector3d(0, 0, 1e-3);
  const Solution near = solve_point(w, target + Eigen::Vector3d(0, 0, 2e-5), std::nullopt, fast());
  for (auto _ : state) benchmark::DoNotOptimize(solve_point(w, target, std::nullopt, fast(), &near.state));
  state.counters["iterations"] = solve_point(w, target, std::nullopt, fast(), &near.state).iterations;
}
BENCHMARK(BM_PointWarm);

void BM_FrictionalEdgeWarm(benchmark::State& state) {
  const Whisker w = bench_whisker();
  const Solution free = solve_edge(w, bench_peg(), std::nullopt, fast());
  const Eigen::Vector3d previous = free.contact_point_W - Eigen::Vector3d(0, 0, 2e-3);
  for (auto _ : state)
    benchmark::DoNotOptimize(solve_frictional_edge(w, bench_peg(), 0.48, previous, fast(), &free.state));
  state.counters["iterations"] = solve_frictional_edge(w, bench_peg(), 0.48, previous, fast(), &free.state).iterations;
}
BENCHMARK(BM_FrictionalEdgeWarm);

}  // namespace

BENCHMARK_MAIN();
