#include "solution_check.hpp"

#include <cmath>
#include <limits>

#include "contact_problem.hpp"
#include "vibrissa/core/checks.hpp"

namespace vibrissa {

void validate(const SolveOptions& o) {
  require_in_range(o.tolerance, std::numeric_limits<double>::min(), 1e-3, "options.tolerance");
  require_integer(o.max_iterations, 1, limits::max_iterations, "options.max_iterations");
}

namespace detail {

bool all_finite(const Solution& s) {
  const auto& wf = s.whisker_frame;
  bool ok = std::isfinite(s.force_magnitude) && std::isfinite(s.arc_length) && std::isfinite(s.angle) &&
            s.contact_point_W.allFinite() && s.force_W.allFinite() && s.moment_W.allFinite() && wf.force.allFinite() &&
            wf.moment.allFinite() && std::isfinite(wf.FT) && std::isfinite(wf.MB) && std::isfinite(wf.FD) &&
            std::isfinite(wf.MD) && std::isfinite(s.residual) && std::isfinite(s.state.force_x) &&
            std::isfinite(s.state.force_y) && std::isfinite(s.state.force_z) && std::isfinite(s.state.arc_length) &&
            std::isfinite(s.state.couple_x) && std::isfinite(s.state.couple_y) && std::isfinite(s.state.couple_z);
  if (s.surface)
    ok = ok && s.surface->normal_W.allFinite() && s.surface->friction_direction_W.allFinite() &&
         std::isfinite(s.surface->friction_force) && std::isfinite(s.surface->clearance) &&
         std::isfinite(s.surface->clearance_arc_length);
  if (s.second_contact_arc_length) ok = ok && std::isfinite(*s.second_contact_arc_length);
  if (s.second_contact)
    ok = ok && std::isfinite(s.second_contact->arc_length) && s.second_contact->contact_point_W.allFinite() &&
         s.second_contact->force_W.allFinite() && s.second_contact->normal_W.allFinite() &&
         std::isfinite(s.second_contact->normal_force);
  for (const auto& v : {s.normal_force, s.edge_force, s.other_root_arc_length}) ok = ok && (!v || std::isfinite(*v));
  for (const auto& p : s.shape_W) ok = ok && p.allFinite();
  return ok;
}

Solution checked_solution(Solution s, double residual_tolerance, const Whisker& w, const Placement& X,
                          const SolveOptions& options) {
  const bool finite = all_finite(s);
  const bool within =
      s.status != Status::converged || (std::isfinite(residual_tolerance) && s.residual <= residual_tolerance);
  if (finite && within) return s;
  Solution out = unloaded_solution(
      w, X, Status::not_converged,
      finite ? "the solver stopped with a residual above the tolerance"
             : "the solver produced non-finite values (load or geometry beyond what the model can represent)",
      options);
  out.iterations = s.iterations;
  out.residual = std::isfinite(s.residual) ? s.residual : std::numeric_limits<double>::max();
  VIBRISSA_DEMAND(all_finite(out));
  return out;
}

}  // namespace detail
}  // namespace vibrissa
