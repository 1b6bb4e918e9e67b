#pragma once
// Runs one of the plotting scripts in figures/ with the Python interpreter found at configure time
// (Debian's /usr/bin/python3 with numpy, matplotlib and h5py). Figures are optional: a missing interpreter
// or package is reported, not fatal.
#include <string>
#include <vector>

namespace vibrissa::cli {

/// Returns the script's exit status; prints a warning and returns non-zero if it could not run.
int run_figure_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace vibrissa::cli
