#pragma once
// Shared by the libFuzzer harnesses: what counts as a finding. Invalid input may throw
// std::invalid_argument (or std::runtime_error for I/O); anything else escaping, a crash, or a Solution that
// breaks its contract (non-finite field, converged above tolerance) aborts the run.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <unistd.h>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::fuzz {

[[noreturn]] inline void finding(const char* what) {
  std::fprintf(stderr, "fuzz finding: %s\n", what);
  std::abort();
}

/// Runs `body`; input errors are fine, everything else is a finding.
template <class Body>
void expect_no_crash(Body&& body) {
  try {
    body();
  } catch (const std::invalid_argument&) {
  } catch (const InternalError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    finding("internal invariant broken");
  } catch (const std::runtime_error&) {
  } catch (const std::bad_alloc&) {
    finding("std::bad_alloc: an input size escaped the limits");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    finding("unexpected exception type");
  }
}

/// The fuzz input as a file (the readers take paths), in the process's own temporary directory.
inline std::filesystem::path input_file(std::string_view data, const char* extension) {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("vibrissa-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const auto path = dir / (std::string("input") + extension);
  std::ofstream(path, std::ios::binary).write(data.data(), static_cast<std::streamsize>(data.size()));
  return path;
}

}  // namespace vibrissa::fuzz
