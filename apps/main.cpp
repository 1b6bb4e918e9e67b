// `vibrissa`: thin command-line front end. Each subcommand parses, calls the library, prints.
// Built twice (apps/CMakeLists.txt): with VIBRISSA_CLI_LIGHT as bin/vibrissa (solve and demo; the rest is
// handed to the full tool, full_cli.hpp), without it as the full tool.
#include <exception>
#include <iostream>

#include "commands.hpp"
#ifdef VIBRISSA_CLI_LIGHT
#include "full_cli.hpp"
#endif
#include "vibrissa/core/checks.hpp"
#include "vibrissa/io/temporary_files.hpp"

int main(int argc, char** argv) {
#ifdef VIBRISSA_CLI_LIGHT
  if (!vibrissa::cli::is_light_command(argc, argv)) return vibrissa::cli::run_full_cli(argv);
#endif
  CLI::App app{"vibrissa: quasi-static 3D mechanics of rodent whiskers touching objects (Huet & Hartmann 2016)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "vibrissa 0.1.0");
  vibrissa::cli::register_solve(app);
  vibrissa::cli::register_demo(app);
#ifndef VIBRISSA_CLI_LIGHT
  vibrissa::cli::register_trial(app);
  vibrissa::cli::register_synth(app);
  vibrissa::cli::register_array(app);
  vibrissa::cli::register_reconstruct(app);
  vibrissa::cli::register_calibrate(app);
  vibrissa::cli::register_sweep(app);
  vibrissa::cli::register_view(app);
  vibrissa::cli::register_modes(app);
  vibrissa::cli::register_dynamics(app);
#endif
  try {
    // A killed run (Ctrl-C, kill, a closed terminal) removes its half-written temporaries and keeps the
    // older outputs (docs/formats.md, "Atomic outputs").
    vibrissa::io::install_cleanup_signal_handlers();
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every flag error exits 1 like any other error (docs/conventions.md),
    // not with CLI11's own codes (104, 105, 114, ...).
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::cerr << "vibrissa: error: " << vibrissa::printable_text(e.what()) << " (see --help)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "vibrissa: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
