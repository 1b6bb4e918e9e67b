#pragma once
// What a deflection returns: the loaded point and the load on the deflected chain (both schemes). The tangent
// at the load is not carried: no solve needs it; the deflected shape gives it (and in a planar problem with a
// normal force, so does the force: t is proportional to (F_y, -F_x)).
#include "vibrissa/core/small_vector.hpp"

namespace vibrissa {

/// Contact kinematics of the deflected chain, in the whisker frame B.
template <class S>
struct ContactKinematics {
  V3<S> p_contact_B;  ///< contact point relative to the base [m]
  V3<S> force_B;      ///< force on the whisker at the contact [N]
  V3<S> couple_B;     ///< couple on the whisker at the contact [N·m]
};

}  // namespace vibrissa
