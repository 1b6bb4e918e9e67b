#include "vibrissa/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <streambuf>
#include <system_error>

#include "output_target.hpp"
#include "vibrissa/io/temporary_files.hpp"

namespace vibrissa::io {
namespace fs = std::filesystem;

namespace {

// A private folder (mode 0700) in the system's temporary directory for the temporary of a direct target.
fs::path make_private_folder(const fs::path& target) {
  std::error_code ec;
  fs::path base = fs::temp_directory_path(ec);
  if (ec) base = "/tmp";
  std::string pattern = (base / "vibrissa-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw std::runtime_error("cannot write " + quoted_path(target) + ": cannot create a temporary folder in " +
                             quoted_path(base) + ": " + std::strerror(errno));
  return pattern;
}

// A stream buffer writing to a descriptor: every flush of the stream reaches it. A failed write ends the
// stream (badbit) and keeps the reason.
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(int fd) : fd_(fd) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  [[nodiscard]] const std::string& error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (sync() != 0) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override {
    const char* data = pbase();
    std::size_t size = static_cast<std::size_t>(pptr() - pbase());
    while (size > 0) {
      const ssize_t n = ::write(fd_, data, size);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        error_ = std::strerror(errno);
        return -1;
      }
      data += n;
      size -= static_cast<std::size_t>(n);
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return 0;
  }

 private:
  int fd_;
  std::array<char, 1 << 16> buffer_{};
  std::string error_;
};

}  // namespace

AtomicFile::AtomicFile(const fs::path& target)
    : target_(target), resolved_(std::make_unique<OutputTarget>(resolve_output_target(target))) {
  const std::string name = target_.native() == "-" ? std::string("stdout") : target_.filename().string();
  if (resolved_->direct()) {
    private_folder_ = make_private_folder(target_);
    temporary_ = private_folder_ / name;
  } else {
    temporary_ = resolved_->path.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + name);
  }
  try {
    if (!private_folder_.empty()) folder_slot_ = register_temporary_folder(private_folder_);
    slot_ = register_temporary(temporary_);
  } catch (...) {
    if (!private_folder_.empty()) {
      unregister_temporary(folder_slot_);
      ::rmdir(private_folder_.c_str());
    }
    throw;
  }
  live_ = true;
  try {
    create_exclusively(temporary_, target_);
  } catch (...) {
    discard();
    throw;
  }
}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : target_(std::move(other.target_)), temporary_(std::move(other.temporary_)),
      private_folder_(std::move(other.private_folder_)), resolved_(std::move(other.resolved_)), slot_(other.slot_),
      folder_slot_(other.folder_slot_), live_(other.live_) {
  other.live_ = false;
}

AtomicFile::~AtomicFile() { discard(); }

bool AtomicFile::direct() const { return resolved_ && resolved_->direct(); }

void AtomicFile::discard() noexcept {
  if (!live_) return;
  ::unlink(temporary_.c_str());
  unregister_temporary(slot_);
  if (!private_folder_.empty()) {
    ::rmdir(private_folder_.c_str());
    unregister_temporary(folder_slot_);
  }
  live_ = false;
}

void AtomicFile::commit() {
  if (!live_) throw std::logic_error("output " + quoted_path(target_) + " was already committed or discarded");
  struct stat st {};
  if (::lstat(temporary_.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    discard();
    throw std::runtime_error("cannot write " + quoted_path(target_) + ": its writer left no file");
  }
  if (resolved_->direct()) {
    pause_if_test_hook_asks(temporary_, target_);
    try {
      const int fd = open_direct_target(*resolved_);
      try {
        copy_file_to(temporary_, fd, target_);
      } catch (...) {
        ::close(fd);
        throw;
      }
      if (::close(fd) != 0 && errno != EINTR)
        throw std::runtime_error("cannot write " + quoted_path(target_) + ": " + std::strerror(errno));
    } catch (...) {
      discard();
      throw;
    }
    discard();
    return;
  }
  if (const int err = sync_path(temporary_, O_RDONLY); err != 0) {
    discard();
    throw std::runtime_error("cannot write " + quoted_path(target_) + ": " + std::strerror(err));
  }
  if (resolved_->exists) copy_permissions(temporary_, resolved_->path);
  pause_if_test_hook_asks(temporary_, target_);
  if (::rename(temporary_.c_str(), resolved_->path.c_str()) != 0) {
    const int err = errno;
    discard();
    throw std::runtime_error("cannot move the finished file into place at " + quoted_path(target_) + ": " +
                             std::strerror(err));
  }
  unregister_temporary(slot_);
  live_ = false;
  const fs::path dir = resolved_->path.parent_path().empty() ? "." : resolved_->path.parent_path();
  sync_path(dir, O_RDONLY | O_DIRECTORY);  // best effort: makes the rename itself durable
}

void write_text_file(const std::string& temporary, const fs::path& target,
                     const std::function<void(std::ostream&)>& write) {
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + quoted_path(target) + ": cannot open its temporary");
  // A stream failure keeps no reason; the system's is in errno right after the failed write (cleared first,
  // so that a stale value is never reported).
  const auto fail = [&](int err) {
    throw std::runtime_error("cannot write " + quoted_path(target) + ": " +
                             (err != 0 ? std::string(std::strerror(err)) : std::string("write failed (disk full?)")));
  };
  errno = 0;
  write(out);
  out.flush();
  if (!out) fail(errno);
  errno = 0;
  out.close();
  if (!out) fail(errno);
}

void StagedFiles::stage_text(const fs::path& target, const std::function<void(std::ostream&)>& write) {
  stage(target, [&](const std::string& temporary) { write_text_file(temporary, target, write); });
}

void StagedFiles::commit() {
  for (AtomicFile& f : files_) f.commit();
  files_.clear();
}

void write_text_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write) {
  const OutputTarget resolved = resolve_output_target(target);
  if (!resolved.direct()) {
    StagedFiles files;
    files.stage_text(target, write);
    files.commit();
    return;
  }
  const int fd = open_direct_target(resolved);
  DescriptorBuffer buffer(fd);
  std::ostream out(&buffer);
  try {
    write(out);
    out.flush();
  } catch (...) {
    ::close(fd);
    throw;
  }
  const bool closed = ::close(fd) == 0 || errno == EINTR;
  if (!out || !closed)
    throw std::runtime_error("cannot write " + quoted_path(target) + ": " +
                             (buffer.error().empty() ? std::string(std::strerror(errno)) : buffer.error()));
}

}  // namespace vibrissa::io
