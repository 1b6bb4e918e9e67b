#pragma once
// Each subcommand of the `vibrissa` tool lives in its own file and registers itself here.
#include <string>

#include <CLI/CLI.hpp>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::cli {

/// A numeric flag checked by the one rule for input numbers (core/checks.hpp, is_input_number): finite, not
/// subnormal, in [lo, hi]; the message shows values in their shortest form (CLI11's own range checks let nan
/// through and print 1.8e308 with all its 309 digits).
inline CLI::Validator number_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        const auto v = parse_decimal(text);
        if (!v) return "must be a number, got " + quote_text(text);
        if (!(is_input_number(*v) && *v >= lo && *v <= hi))
          return "must lie in [" + format_value(lo) + ", " + format_value(hi) + "], got " + format_value(*v);
        return std::string();
      },
      "[" + format_value(lo) + ", " + format_value(hi) + "]");
}

/// An output path: an empty one is an error (issue 23: `-o ""` wrote to standard output and `trial --out ""` to
/// the default folder, the option silently ignored).
inline CLI::Validator output_path() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? std::string("must name a file or folder, got an empty path") : std::string();
      },
      "PATH");
}

void register_solve(CLI::App& app);
void register_demo(CLI::App& app);
void register_trial(CLI::App& app);
void register_synth(CLI::App& app);
void register_array(CLI::App& app);
void register_reconstruct(CLI::App& app);
void register_calibrate(CLI::App& app);
void register_sweep(CLI::App& app);
void register_view(CLI::App& app);
void register_modes(CLI::App& app);
void register_dynamics(CLI::App& app);

}  // namespace vibrissa::cli
