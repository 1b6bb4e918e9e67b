#pragma once
// Every file the tools write is written atomically: to a temporary beside the target (same directory, so the
// rename cannot cross file systems), flushed to disk, then renamed over the target. Until the rename, readers
// see the old file (or none); if the writer throws, the temporary is removed and the old target is untouched.
// Live temporaries are tracked for the signal handlers of temporary_files.hpp.
//
// Test hook: with the environment variable VIBRISSA_TEST_PAUSE_BEFORE_COMMIT set to a file name (e.g.
// "array.h5"), committing a target of that name prints "vibrissa: test hook: paused before renaming ..." to
// standard error and waits for a signal (used by the CLI tests to kill a run deterministically mid-write).
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace vibrissa::io {

class AtomicFile {
 public:
  /// Reserves the temporary `<dir>/.tmp-<pid>-<name>` for `target` (the name keeps its extension last:
  /// matio and matplotlib dispatch on it). Nothing is created on disk yet.
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&&) = delete;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Removes the temporary unless committed.
  ~AtomicFile();

  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  [[nodiscard]] const std::filesystem::path& temporary() const { return temporary_; }
  /// Flushes the temporary to disk and renames it over the target; throws std::runtime_error naming the
  /// target (the temporary is then removed) if the writer produced no file or the rename fails.
  void commit();
  /// Removes the temporary now.
  void discard() noexcept;

 private:
  std::filesystem::path target_, temporary_;
  std::size_t slot_ = 0;
  bool live_ = false;
};

/// Several outputs of one run, renamed over their targets together once all are written: a run that fails or
/// is killed while writing leaves every old output in place. Temporaries not committed are removed when the
/// object is destroyed.
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

/// One file: `write(temporary path as std::string)`, then commit. On any exception the temporary is removed,
/// the old target is untouched and the exception propagates.
template <class F>
void write_atomically(const std::filesystem::path& target, F&& write) {
  StagedFiles files;
  files.stage(target, std::forward<F>(write));
  files.commit();
}
/// One text file through a stream (see StagedFiles::stage_text).
void write_text_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write);

}  // namespace vibrissa::io
