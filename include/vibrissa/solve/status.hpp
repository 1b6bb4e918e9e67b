#pragma once
// Outcome of a solve. A solve never returns NaN: anything but `converged` is reported here, with a message.
#include <string_view>

namespace vibrissa {

enum class Status {
  converged,      ///< equations satisfied to the requested tolerance
  no_contact,     ///< the object is out of reach, or the whisker is not pressed against it
  slipped_off,    ///< equilibrium would need the contact beyond the tip
  not_converged,  ///< the iteration limit was reached or the solver stalled
  /// object modes: the single-contact equilibrium would put another part of the whisker inside the object
  /// (Solution::second_contact_arc_length says where); its loads are reported, flagged by this status
  second_contact,
  /// base-wrench inverse: a least-squares optimum that explains the signals, but the signals cannot determine
  /// the contact (the Jacobian has rank < 3, e.g. bending moments alone): one fit of a family, not *the* contact
  underdetermined,
};

std::string_view to_string(Status status);
/// Inverse of to_string; throws std::invalid_argument for an unknown name.
Status status_from_string(std::string_view name);

}  // namespace vibrissa
