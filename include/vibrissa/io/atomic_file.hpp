#pragma once
// Every file the tools write goes through here (docs/formats.md, "Output paths"). What a path names is decided
// once (src/io/output_target.hpp):
//  - a regular file, or nothing yet: written to a temporary beside it (same directory, so the rename cannot
//    cross file systems), flushed to disk, then renamed over it; an older file's permissions are kept. Until
//    the rename readers see the old file (or none); if the writer throws, the temporary is removed and the old
//    file is untouched;
//  - a symbolic link: followed to its final target, which is replaced as above (the link stays a link; a
//    dangling link gets the file it names);
//  - "-" (standard output), a character device such as /dev/null, a FIFO or a socket: written to directly
//    (never created, truncated or replaced);
//  - anything else (a directory, a block device): std::invalid_argument naming the path, before any writing.
// Writers that need a file name (HDF5, matio) write direct targets through a temporary in a private folder
// of the system's temporary directory, copied to the target at commit. Live temporaries are tracked for the
// signal handlers of temporary_files.hpp. A run's several outputs in one folder are published together by
// io::OutputFolder (output_folder.hpp).
//
// Test hook: with the environment variable VIBRISSA_TEST_PAUSE_BEFORE_COMMIT set to a file name (e.g.
// "array.h5"), committing a target of that name prints "vibrissa: test hook: paused before renaming ..." to
// standard error and waits for a signal (used by the CLI tests to kill a run deterministically mid-write).
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace vibrissa::io {

struct OutputTarget;

class AtomicFile {
 public:
  /// Resolves `target` (throws std::invalid_argument naming it if it cannot be written) and creates an empty
  /// temporary for it, exclusively: `<dir>/.tmp-<pid>-<name>` beside a file (the name keeps its extension
  /// last: matio and matplotlib dispatch on it), `<tmp>/vibrissa-XXXXXX/<name>` for a direct target.
  explicit AtomicFile(const std::filesystem::path& target);
  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&&) = delete;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Removes the temporary unless committed.
  ~AtomicFile();

  /// The path as given.
  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  [[nodiscard]] const std::filesystem::path& temporary() const { return temporary_; }
  /// Written to directly ("-", a character device, FIFO or socket) rather than replaced.
  [[nodiscard]] bool direct() const;
  /// Flushes the temporary to disk and renames it over the target (or copies it to a direct target); throws
  /// std::runtime_error naming the target (the temporary is then removed) if the writer removed the temporary
  /// or the rename or a write fails.
  void commit();
  /// Removes the temporary now.
  void discard() noexcept;

 private:
  std::filesystem::path target_, temporary_, private_folder_;
  std::unique_ptr<OutputTarget> resolved_;
  std::size_t slot_ = 0, folder_slot_ = 0;
  bool live_ = false;
};

/// Several outputs of one run, renamed over their targets together once all are written: a run that fails or
/// is killed while writing leaves every old output in place. Temporaries not committed are removed when the
/// object is destroyed. (Outputs in one folder: OutputFolder, which publishes them as one set.)
class StagedFiles {
 public:
  /// Calls `write(temporary path as std::string)` for `target`; if it throws, the exception propagates and
  /// the temporaries are removed with this object.
  template <class F>
  void stage(const std::filesystem::path& target, F&& write) {
    files_.emplace_back(target);
    write(files_.back().temporary().string());
  }
  /// Writes a text file through a stream; throws std::runtime_error naming `target` if the stream fails.
  void stage_text(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write);
  /// Renames every temporary over its target, in staging order. (Should a rename fail, which takes a
  /// directory turned read-only meanwhile, the targets renamed before it stay replaced.)
  void commit();

 private:
  std::vector<AtomicFile> files_;
};

/// Writes a text file through `write(stream)` to a temporary path (the stream is checked; throws
/// std::runtime_error naming `target` if it fails). The one text writer of AtomicFile, StagedFiles and
/// OutputFolder.
void write_text_file(const std::string& temporary, const std::filesystem::path& target,
                     const std::function<void(std::ostream&)>& write);

/// One file: `write(temporary path as std::string)`, then commit. On any exception the temporary is removed,
/// the old target is untouched and the exception propagates.
template <class F>
void write_atomically(const std::filesystem::path& target, F&& write) {
  StagedFiles files;
  files.stage(target, std::forward<F>(write));
  files.commit();
}
/// One text file through a stream. A direct target ("-", a FIFO, a device, a socket) receives the text as it
/// is written (each flush of the stream reaches it, as `solve --jsonl` needs for a reader at the other end of
/// a FIFO); any other target is replaced atomically when the writer returns.
void write_text_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write);

}  // namespace vibrissa::io
