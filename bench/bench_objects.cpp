// Object modes (issue 24, docs/objects.md): warm solves against a peg with a radius, a wall and a
// 20,480-triangle mesh, beside the warm edge solve they are measured against (the same whisker and whisk as
// bench_solve's BM_EdgeWarm: a 1 kHz frame, 0.05 deg of protraction after the warm state's).
//   build/bench/bench_objects --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "bench_whisker.hpp"

#include <numbers>

#include "vibrissa/objects/cylinder.hpp"
#include "vibrissa/objects/mesh.hpp"
#include "vibrissa/objects/plane.hpp"
#include "vibrissa/solve/object_contact.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace {
using namespace vibrissa;

using bench::bench_whisker;
SolveOptions fast() {
  SolveOptions o;
  o.compute_shape = false;
  return o;
}
Pose previous_frame(const Whisker& w) {
  Pose p = w.placement().pose();
  p.theta -= 0.05 * std::numbers::pi / 180.0;
  return p;
}

void BM_EdgeWarm(benchmark::State& state) {
  const Whisker w = bench_whisker();
  const Edge peg{{0.020, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  const Solution before = solve_edge(w, previous_frame(w), peg, std::nullopt, fast());
  for (auto _ : state) benchmark::DoNotOptimize(solve_edge(w, peg, std::nullopt, fast(), &before.state));
}
BENCHMARK(BM_EdgeWarm);

void warm_object(benchmark::State& state, const Shape& shape) {
  const Whisker w = bench_whisker();
  const ObjectContact o{&shape, {}, true};
  const Solution before = solve_object(w, previous_frame(w), o, std::nullopt, fast());
  if (before.status != Status::converged) state.SkipWithError("the previous frame does not converge");
  for (auto _ : state) benchmark::DoNotOptimize(solve_object(w, w.placement(), o, std::nullopt, fast(), &before.state));
  state.counters["iterations"] = solve_object(w, w.placement(), o, std::nullopt, fast(), &before.state).iterations;
}

void BM_CylinderWarm(benchmark::State& state) {
  const Cylinder peg({0.020, 0.0015, 0.0}, {0.0, 0.0, 1.0}, 0.0015);
  warm_object(state, peg);
}
BENCHMARK(BM_CylinderWarm);

void BM_PlaneWarm(benchmark::State& state) {
  // A wall on the whisker's convex side, across it at 22 mm.
  const Whisker w = bench_whisker();
  const Eigen::Vector3d at = w.placement().to_world(w.rest_point_B(0.022));
  const Eigen::Vector3d t = w.placement().R_WB * w.rest_link_frames_B()[55].col(0);
  const Eigen::Vector3d y = w.placement().R_WB.col(1);
  const Eigen::Vector3d n = (y - y.dot(t) * t).normalized();
  const Plane wall(at + 0.0004 * n, n);
  warm_object(state, wall);
}
BENCHMARK(BM_PlaneWarm);

void BM_MeshWarm(benchmark::State& state) {
  // A 3 mm sphere tessellated into 20,480 triangles, pressed 0.5 mm into the whisker at 22 mm.
  const Whisker w = bench_whisker();
  const Eigen::Vector3d at = w.placement().to_world(w.rest_point_B(0.022));
  const Eigen::Vector3d y = w.placement().R_WB.col(1);
  const Mesh ball(tessellated_sphere(at + 0.0025 * y, 0.003, 5));
  state.counters["triangles"] = static_cast<double>(ball.triangles().size());
  warm_object(state, ball);
}
BENCHMARK(BM_MeshWarm);

}  // namespace

BENCHMARK_MAIN();
