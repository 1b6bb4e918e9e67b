#pragma once
// The last step of every solve: the Solution contract (solve/status.hpp) checked in one place.
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa::detail {

/// Every field of `s` is finite (optionals only when set).
bool all_finite(const Solution& s);

/// Returns `s` if it keeps the contract: every field finite, and `converged` only with a residual within
/// `residual_tolerance` (in the units of s.residual). Otherwise returns a not_converged Solution with the
/// rest shape and no load, the same iteration count, and the residual of `s` (the largest finite double if
/// that was not finite). Every solve mode returns through this.
Solution checked_solution(Solution s, double residual_tolerance, const Whisker& w, const Placement& X_WB,
                          const SolveOptions& options);

}  // namespace vibrissa::detail
