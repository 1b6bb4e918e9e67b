#pragma once
// Object modes (docs/objects.md): the whisker touching the surface of an object (objects/shape.hpp) — a peg with
// a radius, a wall, a sphere, a box, a mesh — without friction or with Coulomb friction and contact history, on
// its side or at its tip. The solver asks the object where its surface is (signed distance, nearest point,
// normal and its derivative), never what kind of object it is.
#include <optional>

#include <Eigen/Core>

#include "vibrissa/core/whisker.hpp"
#include "vibrissa/objects/shape.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa {

/// An object where it is, and how the whisker meets it.
struct ObjectContact {
  const Shape* shape = nullptr;  ///< must outlive the solve
  ObjectPose X_WO;               ///< the shape's frame in the world
  /// true (default): the whisker's surface touches the object (the centre line stays r(s) away, the whisker's
  /// radius); false: its centre line does, as in the edge modes (not for shapes with edges: box, mesh).
  bool thickness = true;
};

/// Throws std::invalid_argument naming the field for a missing shape or thickness off on a shape that needs it.
void validate(const ObjectContact& object);

/// Object mode (frictionless): the whisker touches the object where its surface is tangent to the object's, with
/// the force along the object's normal; on its side (unknowns: the force normal to the whisker and s; the small
/// axial force of a tapered whisker follows) or at its tip (s = L; the force's three components). Root choice as
/// edge mode: warm start -> continuous with `warm`; else `arc_length_hint`; else the rest whisker's deepest point
/// in the object. `approach_W`: the direction in which the whisker moved into the object (the object must push
/// against it). Statuses: converged, no_contact (the rest whisker does not reach into the object, or the object
/// would have to pull), slipped_off (no equilibrium with the tip on the object: it slides off), not_converged,
/// second_contact (another part of the deflected whisker would be inside the object: second_contact_arc_length).
Solution solve_object(const Whisker& whisker, const Placement& X_WB, const ObjectContact& object,
                      std::optional<double> arc_length_hint = std::nullopt, const SolveOptions& options = {},
                      const LoadState* warm = nullptr, const std::optional<Eigen::Vector3d>& approach_W = std::nullopt);

/// Frictional object mode (Coulomb, quasi-static, with contact history; docs/objects.md, "Friction"): the whisker
/// slides freely along its own length; across it (direction b = n x t in the tangent plane) the contact sticks
/// where it was (`previous_contact_W`, a point on the object) while |F . b| <= mu F . n, and otherwise slips
/// toward the frictionless contact with |F . b| = mu F . n opposing the slip. mu = 0 is solve_object; mu -> inf
/// keeps the contact where it was. The outcome is in Solution::friction.
Solution solve_frictional_object(const Whisker& whisker, const Placement& X_WB, const ObjectContact& object, double mu,
                                 const Eigen::Vector3d& previous_contact_W, const SolveOptions& options = {},
                                 const LoadState* warm = nullptr,
                                 const std::optional<Eigen::Vector3d>& approach_W = std::nullopt);

inline Solution solve_object(const Whisker& w, const ObjectContact& object,
                             std::optional<double> arc_length_hint = std::nullopt, const SolveOptions& options = {}) {
  return solve_object(w, w.placement(), object, arc_length_hint, options);
}

}  // namespace vibrissa
