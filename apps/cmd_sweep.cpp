// `vibrissa sweep CONFIG [--out DIR] [--scheduler ADDRESS|serial] [--workers N] [--chunk-size N]`: parameter
// sweeps on Dask (docs/sweeps.md). A client of the Python API, so it is the Python package's command
// (`python -m vibrissa sweep`, vibrissa/sweep.py): this subcommand hands every argument to it unchanged,
// --help included, as the figures are drawn by Python scripts.
#include <cstdlib>

#include "commands.hpp"
#include "run_python.hpp"

namespace vibrissa::cli {

void register_sweep(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "sweep", "Parameter sweeps of array, trial or solve runs on Dask (docs/sweeps.md; `vibrissa sweep --help`)");
  cmd->set_help_flag();  // the Python command prints its own help
  cmd->prefix_command();
  cmd->callback([cmd] {
    std::vector<std::string> args{"sweep"};
    for (const std::string& a : cmd->remaining()) args.push_back(a);
    std::exit(exec_python_module("vibrissa", args));
  });
}

}  // namespace vibrissa::cli
