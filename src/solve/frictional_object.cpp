// Frictional object mode (docs/objects.md, "Friction"): Coulomb friction with contact history on an object's
// surface, as the frictional edge mode on a line. The whisker slides freely along its own length (no friction
// along it, as the spec's model); across it, in the tangent plane (b = n x t), the contact sticks where it was
// while |F . b| <= mu F . n and otherwise slips toward the frictionless contact with |F . b| = mu F . n. At the
// tip (a point of the whisker) the friction acts in the whole tangent plane. Per frame:
//   1. the frictionless contact (solve_object): where the contact would slip to, and release;
//   2. stick at the previous contact point; kept if within the cone;
//   3. slip toward the frictionless point until the cone is met, friction opposing the slip.
// The force's axial part and friction's couple about the centre line depend on the normal in the load frame,
// known only after the walk: each solve is repeated with the normal of its solution until it is unchanged.
#include <cmath>

#include <Eigen/Geometry>

#include "object_mode.hpp"
#include "solution_check.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {

namespace {

Eigen::Vector3d unknowns_of(const detail::Scales& sc, const LoadState& s, bool tip) {
  if (tip) return Eigen::Vector3d(s.force_x, s.force_y, s.force_z) / sc.force;
  return {s.force_y / sc.force, s.force_z / sc.force, s.arc_length / sc.length};
}

}  // namespace

