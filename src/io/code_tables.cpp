#include "code_tables.hpp"

#include <algorithm>
#include <stdexcept>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::io {

namespace {

template <class Enum>
std::string table(std::initializer_list<Enum> values, std::string prefix = {}) {
  std::string out = std::move(prefix);
  for (Enum v : values) {
    if (!out.empty()) out += ", ";
    out += std::to_string(static_cast<int>(v)) + " " + std::string(to_string(v));
  }
  return out;
}

}  // namespace

std::string status_code_table() {
  return table({Status::converged, Status::no_contact, Status::slipped_off, Status::not_converged,
                Status::second_contact, Status::underdetermined},
               std::to_string(kNotSolvedCode) + " not_in_contact");
}

std::string contact_state_code_table() {
  return table({ContactState::free, ContactState::contact, ContactState::pushed_past});
}

std::map<int, std::string> code_labels(const std::string& table) {
  std::map<int, std::string> labels;
  std::size_t at = 0;
  while (at < table.size()) {
    const std::size_t end = std::min(table.find(", ", at), table.size());
    const std::string entry = table.substr(at, end - at);
    const std::size_t space = entry.find(' ');
    VIBRISSA_DEMAND(space != std::string::npos);
    labels[std::stoi(entry.substr(0, space))] = entry.substr(space + 1);
    at = end + 2;
  }
  return labels;
}

std::int8_t status_code(std::string_view name, std::string_view field) {
  if (name == "not_in_contact") return kNotSolvedCode;
  try {
    return static_cast<std::int8_t>(status_from_string(name));
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(std::string(field) + ": unknown solver status '" + std::string(name) + "'");
  }
}

}  // namespace vibrissa::io
