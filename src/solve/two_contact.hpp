#pragma once
// The two-contact equilibrium of the object modes (docs/objects.md, "Two contacts"): where the whisker deflected
// by one contact would pass through the object at a second place, both contacts solved together, frictionless,
// each force along its normal.
#include <array>
#include <optional>
#include <vector>

#include "object_problem.hpp"

namespace vibrissa::detail {

/// The chain under two follower loads (second-order scheme): chain.hpp's walk with the moments of both loads
/// summed at every joint proximal to both (each load's joint weights as deflect() gives them). Per load: the
/// contact point, force and load frame x, y axes in B. `omega_out` (size >= links): every joint's rotation in
/// its link's frame.
struct TwoLoadKinematics {
  std::array<Eigen::Vector3d, 2> p_B, F_B, t_B, y_B;
};
TwoLoadKinematics deflect_two_loads(const Whisker& w, const std::array<LoadState, 2>& loads,
                                    Eigen::Vector3d* omega_out = nullptr);

struct TwoContacts {
  bool solved = false;
  std::array<LoadState, 2> loads;              ///< each contact's side load (its own load frame), s
  std::array<Eigen::Vector3d, 2> point_B{};    ///< on the object
  std::array<Eigen::Vector3d, 2> normal_B{};   ///< the object's normal there
  std::array<SurfaceFeature, 2> feature{};
  std::vector<Eigen::Vector3d> nodes_B;        ///< the deflected whisker
  double residual = 0.0;                       ///< [m]
  int iterations = 0;
  /// Where only one of the two pushes: that single contact (attempt_object's), index 0 or 1; else -1.
  int single = -1;
  ObjectAttempt single_attempt;
};

/// Solves the two-contact equilibrium from a converged side contact `first` (frictionless) and the arc length
/// `s_second` where its deflected whisker is inside the object. Where one force would pull, the single contact
/// at the other place is solved instead (`single`). solved = false where neither settles within a few rounds,
/// where a point of the whisker would still be inside (>= 1e-9 m), at the tip, or in the paper scheme.
TwoContacts solve_two_contacts(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const ObjectAttempt& first,
                               double s_second, const SolveOptions& options);

}  // namespace vibrissa::detail
