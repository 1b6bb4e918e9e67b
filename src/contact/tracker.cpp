#include "vibrissa/contact/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "vibrissa/contact/contact_geometry.hpp"
#include "vibrissa/contact/crossing.hpp"
#include "vibrissa/objects/clearance.hpp"
#include "vibrissa/solve/object_contact.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {

std::string_view to_string(ContactMode mode) {
  switch (mode) {
    case ContactMode::contact_point: return "contact_point";
    case ContactMode::edge: return "edge";
    case ContactMode::frictional_edge: return "frictional_edge";
  }
  return "edge";
}

ContactMode contact_mode_from_string(std::string_view name, const char* field) {
  for (ContactMode m : {ContactMode::contact_point, ContactMode::edge, ContactMode::frictional_edge})
    if (to_string(m) == name) return m;
  throw std::invalid_argument(std::string(field) + " must be 'contact_point', 'edge' or 'frictional_edge', got '" +
                              std::string(name.substr(0, 64)) + "'");
}

void validate(const TrackerOptions& o) {
  if (!(std::isfinite(o.mu) && o.mu >= 0.0))
    throw std::invalid_argument("mu must be finite and >= 0, got " + std::to_string(o.mu));
}

namespace {

/// Cheap rejection: an edge whose line is farther from the base than the whisker is long cannot be crossed.
bool may_reach(const Eigen::Vector3d& base_W, const EdgeSegment& e, double length) {
  const Eigen::Vector3d r = base_W - e.p0;
  return (r - r.dot(e.direction) * e.direction).norm() <= 1.05 * length;
}

}  // namespace

ContactTracker::ContactTracker(const Whisker& whisker, const TrackerOptions& options)
    : whisker_(whisker), options_(options) {
  validate(options_);
  options_.solve.find_other_roots = false;
  const std::size_t n = whisker_.rest_nodes_B().size();
  nodes_prev_W_.resize(n);
  nodes_now_W_.resize(n);
}

void ContactTracker::reset() {
  have_previous_ = false;
  edges_prev_.clear();
  clearance_prev_.clear();
  clearance_bound_.clear();
  clearance_nodes_O_.clear();
  forget_contact();
  frame_ = TrackedFrame{};
}

void ContactTracker::forget_contact() {
  edge_ = -1;
  in_tracked_contact_ = false;
  warm_.reset();
  hint_.reset();
  friction_start_W_.reset();
  approach_W_.reset();
  onset_coordinate_ = std::numeric_limits<double>::quiet_NaN();
}

void ContactTracker::begin_frame() {
  frame_.onset = false;
  frame_.solved = false;
  frame_.edge_coordinate = std::numeric_limits<double>::quiet_NaN();
}

void ContactTracker::place_rest_nodes(const Placement& X) {
  const auto& nodes_B = whisker_.rest_nodes_B();
  for (std::size_t i = 0; i < nodes_B.size(); ++i) nodes_now_W_[i] = X.to_world(nodes_B[i]);
}

void ContactTracker::record_converged(const EdgeSegment* e) {
  const Solution& s = frame_.solution;
  warm_ = s.state;
  hint_ = s.arc_length;
  friction_start_W_ = s.contact_point_W;
  if (e) {
    frame_.edge_coordinate = e->coordinate(s.contact_point_W);
    if (std::isnan(onset_coordinate_)) onset_coordinate_ = frame_.edge_coordinate;
  }
  frame_.onset_edge_coordinate = onset_coordinate_;
}

void ContactTracker::solve_edge_frame(const Placement& X, const EdgeSegment& e,
                                      const std::optional<Eigen::Vector3d>& approach_W, std::optional<double> hint) {
  const LoadState* warm = warm_ ? &*warm_ : nullptr;
  if (options_.mode == ContactMode::frictional_edge) {
    if (!friction_start_W_) friction_start_W_ = nearest_rest_point(whisker_, X, e.line()).on_edge_W;
    frame_.solution = solve_frictional_edge(whisker_, X, e.line(), options_.mu, *friction_start_W_, options_.solve,
                                            warm, approach_W);
  } else {
    frame_.solution = solve_edge(whisker_, X, e.line(), hint, options_.solve, warm, approach_W);
  }
  frame_.solved = true;
  ++solves_;
  if (frame_.solution.status == Status::not_converged) ++failed_solves_;
}

