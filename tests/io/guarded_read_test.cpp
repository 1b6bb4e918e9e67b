// Files parsed by third-party libraries are read once in a child process first (src/io/guarded_read.hpp): a
// crash there is an error naming the file, the caller's process survives, and otherwise the caller's own read
// returns or throws exactly what it would without the guard. Only a single-threaded process forks; ctest runs
// each test in a process of its own, so the tests that need the guard skip themselves in a process that has
// started other threads.
#include <gtest/gtest.h>

#include <unistd.h>

#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "io/guarded_read.hpp"
#include "vibrissa/objects/mesh.hpp"

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

#define REQUIRE_GUARD() \
  if (!single_threaded()) GTEST_SKIP() << "this process runs other threads: the guard is off"

/// Appends the reading process's id to a file and returns the number of lines there: which processes read.
struct PidLog {
  std::filesystem::path file = std::filesystem::temp_directory_path() / ("guarded_read_" + std::to_string(::getpid()));
  PidLog() { std::filesystem::remove(file); }
  ~PidLog() { std::filesystem::remove(file); }
  void append() const { std::ofstream(file, std::ios::app) << ::getpid() << "\n"; }
  [[nodiscard]] int readers() const {
    std::ifstream in(file);
    int n = 0;
    for (std::string line; std::getline(in, line);) ++n;
    return n;
  }
};

TEST(GuardedRead, ReadsInAChildThenHereAndReturnsWhatTheReadReturns) {
  REQUIRE_GUARD();
  const PidLog log;
  int reads_here = 0;  // the child's reads count in its own copy of this variable
  const int value = guarded_read("a.h5", "libhdf5", [&] {
    ++reads_here;
    log.append();
    return 42;
  });
  EXPECT_EQ(value, 42);
  EXPECT_EQ(reads_here, 1);
  EXPECT_EQ(log.readers(), 2);  // the child, then this process
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
  REQUIRE_GUARD();
  int reads_here = 0;
  const auto crashing = [&] {
    ++reads_here;
    std::raise(SIGSEGV);  // what a read past a buffer inside the library does
    return 0;
  };
  EXPECT_EQ(error_of([&] { guarded_read("broken.h5", "libhdf5", crashing); }),
            "broken.h5: libhdf5 crashed reading this file (segmentation fault): it is corrupted, or not the format "
            "its extension says; nothing was read");
  EXPECT_EQ(reads_here, 0);  // the crashing read never ran in this process
  EXPECT_THROW(guarded_read("broken.h5", "libhdf5", crashing), std::invalid_argument);
}

TEST(GuardedRead, HoldsWhereChildrenAreReapedAtOnce) {
  // A process that ignores SIGCHLD cannot wait for its children; the outcome comes through a pipe instead.
  REQUIRE_GUARD();
  const auto before = std::signal(SIGCHLD, SIG_IGN);
  const std::string message = error_of([] {
    guarded_read("broken.h5", "libhdf5", [] {
      std::raise(SIGFPE);
      return 0;
    });
  });
  const int value = guarded_read("a.h5", "libhdf5", [] { return 7; });
  std::signal(SIGCHLD, before);
  EXPECT_EQ(message, "broken.h5: libhdf5 failed reading this file (its reader process ended without a word): it is "
                     "corrupted, or not the format its extension says; nothing was read");
  EXPECT_EQ(value, 7);
}

TEST(GuardedRead, AReaderThatExitsIsAnError) {
  // How a sanitizer ends a process after a report (exit code 1), or a library that calls exit(), even exit(0).
  REQUIRE_GUARD();
  for (const int code : {1, 0}) {
    EXPECT_EQ(error_of([&] { guarded_read("odd.mat", "matio", [&] { std::_Exit(code); return 0; }); }),
              "odd.mat: matio failed reading this file (its reader process exited with " + std::to_string(code) +
                  "): it is corrupted, or not the format its extension says; nothing was read");
  }
}

TEST(GuardedRead, AnInterruptedReadSaysSoAndAnIgnoredSignalStaysIgnored) {
  REQUIRE_GUARD();
  const auto interrupted = [] {
    std::raise(SIGINT);  // Ctrl-C while the child reads: the child ends (default disposition)
    return 5;
  };
  EXPECT_THROW(guarded_read("big.mat", "matio", interrupted), std::runtime_error);
  EXPECT_EQ(error_of([&] { guarded_read("big.mat", "matio", interrupted); }),
            "big.mat: the process reading it was killed by signal " + std::to_string(SIGINT) +
                " (interrupted, or out of memory); nothing was read");
  // Under nohup (SIGINT, SIGHUP ignored) the child ignores them too, and the read goes on.
  const auto before = std::signal(SIGINT, SIG_IGN);
  const std::string message = error_of([&] { EXPECT_EQ(guarded_read("big.mat", "matio", interrupted), 5); });
  std::signal(SIGINT, before);
  EXPECT_EQ(message, "no error");
}

TEST(GuardedRead, AMultithreadedProcessReadsInProcessOnly) {
  // A fork of a multithreaded process may copy a lock another thread holds (thread-safe libhdf5): no child.
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  std::thread other([&] {
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return done; });
  });
  EXPECT_FALSE(single_threaded());
  const PidLog log;
  const int value = guarded_read("a.h5", "libhdf5", [&] {
    log.append();
    return 3;
  });
  {
    const std::lock_guard<std::mutex> lock(m);
    done = true;
  }
  cv.notify_one();
  other.join();
  EXPECT_EQ(value, 3);
  EXPECT_EQ(log.readers(), 1);
}


// Issue 23: assimp on mutated PLY files aborts (ai_assert), crashes (a face index of -1) or loops (a truncated
// header). Each is an error naming the field and the file, within the guard's time limit, without the
// library's own words on stderr.
TEST(GuardedRead, MalformedMeshFilesAreErrorsNotCrashesOrHangs) {
  REQUIRE_GUARD();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("guarded_mesh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string vertices = "0.01 -0.01 -0.01\n0.03 -0.01 -0.01\n0.01 0.01 -0.01\n0.01 -0.01 0.01\n";
  const struct {
    const char* name;
    std::string text, says;
  } cases[] = {
      {"index", header + vertices + "3 0 1 2\n3 0 1 -1\n3 0 2 3\n3 1 2 3\n", "assimp crashed reading this file"},
      {"count", header + vertices + "3 0 1 2\n-1 0 1 3\n3 0 2 3\n3 1 2 3\n", "assimp crashed reading this file"},
      {"truncated", "ply\nformat ascii 1.0\nelement ver", "assimp did not finish reading this file within 2 s"},
  };
  for (const auto& c : cases) {
    const std::string path = (dir / (std::string(c.name) + ".ply")).string();
    std::ofstream(path) << c.text;
    testing::internal::CaptureStderr();
    const std::string message = error_of([&] { (void)Mesh::from_file(path, 1.0, ObjectPose{}); });
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(message.rfind("object.file: cannot read mesh: " + path + ": ", 0), 0u) << c.name << ": " << message;
    EXPECT_NE(message.find(c.says), std::string::npos) << c.name << ": " << message;
    EXPECT_EQ(printed, "") << c.name;
  }
  // A well-formed file is read, through the same guard.
  const std::string good = (dir / "good.ply").string();
  std::ofstream(good) << header << vertices << "3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n";
  EXPECT_EQ(Mesh::from_file(good, 1.0, ObjectPose{})->triangles().size(), 4u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace vibrissa::io
