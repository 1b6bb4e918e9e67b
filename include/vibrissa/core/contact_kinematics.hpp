#pragma once
// What a deflection returns: the loaded point and the load on the deflected chain (both schemes). The tangent
// at the load is not carried: no solve needs it, and the force (normal to it) or the shape gives it.
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
