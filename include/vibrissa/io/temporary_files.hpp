#pragma once
// The live temporary files of this process (written by io::AtomicFile and io::OutputFolder, not yet renamed
// into place) and their temporary folders, kept in preallocated storage so that a signal handler can remove
// them. `install_cleanup_signal_handlers()` (called by the `vibrissa` CLI) makes SIGINT, SIGTERM and SIGHUP
// unlink every live temporary file, then remove every live temporary folder (rmdir: only when it is empty, so
// nothing else in it is ever deleted), and then re-raise the signal with its default action, so the exit
// status is the signal's and no `.tmp-*` file survives.
#include <cstddef>
#include <filesystem>

namespace vibrissa::io {

/// Most temporaries alive at once, and the longest path (bytes, with the terminating NUL) that fits a slot.
inline constexpr std::size_t kMaxLiveTemporaries = 64;
inline constexpr std::size_t kMaxTemporaryPath = 4096;

/// Records `path` as a live temporary file and returns its slot; throws std::runtime_error naming the path when
/// every slot is taken or the path is longer than kMaxTemporaryPath - 1 bytes.
std::size_t register_temporary(const std::filesystem::path& path);
/// The same for a temporary folder: the handler removes it after the files, if it is then empty.
std::size_t register_temporary_folder(const std::filesystem::path& path);
/// Forgets the slot (the file was renamed or removed). Thread-safe.
void unregister_temporary(std::size_t slot) noexcept;
/// Number of live temporaries (for tests).
std::size_t live_temporaries() noexcept;
/// Unlinks every live temporary file, then removes every live temporary folder that is empty.
/// Async-signal-safe: only atomics, unlink() and rmdir().
void unlink_live_temporaries() noexcept;

/// Installs SIGINT, SIGTERM and SIGHUP handlers that call unlink_live_temporaries() and re-raise the signal
/// with the default action. Signals ignored on entry (nohup) stay ignored. Throws std::runtime_error if
/// sigaction fails.
void install_cleanup_signal_handlers();

}  // namespace vibrissa::io
