// Files parsed by third-party libraries are read once in a child process first (src/io/guarded_read.hpp): a
// crash there is an error naming the file, the caller's process survives, and otherwise the caller's own read
// returns or throws exactly what it would without the guard.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "io/guarded_read.hpp"

namespace vibrissa::io {
namespace {

std::string error_of(const auto& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

TEST(GuardedRead, ReturnsWhatTheReadReturnsReadingOnceHere) {
  int reads_here = 0;  // the child's reads count in its own copy of this variable
  const int value = guarded_read("a.h5", "libhdf5", [&] {
    ++reads_here;
    return 42;
  });
  EXPECT_EQ(value, 42);
  EXPECT_EQ(reads_here, 1);
}

TEST(GuardedRead, ThrowsTheReadsOwnError) {
  const auto read = [] {
    throw std::invalid_argument("a.h5: group 'x' missing");
    return 0;
  };
  EXPECT_THROW(guarded_read("a.h5", "libhdf5", read), std::invalid_argument);
  EXPECT_EQ(error_of([&] { guarded_read("a.h5", "libhdf5", read); }), "a.h5: group 'x' missing");
}

TEST(GuardedRead, ALibraryCrashIsAnErrorNamingTheFile) {
  int reads_here = 0;
  const auto crashing = [&] {
    ++reads_here;
    std::raise(SIGSEGV);  // what a read past a buffer inside the library does
    return 0;
  };
  EXPECT_EQ(error_of([&] { guarded_read("broken.h5", "libhdf5", crashing); }),
            "broken.h5: libhdf5 crashed reading this file (Segmentation fault): it is corrupted, or not the format "
            "its extension says; nothing was read");
  EXPECT_EQ(reads_here, 0);  // the crashing read never ran in this process
  EXPECT_THROW(guarded_read("broken.h5", "libhdf5", crashing), std::invalid_argument);
}

TEST(GuardedRead, AReaderThatExitsIsAnError) {
  // How a sanitizer ends a process after a report (exit code 1), or a library that calls exit().
  const auto exiting = [] {
    std::_Exit(1);
    return 0;
  };
  EXPECT_EQ(error_of([&] { guarded_read("odd.mat", "matio", exiting); }),
            "odd.mat: matio failed reading this file (its reader process exited with 1): it is corrupted, or not the "
            "format its extension says; nothing was read");
}

TEST(GuardedRead, AnInterruptedReadSaysSo) {
  const auto interrupted = [] {
    std::raise(SIGINT);  // Ctrl-C while the child reads: the child ends (default disposition)
    return 0;
  };
  EXPECT_THROW(guarded_read("big.mat", "matio", interrupted), std::runtime_error);
  EXPECT_EQ(error_of([&] { guarded_read("big.mat", "matio", interrupted); }),
            "big.mat: reading was interrupted (signal " + std::to_string(SIGINT) + ")");
}

}  // namespace
}  // namespace vibrissa::io
