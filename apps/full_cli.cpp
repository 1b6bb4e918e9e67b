#include "full_cli.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string_view>

namespace vibrissa::cli {

bool is_light_command(int argc, char** argv) {
  if (argc < 2) return false;
  const std::string_view command = argv[1];
  return command == "solve" || command == "demo";
}

int run_full_cli(char** argv) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) {
    std::cerr << "vibrissa: error: cannot locate this executable (/proc/self/exe): " << ec.message() << "\n";
    return 1;
  }
  const fs::path full = exe.parent_path() / VIBRISSA_FULL_CLI_FROM_BIN;
  ::execv(full.c_str(), argv);
  std::cerr << "vibrissa: error: cannot run the full tool " << full << ": " << std::strerror(errno) << "\n";
  return 1;
}

}  // namespace vibrissa::cli