const TrackedFrame& ContactTracker::step(const Placement& X, std::span<const EdgeSegment> edges) {
  if (options_.mode == ContactMode::contact_point)
    throw std::invalid_argument("mode: contact_point needs tracked contact points (step_tracked), not a scene");
  if (have_previous_ && edges.size() != edges_prev_.size())
    throw std::invalid_argument("edges: the scene has " + std::to_string(edges.size()) + " edges now but had " +
                                std::to_string(edges_prev_.size()) + " in the previous frame");
  begin_frame();
  place_rest_nodes(X);
  const auto& arc = whisker_.node_arc_lengths();
  // Earliest crossing since the last frame; `only` restricts to one edge, `skip` excludes one.
  auto earliest = [&](int only, int skip, bool within_extent) {
    std::optional<std::pair<int, Crossing>> best;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const int ki = static_cast<int>(k);
      if ((only >= 0 && ki != only) || ki == skip) continue;
      if (!may_reach(nodes_prev_W_.front(), edges_prev_[k], whisker_.length()) &&
          !may_reach(nodes_now_W_.front(), edges[k], whisker_.length()))
        continue;
      if (auto c = find_crossing(nodes_prev_W_, nodes_now_W_, arc, edges_prev_[k], edges[k], within_extent);
          c && (!best || c->tau < best->second.tau))
        best = std::make_pair(ki, *c);
    }
    return best;
  };
  auto begin_contact = [&](int k, const Crossing& c) {
    forget_contact();
    edge_ = k;
    approach_E_ = c.approach_E;
    hint_ = c.arc_length;
    const EdgeSegment& e = edges[static_cast<std::size_t>(k)];
    friction_start_W_ = e.p0 + c.edge_coordinate * e.direction;
    frame_.state = ContactState::contact;
    frame_.onset = true;
  };

  if (have_previous_) {
    if (frame_.state == ContactState::free) {
      if (auto hit = earliest(-1, -1, true)) begin_contact(hit->first, hit->second);
    } else if (frame_.state == ContactState::pushed_past) {
      if (earliest(edge_, -1, false)) {  // retraction: back across the line it was pushed past (extent aside)
        frame_.state = ContactState::free;
        forget_contact();
      } else if (auto hit = earliest(-1, edge_, true)) {
        begin_contact(hit->first, hit->second);
      }
    }
  }
  frame_.approach_W.setZero();
  if (frame_.state == ContactState::contact) {
    const EdgeSegment& e = edges[static_cast<std::size_t>(edge_)];
    frame_.approach_W = edge_vector_to_world(e, approach_E_);
    solve_edge_frame(X, e, frame_.approach_W, hint_);
    Solution& s = frame_.solution;
    switch (s.status) {
      case Status::converged:
      case Status::second_contact:  // (object modes only)
        if (e.contains(e.coordinate(s.contact_point_W))) {
          record_converged(&e);
        } else {
          frame_.state = ContactState::pushed_past;  // slid off the end of a finite edge
        }
        break;
      case Status::no_contact:  // released: the edge would have to pull
        frame_.state = ContactState::free;
        break;
      case Status::slipped_off:      // past the tip, or snapped past a fold of the equilibrium branch
      case Status::not_converged:    // no equilibrium continues the contact: it slides along and snaps free
      case Status::underdetermined:  // (the inverse only)
        frame_.state = ContactState::pushed_past;
        break;
    }
    s.contact_state = frame_.state;
    if (frame_.state == ContactState::free) forget_contact();
  }
  frame_.edge = frame_.state == ContactState::free ? -1 : edge_;
  edges_prev_.assign(edges.begin(), edges.end());
  std::swap(nodes_prev_W_, nodes_now_W_);
  previous_X_ = X;
  have_previous_ = true;
  return frame_;
}

