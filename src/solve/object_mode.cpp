// Object mode (docs/objects.md): the whisker against an object's surface without friction, on its side or at its
// tip, with the statuses of edge mode and second_contact. The equations are object_problem.hpp's.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include <Eigen/Geometry>

#include "edge_problem.hpp"
#include "object_mode.hpp"
#include "solution_check.hpp"
#include "two_contact.hpp"
#include "vibrissa/objects/clearance.hpp"
#include "vibrissa/solve/solvers.hpp"
#include "vibrissa/solve/whisker_frame_signals.hpp"

namespace vibrissa {

void validate(const ObjectContact& o) {
  if (!o.shape) invalid_input("object: no shape given");
  require_finite(o.X_WO.p_WO, "object.pose.position");
  if (!o.X_WO.R_WO.allFinite() ||
      (o.X_WO.R_WO.transpose() * o.X_WO.R_WO - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9)
    invalid_input("object.pose.rotation must be a rotation matrix");
  if (!o.thickness && o.shape->needs_thickness())
    invalid_input("object.thickness: a " + std::string(o.shape->type()) +
                  " has edges and corners, which only the whisker's surface can touch: thickness must be on");
}

namespace detail {

namespace {

bool is_tip(const Whisker& w, double s) { return s >= w.length() * (1.0 - 1e-12); }

/// Newton steps a warm attempt on an object with creases takes before the sliding attempt takes over.
constexpr int warm_creased_iterations = 12;
/// Features of a creased shape attempt_on_features holds in turn before it gives up.
constexpr int feature_rounds = 12;
/// Points between two contacts across a crease at which attempt_by_bracketing looks for the crease.
constexpr int crease_samples = 16;
/// Links each side of the contact on which a warm sliding attempt looks for the whisker's nearest point.
constexpr int sliding_window = 4;

/// Scaled unknowns of a side attempt from a force in B at arc length s of the rest whisker (its rest frame there).
Eigen::Vector3d side_unknowns(const Whisker& w, const Scales& sc, const Eigen::Vector3d& F_B, double s) {
  int k;
  double h;
  w.locate(s, k, h);
  const Eigen::Matrix3d& R = w.rest_link_frames_B()[static_cast<std::size_t>(std::clamp(k, 0, w.links() - 1))];
  return {F_B.dot(R.col(1)) / sc.force, F_B.dot(R.col(2)) / sc.force, s / sc.length};
}

/// Scaled unknowns of a tip attempt from a force in B (the tip link's rest frame).
Eigen::Vector3d tip_unknowns(const Whisker& w, const Scales& sc, const Eigen::Vector3d& F_B) {
  const Eigen::Matrix3d& R = w.rest_link_frames_B().back();
  return R.transpose() * F_B / sc.force;
}

/// The deflected whisker's smallest gap on the links about arc length s (sliding_window each side), or on the
/// whole whisker where the smallest of those is at the window's end (the nearest point lies beyond it).
Clearance nearest_about(const PlacedShape& placed, const Whisker& w, const std::vector<Eigen::Vector3d>& nodes,
                        bool thickness, double s) {
  const std::vector<double> none;
  const std::span<const double> radii = thickness ? std::span<const double>(w.node_radii()) : std::span<const double>(none);
  int k;
  double h;
  w.locate(s, k, h);
  const int last = static_cast<int>(nodes.size()) - 1;
  const auto lo = static_cast<std::size_t>(std::clamp(k - sliding_window, 0, last));
  const auto hi = static_cast<std::size_t>(std::clamp(k + 1 + sliding_window, 0, last));
  const std::size_t count = hi - lo + 1;
  const std::span<const Eigen::Vector3d> all(nodes);
  const std::span<const double> arc(w.node_arc_lengths());
  const Clearance c = clearance(placed, all.subspan(lo, count), arc.subspan(lo, count),
                                radii.empty() ? radii : radii.subspan(lo, count));
  const bool at_end = (lo > 0 && c.arc_length <= arc[lo]) || (hi < nodes.size() - 1 && c.arc_length >= arc[hi]);
  return at_end ? clearance(placed, nodes, arc, radii) : c;
}

}  // namespace

Touch first_touch(const Whisker& w, const ObjectGeometryB& g, const DeepestPoint& d) {
  if (g.core_B) return {d.gap * d.normal_B, d.arc_length};  // onto the nearest point seen along the line
  // The rest whisker's smallest gap with the object moved by -tau along the deepest point's normal.
  const std::vector<double> none;
  const std::span<const double> radii = g.thickness ? std::span<const double>(w.node_radii()) : std::span<const double>(none);
  auto gap = [&](double tau) {
    const PlacedShape moved{g.shape, ObjectPose{g.R_BO, g.p_BO + g.offset_B - tau * d.normal_B}};
    return clearance(moved, w.rest_nodes_B(), w.node_arc_lengths(), radii);
  };
  double lo = 0.0, hi = std::max(-d.gap, 1e-9 * w.length());
  Clearance at_hi = gap(hi);
  for (int i = 0; i < 60 && at_hi.gap < 0.0; ++i) {
    lo = hi;
    hi *= 2.0;
    at_hi = gap(hi);
  }
  // The gap's root between lo (inside) and hi (clear): regula falsi, halving the retained end's value when the
  // same end is kept twice (the Illinois method), a bisection where that point is not inside the bracket. Each
  // evaluation is a clearance query of the whole whisker: this takes a few where bisection took dozens.
  double f_lo = gap(lo).gap, f_hi = at_hi.gap;
  int kept = 0;  // +1: lo was kept last time, -1: hi
  // The touch is the continuation's start, not a solution: its first step moves the object by a quarter of the
  // way, so a touch within 1e-6 of the depth (the whisker clear of the object by at most that) starts the same
  // path (was 1e-13 of the length: dozens of whole-whisker clearance queries).
  const double precision = std::max(1e-6 * hi, 1e-13 * w.length());
  for (int i = 0; i < 100 && hi - lo > precision; ++i) {
    double x = std::isfinite(f_hi) && f_lo < 0.0 ? lo + (hi - lo) * (-f_lo) / (f_hi - f_lo) : 0.5 * (lo + hi);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const Clearance c = gap(x);
    if (c.gap < 0.0) {
      lo = x;
      f_lo = c.gap;
      if (kept == -1) f_hi *= 0.5;
      kept = -1;
    } else {
      hi = x;
      f_hi = c.gap;
      at_hi = c;
      if (kept == 1) f_lo *= 0.5;
      kept = 1;
    }
  }
  return {-hi * d.normal_B, at_hi.arc_length};
}

bool core_within_reach(const Whisker& w, const ObjectGeometryB& g) {
  EdgeGeometryB line;
  line.point = g.core_B->point + g.offset_B;
  line.direction = g.core_B->direction;
  normal_basis(line.direction, line.e1, line.e2);
  if (within_reach(w, line)) return true;
  // Within reach of the cylinder's surface: the line moved toward the base by its radius and the whisker's.
  const Eigen::Vector3d r = line.point - line.point.dot(line.direction) * line.direction;
  const double rho = g.core_B->radius + (g.thickness ? w.node_radii().front() : 0.0);
  if (!(r.norm() > rho)) return true;
  line.point -= rho * r.normalized();
  return within_reach(w, line);
}

bool valid_contact(const Whisker& w, const ObjectGeometryB& g, const ObjectAttempt& a, double sigma) {
  const ObjectContactPoint p = contact_point_at(w, g, a.state, a.tip, sigma);
  if (p.F_B.dot(p.normal_B) < -1e-12 * p.F_B.norm()) return false;  // the object would pull
  // At the tip: the whisker's gap must fall toward the tip (else its side touches first).
  if (a.tip) return p.normal_B.dot(p.t_B) - p.slope <= 1e-9;
  return true;
}

ObjectAttempt attempt_object(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                             double& sigma, bool tip, const Eigen::Vector3d& u0, const SolveOptions& options,
                             const WarmAttempt& warm) {
  // A warm start's force is near the solution's: solved at once to the tolerance the polish below asks of it
  // (half of it), instead of to the plain tolerance and then polished.
  SolveOptions first = options;
  if (warm.warm) {
    const double f0 = tip ? u0.norm() : std::hypot(u0[0], u0[1]);
    if (f0 > 0.0) first.tolerance = std::min(options.tolerance, 0.5e-11 * std::max(f0, 1e-4) * sc.length);
  }
  ObjectAttempt a = tip ? attempt_tip(w, sc, g, law, u0, first, warm.piece)
                        : attempt_side(w, sc, g, law, sigma, u0, first, warm.piece);
  a.piece = warm.piece;
  int iterations = a.lm.iterations;
  if (!tip && a.status == Status::slipped_off) {  // the side contact would need s > L: the tip touches
    const ObjectContactPoint p = contact_point_at(w, g, a.state, false, sigma);
    ObjectAttempt t = attempt_tip(w, sc, g, law, tip_unknowns(w, sc, p.F_B), options);
    iterations += t.lm.iterations;
    if (t.status == Status::converged && valid_contact(w, g, t, sigma)) a = t;
    else a.status = Status::slipped_off;
  } else if (tip && a.status == Status::converged && !valid_contact(w, g, a, sigma)) {
    // The tip's contact is not the whisker's nearest point: its side touches.
    const ObjectContactPoint p = contact_point_at(w, g, a.state, true, sigma);
    ObjectAttempt s = attempt_side(w, sc, g, law, sigma, side_unknowns(w, sc, p.F_B, 0.995 * w.length()), options);
    iterations += s.lm.iterations;
    a = s;
  } else if (tip && a.status != Status::converged) {
    a.status = Status::slipped_off;  // no equilibrium with the tip on the object: it slides off
  } else if (!tip && g.core_B && a.status == Status::converged) {
    // On a line core the equations fix the force's line, not its sense: a force toward the axis belongs to a
    // contact on the axis's other side (the same point where the radius is small).
    const ObjectContactPoint p = contact_point_at(w, g, a.state, false, sigma);
    if (p.F_B.dot(p.normal_B) < 0.0) {
      ObjectAttempt other = attempt_side(w, sc, g, law, -sigma, a.lm.u, options);
      iterations += other.lm.iterations;
      if (other.status == Status::converged) {
        a = other;
        sigma = -sigma;
      }
    }
  }
  // The distance equation on the loaded link's lowest piece (object_problem.hpp), until the piece it holds on
  // is the lowest (each a smooth system, started from the last solution).
  if (a.status == Status::converged) {
    ClearancePiece piece = a.piece;
    for (int change = 0; change < 4; ++change) {
      const ClearancePiece lowest = lowest_piece(w, g, a.state);
      if (lowest == piece) break;
      piece = lowest;
      ObjectAttempt b = a.tip ? attempt_tip(w, sc, g, law, a.lm.u, options, piece)
                              : attempt_side(w, sc, g, law, sigma, a.lm.u, options, piece);
      iterations += b.lm.iterations;
      if (b.status != Status::converged) break;
      b.piece = piece;
      a = b;
    }
  }
  // The force's direction is solved to the tolerance in units of E I_0 / L^2: a small force is polished with a
  // tolerance scaled by its size, so that its direction holds relative to its magnitude.
  const double f = std::hypot(a.state.force_x, std::hypot(a.state.force_y, a.state.force_z)) / sc.force;
  // (the residual bounds the direction's error by about residual / f: polished only where that exceeds 1e-11)
  if (a.status == Status::converged && f > 0.0 && a.lm.residual > 1e-11 * f) {
    SolveOptions tight = options;
    tight.tolerance = options.tolerance * std::max(f, 1e-4);
    ObjectAttempt b = a.tip ? attempt_tip(w, sc, g, law, a.lm.u, tight, a.piece)
                            : attempt_side(w, sc, g, law, sigma, a.lm.u, tight, a.piece);
    b.piece = a.piece;
    iterations += b.lm.iterations;
    if (b.status == Status::converged) a = b;
  }
  a.lm.iterations = iterations;
  return a;
}

ObjectAttempt attempt_by_sliding(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                                 double& sigma, const Eigen::Vector3d& u0, const SolveOptions& options,
                                 const WarmAttempt& warm) {
  const bool local = warm.warm;
  // Alternate: the force with s held (gap and force direction), then s moved to where the deflected whisker is
  // nearest the object; then every equation from there.
  Eigen::Vector3d u = u0;
  int iterations = 0;
  const std::vector<double> none;
  const PlacedShape placed{g.shape, ObjectPose{g.R_BO, g.p_BO + g.offset_B}};
  std::vector<Eigen::Vector3d> nodes;
  for (int round = 0; round < (local ? 1 : 30); ++round) {  // warm: one move to the nearest point
    const ObjectAttempt held =
        attempt_side(w, sc, g, law, sigma, u, options, ClearancePiece::centre, u[2] * sc.length);
    iterations += held.lm.iterations;
    if (held.status != Status::converged) break;
    u = held.lm.u;
    deflected_nodes(w, g, Placement{}, held.state, nodes);
    const Clearance c = local ? nearest_about(placed, w, nodes, g.thickness, held.state.arc_length)
                              : clearance(placed, nodes, w.node_arc_lengths(), g.thickness ? w.node_radii() : none);
    const double s_next = std::clamp(c.arc_length, 1e-6 * sc.length, sc.length) / sc.length;
    if (std::abs(s_next - u[2]) < 1e-9) break;
    u[2] = s_next;
  }
  ObjectAttempt a = attempt_object(w, sc, g, law, sigma, false, u, options, warm);
  a.lm.iterations += iterations;
  return a;
}

ObjectAttempt attempt_by_bracketing(const Whisker& w, const Scales& sc, const ObjectGeometryB& g,
                                   const FrictionLaw& law, double& sigma, const ObjectAttempt& from,
                                   const SolveOptions& options) {
  ObjectAttempt failed = from;
  failed.status = Status::not_converged;
  failed.lm.iterations = 0;
  if (from.tip || g.core_B) return failed;
  int iterations = 0;
  // The held solve at s (gap and force direction), from u; its tangency g'(s) = n . t - r'.
  struct Held {
    bool ok = false;
    double tangency = 0.0;
    Eigen::Vector3d u;
    ObjectAttempt attempt;
    Eigen::Vector3d c_B;
  };
  auto held_at = [&](double s, Eigen::Vector3d u) {
    u[2] = s / sc.length;
    const ObjectAttempt h = attempt_side(w, sc, g, law, sigma, u, options, ClearancePiece::centre, s);
    iterations += h.lm.iterations;
    Held out;
    out.ok = h.status == Status::converged;
    if (!out.ok) return out;
    const ObjectContactPoint p = contact_point_at(w, g, h.state, false, sigma);
    out.tangency = p.normal_B.dot(p.t_B) - p.slope;
    out.u = h.lm.u;
    out.attempt = h;
    out.c_B = p.c_B;
    return out;
  };
  const double L = w.length(), link = L / w.links();
  double s0 = std::clamp(from.state.arc_length, link, L - link);
  Held h0 = held_at(s0, from.lm.u);
  if (!h0.ok) {
    failed.lm.iterations = iterations;
    return failed;
  }
  // The gap's minimum: the tangency rises through zero from below (lo) to above (hi) as s grows.
  const double direction = h0.tangency > 0.0 ? -1.0 : 1.0;
  double step = link, s1 = s0;
  Held h1;
  for (int i = 0; i < 12; ++i) {
    s1 = std::clamp(s0 + direction * step, 1e-3 * L, L * (1.0 - 1e-9));
    h1 = held_at(s1, h0.u);
    if (!h1.ok) break;
    if ((h1.tangency > 0.0) != (h0.tangency > 0.0)) break;
    s0 = s1;
    h0 = h1;
    step *= 2.0;
    if (s1 <= 1e-3 * L || s1 >= L * (1.0 - 1e-9)) {
      h1.ok = false;
      break;
    }
  }
  if (!h1.ok || (h1.tangency > 0.0) == (h0.tangency > 0.0)) {
    failed.lm.iterations = iterations;
    return failed;
  }
  double lo = s0, hi = s1;
  Held at_lo = h0, at_hi = h1;
  if (lo > hi) {
    std::swap(lo, hi);
    std::swap(at_lo, at_hi);
  }
  while (hi - lo > 1e-9 * L) {
    const double mid = 0.5 * (lo + hi);
    const Held m = held_at(mid, at_lo.u);
    if (!m.ok) break;
    if (m.tangency > 0.0) {
      hi = mid;
      at_hi = m;
    } else {
      lo = mid;
      at_lo = m;
    }
  }
  // The crease between: the feature nearest to the segment between the two contact points (its middle, else
  // the first edge or vertex along it).
  SurfacePoint crease = g.query(0.5 * (at_lo.c_B + at_hi.c_B));
  for (int k = 1; k < crease_samples && crease.feature == SurfaceFeature::face; ++k) {
    const SurfacePoint q = g.query(at_lo.c_B + (k / double(crease_samples)) * (at_hi.c_B - at_lo.c_B));
    if (q.feature != SurfaceFeature::face) crease = q;
  }
  ObjectAttempt a = attempt_on_features(w, sc, g, law, sigma, at_lo.attempt, options, crease);
  iterations += a.lm.iterations;
  a.lm.iterations = iterations;
  return a;
}

ObjectAttempt attempt_on_features(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                                  double& sigma, const ObjectAttempt& from, const SolveOptions& options,
                                  const std::optional<SurfacePoint>& feature) {
  ObjectAttempt failed = from;
  failed.status = Status::not_converged;
  failed.lm.iterations = 0;
  if (g.core_B || from.tip) return failed;
  ObjectContactPoint at = contact_point_at(w, g, from.state, false, sigma);
  if (feature) at.surface = *feature;
  Eigen::Vector3d u = from.lm.u;
  int iterations = 0;
  for (int round = 0; round < feature_rounds; ++round) {
    const SurfacePoint& q = at.surface;
    if (q.feature_id < 0 || q.feature == SurfaceFeature::vertex) break;
    ObjectGeometryB held = g;
    held.held_feature = q.feature_id;
    double held_sigma = sigma;
    if (q.feature == SurfaceFeature::edge) {  // an edge: a peg of radius 0 along its line (the line core's terms)
      held.core_B = LineCore{q.closest - g.offset_B, q.edge_direction, 0.0};
      held_sigma = core_side(held, at.c_B, at.t_B);
    }
    const ObjectAttempt a = attempt_object(w, sc, held, law, held_sigma, false, u, options);
    iterations += a.lm.iterations;
    if (a.status != Status::converged || a.tip) break;
    // The feature nearest to the contact: where it is the held one (or the same edge seen from the other
    // triangle: the same distance and normal), the solution is the object's; polished with the plain queries.
    const ObjectContactPoint on = contact_point_at(w, held, a.state, false, held_sigma);
    at = contact_point_at(w, g, a.state, false, sigma);
    if (std::abs(at.surface.signed_distance - on.surface.signed_distance) <= 1e-15 * sc.length &&
        (at.surface.normal - on.surface.normal).norm() <= 1e-12) {
      ObjectAttempt b = attempt_object(w, sc, g, law, sigma, false, a.lm.u, options);
      b.lm.iterations += iterations;
      return b;
    }
    u = a.lm.u;
  }
  failed.lm.iterations = iterations;
  return failed;
}

ObjectOutcome solve_object_contact(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                                   std::optional<double> hint, const SolveOptions& options, const LoadState* warm) {
  ObjectOutcome out;
  std::optional<DeepestPoint> deepest;
  auto deep = [&]() -> const DeepestPoint& {
    if (!deepest) deepest = deepest_rest_point(w, g);
    return *deepest;
  };
  // The start: the warm state; else zero force at the hint; else the cantilever push out of the deepest point.
  bool tip = false;
  Eigen::Vector3d u0;
  double sigma = 1.0;
  auto cold_start = [&] {
    const DeepestPoint& d = deep();
    const double c = cantilever_compliance(w, d.arc_length);
    const Eigen::Vector3d F_B = c > 0.0 ? Eigen::Vector3d(-d.gap / c * d.normal_B) : Eigen::Vector3d::Zero();
    tip = is_tip(w, d.arc_length);
    u0 = tip ? tip_unknowns(w, sc, F_B) : side_unknowns(w, sc, F_B, d.arc_length);
    int k;
    double h;
    w.locate(d.arc_length, k, h);
    sigma = core_side(g, w.rest_point_B(d.arc_length),
                      w.rest_link_frames_B()[static_cast<std::size_t>(std::clamp(k, 0, w.links() - 1))].col(0));
  };
  LoadState start;  // warm: the load the first attempt starts at (its walk made once, for it and the checks)
  if (warm) {
    tip = is_tip(w, warm->arc_length);
    u0 = tip ? Eigen::Vector3d(warm->force_x, warm->force_y, warm->force_z) / sc.force
             : Eigen::Vector3d(warm->force_y / sc.force, warm->force_z / sc.force, warm->arc_length / sc.length);
    // The record the solve of the warm state left (its kinematics and their derivatives): no walk to start.
    const std::optional<Eigen::Vector3d> carried = tip ? std::nullopt : adopt_side_sensitivity(w, sc, g, law, *warm);
    if (carried) u0 = *carried;
    start = tip || carried ? *warm : start_side_load(w, sc, g, law, u0);
    if (g.core_B) {  // the side of the line core the warm contact is on
      const ObjectContactPoint p = contact_point_at(w, g, start, tip, 1.0);
      sigma = core_side(g, p.c_B, p.t_B);
    }
  } else {
    // Pressed against the object: the rest whisker reaches into it. Seen along a line core (an infinite cylinder)
    // the whisker may also have swept past it entirely; as in edge mode, a line within reach is solved and the
    // contact's side decides (object_solution).
    if (g.core_B ? !core_within_reach(w, g) : deep().gap > 0.0) {
      out.attempt.status = Status::no_contact;
      return out;
    }
    cold_start();
    if (hint) {
      tip = is_tip(w, *hint);
      u0 = tip ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.0, 0.0, std::clamp(*hint, 1e-6 * sc.length, w.length()) / sc.length);
    }
  }
  WarmAttempt first;
  SolveOptions first_options = options;
  if (warm) {
    first = {true, lowest_piece(w, g, start)};
    // On an object with creases (a mesh, a box) a warm attempt that does not converge within a few Newton steps
    // has stalled at a crease's band: the sliding attempt below crosses it (docs/objects.md, "Speed").
    if (g.shape->needs_thickness()) first_options.max_iterations = std::min(options.max_iterations, warm_creased_iterations);
  }
  // A warm side contact on an object with creases (a mesh, a box) starts by sliding: from the previous frame's
  // contact the tangency's root is usually across a crease's band, where Newton's steps stall; the force with s
  // held, then s moved to the nearest point about it, land beside the root (docs/objects.md, "Speed").
  const bool slide_first = warm && !tip && g.shape->needs_thickness();
  out.attempt = slide_first ? attempt_by_sliding(w, sc, g, law, sigma, u0, options, first)
                            : attempt_object(w, sc, g, law, sigma, tip, u0, first_options, first);
  int iterations = out.attempt.lm.iterations;
  if (out.attempt.status == Status::not_converged && g.shape->needs_thickness()) {
    out.attempt = attempt_by_bracketing(w, sc, g, law, sigma, out.attempt, options);
    iterations += out.attempt.lm.iterations;
  }
  if (out.attempt.status == Status::not_converged && !tip) {
    out.attempt = attempt_by_sliding(w, sc, g, law, sigma, u0, options);
    iterations += out.attempt.lm.iterations;
  }
  if (out.attempt.status == Status::not_converged && (warm || hint)) {
    if (g.core_B || deep().gap <= 0.0) {
      cold_start();
      out.attempt = attempt_object(w, sc, g, law, sigma, tip, u0, options);
      iterations += out.attempt.lm.iterations;
    }
  }
  if (out.attempt.status == Status::not_converged && (g.core_B || deep().gap <= 0.0)) {
    // Continuation from touch: the object moved back along the normal at the rest whisker's deepest point until it
    // just touches it (zero force there), then returned to its place in adaptive steps.
    const Touch touch = first_touch(w, g, deep());
    const Eigen::Vector3d away = touch.offset_B;
    bool step_tip = is_tip(w, touch.arc_length);
    Eigen::Vector3d u = step_tip ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.0, 0.0, touch.arc_length / sc.length);
    double lambda = 0.0, step = 0.25;
    ObjectAttempt last = out.attempt;
    bool have_step = false;  // `last` is a converged step
    while (lambda < 1.0 && step > 1.0 / 1024.0) {
      const double next = std::min(1.0, lambda + step);
      ObjectGeometryB gi = g;
      gi.offset_B = (1.0 - next) * away;
      ObjectAttempt a = attempt_object(w, sc, gi, law, sigma, step_tip, u, options);
      iterations += a.lm.iterations;
      if (a.status == Status::not_converged && !step_tip && have_step && g.shape->needs_thickness()) {
        // Stalled in a crease's band: the contact may move to the next crease (the gap's minimum bracketed
        // along the whisker from the last step's contact).
        ObjectAttempt b = attempt_by_bracketing(w, sc, gi, law, sigma, last, options);
        iterations += b.lm.iterations;
        if (b.status == Status::converged) a = b;
      }
      if (a.status == Status::converged && valid_contact(w, gi, a, sigma)) {
        have_step = true;
        step_tip = a.tip;
        u = a.lm.u;
        lambda = next;
        last = a;
        step = std::min(2.0 * step, 0.5);
      } else {
        if (a.status == Status::slipped_off) last = a;
        step *= 0.5;
      }
    }
    if (lambda < 1.0) {
      last.status = Status::slipped_off;
      out.folded = true;
    }
    out.attempt = last;
  }
  out.attempt.lm.iterations = iterations;
  out.sigma = sigma;
  return out;
}

namespace {

/// The outputs of a two-contact equilibrium (Solution's SecondContact says which are whose).
void two_contact_solution(const Whisker& w, const Placement& X, const TwoContacts& two, Solution& out) {
  const TwoLoadKinematics k = deflect_two_loads(w, two.loads);
  const Eigen::Vector3d F_B = k.F_B[0] + k.F_B[1], M_B = k.p_B[0].cross(k.F_B[0]) + k.p_B[1].cross(k.F_B[1]);
  out.state = two.loads[0];
  out.arc_length = two.loads[0].arc_length;
  out.force_magnitude = F_B.norm();
  out.force_W = X.R_WB * F_B;
  out.moment_W = X.R_WB * M_B;
  out.whisker_frame = whisker_frame_signals(F_B, M_B);
  out.contact_point_W = X.to_world(two.point_B[0]);
  out.normal_force = k.F_B[0].dot(two.normal_B[0]);
  out.residual = two.residual;
  if (out.surface) {
    out.surface->normal_W = X.R_WB * two.normal_B[0];
    out.surface->friction_direction_W = X.R_WB * two.normal_B[0].cross(k.t_B[0]).normalized();
    out.surface->feature = two.feature[0];
    out.surface->tip = false;
    out.surface->friction_force = 0.0;
    out.surface->clearance = 0.0;
    out.surface->clearance_arc_length = two.loads[0].arc_length;
  }
  SecondContact second;
  second.arc_length = two.loads[1].arc_length;
  second.contact_point_W = X.to_world(two.point_B[1]);
  second.force_W = X.R_WB * k.F_B[1];
  second.normal_W = X.R_WB * two.normal_B[1];
  second.normal_force = k.F_B[1].dot(two.normal_B[1]);
  second.feature = two.feature[1];
  out.second_contact = second;
  out.second_contact_arc_length.reset();
  // The shape always (the state holds the first contact's load alone: deflected_shape() of it is not this one).
  out.shape_W.clear();
  for (const auto& p : two.nodes_B) out.shape_W.push_back(X.to_world(p));
  set_status(out, Status::converged, "two contacts on the whisker's side");
}

}  // namespace

Solution object_solution(const Whisker& w, const Placement& X, const ObjectContact& object, const ObjectGeometryB& g,
                         const ObjectOutcome& o, const SolveOptions& options,
                         const std::optional<Eigen::Vector3d>& approach_W, int two_contact_rounds) {
  const ObjectAttempt& a = o.attempt;
  if (a.status == Status::no_contact)
    return unloaded_solution(w, X, Status::no_contact, "the whisker does not reach into the object", options);
  if (a.status == Status::slipped_off) {
    Solution off = unloaded_solution(
        w, X, Status::slipped_off,
        o.folded ? "the contact equilibrium ends in a fold: the whisker snaps past the object (push-past)"
                 : "no equilibrium with the tip on the object: the whisker slips off",
        options);
    off.fold = o.folded;
    off.iterations = a.lm.iterations;
    off.arc_length = std::min(a.state.arc_length, w.length());
    return off;
  }
  Solution out;
  const ContactKinematics<double> solved = kinematics_at(w, g, a.state);
  fill_solution(w, X, a.state, options, std::nullopt, out, nullptr, &solved);
  out.iterations = a.lm.iterations;
  out.residual = a.lm.residual * w.length();
  if (a.status != Status::converged) {
    set_status(out, a.status, "no equilibrium on the object within the iteration limit");
    return out;
  }
  const ObjectContactPoint p = contact_point_at(w, g, a.state, a.tip, o.sigma);
  const Eigen::Vector3d n_W = X.R_WB * p.normal_B;
  SurfaceContact sc;
  sc.normal_W = n_W;
  sc.friction_direction_W = X.R_WB * p.friction_B;
  sc.tip = a.tip;
  sc.feature = p.surface.feature;
  sc.friction_force = out.force_W.dot(sc.friction_direction_W);
  out.contact_point_W = X.to_world(p.point_B);
  out.normal_force = out.force_W.dot(n_W);
  set_status(out, Status::converged, a.tip ? "contact at the tip" : "contact on the whisker's side");
  // Pushed, never pulled: the force along the normal; on a line core also as edge mode judges it, no negative
  // work on the displacement from the rest shape (edge_mode.cpp).
  if (*out.normal_force < -1e-12 * out.force_magnitude ||
      (g.core_B && out.force_W.dot(X.R_WB * (p.c_B - w.rest_point_B(out.arc_length))) <
                       -1e-12 * out.force_magnitude * w.length())) {
    set_status(out, Status::no_contact, "the object would have to pull the whisker: not pressed against it");
  } else if (approach_W && out.force_W.dot(*approach_W) > 0.0) {
    set_status(out, Status::no_contact, "the whisker is on the far side of the object for the given approach direction");
  }
  if (out.status == Status::converged) {  // nowhere else inside the object
    std::vector<Eigen::Vector3d> nodes;
    deflected_nodes(w, g, X, a.state, nodes);
    const std::vector<double> none;
    const PlacedShape placed{object.shape, object.X_WO};
    const Clearance c = clearance(placed, nodes, w.node_arc_lengths(), g.thickness ? w.node_radii() : none,
                                  -second_contact_depth);
    sc.clearance = std::min(c.gap, 0.0);
    sc.clearance_arc_length = c.gap < 0.0 ? c.arc_length : a.state.arc_length;
    if (c.gap < -second_contact_depth && two_contact_rounds > 0) {
      const TwoContacts two = solve_two_contacts(w, Scales(w), g, a, c.arc_length, options);
      // The single contact of `attempt` (on `geometry`, side `sigma`) instead, when it converges.
      const auto single_contact = [&](const ObjectAttempt& attempt, const ObjectGeometryB& geometry,
                                      double side) -> std::optional<Solution> {
        ObjectOutcome single = o;
        single.attempt = attempt;
        single.attempt.lm.iterations += a.lm.iterations + two.iterations;
        single.sigma = side;
        Solution s = object_solution(w, X, object, geometry, single, options, approach_W, two_contact_rounds - 1);
        if (s.status == Status::converged) return s;
        return std::nullopt;
      };
      if (two.solved && two.single >= 0) {  // one of the two pulls: the single contact at the other place
        if (auto s = single_contact(two.single_attempt, g, 1.0)) return *s;
      } else if (two.solved) {
        out.surface = sc;
        two_contact_solution(w, X, two, out);
        out.iterations = a.lm.iterations + two.iterations;
        return out;
      } else if (!a.tip && !g.core_B) {
        // Neither: the contact may have jumped to the second place alone (on a mesh, to the next crease).
        const Scales scales(w);
        ObjectAttempt from = a;
        from.state.arc_length = c.arc_length;
        from.lm.u[2] = c.arc_length / scales.length;
        double sigma = 1.0;
        // On a creased shape: holding the feature the whisker enters there (an edge: the crease), else directly.
        ObjectAttempt b = from;
        b.status = Status::not_converged;
        if (g.shape->needs_thickness())
          b = attempt_on_features(w, scales, g, FrictionLaw{}, sigma, from, options,
                                  g.query(X.R_WB.transpose() * (c.point_W - X.p_W_base)));
        if (b.status != Status::converged || std::abs(b.state.arc_length - a.state.arc_length) < 1e-9 * scales.length)
          b = attempt_object(w, scales, g, FrictionLaw{}, sigma, false, from.lm.u, options);
        if (b.status == Status::not_converged && g.shape->needs_thickness())
          b = attempt_by_bracketing(w, scales, g, FrictionLaw{}, sigma, from, options);
        if (b.status == Status::converged && valid_contact(w, g, b, sigma))
          if (auto s = single_contact(b, g, sigma)) return *s;
        if (g.shape->needs_thickness()) {
          // The whisker enters beside its contact across a crease (on the same link: its chord passes over the
          // crease, which the load point's own feature does not see): the contact held on that crease, an edge
          // as a peg of radius 0 (its normal there is the mesh's at the edge), checked against the mesh itself.
          const ObjectContactPoint at = contact_point_at(w, g, a.state, false, o.sigma);
          const Eigen::Vector3d p_B = X.R_WB.transpose() * (c.point_W - X.p_W_base);
          SurfacePoint crease = g.query(p_B);
          for (int j = 1; j < crease_samples && crease.feature == SurfaceFeature::face; ++j) {
            const SurfacePoint q = g.query(at.c_B + (j / double(crease_samples)) * (p_B - at.c_B));
            if (q.feature == SurfaceFeature::edge) crease = q;
          }
          if (crease.feature == SurfaceFeature::edge) {
            ObjectGeometryB held = g;
            held.last_deflected.reset();
            held.held_feature = crease.feature_id;
            held.core_B = LineCore{crease.closest - g.offset_B, crease.edge_direction, 0.0};
            double held_sigma = core_side(held, at.c_B, at.t_B);
            for (const Eigen::Vector3d& u : {a.lm.u, from.lm.u}) {
              ObjectAttempt h = attempt_object(w, scales, held, FrictionLaw{}, held_sigma, false, u, options);
              if (h.status != Status::converged || !valid_contact(w, held, h, held_sigma)) continue;
              if (auto s = single_contact(h, held, held_sigma)) return *s;
            }
          }
        }
      }
    }
    if (c.gap < -second_contact_depth) {
      set_status(out, Status::second_contact,
                 "another part of the whisker would be inside the object: a second contact (not solved)");
      out.second_contact_arc_length = c.arc_length;
    }
  }
  out.surface = sc;
  return out;
}

}  // namespace detail

