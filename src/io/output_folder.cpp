#include "vibrissa/io/output_folder.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "output_target.hpp"
#include "vibrissa/core/checks.hpp"
#include "vibrissa/io/figure_files.hpp"
#include "vibrissa/io/temporary_files.hpp"

namespace vibrissa::io {
namespace fs = std::filesystem;

struct OutputFolder::Entry {
  std::string name;
  fs::path temporary;               ///< staged file (unless `through`)
  std::size_t slot = 0;             ///< its slot in the temporary-file registry
  bool live = false;                ///< the temporary exists and is registered
  std::optional<AtomicFile> through;  ///< the folder's entry is a link or special file: written through it
};

namespace {

std::string error_text(int err) { return std::strerror(err); }

// Names in `dir` (without "." and ".."); throws std::runtime_error naming it.
std::vector<std::string> list_folder(const fs::path& dir) {
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr)
    throw std::runtime_error("cannot read the output folder " + quoted_path(dir) + ": " + error_text(errno));
  std::vector<std::string> names;
  while (const dirent* e = ::readdir(d)) {
    const std::string_view n = e->d_name;
    if (n != "." && n != "..") names.emplace_back(n);
  }
  ::closedir(d);
  return names;
}

bool is_folder_no_follow(const fs::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

// The absolute path of `folder` with every symbolic link resolved (the folder itself may not exist yet).
fs::path resolve_folder(const fs::path& requested, bool& exists) {
  if (requested.empty()) invalid_input("the output folder path is empty");
  const fs::path followed = follow_symlinks(requested);
  struct stat st {};
  exists = ::stat(followed.c_str(), &st) == 0;
  if (exists && !S_ISDIR(st.st_mode)) invalid_input("output folder " + quoted_path(requested) + " is not a folder");
  if (!exists && errno != ENOENT)
    throw std::runtime_error("cannot use the output folder " + quoted_path(requested) + ": " + error_text(errno));
  std::error_code ec;
  fs::path real = exists ? fs::canonical(followed, ec) : fs::weakly_canonical(fs::absolute(followed, ec), ec);
  if (ec)
    throw std::runtime_error("cannot use the output folder " + quoted_path(requested) + ": " + ec.message());
  if (real.filename().empty() && real != real.root_path()) real = real.parent_path();
  return real;
}

// The process's working directory if it lies in `folder` (the swap would leave it in the old folder).
std::optional<fs::path> working_directory_inside(const fs::path& folder) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (ec) return std::nullopt;
  const auto [f, c] = std::mismatch(folder.begin(), folder.end(), cwd.begin(), cwd.end());
  if (f != folder.end()) return std::nullopt;
  return cwd;
}

}  // namespace

OutputFolder::OutputFolder(const fs::path& folder, std::span<const std::string_view> older_outputs) {
  for (const std::string_view n : older_outputs) older_outputs_.emplace_back(n);
  folder_ = resolve_folder(folder, existed_);
  if (!existed_) {
    std::error_code ec;
    fs::create_directories(folder_.parent_path(), ec);
    if (ec)
      throw std::runtime_error("cannot create the output folder " + quoted_path(folder) + ": " + ec.message());
  }
  // The staging sibling (none for the root, whose parent is itself).
  const fs::path parent = folder_.parent_path();
  if (folder_.has_filename() && parent != folder_) {
    const std::string base = ".tmp-" + std::to_string(::getpid()) + "-";
    for (int k = 0; k < 100 && staging_.empty(); ++k) {
      const fs::path candidate =
          parent / (base + (k == 0 ? std::string() : std::to_string(k) + "-") + folder_.filename().string());
      if (::mkdir(candidate.c_str(), existed_ ? 0700 : 0777) == 0) {
        staging_ = candidate;
      } else if (errno != EEXIST) {
        break;  // no writable parent: published in place
      }
    }
  }
  if (staging_.empty() && !existed_) {
    if (::mkdir(folder_.c_str(), 0777) != 0 && errno != EEXIST)
      throw std::runtime_error("cannot create the output folder " + quoted_path(folder) + ": " + error_text(errno));
    existed_ = true;
  }
  if (staging_.empty()) return;
  if (existed_) copy_permissions(staging_, folder_);  // before any file is made in it (a set-group-ID folder)
  try {
    staging_slot_ = register_temporary_folder(staging_);
  } catch (...) {
    ::rmdir(staging_.c_str());
    throw;
  }
}

