#pragma once
// Files parsed by third-party libraries (HDF5 by libhdf5, MATLAB .mat by matio) are read once in a child
// process before they are read here: a corrupted or hostile file that crashes the library (a read past a
// buffer in its object-header code, found by fuzzing: docs/formats.md, "Fuzzing") ends the child, not the
// caller, and becomes an error that names the file. Our own parsers (JSON, CSV, Janelia, pickle) are fuzzed and
// read in-process only.
#include <string>
#include <string_view>

namespace vibrissa::io {

/// Runs `read` in a forked child process and discards what it returns. Returns normally if the child returned
/// or threw (a file the library reads without crashing: the caller then reads it itself, which returns or
/// throws the same); throws std::invalid_argument naming `path` and `library` if the child ended any other way
/// (killed by a signal, or stopped by a sanitizer). Where fork is unavailable, or fails, returns at once.
void probe_in_child(const std::string& path, std::string_view library, void (*read)(const void* context),
                    const void* context);

/// `read()` (a callable returning the file's contents), after probe_in_child() has read the file once in a
/// child process.
template <class Read>
auto guarded_read(const std::string& path, std::string_view library, const Read& read) {
  probe_in_child(
      path, library, [](const void* r) { (void)(*static_cast<const Read*>(r))(); }, &read);
  return read();
}

}  // namespace vibrissa::io
