#pragma once
// The whisker model (spec §2.1): an intrinsically curved, tapered rod discretised as N rigid links joined by
// bending/torsion springs. A Whisker is its rest geometry and stiffness only (the model, as Pinocchio's
// Model): immutable after construction and shared by every frame and thread. Where it is — a Placement
// (R_WB, p_W_base) — is a small value given to each solve; the forward model (chain.hpp) works in B and
// writes only into caller-owned storage.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/cubic_spline.hpp"
#include "vibrissa/core/pose.hpp"

namespace vibrissa {

/// How the continuous rod is discretised into joints (docs/conventions.md, "Discretisation").
enum class Scheme {
  second_order,  ///< default: trapezoidal joint compliance, error O(1/N^2)
  paper,         ///< Elastica3D v1's chain exactly (published_chain.hpp), O(1/N)
};

/// Boundary condition at the follicle (spec §2.1).
enum class BaseJoint {
  elastic,  ///< paper scheme: the base joint has the spring of a whole link; second-order: see docs
  rigid,    ///< the first link is clamped in the follicle
};

/// Everything about a whisker except its rest shape. Defaults are the spec's (§2.1).
struct WhiskerProperties {
  int links = 100;                     ///< N, number of rigid links
  double base_radius = 100e-6;         ///< [m]
  double taper_ratio = 15.0;           ///< base radius / tip radius (linear taper in arc length)
  std::vector<double> radii;           ///< optional per-node radii [m], base to tip, equally spaced in s
  double youngs_modulus = 3.3e9;       ///< [Pa]
  std::vector<double> youngs_moduli;   ///< optional per-node E [Pa], base to tip, equally spaced in s
  double poisson_ratio = 0.38;         ///< G = E / (2 (1 + nu)), eq. (2)
  BaseJoint base = BaseJoint::elastic;
  std::optional<double> base_stiffness;  ///< optional follicle spring [N·m/rad] in series at the base
  Scheme scheme = Scheme::second_order;
};

void validate(const WhiskerProperties& props);

class Whisker;
/// Throws std::invalid_argument naming `source` unless the built whisker is usable: arc length within
/// limits (core/limits.hpp), every link of positive finite length, every joint compliance finite.
void check_rest_geometry(const Whisker& whisker, std::string_view source);

class Whisker {
 public:
  /// Rest shape from 3D points, base first (>= 3). The second-order scheme resamples them into `links`
  /// equal links; the paper scheme keeps them as its nodes (links = points - 1), as Elastica3D does. Without a pose the points are in world coordinates and
  /// their placement becomes placement(); with a pose only their shape is used and placement() is the pose.
  static Whisker from_points(const std::vector<Eigen::Vector3d>& points, const WhiskerProperties& props,
                             const std::optional<Pose>& pose = std::nullopt);
  /// Planar rest shape y = a x^2 in the whisker frame, arc length `length` [m], a [1/m].
  static Whisker from_parabola(double length, double a, const WhiskerProperties& props, const Pose& pose = {});
  /// Planar rest shape y = A x^3 + B x^2 in the whisker frame, A [1/m^2], B [1/m].
  static Whisker from_cubic(double length, double A, double B, const WhiskerProperties& props,
                            const Pose& pose = {});

  // --- geometry in the whisker-centred frame B ---
  [[nodiscard]] int links() const { return static_cast<int>(link_length_.size()); }
  [[nodiscard]] double length() const { return arc_.back(); }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& rest_nodes_B() const { return nodes_B_; }
  [[nodiscard]] const std::vector<double>& link_lengths() const { return link_length_; }
  /// Arc length of each node from the base [m] (size N+1).
  [[nodiscard]] const std::vector<double>& node_arc_lengths() const { return arc_; }
  /// Rest orientation of link i relative to link i-1 (link 0: relative to B).
  [[nodiscard]] const std::vector<Eigen::Matrix3d>& rest_joint_rotations() const { return Q_rest_; }
  /// Rest orientation of link i in B (columns: tangent, normal, binormal; parallel-transported).
  [[nodiscard]] const std::vector<Eigen::Matrix3d>& rest_link_frames_B() const { return R_link_B_; }
  [[nodiscard]] const std::vector<double>& node_radii() const { return radius_; }
  [[nodiscard]] const std::vector<double>& node_youngs_moduli() const { return youngs_; }
  [[nodiscard]] const WhiskerProperties& properties() const { return props_; }

  /// Index of the link that holds arc length s, and the distance h of s past that link's first node.
  /// Beyond the tip the last link is extended straight (used by solvers to detect slip-off).
  void locate(double s, int& link, double& h) const;
  [[nodiscard]] Eigen::Vector3d rest_point_B(double s) const;