double ContactTracker::object_clearance(std::size_t k, const PlacedShape& object, double& arc_length) {
  if (clearance_bound_.size() != clearance_nodes_O_.size() || k >= clearance_bound_.size()) {
    clearance_bound_.resize(k + 1, -std::numeric_limits<double>::infinity());
    clearance_nodes_O_.resize(k + 1);
  }
  std::vector<Eigen::Vector3d>& before = clearance_nodes_O_[k];
  // The signed distance changes no faster than the point moves: the gap is at least the bound then less the
  // largest motion of a node since (a link's points move no more than its ends).
  if (clearance_bound_[k] > 0.0 && before.size() == nodes_now_W_.size()) {
    double moved = 0.0;
    for (std::size_t i = 0; i < before.size(); ++i)
      moved = std::max(moved, (object.X_WO.to_object(nodes_now_W_[i]) - before[i]).squaredNorm());
    const double lower = clearance_bound_[k] - std::sqrt(moved);
    if (lower > 0.0) {
      arc_length = 0.0;
      return lower;
    }
  }
  // Inside the object last frame: only whether it still is matters (no onset with it, release when clear).
  const bool sign_only = have_previous_ && k < clearance_prev_.size() && clearance_prev_[k] < 0.0;
  const std::vector<double> none;
  const Clearance c = clearance(object, nodes_now_W_, whisker_.node_arc_lengths(),
                                options_.thickness ? whisker_.node_radii() : none, 0.0, sign_only);
  arc_length = c.arc_length;
  clearance_bound_[k] = c.lower_bound;
  before.resize(nodes_now_W_.size());
  for (std::size_t i = 0; i < before.size(); ++i) before[i] = object.X_WO.to_object(nodes_now_W_[i]);
  return c.gap;
}

const TrackedFrame& ContactTracker::step(const Placement& X, std::span<const PlacedShape> objects) {
  if (options_.mode == ContactMode::contact_point)
    throw std::invalid_argument("mode: contact_point needs tracked contact points (step_tracked), not a scene");
  if (have_previous_ && objects.size() != clearance_prev_.size())
    throw std::invalid_argument("objects: the scene has " + std::to_string(objects.size()) + " objects now but had " +
                                std::to_string(clearance_prev_.size()) + " in the previous frame");
  begin_frame();
  place_rest_nodes(X);
  thread_local std::vector<double> now, where;
  now.assign(objects.size(), 0.0);
  where.assign(objects.size(), 0.0);
  for (std::size_t k = 0; k < objects.size(); ++k) now[k] = object_clearance(k, objects[k], where[k]);
  if (have_previous_) {
    if (frame_.state == ContactState::pushed_past && now[static_cast<std::size_t>(edge_)] >= 0.0) {
      frame_.state = ContactState::free;  // clear of the object it was pushed past
      forget_contact();
    }
    if (frame_.state != ContactState::contact) {
      // Onset: of the objects the whisker was clear of and is inside now, the one it is deepest in.
      int hit = -1;
      double deepest = 0.0;
      for (std::size_t k = 0; k < objects.size(); ++k) {
        const int ki = static_cast<int>(k);
        if (frame_.state == ContactState::pushed_past && ki == edge_) continue;
        if (!(now[k] < deepest && clearance_prev_[k] >= 0.0)) continue;
        deepest = now[k];
        hit = ki;
      }
      if (hit >= 0) {
        forget_contact();
        edge_ = hit;
        const auto uk = static_cast<std::size_t>(hit);
        hint_ = where[uk];
        const Eigen::Vector3d p_B = whisker_.rest_point_B(where[uk]);
        const Eigen::Vector3d v = X.to_world(p_B) - previous_X_.to_world(p_B);
        approach_W_ = v.norm() > 0.0 ? std::optional<Eigen::Vector3d>(v.normalized()) : std::nullopt;
        friction_start_W_ = objects[uk].nearest_W(X.to_world(p_B)).closest;
        frame_.state = ContactState::contact;
        frame_.onset = true;
      }
    }
  }
  frame_.approach_W.setZero();
  if (frame_.state == ContactState::contact) {
    const PlacedShape& o = objects[static_cast<std::size_t>(edge_)];
    const ObjectContact object{o.shape, o.X_WO, options_.thickness};
    frame_.approach_W = approach_W_.value_or(Eigen::Vector3d::Zero());
    const LoadState* warm = warm_ ? &*warm_ : nullptr;
    frame_.solution = options_.mode == ContactMode::frictional_edge
                          ? solve_frictional_object(whisker_, X, object, options_.mu, *friction_start_W_, options_.solve,
                                                    warm, approach_W_)
                          : solve_object(whisker_, X, object, hint_, options_.solve, warm, approach_W_);
    frame_.solved = true;
    ++solves_;
    Solution& s = frame_.solution;
    if (s.status == Status::not_converged) ++failed_solves_;
    switch (s.status) {
      case Status::converged:
      case Status::second_contact: record_converged(nullptr); break;
      case Status::no_contact: frame_.state = ContactState::free; break;
      case Status::slipped_off:
      case Status::not_converged:
      case Status::underdetermined: frame_.state = ContactState::pushed_past; break;
    }
    s.contact_state = frame_.state;
    if (frame_.state == ContactState::free) forget_contact();
  }
  frame_.edge = frame_.state == ContactState::free ? -1 : edge_;
  clearance_prev_.assign(now.begin(), now.end());
  std::swap(nodes_prev_W_, nodes_now_W_);
  previous_X_ = X;
  have_previous_ = true;
  return frame_;
}