OutputFolder::~OutputFolder() { discard(); }

void OutputFolder::discard() noexcept {
  for (Entry& e : entries_) {
    if (e.live) {
      ::unlink(e.temporary.c_str());
      unregister_temporary(e.slot);
      e.live = false;
    }
    if (e.through) e.through->discard();
  }
  if (!staging_.empty() && !committed_) {
    ::rmdir(staging_.c_str());
    unregister_temporary(staging_slot_);
    staging_.clear();
  }
}

std::string OutputFolder::reserve(std::string_view name) {
  const fs::path file(name);
  if (name.empty() || file.has_parent_path() || name == "." || name == "..")
    throw std::logic_error("OutputFolder: '" + std::string(name) + "' is not a file name");
  const std::lock_guard lock(mutex_);
  if (committed_) throw std::logic_error("OutputFolder: staged after commit");
  for (const Entry& e : entries_)
    if (e.name == name) throw std::logic_error("OutputFolder: '" + std::string(name) + "' staged twice");
  Entry& e = entries_.emplace_back();
  e.name = name;
  const fs::path target = folder_ / file;
  struct stat st {};
  if (::lstat(target.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    invalid_input("cannot write " + quoted_path(target) + ": it is a directory");
  if (::lstat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    e.through.emplace(target);  // a link, FIFO, device or socket: written through it
    return e.through->temporary().string();
  }
  e.temporary = staging_.empty() ? folder_ / (".tmp-" + std::to_string(::getpid()) + "-" + std::string(name))
                                 : staging_ / file;
  e.slot = register_temporary(e.temporary);
  e.live = true;
  create_exclusively(e.temporary, target);
  return e.temporary.string();
}

void OutputFolder::stage_text(std::string_view name, const std::function<void(std::ostream&)>& write) {
  stage(name, [&](const std::string& temporary) { write_text_file(temporary, folder_ / fs::path(name), write); });
}

void OutputFolder::commit() {
  const std::lock_guard lock(mutex_);
  if (committed_) throw std::logic_error("OutputFolder: committed twice");
  for (const Entry& e : entries_) {
    struct stat st {};
    if (e.live && (::lstat(e.temporary.c_str(), &st) != 0 || !S_ISREG(st.st_mode)))
      throw std::runtime_error("cannot write " + quoted_path(folder_ / e.name) + ": its writer left no file");
    if (e.live) {
      if (const int err = sync_path(e.temporary, O_RDONLY); err != 0)
        throw std::runtime_error("cannot write " + quoted_path(folder_ / e.name) + ": " + error_text(err));
    }
  }
  for (const Entry& e : entries_)
    if (e.live) pause_if_test_hook_asks(e.temporary, folder_ / e.name);
  if (staging_.empty())
    commit_in_place();
  else
    commit_by_swap();
  // Outputs written through a link or special file of the folder, after the set.
  for (Entry& e : entries_)
    if (e.through) e.through->commit();
}

void OutputFolder::commit_in_place() {
  remove_figures(folder_, std::vector<std::string_view>(older_outputs_.begin(), older_outputs_.end()));
  for (Entry& e : entries_) {
    if (!e.live) continue;
    const fs::path target = folder_ / e.name;
    if (std::error_code ec; fs::exists(target, ec)) copy_permissions(e.temporary, target);
    if (::rename(e.temporary.c_str(), target.c_str()) != 0)
      throw std::runtime_error("cannot move the finished file into place at " + quoted_path(target) + ": " +
                               error_text(errno));
    unregister_temporary(e.slot);
    e.live = false;
  }
  committed_ = true;
  sync_path(folder_, O_RDONLY | O_DIRECTORY);
}

void OutputFolder::commit_by_swap() {
  const auto is_staged_file = [&](const std::string& n) {
    return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.live && e.name == n; });
  };
  const auto is_older_output = [&](const std::string& n) {
    return std::find(older_outputs_.begin(), older_outputs_.end(), n) != older_outputs_.end();
  };
  // 1. Carry whatever else the folder holds: hard links now, the rest moved after the swap.
  std::vector<std::string> linked, to_move;
  const auto undo_links = [&] {
    for (const std::string& n : linked) ::unlink((staging_ / n).c_str());
  };
  const std::optional<fs::path> cwd = existed_ ? working_directory_inside(folder_) : std::nullopt;
  try {
    if (existed_) {
      for (const std::string& n : list_folder(folder_)) {
        if (is_staged_file(n) || is_older_output(n)) continue;
        const fs::path from = folder_ / n;
        if (!is_folder_no_follow(from) && ::linkat(AT_FDCWD, from.c_str(), AT_FDCWD, (staging_ / n).c_str(), 0) == 0)
          linked.push_back(n);
        else
          to_move.push_back(n);
      }
    }
    sync_path(staging_, O_RDONLY | O_DIRECTORY);
  } catch (...) {
    undo_links();
    throw;
  }
  // 2. The swap: one step from the old set to the new one.
  const unsigned flags = existed_ ? RENAME_EXCHANGE : RENAME_NOREPLACE;
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, folder_.c_str(), flags) != 0) {
    const int err = errno;
    undo_links();
    if (err == EINVAL || err == ENOSYS || err == EBUSY || err == EXDEV || err == ENOTSUP || err == EPERM) {
      // Not swappable here (a mount point, a file system without RENAME_EXCHANGE): one by one, in place.
      if (!existed_ && ::mkdir(folder_.c_str(), 0777) != 0 && errno != EEXIST)
        throw std::runtime_error("cannot create the output folder " + quoted_path(folder_) + ": " + error_text(errno));
      for (Entry& e : entries_) {
        if (!e.live) continue;
        const fs::path moved = folder_ / (".tmp-" + std::to_string(::getpid()) + "-" + e.name);
        if (::rename(e.temporary.c_str(), moved.c_str()) != 0)
          throw std::runtime_error("cannot move the finished file into " + quoted_path(folder_) + ": " +
                                   error_text(errno));
        unregister_temporary(e.slot);
        e.temporary = moved;
        e.slot = register_temporary(moved);
      }
      ::rmdir(staging_.c_str());
      unregister_temporary(staging_slot_);
      staging_.clear();
      commit_in_place();
      return;
    }
    throw std::runtime_error("cannot publish the outputs in " + quoted_path(folder_) + ": " + error_text(err));
  }
  committed_ = true;
  for (Entry& e : entries_) {
    if (!e.live) continue;
    unregister_temporary(e.slot);  // renamed with the folder
    e.live = false;
  }
  unregister_temporary(staging_slot_);  // the name now holds the older folder (or nothing)
  const fs::path old = staging_;  // the older folder now has the sibling's name
  if (cwd) {  // the working directory moved with the old folder: back to the same path in the new one
    std::error_code ec;
    fs::current_path(*cwd, ec);
    if (ec) fs::current_path(folder_, ec);
  }
  // 3. Entries that could not be linked move over; then the old folder goes.
  std::string stranded;
  for (const std::string& n : to_move)
    if (::rename((old / n).c_str(), (folder_ / n).c_str()) != 0)
      stranded += (stranded.empty() ? "" : ", ") + quoted_path(n) + " (" + error_text(errno) + ")";
  if (existed_) {
    for (const std::string& n : list_folder(old)) {
      const fs::path p = old / n;
      if (is_older_output(n)) {
        std::error_code ec;
        fs::remove_all(p, ec);
      } else if (!is_folder_no_follow(p)) {
        ::unlink(p.c_str());
      }
    }
  }
  if (existed_) ::rmdir(old.c_str());
  staging_.clear();
  sync_path(folder_.parent_path(), O_RDONLY | O_DIRECTORY);
  if (!stranded.empty())
    throw std::runtime_error("the new outputs are in " + quoted_path(folder_) + ", but " + stranded +
                             " could not be moved back into it from " + quoted_path(old));
}

}  // namespace vibrissa::io
