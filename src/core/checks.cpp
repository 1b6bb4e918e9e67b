#include "vibrissa/core/checks.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>

namespace vibrissa {

std::string format_value(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::array<char, 64> buf{};
  const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);  // shortest round trip
  if (ec != std::errc()) return "?";
  return std::string(buf.data(), end);
}

std::string format_value(const Eigen::Vector3d& v) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < 3; ++i) {
    if (i > 0) out.append(", ");
    out.append(format_value(v[i]));
  }
  out.append("]");
  return out;
}

namespace {

// Length of the well-formed UTF-8 sequence at text[i] (RFC 3629: no overlong forms, no surrogates, at most
// U+10FFFF), or 0 if the bytes there are not one.
std::size_t utf8_sequence(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  else if (c >= 0xE0 && c <= 0xEF) n = 3, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
  else if (c >= 0xF0 && c <= 0xF4) n = 4, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
  else return 0;
  if (i + n > text.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

// printable_text of text[0, limit), cut before a character that would cross the limit.
std::string printable_prefix(std::string_view text, std::size_t limit, std::size_t& used) {
  std::string out;
  out.reserve(std::min(text.size(), limit) + 8);
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t n = utf8_sequence(text, i);
    if (i + std::max<std::size_t>(n, 1) > limit) break;
    const auto c = static_cast<unsigned char>(text[i]);
    if (n == 0 || (n == 1 && (c < 0x20 || c == 0x7f))) {
      out.push_back('?');
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  used = i;
  return out;
}

}  // namespace

std::string printable_text(std::string_view text) {
  std::size_t used = 0;
  return printable_prefix(text, text.size(), used);
}

std::string quote_text(std::string_view text) {
  std::size_t used = 0;
  std::string out = printable_prefix(text, limits::max_quoted_chars, used);
  if (used < text.size()) {
    out.append("... (");
    out.append(std::to_string(text.size()));
    out.append(" bytes)");
  }
  return out;
}

std::optional<double> parse_decimal(std::string_view text) {
  if (text.empty()) return std::nullopt;
  const char* first = text.data() + (text[0] == '+' ? 1 : 0);
  const char* last = text.data() + text.size();
  double v = 0.0;
  const auto [end, ec] = std::from_chars(first, last, v, std::chars_format::general);
  if (ec != std::errc() || end != last || first == last) return std::nullopt;
  return v;
}

void invalid_input(const std::string& message) { throw std::invalid_argument(message); }

bool is_input_number(double v) {
  return std::isfinite(v) && (v == 0.0 || std::abs(v) >= std::numeric_limits<double>::min());
}

namespace {
const std::string kNormalRule = "finite, and 0 or at least 2.2250738585072014e-308 in magnitude (no subnormal numbers)";
}  // namespace

void require_finite(double v, std::string_view field) {
  if (!is_input_number(v)) invalid_input(std::string(field) + " must be " + kNormalRule + ", got " + format_value(v));
}

void require_finite(const Eigen::Vector3d& v, std::string_view field) {
  if (!(is_input_number(v.x()) && is_input_number(v.y()) && is_input_number(v.z())))
    invalid_input(std::string(field) + " must be " + kNormalRule + " in every component, got " + format_value(v));
}

void require_positive(double v, std::string_view field) {
  if (!(is_input_number(v) && v > 0.0))
    invalid_input(std::string(field) + " must be a positive finite number of at least 2.2250738585072014e-308, got " +
                  format_value(v));
}

void require_in_range(double v, double lo, double hi, std::string_view field) {
  if (!(v >= lo && v <= hi && is_input_number(v)))
    invalid_input(std::string(field) + " must lie in [" + format_value(lo) + ", " + format_value(hi) + "], got " +
                  format_value(v));
}

int require_integer(double v, int lo, int hi, std::string_view field) {
  if (!(v >= lo && v <= hi && v == std::floor(v)))
    invalid_input(std::string(field) + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                  "], got " + format_value(v));
  return static_cast<int>(v);
}

void require_at_most(std::size_t count, std::size_t max, std::string_view what) {
  if (count > max)
    invalid_input(std::string(what) + ": " + std::to_string(count) + " is more than the limit of " +
                  std::to_string(max) + " (docs/formats.md, \"Limits\")");
}

void require_normalizable(const Eigen::Vector3d& v, std::string_view field) {
  require_finite(v, field);
  const double n2 = v.squaredNorm();
  if (!(n2 >= std::numeric_limits<double>::min() && n2 <= std::numeric_limits<double>::max()))
    invalid_input(std::string(field) + " must be non-zero with a length between 1e-150 and 1e150 (a unit vector " +
                  "is best), got " + format_value(v));
}

Eigen::Vector3d unit_direction(const Eigen::Vector3d& v, std::string_view field) {
  require_finite(v, field);
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) invalid_input(std::string(field) + " must be non-zero, got " + format_value(v));
  const double n2 = v.squaredNorm();
  if (n2 >= std::numeric_limits<double>::min() && n2 <= std::numeric_limits<double>::max()) return v / std::sqrt(n2);
  return (v / largest).normalized();  // tiny or huge: rescale first so the norm neither underflows nor overflows
}

void internal_error(const char* condition, const char* file, int line) {
  throw InternalError(std::string("vibrissa internal error (a bug, please report it): ") + condition +
                      " failed at " + file + ":" + std::to_string(line));
}

}  // namespace vibrissa
