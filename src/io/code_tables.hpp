#pragma once
// The integer codes binary outputs store for enums, and their code tables (docs/formats.md, "Codes"): every
// code dataset carries units "code" and a "codes" attribute in this text form.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "vibrissa/solve/solution.hpp"
#include "vibrissa/solve/status.hpp"

namespace vibrissa::io {

/// Code of a frame without a solve, "not_in_contact" (solver status datasets).
inline constexpr std::int8_t kNotSolvedCode = -1;

/// "-1 not_in_contact, 0 converged, 1 no_contact, 2 slipped_off, 3 not_converged, 4 second_contact,
/// 5 underdetermined" (one table for every solver status; the forward solves never give 5)
std::string status_code_table();
/// "0 free, 1 contact, 2 pushed_past"
std::string contact_state_code_table();

/// The names of the codes of a code table ("0 free, 1 contact" -> {0: "free", 1: "contact"}); empty for "".
std::map<int, std::string> code_labels(const std::string& table);

/// Status code of a solver status name or "not_in_contact" (no solve: the frame is not in contact);
/// throws std::invalid_argument naming `field` and the value otherwise.
std::int8_t status_code(std::string_view name, std::string_view field);

}  // namespace vibrissa::io
