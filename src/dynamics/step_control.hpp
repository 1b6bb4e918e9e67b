#pragma once
// Step-size control shared by both integrators of dynamics::simulate() (docs/dynamics.md, "Integrator"): the
// linear chain's trapezoidal rule (simulate.cpp) and the nonlinear chain's SDIRK2 (nonlinear_simulate.cpp).
//
// Both methods are second order and estimate the local error of a step as O(h^3) (step doubling / an embedded
// third-order companion), so the next step is h * clamp(0.9 (tol / err)^(1/3), 0.2, 4), at most max_step; a step
// whose solve failed is retried at h / 4. Steps land on the output times (a step within 1 % of the output is
// stretched to it; a step shortened to land on an output says nothing against the step planned before it). The
// first step is min(max_step, 1e-5 s). Stops with max_steps (accepted + rejected) or step_too_small (a rejected
// step's successor below 1e-14 max(1, t) s).
#include <algorithm>
#include <cmath>

#include "vibrissa/dynamics/simulate.hpp"

namespace vibrissa::dynamics::detail {

/// The outcome of one attempted step: `solved` false when the method's solve failed (then err, tol are unused).
struct StepAttempt {
  bool solved = true;
  double err = 0.0, tol = 0.0;  ///< error estimate and tolerance, same norm
};

/// Integrates from t = 0 to the last of `frames` output times k / options.output_rate. `attempt(t, h)` takes a
/// step of length h from the accepted state at t into a scratch state and returns its StepAttempt; `accept(t, h)`
/// makes that scratch state the accepted one (t the step's start); `record(frame, t)` writes output frame k
/// (k >= 1; the caller records frame 0). Fills ts.status, steps, rejected_steps, smallest_step, largest_step.
template <class Attempt, class Accept, class Record>
void integrate_with_step_control(const SimulationOptions& options, long frames, TimeSeries& ts, Attempt&& attempt,
                                 Accept&& accept, Record&& record) {
  const double max_step = options.max_step > 0.0 ? options.max_step : 1.0 / options.output_rate;
  double t = 0.0, h_next = std::min(max_step, 1e-5);
  for (long f = 1; f < frames; ++f) {
    const double t_out = static_cast<double>(f) / options.output_rate;
    while (t < t_out) {
      if (ts.steps + ts.rejected_steps >= options.max_steps) {
        ts.status = SimulationStatus::max_steps;
        return;
      }
      double h = h_next;
      const bool last = t + 1.01 * h >= t_out;  // land on the output time (no sliver step after it)
      if (last) h = t_out - t;
      const StepAttempt a = attempt(t, h);
      double factor = 0.25;
      if (a.solved) factor = a.err > 0.0 ? std::clamp(0.9 * std::cbrt(a.tol / a.err), 0.2, 4.0) : 4.0;
      if (a.solved && a.err <= a.tol) {
        accept(t, h);
        t = last ? t_out : t + h;
        ++ts.steps;
        ts.smallest_step = ts.steps == 1 ? h : std::min(ts.smallest_step, h);
        ts.largest_step = std::max(ts.largest_step, h);
        if (!(last && h < h_next)) h_next = std::min(h * factor, max_step);
      } else {
        ++ts.rejected_steps;
        h_next = h * factor;
        if (h_next < 1e-14 * std::max(1.0, t_out)) {
          ts.status = SimulationStatus::step_too_small;
          return;
        }
      }
    }
    record(f, t_out);
  }
}

}  // namespace vibrissa::dynamics::detail
