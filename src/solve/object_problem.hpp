#pragma once
// The object equations (docs/objects.md, "Equations"). The whisker's surface is the envelope of spheres of
// radius r(s) about its centre line c(s) (its thickness; zero with thickness off), so its gap to the object at s
// is g(s) = d(c(s)) - r(s), d the object's signed distance. A side contact at s: g(s) = 0, tangency
// g'(s) = n . t - r'(s) = 0 (t the load frame's x axis: the whisker's tangent at s), and the force along the
// normal n; the force has the small axial part F_x = r' F_T / sqrt(1 - r'^2) that tilts it off the normal plane
// of a tapered whisker. A tip contact (s = L, the tip's hemispherical cap): g(L) = 0 and the force (three
// components) along n. Objects with a line core (an infinite cylinder) write the side contact in the line's
// terms: (c - its projection on the axis) = (R + r) u, u normal to the axis with u . t = r', and F . a = 0: at
// zero radius and thickness off exactly edge mode's equations.
#include <array>
#include <optional>
#include <vector>

#include "contact_problem.hpp"
#include "vibrissa/objects/shape.hpp"
#include "vibrissa/solve/object_contact.hpp"

namespace vibrissa::detail {

/// The object in the whisker frame B for one solve (and an offset that moves it: continuation from touch).
struct ObjectGeometryB {
  const Shape* shape = nullptr;
  Eigen::Matrix3d R_BO = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_BO = Eigen::Vector3d::Zero();
  Eigen::Vector3d offset_B = Eigen::Vector3d::Zero();
  std::optional<LineCore> core_B;  ///< the shape's line core in B
  bool thickness = true;
  /// A feature of a creased shape the queries hold to (Shape::nearest_on_feature; -1: the nearest feature):
  /// attempt_on_features.
  std::int64_t held_feature = -1;
  /// The whisker's kinematics (with the load frame's axes) at the last load contact_point_at or lowest_piece
  /// deflected it with: the same load is asked for several times in a solve (checks, the piece, the outputs).
  /// It depends on the whisker and the load alone; a geometry belongs to one solve (one thread, one whisker).
  /// The residuals' own evaluations go through the same record (walk_deflected), so that the checks and outputs
  /// at a solved load walk no more.
  struct Deflected {
    std::array<double, 7> load{};  ///< force, couple, s
    ContactKinematics<double> k;
    FollowerVectors<double> follow;
    std::vector<Eigen::Vector3d> omega;  ///< the joint rotations (second-order scheme; empty: not recorded)
  };
  mutable std::optional<Deflected> last_deflected;
  /// The last walk with derivatives, keyed by its inputs (values and derivatives): a warm start makes its first
  /// one early (start_side_load) and the attempt's first evaluation takes it from here.
  struct DeflectedJacobian {
    std::array<Dual<3>, 7> input;  ///< force, couple, s
    ContactKinematics<Dual<3>> k;
    FollowerVectors<Dual<3>> follow;
    /// The side unknowns whose derivatives these are (set by a side residual's evaluation; none: another's).
    std::optional<Eigen::Vector3d> side_u;
    bool estimated = false;  ///< derivatives adopted from a warm state's record (adopt_side_sensitivity)
  };
  mutable std::optional<DeflectedJacobian> last_jacobian;
  /// The shape's query at c_B (B frame).
  [[nodiscard]] SurfacePoint query(const Eigen::Vector3d& c_B) const;
};
ObjectGeometryB object_in_body(const Placement& X_WB, const ObjectContact& object);

/// How the force's friction part is fixed (frictional object mode).
struct FrictionLaw {
  enum class Kind { frictionless, stick, slip };
  Kind kind = Kind::frictionless;
  Eigen::Vector3d previous_B = Eigen::Vector3d::Zero();  ///< stick: where the contact was on the object (B)
  double sigma_mu = 0.0;  ///< slip on the side: F . b = -sigma_mu F . n (sigma: the slip's sign along b)
  Eigen::Vector3d slip_B = Eigen::Vector3d::Zero();  ///< slip at the tip: the unit slip direction (B)
  /// Frictional laws: the contact normal in the load frame (from the last evaluation, iterated to a fixed
  /// point): it fixes the force's axial part and the couple of friction acting on the whisker's surface.
  Eigen::Vector3d normal_L = Eigen::Vector3d::UnitY();
};

/// The piece of the loaded link whose gap the distance equation holds (object_problem.cpp, piece_gap): the load
/// point itself, the link's start or end node, or the chord's nearest point.
enum class ClearancePiece { centre, start_node, end_node, chord };

struct ObjectAttempt {
  LMResult lm;
  Status status = Status::not_converged;
  bool tip = false;
  ClearancePiece piece = ClearancePiece::centre;  ///< where the distance equation held
  LoadState state;  ///< the load at lm.u (force, couple, s)
};

/// Everything a converged contact is checked and reported with (doubles, at a load).
struct ObjectContactPoint {
  Eigen::Vector3d c_B, F_B, t_B, y_B;  ///< centre-line point, force, load frame x (tangent) and y
  SurfacePoint surface;               ///< the query at c_B (B)
  double radius = 0.0, slope = 0.0;   ///< r(s), r'(s) (0 with thickness off)
  Eigen::Vector3d normal_B;           ///< the contact normal (line core: u; else surface.normal)
  Eigen::Vector3d point_B;            ///< the contact point on the object
  Eigen::Vector3d friction_B;         ///< b = n x t normalised (side); tip: the tangential part of F, normalised
  [[nodiscard]] Eigen::Vector3d normal_in_load_frame() const;
};

/// The side contact's equations from scaled unknowns u0 = (F_y, F_z, s) / scales; `sigma` the side of a line
/// core (+-1). With `pinned`, s is held there and the tangency is not asked (the gap and the force's direction
/// only: attempt_by_sliding).
ObjectAttempt attempt_side(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                           double sigma, const Eigen::Vector3d& u0, const SolveOptions& options,
                           ClearancePiece piece = ClearancePiece::centre,
                           std::optional<double> pinned = std::nullopt);
/// The load at which attempt_side() from u0 evaluates first, with that evaluation made now and recorded in g (its
/// walk with derivatives, and its values for the checks at that load: lowest_piece, contact_point_at).
LoadState start_side_load(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                          const Eigen::Vector3d& u0);
/// A warm side start from the record a frictionless object solve left with its state (LoadSensitivity): where it
/// was made on this whisker and its unknowns give exactly the state's load, g's records take the kinematics there
/// and their derivatives (an estimate: the first Newton step from it is checked, newton_line_search()), and the
/// unknowns are returned; else none (the record is ignored).
std::optional<Eigen::Vector3d> adopt_side_sensitivity(const Whisker& w, const Scales& sc, const ObjectGeometryB& g,
                                                      const FrictionLaw& law, const LoadState& warm);
/// The record a frictionless side contact solved at unknowns u (load `state`) leaves with its state: the kinematics
/// there with the last walk with derivatives carried to u by one secant update (as ContactEvaluations). Empty
/// (whisker 0) where g's records do not hold that load or a side walk with derivatives.
LoadSensitivity side_sensitivity(const Whisker& w, const ObjectGeometryB& g, const Eigen::Vector3d& u,
                                 const LoadState& state);
/// The tip contact's equations from scaled unknowns u0 = (F_x, F_y, F_z) / force scale.
ObjectAttempt attempt_tip(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                          const Eigen::Vector3d& u0, const SolveOptions& options,
                          ClearancePiece piece = ClearancePiece::centre);
/// The loaded link's piece with the lowest gap at a load (centre where pieces do not apply).
ClearancePiece lowest_piece(const Whisker& w, const ObjectGeometryB& g, const LoadState& state);

/// The whisker's deflection by a load in the load frame with the load frame's x and y axes (`follow` given as
/// (1, 0, 0), (0, 1, 0)): deflect_for_solve() through the geometry's record of the last one (its values; a
/// Dual<3> evaluation is recorded without the joint rotations).
template <class S>
ContactKinematics<S> walk_deflected(const Whisker& w, const ObjectGeometryB& g, const V3<S>& F_L, const V3<S>& C_L,
                                    const S& s, FollowerVectors<S>& follow);
/// The deflected whisker's nodes at a solved load, in the frame of X (B: Placement{}), from the record where it
/// holds that load's joint rotations (deflected_shape() otherwise).
void deflected_nodes(const Whisker& w, const ObjectGeometryB& g, const Placement& X, const LoadState& state,
                     std::vector<Eigen::Vector3d>& nodes);
/// The kinematics at a solved load (through the record).
ContactKinematics<double> kinematics_at(const Whisker& w, const ObjectGeometryB& g, const LoadState& state);

/// The contact at a solved load (tip: state.arc_length == L).
ObjectContactPoint contact_point_at(const Whisker& w, const ObjectGeometryB& g, const LoadState& state, bool tip,
                                    double sigma);

/// Side of a line core at a configuration: the sign of (c - axis) . (a x t).
double core_side(const ObjectGeometryB& g, const Eigen::Vector3d& c_B, const Eigen::Vector3d& t_B);

/// r(s) and r'(s) (`slope`) of the whisker's linear taper between nodes.
double whisker_radius_at(const Whisker& w, double s, double& slope);
/// The gap of a piece of the loaded link at arc length s whose load point is c_B with the load frame's x and y
/// axes t_B, y_B (doubles; the solves' piece_gap).
double piece_gap_at(ClearancePiece piece, const Whisker& w, const ObjectGeometryB& g, double s,
                    const Eigen::Vector3d& c_B, const Eigen::Vector3d& t_B, const Eigen::Vector3d& y_B);
/// Whether pieces other than the load point apply (second-order scheme; not a line without radius).
bool contact_pieces_apply(const Whisker& w, const ObjectGeometryB& g);
/// The frictionless side load (its axial part from the taper) of normal components F_y, F_z at s.
LoadState side_load_state(const Whisker& w, const ObjectGeometryB& g, double force_y, double force_z, double s);

/// The rest whisker's deepest point into the object: arc length, gap (< 0 inside), the object's normal there.
struct DeepestPoint {
  double arc_length = 0.0;
  double gap = 0.0;  ///< [m]
  Eigen::Vector3d normal_B = Eigen::Vector3d::UnitY();
};
DeepestPoint deepest_rest_point(const Whisker& w, const ObjectGeometryB& g);

}  // namespace vibrissa::detail
