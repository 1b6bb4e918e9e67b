#pragma once
// Runs one of the plotting scripts in figures/ with the Python interpreter found at configure time
// (Debian's /usr/bin/python3 with numpy, matplotlib and h5py), or $VIBRISSA_PYTHON when set. Figures are
// optional: a missing interpreter or package is reported, not fatal. And hands a subcommand implemented in
// the Python package (`vibrissa sweep`) to that interpreter.
#include <cstdio>
#include <string>
#include <vector>

namespace vibrissa::cli {

/// Returns the script's exit status; prints a warning and returns non-zero if it could not run.
int run_figure_script(const std::string& script, const std::vector<std::string>& args);

/// A figure script started before its data exist, so that the interpreter and its imports (~0.4 s of CPU:
/// matplotlib, NumPy, h5py) load while the caller computes: the script runs with `--start-on-stdin` and waits
/// for a line on its standard input. run() sends "go" once the data are written and waits for the figures;
/// destroyed without run() (the computation failed), it closes the pipe and the script exits drawing nothing.
class EarlyFigureScript {
 public:
  EarlyFigureScript(const std::string& script, const std::vector<std::string>& args);
  ~EarlyFigureScript();
  EarlyFigureScript(const EarlyFigureScript&) = delete;
  EarlyFigureScript& operator=(const EarlyFigureScript&) = delete;
  /// Lets the script draw and waits for it; returns its exit status, as run_figure_script (warnings included).
  int run();

 private:
  std::string script_;
  std::FILE* pipe_ = nullptr;  ///< the script's standard input (popen); null if it could not start
};

struct FigureScript {
  std::string script;  ///< a file in figures/, or with `module` a module of the vibrissa package
  std::vector<std::string> args;
  bool module = false;  ///< run `python -m script args` with the package on PYTHONPATH (run_python_module)
};
/// Runs several scripts at once (each is its own Python process and writes its own file), as run_figure_script.
void run_figure_scripts(const std::vector<FigureScript>& scripts);

/// Runs `python -m <module> <args...>` with the vibrissa package of this installation (or build tree) on
/// PYTHONPATH and returns its exit status (a warning is printed when it fails).
int run_python_module(const std::string& module, const std::vector<std::string>& args);

/// Replaces this process by `python -m <module> <args...>` with the vibrissa package of this installation (or
/// build tree) on PYTHONPATH; returns 1 (after a message) only if the interpreter cannot be started.
int exec_python_module(const std::string& module, const std::vector<std::string>& args);

}  // namespace vibrissa::cli