Solution solve_frictional_object(const Whisker& w, const Placement& X, const ObjectContact& object, double mu,
                                 const Eigen::Vector3d& previous_contact_W, const SolveOptions& options,
                                 const LoadState* warm, const std::optional<Eigen::Vector3d>& approach_W) {
  validate(options);
  validate(object);
  require_finite(mu, "friction_coefficient");
  if (mu < 0.0) invalid_input("friction_coefficient must be >= 0, got " + format_value(mu));
  require_finite(previous_contact_W, "previous_contact");
  SolveOptions inner = options;
  inner.compute_shape = false;
  inner.find_other_roots = false;
  Solution free = solve_object(w, X, object, std::nullopt, inner, warm, approach_W);
  auto finish = [&](Solution s, FrictionState friction) {
    if (options.compute_shape && (s.status == Status::converged || s.status == Status::second_contact))
      deflected_shape(w, X, s.state, s.shape_W);
    s.friction = s.status == Status::converged || s.status == Status::second_contact ? friction : FrictionState::none;
    return detail::checked_solution(std::move(s), options.tolerance, w, X, options);
  };
  if (free.status != Status::converged) return finish(std::move(free), FrictionState::none);
  if (mu == 0.0) {
    free.message = "frictionless: slipping on the object";
    return finish(std::move(free), FrictionState::slip);
  }
  const detail::Scales sc(w);
  const detail::ObjectGeometryB g = detail::object_in_body(X, object);
  const bool tip = free.surface->tip;
  const detail::ObjectContactPoint centre_line = detail::contact_point_at(w, g, free.state, tip, 1.0);
  const double sigma = detail::core_side(g, centre_line.c_B, centre_line.t_B);  // a line core's side
  const detail::ObjectContactPoint at_free = detail::contact_point_at(w, g, free.state, tip, sigma);
  const Eigen::Vector3d previous_B = g.query(X.to_body(previous_contact_W)).closest;  // on the surface

  // A frictional solve from `start`, repeated with the solution's normal in the load frame until it holds.
  auto solve_law = [&](detail::FrictionLaw law, const LoadState& start) {
    law.normal_L = detail::contact_point_at(w, g, start, tip, sigma).normal_in_load_frame();
    Eigen::Vector3d u = unknowns_of(sc, start, tip);
    detail::ObjectAttempt a;
    int iterations = 0;
    // The distance equation on the loaded link's lowest piece, as the frictionless solve (object_mode.cpp).
    detail::ClearancePiece piece = detail::ClearancePiece::centre;
    for (int change = 0; change < 4; ++change) {
      for (int round = 0; round < 8; ++round) {
        a = tip ? detail::attempt_tip(w, sc, g, law, u, inner, piece)
                : detail::attempt_side(w, sc, g, law, sigma, u, inner, piece);
        iterations += a.lm.iterations;
        if (a.status != Status::converged) break;
        const Eigen::Vector3d normal = detail::contact_point_at(w, g, a.state, tip, sigma).normal_in_load_frame();
        const double moved = (normal - law.normal_L).cwiseAbs().maxCoeff();
        law.normal_L = normal;
        u = a.lm.u;
        if (moved < 1e-14) break;
      }
      if (a.status != Status::converged) break;
      const detail::ClearancePiece lowest = detail::lowest_piece(w, g, a.state);
      if (lowest == piece) break;
      piece = lowest;
    }
    a.piece = piece;
    a.lm.iterations = iterations;
    return a;
  };
  auto cone = [&](const detail::ObjectAttempt& a, double& friction, double& normal) {
    const detail::ObjectContactPoint p = detail::contact_point_at(w, g, a.state, tip, sigma);
    normal = p.F_B.dot(p.normal_B);
    friction = tip ? (p.F_B - normal * p.normal_B).norm() : p.F_B.dot(p.friction_B);
  };
  auto solution_of = [&](const detail::ObjectAttempt& a, std::string_view message) {
    detail::ObjectOutcome o;
    o.attempt = a;
    o.sigma = sigma;
    Solution s = detail::object_solution(w, X, object, g, o, inner, approach_W);
    if (s.status == Status::converged) s.message = message;
    s.iterations += free.iterations;
    return s;
  };

  // 2. Stick at the previous contact.
  detail::FrictionLaw stick_law;
  stick_law.kind = detail::FrictionLaw::Kind::stick;
  stick_law.previous_B = previous_B;
  const detail::ObjectAttempt stick = solve_law(stick_law, warm ? *warm : free.state);
  if (stick.status == Status::converged) {
    double friction = 0.0, normal = 0.0;
    cone(stick, friction, normal);
    if (normal > 0.0 && std::abs(friction) <= mu * normal * (1.0 + 1e-9)) {
      Solution s = solution_of(stick, "stick: the contact holds its previous point on the object");
      if (s.status == Status::converged || s.status == Status::second_contact)
        return finish(std::move(s), FrictionState::stick);
    }
  }
  // 3. Slip toward the frictionless point until the cone is met.
  detail::FrictionLaw slip_law;
  slip_law.kind = detail::FrictionLaw::Kind::slip;
  const Eigen::Vector3d travel = at_free.point_B - previous_B;
  if (tip) {
    const Eigen::Vector3d tangential = travel - travel.dot(at_free.normal_B) * at_free.normal_B;
    if (tangential.norm() == 0.0) {
      free.message = "slip: previous contact coincides with the frictionless point";
      return finish(std::move(free), FrictionState::slip);
    }
    slip_law.slip_B = tangential.normalized();
    slip_law.sigma_mu = mu;
  } else {
    const double along = travel.dot(at_free.friction_B);
    if (along == 0.0) {
      free.message = "slip: previous contact coincides with the frictionless point";
      return finish(std::move(free), FrictionState::slip);
    }
    slip_law.sigma_mu = (along > 0.0 ? 1.0 : -1.0) * mu;
  }
  detail::ObjectAttempt slip = solve_law(slip_law, stick.status == Status::converged ? stick.state : free.state);
  if (slip.status != Status::converged && stick.status == Status::converged) slip = solve_law(slip_law, free.state);
  slip.lm.iterations += stick.lm.iterations;
  Solution s = solution_of(slip, "slip: the contact moved across the whisker with |F . b| = mu F . n");
  return finish(std::move(s), FrictionState::slip);
}

}  // namespace vibrissa
