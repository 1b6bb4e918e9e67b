#pragma once
// Files parsed by third-party libraries (HDF5 by libhdf5, MATLAB .mat by matio) are read once in a child process
// before they are read here: a corrupted file that crashes the library (libhdf5 1.10.8 reads past buffers and
// divides by zero on mutated files: docs/formats.md, "Files parsed by libraries") ends the child, not the
// caller, and becomes an error that names the file. Only a single-threaded process forks for this: a fork of a
// multithreaded one copies locks other threads may hold (Debian's libhdf5 is built thread-safe, with a global
// lock), and its child could wait on them forever; so the CLI is guarded, and a Python process, which usually
// runs other threads (NumPy's BLAS pool, the package's worker thread), usually is not. Our own parsers (JSON,
// CSV, Janelia, pickle) are fuzzed and read in-process only.
#include <string>
#include <string_view>

namespace vibrissa::io {

/// Runs `read` in a forked child process and discards what it returns. Returns normally if the child returned
/// or threw (the caller then reads the file itself, which returns or throws the same); throws
/// std::invalid_argument naming `path` and `library` if the child crashed (SIGSEGV, SIGBUS, SIGFPE, SIGILL,
/// SIGABRT, SIGSYS, SIGTRAP) or ended without reporting (a sanitizer's exit, a library's exit()), and
/// std::runtime_error if another signal ended it (Ctrl-C, a kill, the out-of-memory killer). Returns at once,
/// without the guard, in a process with more than one thread, where fork fails, or off Linux. With
/// `timeout_s` > 0 a child still reading after that many seconds is killed and std::invalid_argument says so
/// (a malformed file can make a library loop: assimp on a truncated PLY header).
void probe_in_child(const std::string& path, std::string_view library, void (*read)(const void* context),
                    const void* context, double timeout_s = 0.0);

/// `read()` (a callable returning the file's contents), after probe_in_child() has read the file once in a
/// child process.
template <class Read>
auto guarded_read(const std::string& path, std::string_view library, const Read& read, double timeout_s = 0.0) {
  probe_in_child(
      path, library, [](const void* r) { (void)(*static_cast<const Read*>(r))(); }, &read, timeout_s);
  return read();
}

/// Whether this process has exactly one thread (Linux: /proc/self/task); false where that cannot be told.
bool single_threaded();

}  // namespace vibrissa::io
