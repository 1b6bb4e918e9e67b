#pragma once
// Natural modes about a deflected equilibrium (issue 27 item 4; docs/dynamics.md, "Modes about a deflected
// equilibrium"). The chain's joints, springs and links are those of the linear model (linear_model.hpp); the
// whisker is held by one load at a material point: a force (dead: fixed direction; follower: turning with its
// link) or a contact. The equilibrium is found in the chain's joint rotations, then the motion about it is
//     M(q*) dq'' + C dq' + K_T dq = 0,   K_T = d/dq [spring moments - load moments] at q*,
// in spatial increments dtheta_j (B axes) of every joint about its deflected node — the linear model's
// coordinates, so that at zero load K_T = K and M(q*) = M exactly. K_T is exact (analytic derivative of the
// equilibrium equations below; tests compare it with finite differences): it holds the springs' tangent
// (the joint law of eqs. (1)-(3) inverted: omega_j = Kw_j (m + (Kw_j m) x m / 2), follicle spring in series)
// and the load's geometric stiffness. A contact adds a constraint on the contact's material point:
//   stick: the point is pinned (3 constraints; the contact force is the reaction, a dead load in K_T);
//   slip: only its motion along the contact normal is held (1 constraint; frictionless sliding in the tangent
//         plane; the sliding of the contact along the whisker's curvature, a term of order |F| times the
//         whisker's curvature, is left out).
// The contact is held bilateral: modes that would lift the whisker off are not distinguished (small vibrations
// about a pressed contact do not release it while their amplitude keeps the normal force positive).
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/dynamics/modes.hpp"

namespace vibrissa::dynamics {

enum class ContactModel { none, stick, slip };
std::string_view to_string(ContactModel model);

/// The load that holds the whisker at its equilibrium, B axes.
struct HeldLoad {
  double arc_length = 0.0;                              ///< material point of the load [m]
  Eigen::Vector3d force_B = Eigen::Vector3d::Zero();    ///< force on the whisker [N] (for a contact: a start)
  bool follower = false;                                ///< the force turns with its link (force mode)
  ContactModel contact = ContactModel::none;
  Eigen::Vector3d normal_B = Eigen::Vector3d::Zero();   ///< slip: the held direction (unit)
  /// A contact's point in B [m] (the quasi-static solve's contact point); none: where the start puts the load's
  /// material point.
  std::optional<Eigen::Vector3d> contact_point_B;
};

/// A configuration of the chain: the rotation vector of every joint in the axes of B at rest (the quasi-static
/// walk's omega, chain.hpp), N of them.
using JointRotations = std::vector<Eigen::Vector3d>;

/// Generalised force of the springs minus the load's, per joint (3N): the spring moment of joint j in B minus
/// the moment of `force_B` at the material point `arc_length` about node j (B). Zero at an equilibrium.
Eigen::VectorXd equilibrium_residual(const Whisker& whisker, const JointRotations& omega, const Eigen::Vector3d& force_B,
                                     double arc_length);
/// K_T = d residual / d theta (3N x 3N), theta the spatial joint increments; `follower`: the force turns with
/// its link (its derivative enters K_T), else it is dead.
Eigen::MatrixXd tangent_stiffness(const Whisker& whisker, const JointRotations& omega, const Eigen::Vector3d& force_B,
                                  double arc_length, bool follower);
/// The configuration after the spatial joint increments `dtheta` (3N): joint j's relative rotation becomes
/// exp(R_pre^T dtheta_j) exp(omega_j), R_pre the rotation of the chain proximal to joint j.
JointRotations apply_increments(const JointRotations& omega, const Eigen::VectorXd& dtheta);
/// Node positions in B of a configuration (N+1).
std::vector<Eigen::Vector3d> chain_nodes_B(const Whisker& whisker, const JointRotations& omega);

struct HeldEquilibrium {
  JointRotations omega;
  Eigen::Vector3d force_B = Eigen::Vector3d::Zero();  ///< the load (a contact: its reaction) [N]
  Eigen::Vector3d contact_B = Eigen::Vector3d::Zero();  ///< the load's material point [m]
  double residual = 0.0;   ///< largest |residual| / largest spring moment at the end
  int iterations = 0;
};

/// Newton's method from `start` (e.g. the quasi-static solve's joint rotations) on the linear model's chain:
/// force loads keep their force (dead or follower) and find q; contacts pin the material point at
/// load.contact_point_B (default: where `start` puts it) and find q and the reaction (starting from load.force_B). Throws std::runtime_error naming the residual
/// if it does not converge (1e-10 relative) in 50 iterations.
HeldEquilibrium held_equilibrium(const Whisker& whisker, const HeldLoad& load, const JointRotations& start);

struct DeflectedModes {
  Modes modes;                 ///< frequencies, damping ratios (zeta_n = beta v^T K_s v / (2 omega_n)), shapes
  HeldEquilibrium equilibrium;
  int constraints = 0;         ///< independent constraints: 0, 1 (slip), 3 (stick; 2 where the point cannot move along
                               ///< the whisker to first order, e.g. the tip of a straight whisker)
  /// |K_T - K_T^T| / |K_T| of the (constrained) tangent stiffness. The joint law (eqs. (1)-(3), moments in the
  /// joint's mid frame) is not exactly the gradient of an energy, so even a dead load's K_T is symmetric only to
  /// the order of the joint angles (docs/dynamics.md); a follower force is not conservative. Above 1e-9 the
  /// eigenproblem is solved as unsymmetric and the frequencies come from the real parts.
  double asymmetry = 0.0;
  double largest_imaginary = 0.0;  ///< largest |Im lambda| / |lambda| of K_T v = lambda M v (0 when symmetric)
};

/// The `count` lowest modes about the equilibrium of `load` (all with count <= 0). `start`: joint rotations to
/// start Newton from (empty: the rest shape).
DeflectedModes deflected_modes(const Whisker& whisker, const DynamicsProperties& props, const HeldLoad& load,
                               const JointRotations& start = {}, int count = 0);

}  // namespace vibrissa::dynamics
