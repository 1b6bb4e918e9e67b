#pragma once
// Input checks versus internal invariants (as Drake's THROW_UNLESS vs DEMAND).
//  - Input: anything a user, a file or a caller can get wrong. The require_* functions throw
//    std::invalid_argument with a message naming the field and the value (format_value, quote_text).
//  - Invariants: conditions the library itself guarantees. VIBRISSA_DEMAND throws InternalError (a
//    std::logic_error, never a std::invalid_argument), so a broken invariant is never mistaken for bad input.
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "vibrissa/core/limits.hpp"

namespace vibrissa {

/// The one format for numbers in messages: the shortest text that reads back as the same double
/// ("0.03", "0.0300000001", "1e-300", "1e+300", "nan", "inf"), so a value never prints like its bound.
std::string format_value(double v);
/// "[x, y, z]" with format_value.
std::string format_value(const Eigen::Vector3d& v);
/// Text for a message, always valid UTF-8: control bytes and bytes that are not UTF-8 are shown as '?'.
std::string printable_text(std::string_view text);
/// Input text for a message: printable_text of at most limits::max_quoted_chars bytes (never half a
/// character), then "... (N bytes)".
std::string quote_text(std::string_view text);

/// The number in `text` if all of it is one decimal number ("1.5", "-2e-3", "+7", "inf", "nan"); nullopt
/// for anything else (hexadecimal "0x10", trailing text, empty). The one text-to-number rule of every reader.
std::optional<double> parse_decimal(std::string_view text);

/// Throws std::invalid_argument(message).
[[noreturn]] void invalid_input(const std::string& message);

/// The one rule for a number given as input (files, flags, Python): finite, and zero or normal. A subnormal
/// (0 < |v| < 2.2e-308, e.g. 1e-310) is rejected like nan and inf: its reciprocal or square overflows or
/// underflows inside the model.
bool is_input_number(double v);
/// Throws std::invalid_argument naming `field` unless every component is_input_number.
void require_finite(double v, std::string_view field);
void require_finite(const Eigen::Vector3d& v, std::string_view field);
/// ... unless v is_input_number and > 0.
void require_positive(double v, std::string_view field);
/// ... unless v is_input_number and lo <= v <= hi.
void require_in_range(double v, double lo, double hi, std::string_view field);
/// An integer field given as a double (JSON, CSV, HDF5 attributes): throws unless v is integral and in
/// [lo, hi] (which also rules out the undefined conversion of huge values).
int require_integer(double v, int lo, int hi, std::string_view field);
/// A count asked for by the input (frames, points, columns): throws unless count <= max.
void require_at_most(std::size_t count, std::size_t max, std::string_view what);
/// A direction the solvers normalise as given: finite, and its squared norm neither underflows (zero, or
/// shorter than ~1e-154) nor overflows.
void require_normalizable(const Eigen::Vector3d& v, std::string_view field);
/// A direction of any length: finite and non-zero; returned as a unit vector (scaled first, so that tiny or
/// huge components do not underflow or overflow).
Eigen::Vector3d unit_direction(const Eigen::Vector3d& v, std::string_view field);

/// A broken internal invariant: a bug in vibrissa, not bad input.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};
[[noreturn]] void internal_error(const char* condition, const char* file, int line);

}  // namespace vibrissa

/// Checks an internal invariant (always on, also in Release): throws vibrissa::InternalError if false.
#define VIBRISSA_DEMAND(condition) \
  ((condition) ? static_cast<void>(0) : ::vibrissa::internal_error(#condition, __FILE__, __LINE__))
