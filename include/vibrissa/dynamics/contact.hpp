#pragma once
// Contact during motion (docs/dynamics.md, "Contact during motion"): objects whose surface is the set of points at
// a radius from a line (a peg, a cylinder's side, an edge), met by the whisker as a unilateral contact with
// Coulomb friction. The normal force is a stiff penalty, F_n = max(0, k_n (-g) - c_n g'), g the gap (< 0:
// penetration), so the penetration is F_n / k_n (the stated tolerance); c_n damps the contact critically for the
// whisker's effective mass there (damping_ratio). Friction has the quasi-static frictional edge mode's law (spec
// §3.1, solve_frictional_edge): the whisker slides freely along its own length, so the friction force lies across
// the whisker; an elastic-plastic stick spring of stiffness k_t holds the contact's place along the line at an
// anchor while |F . e| <= mu |F - (F . e) e| (e the line's direction); beyond it the anchor slides (slip) with
// the bound met, opposing the slip (docs/dynamics.md, "Contact during motion"). Events: touch, slip (onset), stick, release.
// Surfaces (planes, spheres, finite cylinders, boxes, meshes: objects/shape.hpp) are met through the shape's own
// query: per link of the deflected centre line the nearest approach to the surface (objects/clearance.hpp's
// link_minimum), the same penalty and damping along the surface's normal, and friction with the frictional object
// mode's law (docs/objects.md, "Friction"): across the whisker in the tangent plane (b = n x t), in the whole
// tangent plane at the tip; up to two separate contact points per surface.
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/solve/object_contact.hpp"
#include "vibrissa/solve/options.hpp"

namespace vibrissa::dynamics {

/// A line object: the surface at `radius` from the line through point_W along direction_W (world frame, fixed).
struct LineObstacle {
  Eigen::Vector3d point_W = Eigen::Vector3d::Zero();        ///< [m]
  Eigen::Vector3d direction_W = Eigen::Vector3d::UnitZ();   ///< unit
  double radius = 0.0;                                      ///< [m]; 0: an edge
  /// true: the whisker's surface touches (its centre line stays r(s) + radius away); false: its centre line.
  bool thickness = false;
  double friction_coefficient = 0.0;                        ///< Coulomb mu, >= 0
};

/// Throws std::invalid_argument naming the field for a non-finite point, a zero direction, a negative radius
/// or friction coefficient.
void validate(const LineObstacle& obstacle);

/// A surface: a placed shape fixed in the world (objects/shape.hpp), met by the whisker's surface (thickness: the
/// centre line stays r(s) from it, as the static object modes) or by its centre line.
struct SurfaceObstacle {
  std::shared_ptr<const Shape> shape;
  ObjectPose X_WO;
  bool thickness = true;
  double friction_coefficient = 0.0;  ///< Coulomb mu, >= 0
};
/// Throws std::invalid_argument naming the field for a missing shape, thickness off on a shape with edges (box,
/// mesh), a negative or non-finite friction coefficient.
void validate(const SurfaceObstacle& obstacle);

/// An object in motion: a line (the fast path: pegs, edges) or a surface.
using Obstacle = std::variant<LineObstacle, SurfaceObstacle>;
void validate(const Obstacle& obstacle);
double friction_coefficient(const Obstacle& obstacle);

/// A placed shape in motion with friction `mu`: a line object if it has a line core (an infinite cylinder: a peg),
/// else a surface.
Obstacle obstacle(std::shared_ptr<const Shape> shape, const ObjectPose& X_WO, bool thickness, double mu);

/// An edge (solve_edge's, centre line touches it) with friction `mu`.
LineObstacle line_obstacle(const Edge& edge, double mu);
/// A placed shape with a line core (a peg: objects::Cylinder) with friction `mu`; throws std::invalid_argument
/// naming the shape's type for shapes without one (those are surfaces in motion: obstacle() above).
LineObstacle line_obstacle(const ObjectContact& object, double mu);

/// Penalty and damping of the contacts.
struct ContactLaw {
  /// Normal penalty stiffness k_n [N/m]: the penetration is F_n / k_n (1 nm per 10 uN with the default).
  double stiffness = 1e4;
  /// Stick spring k_t [N/m]; 0: the normal stiffness. A stuck contact creeps by at most mu F_n / k_t.
  double tangential_stiffness = 0.0;
  /// Normal damping as a fraction of the critical damping of the whisker's effective mass at the contact
  /// (1: an impact without rebound).
  double damping_ratio = 1.0;
};
void validate(const ContactLaw& law);

enum class ContactState : int { none = 0, stick = 1, slip = 2 };
std::string_view to_string(ContactState state);

enum class ContactEventType { touch, slip, stick, release };
std::string_view to_string(ContactEventType type);

/// A change of a contact's state, at the end of the integrator step where it happened (the step is short there:
/// the error control resolves the kink in the force); a touch or a release is placed inside its step by linear
/// interpolation of the gap.
struct ContactEvent {
  double time = 0.0;                                   ///< [s]
  ContactEventType type = ContactEventType::touch;
  int object = 0;                                      ///< index into SimulationOptions::objects
  double arc_length = 0.0;                             ///< of the contact on the whisker [m]
  Eigen::Vector3d point_W = Eigen::Vector3d::Zero();   ///< contact point on the whisker's centre line [m]
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();   ///< contact force on the whisker [N]
};

/// One object's contact per output frame.
struct ContactChannels {
  std::vector<ContactState> state;
  std::vector<double> arc_length;                      ///< [m] (of the nearest point when not touching)
  std::vector<double> gap;                             ///< [m], < 0: penetration
  std::vector<Eigen::Vector3d> point_W;                ///< nearest point of the whisker's centre line [m]
  std::vector<Eigen::Vector3d> force_W;                ///< on the whisker [N]
};

}  // namespace vibrissa::dynamics
