#pragma once
// Each subcommand of the `vibrissa` tool lives in its own file and registers itself here.
#include <CLI/CLI.hpp>

namespace vibrissa::cli {

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
