// The Solution contract every mode keeps (solve/status.hpp): finite fields, converged only within tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "../../src/solve/solution_check.hpp"
#include "vibrissa/solve/solvers.hpp"

using namespace vibrissa;

TEST(SolutionContract, AbsurdDeadLoadIsNotConvergedAndFinite) {
  // Once: "converged" with residual 1e300 (the tolerance 1e-14 |F| overflowed to infinity).
  const Whisker w = Whisker::from_parabola(0.03, 5.0, WhiskerProperties{});
  const Solution s = solve_dead_load(w, Eigen::Vector3d(0, 1e300, 0), 0.02);
  EXPECT_EQ(s.status, Status::not_converged);
  EXPECT_TRUE(detail::all_finite(s));
  EXPECT_EQ(s.force_magnitude, 0.0);
}

TEST(SolutionContract, ConvergedAboveToleranceIsDowngraded) {
  const Whisker w = Whisker::from_parabola(0.03, 5.0, WhiskerProperties{});
  SolveOptions o;
  Solution s = solve_point(w, Eigen::Vector3d(0.02, 0.001, 0.0), std::nullopt, o);
  ASSERT_EQ(s.status, Status::converged);
  s.residual = 1e-3;
  const Solution checked = detail::checked_solution(s, o.tolerance, w, w.placement(), o);
  EXPECT_EQ(checked.status, Status::not_converged);
  EXPECT_EQ(checked.contact_state, ContactState::free);
  EXPECT_EQ(checked.residual, 1e-3);
  EXPECT_EQ(checked.force_magnitude, 0.0);
  s.residual = 0.0;
  s.force_magnitude = std::nan("");
  EXPECT_EQ(detail::checked_solution(s, o.tolerance, w, w.placement(), o).status, Status::not_converged);
}

TEST(SolutionContract, TinyEdgeDirectionIsRejectedWithItsValue) {
  const Whisker w = Whisker::from_parabola(0.03, 5.0, WhiskerProperties{});
  Edge e;
  e.point = Eigen::Vector3d(0.02, 0.001, 0.0);
  e.direction = Eigen::Vector3d(1e-300, 0, 0);
  try {
    (void)solve_edge(w, e);
    FAIL();
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("edge.direction must be non-zero with a length between"), std::string::npos);
    EXPECT_NE(std::string(ex.what()).find("[1e-300, 0, 0]"), std::string::npos);
  }
}

TEST(SolutionContract, OptionsAreRangeChecked) {
  const Whisker w = Whisker::from_parabola(0.03, 5.0, WhiskerProperties{});
  SolveOptions o;
  o.tolerance = 1e300;
  EXPECT_THROW((void)solve_point(w, Eigen::Vector3d(0.02, 0.001, 0.0), std::nullopt, o), std::invalid_argument);
  o = {};
  o.max_iterations = 0;
  EXPECT_THROW((void)solve_force(w, 0.001, 0.02, 0.0, o), std::invalid_argument);
}