  // --- joint compliances (see chain.hpp) ---
  /// Bending compliance per unit weight at joint j: 1 / (E I) [1/(N·m^2)].
  [[nodiscard]] const std::vector<double>& bending_compliance() const { return cb_; }
  /// Torsional compliance per unit weight at joint j: 1 / (G J) [1/(N·m^2)].
  [[nodiscard]] const std::vector<double>& torsion_compliance() const { return ct_; }
  /// Arc-length weight of joint j when the load lies distal to its link [m].
  [[nodiscard]] const std::vector<double>& joint_weight() const { return weight_; }
  /// Weight of the last loaded joint j for a load h past node j: weight_at_load_base + h * weight_at_load_slope.
  [[nodiscard]] double loaded_joint_weight_base(int j) const { return weight_load_base_[static_cast<std::size_t>(j)]; }
  [[nodiscard]] double loaded_joint_weight_slope() const { return weight_load_slope_; }
  /// Second-order scheme: compliance per unit weight of joint j expressed in link j's frame,
  /// H diag(1/GJ, 1/EI, 1/EI) H^T with H the rotation to the joint's mid frame (half the rest rotation), so
  /// that twist and bending are split in the frame halfway between the two links [1/(N·m^2)].
  [[nodiscard]] const std::vector<Eigen::Matrix3d>& joint_compliance_link() const { return compliance_link_; }
  /// joint_compliance_link() in the axes of B at rest, R_j K_j R_j^T with R_j = rest_link_frames_B()[j]: the
  /// forward walk (chain.hpp) carries its vectors in these axes [1/(N·m^2)].
  [[nodiscard]] const std::vector<Eigen::Matrix3d>& joint_compliance_B() const { return compliance_B_; }
  /// joint_compliance_B() times joint_weight(): the compliance of joint j to a load distal to its link [1/(N·m)].
  [[nodiscard]] const std::vector<Eigen::Matrix3d>& weighted_joint_compliance_B() const { return weighted_compliance_B_; }
  /// Rest link vectors in B, l_i times the first column of rest_link_frames_B()[i] [m].
  [[nodiscard]] const std::vector<Eigen::Vector3d>& rest_link_vectors_B() const { return link_vector_B_; }
  /// Rest curvature vector across link k in its own frame [rad/m]: the second-order scheme turns the
  /// load frame by (h - l_k/2) times it, so that "normal to the whisker" follows the smooth rest tangent
  /// rather than the chord (zero for the paper's scheme, whose load is normal to the link).
  [[nodiscard]] const std::vector<Eigen::Vector3d>& load_frame_curvature() const { return load_curvature_; }
  /// Extra bending compliance of the follicle spring at joint 0 [1/(N·m)] (0 if none).
  [[nodiscard]] double base_extra_compliance() const { return base_extra_compliance_; }
  /// Bending stiffness at the base E I_0 [N·m^2] (scales every solve).
  [[nodiscard]] double base_bending_stiffness() const { return 1.0 / cb_.front(); }
  /// A 64-bit hash (FNV-1a) of every number the chain's mechanics are built from (rest nodes, radii, moduli,
  /// compliances, weights, scheme): whiskers that deflect alike share it, a different whisker almost surely
  /// has another. The placement is not part of it. A solve's warm-start record is used only on a whisker with
  /// the fingerprint it was made on (solution.hpp, LoadSensitivity).
  [[nodiscard]] std::uint64_t mechanics_fingerprint() const { return fingerprint_; }

  /// Paper scheme: MATLAB splines (cubic_spline.hpp) against node arc length through the rest nodes in B,
  /// and through E and I = pi r^4 / 4 at nodes 1..N, with which Elastica3D re-meshes the chain for each load.
  struct PublishedRemesh {
    std::array<CubicSpline, 3> node_B;
    CubicSpline youngs, inertia;
  };
  [[nodiscard]] const PublishedRemesh& published_remesh() const { return remesh_; }

  /// The placement the whisker was built with (the pose given to the factory, or where its points lay).
  /// Solves called without a Placement use it; per-frame code passes its own.
  [[nodiscard]] const Placement& placement() const { return placement_; }
  /// A copy of the model whose placement() is `X_WB` (copies every array: per-frame code passes a
  /// Placement to the solve instead).
  [[nodiscard]] Whisker with_placement(const Placement& X_WB) const {
    Whisker w = *this;
    w.placement_ = X_WB;
    return w;
  }

 private:
  Whisker() = default;
  void build(std::vector<Eigen::Vector3d> nodes_B, const WhiskerProperties& props);

  WhiskerProperties props_;
  std::vector<Eigen::Vector3d> nodes_B_;
  std::vector<double> link_length_, arc_;
  std::vector<Eigen::Matrix3d> Q_rest_, R_link_B_;
  std::vector<double> radius_, youngs_;
  std::vector<Eigen::Vector3d> load_curvature_;
  std::vector<Eigen::Matrix3d> compliance_link_, compliance_B_, weighted_compliance_B_;
  std::vector<Eigen::Vector3d> link_vector_B_;
  std::vector<double> cb_, ct_, weight_, weight_load_base_;
  double weight_load_slope_ = 0.0;
  double base_extra_compliance_ = 0.0;
  std::uint64_t fingerprint_ = 0;
  PublishedRemesh remesh_;
  Placement placement_;
};

}  // namespace vibrissa
