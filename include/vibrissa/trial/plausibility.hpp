#pragma once
// Unit guardrails of a trial (core/plausibility.hpp applied to a trial's data; docs/conventions.md,
// "Plausible ranges"): the warnings `vibrissa trial` prints, summary.json lists, and Python raises.
#include <string>
#include <vector>

#include "vibrissa/trial/format.hpp"

namespace vibrissa::trial {

/// One sentence per implausible property of `trial`, naming the quantity, the value and the likely mistake:
/// the whisker (rest shape length, base radius, Young's modulus: a length in metres declared mm reads as a
/// 35 um whisker), the angle series (radians declared as degrees, degrees as radians), and every edge (peg)
/// that passes farther from the whisker base, in every frame, than the whisker can reach.
std::vector<std::string> trial_warnings(const Trial& trial);

}  // namespace vibrissa::trial
