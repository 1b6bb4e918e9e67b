#pragma once
// What a deflection returns: the loaded point and the load on the deflected chain (both schemes). The tangent
// at the load is not carried: no solve needs it; the deflected shape gives it (and in a planar problem with a
// normal force, so does the force: t is proportional to (F_y, -F_x)).
#include <array>

#include "vibrissa/core/small_vector.hpp"

namespace vibrissa {

/// Contact kinematics of the deflected chain, in the whisker frame B.
template <class S>
struct ContactKinematics {
  V3<S> p_contact_B;  ///< contact point relative to the base [m]
  V3<S> force_B;      ///< force on the whisker at the contact [N]
  V3<S> couple_B;     ///< couple on the whisker at the contact [N·m]
};

/// Vectors fixed in the load frame of the loaded link (they follow it as the chain bends, as the load does):
/// given in that frame, a walk that carries them returns them in B. The object solves carry the load frame's x
/// and y axes: x is the whisker's tangent at the load (second-order scheme: the smooth rest tangent at s,
/// carried with link k; paper scheme: the last link of the re-meshed chain).
template <class S>
using FollowerVectors = std::array<V3<S>, 2>;

}  // namespace vibrissa