Solution solve_object(const Whisker& w, const Placement& X, const ObjectContact& object, std::optional<double> hint,
                      const SolveOptions& options, const LoadState* warm,
                      const std::optional<Eigen::Vector3d>& approach_W) {
  validate(options);
  validate(object);
  if (hint) require_finite(*hint, "load.arc_length_hint");
  if (approach_W) require_finite(*approach_W, "load.approach");
  const detail::Scales sc(w);
  // A mesh answers this solve's queries from its triangles about the contact (Shape::local_view: about each place
  // asked within a quarter of a link of its surface): the same answers as its tree's.
  const std::unique_ptr<const Shape> view = object.shape->local_view(0.25 * w.length() / w.links());
  ObjectContact local = object;
  if (view) local.shape = view.get();
  const detail::ObjectGeometryB g = detail::object_in_body(X, local);
  const detail::ObjectOutcome o = detail::solve_object_contact(w, sc, g, detail::FrictionLaw{}, hint, options, warm);
  Solution out = detail::object_solution(w, X, local, g, o, options, approach_W, detail::default_two_contact_rounds);
  if (out.status != Status::converged && out.status != Status::second_contact) out.surface.reset();
  // The record for the next frame's warm start: a single side contact whose state is the attempt's.
  const LoadState& s = out.state;
  const LoadState& a = o.attempt.state;
  if (out.status == Status::converged && !o.attempt.tip && !out.second_contact && s.force_x == a.force_x &&
      s.force_y == a.force_y && s.force_z == a.force_z && s.couple_x == a.couple_x && s.couple_y == a.couple_y &&
      s.couple_z == a.couple_z && s.arc_length == a.arc_length)
    out.state.sensitivity = detail::side_sensitivity(w, g, o.attempt.lm.u, a);
  return detail::checked_solution(std::move(out), options.tolerance, w, X, options);
}

}  // namespace vibrissa
