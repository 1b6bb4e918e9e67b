#pragma once
// Runs one of the plotting scripts in figures/ with the Python interpreter found at configure time
// (Debian's /usr/bin/python3 with numpy, matplotlib and h5py). Figures are optional: a missing interpreter
// or package is reported, not fatal.
#include <string>
#include <vector>

namespace vibrissa::cli {

/// Returns the script's exit status; prints a warning and returns non-zero if it could not run.
int run_figure_script(const std::string& script, const std::vector<std::string>& args);

struct FigureScript {
  std::string script;
  std::vector<std::string> args;
};
/// Runs several scripts at once (each is its own Python process and writes its own file), as run_figure_script.
void run_figure_scripts(const std::vector<FigureScript>& scripts);

}  // namespace vibrissa::cli
