#pragma once
// What an output path names, decided in one place for every file the tools write (docs/formats.md, "Output
// paths"): a regular file (or nothing yet) is replaced atomically by a temporary renamed over it; "-" is
// standard output; an existing character device (/dev/null), FIFO or socket is written to directly; a symbolic
// link is followed to its final target, which is then treated by these rules (a dangling link: the file it
// names is created); anything else (a directory, a block device) is an error naming the path.
#include <cstddef>
#include <filesystem>
#include <string>

namespace vibrissa::io {

struct OutputTarget {
  enum class Kind { file, standard_output, character_device, fifo, socket };
  Kind kind = Kind::file;
  /// Where the bytes go: for `file` the path renamed over (symbolic links followed; the final link target),
  /// otherwise the device, FIFO or socket itself ("-" for standard output).
  std::filesystem::path path;
  /// The path as given (for messages).
  std::filesystem::path requested;
  /// `file` only: an older file is there (its permissions are kept).
  bool exists = false;
  /// Written to directly (everything but `file`): no temporary beside it, no rename.
  [[nodiscard]] bool direct() const { return kind != Kind::file; }
};

/// Resolves `requested` by the rules above. Throws std::invalid_argument naming the path for an empty name, a
/// directory, a block device or other special file, a loop of symbolic links or a folder that does not exist.
OutputTarget resolve_output_target(const std::filesystem::path& requested);

/// Follows a chain of symbolic links (at most 40) to the path it ends at, which may not exist (a dangling
/// link); `requested` itself if it is not a link. Relative link targets are taken relative to the link's
/// folder. Throws std::invalid_argument naming `requested` for a loop (or a chain longer than 40).
std::filesystem::path follow_symlinks(const std::filesystem::path& requested);

/// Opens a direct target for writing: standard output (a duplicate of descriptor 1, after flushing
/// std::cout and stdout), a character device or FIFO (O_WRONLY, never O_CREAT or O_TRUNC; a FIFO waits
/// for a reader, as a shell's redirection does) or a socket (connected as a stream). Returns the descriptor;
/// throws std::runtime_error naming the path.
int open_direct_target(const OutputTarget& target);

/// Writes all `size` bytes to `fd` (retrying short writes and EINTR); throws std::runtime_error naming `what`
/// with the system's reason (e.g. "No space left on device").
void write_all(int fd, const char* data, std::size_t size, const std::filesystem::path& what);
/// Copies the file `from` to `fd` (see write_all).
void copy_file_to(const std::filesystem::path& from, int fd, const std::filesystem::path& what);

/// "'<path>'" for messages (printable_text of the path).
std::string quoted_path(const std::filesystem::path& p);

// Shared by AtomicFile and OutputFolder.
/// Creates `path` as a new empty file (mode 0666 less the umask) without following anything already there:
/// a stale file of an earlier process with the same id (or a link someone placed at the predictable name)
/// is removed first. Throws std::runtime_error naming `target`.
void create_exclusively(const std::filesystem::path& path, const std::filesystem::path& target);
/// fsync of a file (or, with O_DIRECTORY in `flags`, a folder); returns errno or 0 (EINVAL, a file system
/// that cannot sync, counts as success).
int sync_path(const std::filesystem::path& path, int flags);
/// Gives `path` the permission bits (and, where allowed, the owner and group) of `model`, best effort.
void copy_permissions(const std::filesystem::path& path, const std::filesystem::path& model);
/// The test hook of atomic_file.hpp: pauses for a signal if VIBRISSA_TEST_PAUSE_BEFORE_COMMIT names `target`.
void pause_if_test_hook_asks(const std::filesystem::path& temporary, const std::filesystem::path& target);

}  // namespace vibrissa::io
