#pragma once
// The edge equations (spec §2.1, last paragraphs): the contact lies on the line (two equations) and the
// force's component along the line equals -c · F_N, where F_N is its component normal to the line:
// c = 0 is the frictionless edge mode of the paper; c = sigma · mu is Coulomb slip opposing the slip
// direction sigma (frictional edge mode, spec §4.4 "future work").
#include <cmath>

#include "contact_problem.hpp"
#include "vibrissa/solve/status.hpp"

namespace vibrissa::detail {

struct EdgeGeometryB {
  Eigen::Vector3d point;      ///< a point of the line, whisker frame [m]
  Eigen::Vector3d direction;  ///< unit direction, whisker frame
  Eigen::Vector3d e1, e2;     ///< basis of the plane normal to the line
};

EdgeGeometryB edge_in_body(const Placement& X_WB, const Edge& edge);

struct EdgeAttempt {
  LMResult lm;
  Status status = Status::not_converged;
  bool folded = false;  ///< the equilibrium branch from first touch ends before the target: push-past
  ContactEvaluations evaluations;  ///< the last kinematics evaluated (the solved point's among them)
};

/// Solves the edge equations with friction factor c from scaled unknowns u0. `known`: evaluations already made
/// for this whisker (reused where the attempt evaluates at exactly their load).
EdgeAttempt attempt_edge(const Whisker& w, const Scales& sc, const EdgeGeometryB& g, double c,
                         const Eigen::Vector3d& u0, const SolveOptions& options,
                         const ContactEvaluations* known = nullptr);

/// solve_edge() whose first attempt reuses `known` evaluations (nullptr: none).
Solution solve_edge_from(const Whisker& w, const Placement& X_WB, const Edge& edge, std::optional<double> hint,
                         const SolveOptions& options, const LoadState* warm,
                         const std::optional<Eigen::Vector3d>& approach_W, const ContactEvaluations* known);

/// Globalisation by continuation when a direct solve fails: the line is moved from where it just touches
/// the rest whisker (exact solution: zero force at the nearest rest point) to its true place in adaptive
/// steps, each warm-started from the last. Returns the final attempt (or `failed` if no step succeeds).
EdgeAttempt continue_from_touch(const Whisker& w, const Scales& sc, const EdgeGeometryB& g, double s_touch,
                                const SolveOptions& options, const EdgeAttempt& failed);

/// Checks that a converged edge contact pushes the whisker (and opposes `approach_W` if given); rewrites
/// the status to no_contact if it does not.
void check_contact_side(const Whisker& w, const Placement& X_WB, const std::optional<Eigen::Vector3d>& approach_W,
                        Solution& out);

/// Whether the line is within the whisker's reach: seen along the line, the rest whisker gets at least as far
/// from the base as the line is (a rotation about the base could bring them together).
bool within_reach(const Whisker& w, const EdgeGeometryB& g);

/// Arc length of the rest whisker's point nearest the line, seen along it: where continuation from first touch
/// starts, and a cold solve when the cantilever guess does not apply (edge_mode.cpp).
double nearest_rest_arc_length(const Whisker& w, const EdgeGeometryB& g);

}  // namespace vibrissa::detail
