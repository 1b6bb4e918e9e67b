// Speed of the engine at N = 100 (issue 2, item 11; issue 13): forward evaluation, its Jacobian (Dual<3>
// reference and analytic), contact-point and edge solves, cold and warm; "iterations" counts accepted LM steps.
// Issue 13's targets are ratios to BM_Forward from one run (docs/performance.md, "Engine"):
//   build/bench/bench_solve --benchmark_format=json --benchmark_repetitions=5 | bench/ratios.py
#include <benchmark/benchmark.h>

#include <numbers>
#include <string>
#include <utility>

#include "vibrissa/core/chain_jacobian.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace {
using namespace vibrissa;

Whisker bench_whisker() {
  Pose pose;
  pose.theta = 10.0 * std::numbers::pi / 180.0;
  pose.phi = 10.0 * std::numbers::pi / 180.0;
  pose.zeta = 30.0 * std::numbers::pi / 180.0;
  return Whisker::from_parabola(0.040, 12.0, WhiskerProperties{}, pose);
}
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
SolveOptions secant() {  // SolveOptions::secant_jacobians: Broyden Jacobians, carried between frames
  SolveOptions o = fast();
  o.secant_jacobians = true;
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

// Each contact solve runs with the default options (names as in issue 13's table) and with
// SolveOptions::secant_jacobians (suffix "Secant"; results equal to within the tolerance, not to rounding).
void BM_EdgeCold(benchmark::State& state, const SolveOptions& o) {
  const Whisker w = bench_whisker();
  const Edge peg = bench_peg();
  for (auto _ : state) benchmark::DoNotOptimize(solve_edge(w, peg, std::nullopt, o));
  state.counters["iterations"] = solve_edge(w, peg, std::nullopt, o).iterations;
}

void BM_EdgeWarm(benchmark::State& state, const SolveOptions& o) {
  // Warm start from the previous frame of a 1 kHz whisk (0.05 deg of protraction earlier), solved cold.
  const Whisker w = bench_whisker();
  Pose prev = w.placement().pose();
  prev.theta -= 0.05 * std::numbers::pi / 180.0;
  const Solution before = solve_edge(w, prev, bench_peg(), std::nullopt, o);
  for (auto _ : state) benchmark::DoNotOptimize(solve_edge(w, bench_peg(), std::nullopt, o, &before.state));
  state.counters["iterations"] = solve_edge(w, bench_peg(), std::nullopt, o, &before.state).iterations;
}

void BM_EdgeTracked(benchmark::State& state, const SolveOptions& o) {
  // A frame of a tracked 1 kHz whisk: the previous frame was itself warm-started, ten frames from a cold one.
  const Whisker w = bench_whisker();
  Solution before;
  for (int i = 10; i >= 1; --i) {
    Pose p = w.placement().pose();
    p.theta -= i * 0.05 * std::numbers::pi / 180.0;
    before = solve_edge(w, p, bench_peg(), std::nullopt, o, i == 10 ? nullptr : &before.state);
  }
  for (auto _ : state) benchmark::DoNotOptimize(solve_edge(w, bench_peg(), std::nullopt, o, &before.state));
  state.counters["iterations"] = solve_edge(w, bench_peg(), std::nullopt, o, &before.state).iterations;
}

void BM_PointCold(benchmark::State& state, const SolveOptions& o) {
  const Whisker w = bench_whisker();
  const Eigen::Vector3d target = solve_edge(w, bench_peg()).contact_point_W + Eigen::Vector3d(0, 0, 1e-3);
  for (auto _ : state) benchmark::DoNotOptimize(solve_point(w, target, std::nullopt, o));
  state.counters["iterations"] = solve_point(w, target, std::nullopt, o).iterations;
}

void BM_PointWarm(benchmark::State& state, const SolveOptions& o) {
  const Whisker w = bench_whisker();
  const Eigen::Vector3d target = solve_edge(w, bench_peg()).contact_point_W + Eigen::Vector3d(0, 0, 1e-3);
  const Solution near = solve_point(w, target + Eigen::Vector3d(0, 0, 2e-5), std::nullopt, o);
  for (auto _ : state) benchmark::DoNotOptimize(solve_point(w, target, std::nullopt, o, &near.state));
  state.counters["iterations"] = solve_point(w, target, std::nullopt, o, &near.state).iterations;
}

void BM_FrictionalEdgeWarm(benchmark::State& state, const SolveOptions& o) {
  const Whisker w = bench_whisker();
  const Solution free = solve_edge(w, bench_peg(), std::nullopt, o);
  const Eigen::Vector3d previous = free.contact_point_W - Eigen::Vector3d(0, 0, 2e-3);
  for (auto _ : state) benchmark::DoNotOptimize(solve_frictional_edge(w, bench_peg(), 0.48, previous, o, &free.state));
  state.counters["iterations"] = solve_frictional_edge(w, bench_peg(), 0.48, previous, o, &free.state).iterations;
}

}  // namespace

int main(int argc, char** argv) {
  using Solve = void (*)(benchmark::State&, const SolveOptions&);
  const std::pair<const char*, Solve> solves[] = {{"BM_EdgeCold", BM_EdgeCold},   {"BM_EdgeWarm", BM_EdgeWarm},
                                                  {"BM_EdgeTracked", BM_EdgeTracked}, {"BM_PointCold", BM_PointCold},
                                                  {"BM_PointWarm", BM_PointWarm}, {"BM_FrictionalEdgeWarm", BM_FrictionalEdgeWarm}};
  for (const auto& [name, solve] : solves) benchmark::RegisterBenchmark(name, solve, fast());
  for (const auto& [name, solve] : solves) benchmark::RegisterBenchmark((std::string(name) + "Secant").c_str(), solve, secant());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
