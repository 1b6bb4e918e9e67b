#pragma once
// An empty scratch folder per test program run and name, under the system temporary directory.
#include <unistd.h>

#include <filesystem>
#include <string>

namespace vibrissa::test {

inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("vibrissa_io_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace vibrissa::test
