#pragma once
// What a deflection returns: the loaded point, load and tangent of the deflected chain (both schemes).
#include "vibrissa/core/small_vector.hpp"

namespace vibrissa {

/// Contact kinematics of the deflected chain, in the whisker frame B.
template <class S>
struct ContactKinematics {
  V3<S> p_contact_B;  ///< contact point relative to the base [m]
  V3<S> force_B;      ///< force on the whisker at the contact [N]
  V3<S> couple_B;     ///< couple on the whisker at the contact [N·m]
  V3<S> tangent_B;    ///< unit tangent of the loaded link
};

}  // namespace vibrissa
