#include "vibrissa/solve/status.hpp"

#include "vibrissa/solve/solution.hpp"

#include <stdexcept>
#include <string>

namespace vibrissa {

std::string_view to_string(Status status) {
  switch (status) {
    case Status::converged: return "converged";
    case Status::no_contact: return "no_contact";
    case Status::slipped_off: return "slipped_off";
    case Status::not_converged: return "not_converged";
    case Status::second_contact: return "second_contact";
    case Status::underdetermined: return "underdetermined";
  }
  return "not_converged";
}

std::string_view to_string(ContactState state) {
  switch (state) {
    case ContactState::free: return "free";
    case ContactState::contact: return "contact";
    case ContactState::pushed_past: return "pushed_past";
  }
  return "free";
}

std::string_view to_string(FrictionState state) {
  switch (state) {
    case FrictionState::none: return "none";
    case FrictionState::stick: return "stick";
    case FrictionState::slip: return "slip";
  }
  return "none";
}

Status status_from_string(std::string_view name) {
  for (Status s : {Status::converged, Status::no_contact, Status::slipped_off, Status::not_converged,
                   Status::second_contact, Status::underdetermined})
    if (to_string(s) == name) return s;
  throw std::invalid_argument("status: unknown value \"" + std::string(name) + "\"");
}

}  // namespace vibrissa
