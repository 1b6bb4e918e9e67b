#include "vibrissa/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "vibrissa/io/temporary_files.hpp"

namespace vibrissa::io {
namespace {

std::string quoted(const std::filesystem::path& p) {
  std::string out(1, '\'');
  out += p.string();
  out += '\'';
  return out;
}

// fsync of a file or directory; returns errno or 0. EINVAL means the file system cannot sync (ignored).
int sync_path(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return errno;
  const int rc = ::fsync(fd) == 0 || errno == EINVAL ? 0 : errno;
  ::close(fd);
  return rc;
}

void pause_if_test_hook_asks(const AtomicFile& file) {
  const char* name = std::getenv("VIBRISSA_TEST_PAUSE_BEFORE_COMMIT");
  if (name == nullptr || file.target().filename() != name) return;
  std::cerr << "vibrissa: test hook: paused before renaming " << file.temporary().string() << " to "
            << file.target().string() << std::endl;
  for (;;) ::pause();
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  if (target_.filename().empty()) throw std::invalid_argument("output path " + quoted(target_) + " names no file");
  temporary_ = target_.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + target_.filename().string());
  slot_ = register_temporary(temporary_);
  live_ = true;
}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : target_(std::move(other.target_)), temporary_(std::move(other.temporary_)), slot_(other.slot_),
      live_(other.live_) {
  other.live_ = false;
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
  if (!live_) return;
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
  unregister_temporary(slot_);
  live_ = false;
}

void AtomicFile::commit() {
  if (!live_) throw std::logic_error("output " + quoted(target_) + " was already committed or discarded");
  if (const int err = sync_path(temporary_, O_RDONLY); err != 0) {
    discard();
    throw std::runtime_error("cannot write " + quoted(target_) + ": " + std::strerror(err));
  }
  pause_if_test_hook_asks(*this);
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) {
    discard();
    throw std::runtime_error("cannot move the finished file into place at " + quoted(target_) + ": " +
                             ec.message());
  }
  unregister_temporary(slot_);
  live_ = false;
  const std::filesystem::path dir = target_.parent_path().empty() ? "." : target_.parent_path();
  sync_path(dir, O_RDONLY | O_DIRECTORY);  // best effort: makes the rename itself durable
}

void StagedFiles::stage_text(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write) {
  stage(target, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open " + quoted(target) + " for writing");
    write(out);
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + quoted(target) + " (disk full?)");
  });
}

void StagedFiles::commit() {
  for (AtomicFile& f : files_) f.commit();
  files_.clear();
}

void write_text_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write) {
  StagedFiles files;
  files.stage_text(target, write);
  files.commit();
}

}  // namespace vibrissa::io
