#pragma once
// The `vibrissa` executable is split in two so that a `vibrissa solve` process starts fast
// (docs/architecture.md, "Executables"): bin/vibrissa runs the light subcommands (solve, demo) itself and
// links neither HDF5 nor matio; every other command line is handed, unchanged, to the full tool
// <bin>/VIBRISSA_FULL_CLI_FROM_BIN (<prefix>/libexec/vibrissa/vibrissa-full), which has all subcommands.

namespace vibrissa::cli {

/// True when argv names a subcommand the light executable runs itself.
bool is_light_command(int argc, char** argv);
/// Replaces this process by the full tool with the same arguments; returns only on failure (exit status 1,
/// after a message naming the path).
int run_full_cli(char** argv);

}  // namespace vibrissa::cli
