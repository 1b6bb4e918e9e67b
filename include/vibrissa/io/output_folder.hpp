#pragma once
// The outputs of one run in one folder (`vibrissa trial --out`, `vibrissa array --out`), published as one set
// (docs/formats.md, "Output folders"): after any kill, even SIGKILL, the folder holds the complete older set
// or the complete new one, never a mix.
//
// How: every output is written into a fresh sibling folder `.tmp-<pid>-<name>` (given the folder's
// permissions, owner and group); at commit, whatever else the folder holds — files the run does not write —
// is hard-linked into it, and the two folders are swapped in one step (renameat2 with RENAME_EXCHANGE); the
// old folder, now at the sibling's name, is then removed. Entries this cannot link (subfolders, or files on a
// file system without hard links) are moved over right after the swap. Names listed as `older_outputs`
// (figures an older run drew) are not carried over. An output whose name is a symbolic link, FIFO, character
// device or socket in the folder is written through it (atomic_file.hpp) after the swap, and the entry stays.
//
// Where the folder cannot be swapped (it is a mount point or the root, its parent folder is not writable, or
// the file system has no RENAME_EXCHANGE) the outputs are written as `.tmp-<pid>-<name>` temporaries inside
// it and renamed over their targets one after the other once all are written: an error or a signal still
// leaves the older set, but a SIGKILL during those renames can leave a mix.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <list>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vibrissa/io/atomic_file.hpp"

namespace vibrissa::io {

class OutputFolder {
 public:
  /// Prepares to write into `folder` (created with its parents if missing; a symbolic link is followed). Throws
  /// std::invalid_argument naming it if it is not a folder, std::runtime_error if it cannot be created.
  explicit OutputFolder(const std::filesystem::path& folder, std::span<const std::string_view> older_outputs = {});
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  /// Removes everything staged unless committed.
  ~OutputFolder();

  /// Calls `write(temporary path as std::string)` for the output `name` (a file name, no folders). Safe to call
  /// from several threads at once. If `write` throws, the exception propagates (the run's other outputs stay
  /// staged until this object is destroyed).
  template <class F>
  void stage(std::string_view name, F&& write) {
    write(reserve(name));
  }
  /// A text output through a stream (write_text_file).
  void stage_text(std::string_view name, const std::function<void(std::ostream&)>& write);
  /// Publishes every staged output together (see above). Throws std::runtime_error naming the folder if the
  /// swap fails (then nothing changed) or if, after it, an entry could not be moved over (then the message
  /// says where it is).
  void commit();

  /// The folder, absolute, symbolic links resolved.
  [[nodiscard]] const std::filesystem::path& path() const { return folder_; }
  /// Whether the outputs are published by swapping folders (false: renamed one by one, see above).
  [[nodiscard]] bool swaps() const { return !staging_.empty(); }

 private:
  struct Entry;
  std::string reserve(std::string_view name);
  void discard() noexcept;
  void commit_in_place();
  void commit_by_swap();

  std::filesystem::path folder_, staging_;
  std::vector<std::string> older_outputs_;
  bool existed_ = false, committed_ = false;
  std::size_t staging_slot_ = 0;
  std::mutex mutex_;
  std::list<Entry> entries_;
};

}  // namespace vibrissa::io