const TrackedFrame& ContactTracker::step_tracked(const Placement& X, const EdgeSegment* edge, const TrackedInput& in) {
  const bool point_mode = options_.mode == ContactMode::contact_point;
  if (!point_mode && edge == nullptr)
    throw std::invalid_argument(std::string("edge: mode ") + std::string(to_string(options_.mode)) + " needs an edge");
  if (point_mode && in.in_contact && !in.p_W_contact)
    throw std::invalid_argument("p_W_contact: contact_point mode needs the tracked contact point of every contact frame");
  begin_frame();
  if (!in.in_contact) {
    forget_contact();
    frame_.state = ContactState::free;
    frame_.approach_W.setZero();
  } else {
    if (!in_tracked_contact_) {  // onset
      forget_contact();
      in_tracked_contact_ = true;
      frame_.onset = true;
      if (edge && have_previous_ && !in.approach_W) {
        const Edge line = edge->line();
        const Eigen::Vector3d a =
            approach_direction(whisker_, previous_X_, X, nearest_rest_point(whisker_, X, line).arc_length, line);
        if (a.norm() > 0.0) approach_W_ = a;
      }
      if (in.initial_contact_W) friction_start_W_ = in.initial_contact_W;
    }
    if (in.approach_W) approach_W_ = in.approach_W;  // the caller's direction, frame by frame
    frame_.approach_W = approach_W_.value_or(Eigen::Vector3d::Zero());
    const std::optional<double> hint = in.arc_length_hint ? in.arc_length_hint : hint_;
    if (point_mode) {
      const std::optional<Eigen::Vector3d> direction =
          edge ? std::optional<Eigen::Vector3d>(edge->direction) : std::nullopt;
      frame_.solution =
          solve_point(whisker_, X, *in.p_W_contact, hint, options_.solve, warm_ ? &*warm_ : nullptr, direction);
      frame_.solved = true;
      ++solves_;
      if (frame_.solution.status == Status::not_converged) ++failed_solves_;
    } else {
      solve_edge_frame(X, *edge, approach_W_, hint);
    }
    frame_.state = frame_.solution.contact_state;
    if (frame_.solution.status == Status::converged) {
      record_converged(edge);
    } else {  // keep the data's contact; restart cold (and friction afresh) at the next frame
      warm_.reset();
      hint_.reset();
      friction_start_W_.reset();
    }
  }
  frame_.edge = frame_.state == ContactState::free || edge == nullptr ? -1 : 0;
  previous_X_ = X;
  have_previous_ = true;
  return frame_;
}

}  // namespace vibrissa
