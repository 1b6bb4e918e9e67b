// `vibrissa`: thin command-line front end. Each subcommand parses, calls the library, prints.
#include <exception>
#include <iostream>

#include "commands.hpp"
#include "vibrissa/io/temporary_files.hpp"

int main(int argc, char** argv) {
  CLI::App app{"vibrissa: quasi-static 3D mechanics of rodent whiskers touching objects (Huet & Hartmann 2016)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "vibrissa 0.1.0");
  vibrissa::cli::register_solve(app);
  vibrissa::cli::register_demo(app);
  vibrissa::cli::register_trial(app);
  vibrissa::cli::register_synth(app);
  vibrissa::cli::register_array(app);
  vibrissa::cli::register_reconstruct(app);
  vibrissa::cli::register_calibrate(app);
  try {
    // A killed run (Ctrl-C, kill, a closed terminal) removes its half-written temporaries and keeps the
    // older outputs (docs/formats.md, "Atomic outputs").
    vibrissa::io::install_cleanup_signal_handlers();
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "vibrissa: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
