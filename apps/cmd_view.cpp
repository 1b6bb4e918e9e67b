// `vibrissa view RESULT [-o OUT.html]`: the interactive 3D viewer (docs/viewer.md), one self-contained HTML
// page. Written by the Python package (python -m vibrissa view, vibrissa/viewer.py), so this subcommand hands
// every argument to it unchanged, --help included, as `vibrissa sweep` does.
#include <cstdlib>

#include "commands.hpp"
#include "run_python.hpp"

namespace vibrissa::cli {

void register_view(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "view", "Write an interactive 3D viewer of an array, trial, solve or sweep result: one HTML file (docs/viewer.md; `vibrissa view --help`)");
  cmd->set_help_flag();  // the Python command prints its own help
  cmd->prefix_command();
  cmd->callback([cmd] {
    std::vector<std::string> args{"view"};
    for (const std::string& a : cmd->remaining()) args.push_back(a);
    std::exit(exec_python_module("vibrissa", args));
  });
}

}  // namespace vibrissa::cli
