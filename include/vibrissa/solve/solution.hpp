#pragma once
// Everything a solve reports (spec §2.4). World-frame quantities unless the name says otherwise; the
// whisker-centred frame B is the rest frame of spec §2.1 at the whisker's current pose.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/objects/shape.hpp"
#include "vibrissa/solve/status.hpp"

namespace vibrissa {

/// What a contact solve learned about the chain at its solution, kept with its LoadState for the next frame:
/// the contact kinematics there and their derivatives with respect to the solve's unknowns (its last Jacobian,
/// moved to the solution by one secant update). The kinematics are in the whisker frame, so they hold whatever
/// the pose: a warm start from the state has its starting residual without walking the chain and takes its
/// first Newton step from these derivatives; every later Jacobian is evaluated, and a first step that does not
/// shrink the residual tenfold is taken again from an evaluated one. It changes what a warm solve costs (one
/// forward evaluation and one Jacobian instead of one and two on a 1 kHz frame), not its root: results agree
/// with a warm start from the same four numbers typed in to within the tolerance (5e-13 relative on a tracked
/// whisk, tests/solve/test_warm_start_record.cpp).
/// Internal to the solvers: used only on a whisker with the same mechanics_fingerprint() and only while the
/// state's load is exactly the one it was made at; never written to files (a state read back starts without it).
/// The frictionless object mode leaves the same record of a side contact, with the load frame's x and y axes its
/// walk carries (`followers`, `object` set; docs/objects.md, "Speed"); only an object solve adopts those.
struct LoadSensitivity {
  std::uint64_t whisker = 0;           ///< Whisker::mechanics_fingerprint() it was made on (0: none)
  std::array<double, 3> unknowns{};    ///< the solve's scaled unknowns (F_y, F_z, s) it holds at (internal)
  std::array<double, 36> kinematics{};  ///< p_contact_B, force_B, couple_B: each value, then 3 derivatives (internal)
  bool object = false;                 ///< made by the object mode: `followers` hold (internal)
  std::array<double, 24> followers{};  ///< the load frame's x and y axes in B, as `kinematics` (internal)
};

/// Unknowns of a contact solve: force components in the frame of the loaded link (x along the link) and
/// the arc length of contact. Pass a previous solution's state to warm-start the next frame.
struct LoadState {
  double force_x = 0.0;  ///< axial component [N] (zero for the model's normal load; object contacts: see docs/objects.md)
  double force_y = 0.0;  ///< [N]
  double force_z = 0.0;  ///< [N]
  double arc_length = 0.0;  ///< [m]
  /// Couple in the same frame [N·m]: zero except where friction acts on the whisker's surface, off its centre
  /// line (frictional object contacts with the whisker's thickness: a twist about the whisker).
  double couple_x = 0.0, couple_y = 0.0, couple_z = 0.0;
  LoadSensitivity sensitivity;  ///< set by the solve that produced this state (speeds up the next warm start)
};

/// Base signals in the whisker-centred frame (spec §2.4, Fig. 3b).
struct WhiskerFrameSignals {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< (Fx, Fy, Fz) [N]
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  ///< (Mx, My, Mz) [N·m]
  double FT = 0.0;  ///< transverse force sqrt(Fy^2 + Fz^2) [N]
  double MB = 0.0;  ///< bending moment sqrt(My^2 + Mz^2) [N·m]
  double FD = 0.0;  ///< direction atan2(Fz, Fy) [rad]
  double MD = 0.0;  ///< direction atan2(Mz, My) [rad]
};

/// Whether the whisker touches its object after a solve or a tracked frame (the same codes in every file).
enum class ContactState : std::int8_t {
  free = 0,         ///< not touching: out of reach, released (the object would have to pull), or never touched
  contact = 1,      ///< touching, in equilibrium
  pushed_past = 2,  ///< slipped off the tip, snapped past a fold of the equilibrium branch, or off a finite edge's
                    ///< end: the rest whisker lies beyond the object until it retracts (spec §3.4, Fig. 4a)
};
std::string_view to_string(ContactState state);

/// Coulomb friction state of a contact (frictional edge mode); `none` for every other mode and without contact.
enum class FrictionState : std::int8_t {
  none = 0,
  stick = 1,  ///< the contact held its previous point: |F_edge| <= mu F_N
  slip = 2,   ///< the contact moved along the edge with |F_edge| = mu F_N, opposing the slip
};
std::string_view to_string(FrictionState state);

/// Where an object touches the whisker (object modes, docs/objects.md), world frame.
struct SurfaceContact {
  Eigen::Vector3d normal_W = Eigen::Vector3d::Zero();  ///< the object's outward unit normal at the contact
  /// Unit direction of friction: in the tangent plane, across the whisker (n x t normalised)
  Eigen::Vector3d friction_direction_W = Eigen::Vector3d::Zero();
  bool tip = false;  ///< the contact is at the whisker's tip (s = L), not on its side
  SurfaceFeature feature = SurfaceFeature::face;  ///< which part of the object
  double friction_force = 0.0;  ///< F . friction_direction [N] (0 without friction)
  /// Smallest gap between the whisker's surface (its centre line when thickness is off) and the object over the
  /// whole deflected whisker, and where [m]: ~0 at the contact; below -tolerance the status is second_contact.
  double clearance = 0.0;
  double clearance_arc_length = 0.0;
};

/// The second of two contacts solved together (object modes, frictionless: docs/objects.md, "Two contacts").
/// The Solution's contact fields (arc_length, contact_point_W, normal_force, surface, state) are the first
/// contact's; force_W, moment_W, force_magnitude and whisker_frame are the totals at the base; the first contact's
/// own force is force_W - second_contact->force_W. shape_W is always filled (deflected_shape() of `state`, the
/// first contact's load alone, is not the two contacts' shape).
struct SecondContact {
  double arc_length = 0.0;                                    ///< [m]
  Eigen::Vector3d contact_point_W = Eigen::Vector3d::Zero();  ///< on the object [m]
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();          ///< this contact's force on the whisker [N]
  Eigen::Vector3d normal_W = Eigen::Vector3d::Zero();         ///< the object's outward unit normal there
  double normal_force = 0.0;                                  ///< force_W . normal_W [N]
  SurfaceFeature feature = SurfaceFeature::face;
};

/// One root of a contact solve (an equilibrium through the same target).
struct Root {
  double arc_length = 0.0;       ///< s [m]
  double force_magnitude = 0.0;  ///< |F| [N]
  double residual = 0.0;         ///< [m]
};

struct Solution {
  Status status = Status::not_converged;
  ContactState contact_state = ContactState::free;
  FrictionState friction = FrictionState::none;
  /// slipped_off because the contact equilibrium branch ends in a fold (push-past by snap-through), not at the tip.
  bool fold = false;
  std::string_view message;  ///< human-readable detail (static text); decide from the typed fields, never from this
  double force_magnitude = 0.0;  ///< |F| [N]
  double arc_length = 0.0;       ///< s_applied [m]
  double angle = 0.0;            ///< force-mode angle of F (docs/conventions.md, "Loads and signs") [rad]
  Eigen::Vector3d contact_point_W = Eigen::Vector3d::Zero();  ///< [m]
  /// Force the whisker transmits to the follicle: the contact force, world [N] (as the published model).
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();
  /// Moment of the contact force about the base, world [N·m].
  Eigen::Vector3d moment_W = Eigen::Vector3d::Zero();
  WhiskerFrameSignals whisker_frame;
  std::optional<double> normal_force;  ///< component of F normal to the edge [N] (edge modes); F . n (object modes)
  std::optional<double> edge_force;    ///< component of F along the edge direction [N] (edge modes)
  double residual = 0.0;               ///< final residual [m]
  int iterations = 0;
  std::vector<Eigen::Vector3d> shape_W;  ///< deflected nodes, base to tip [m]
  std::optional<double> other_root_arc_length;  ///< another root exists at this arc length [m]
  /// Every distinct root the solve found, by arc length (point mode with a hint or find_other_roots).
  std::vector<Root> roots;
  LoadState state;                     ///< the solved unknowns, for warm starts
  std::optional<SurfaceContact> surface;  ///< object modes: normal, friction direction, tip, clearance
  std::optional<double> second_contact_arc_length;  ///< status second_contact: where the whisker enters the object [m]
  /// Object modes: a second contact solved with the first (status converged; the totals as SecondContact says).
  std::optional<SecondContact> second_contact;
};

}  // namespace vibrissa
