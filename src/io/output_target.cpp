#include "output_target.hpp"

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::io {

namespace fs = std::filesystem;

std::string quoted_path(const fs::path& p) {
  std::string out(1, '\'');
  out += printable_text(p.native());
  out += '\'';
  return out;
}

namespace {

[[noreturn]] void refuse(const fs::path& requested, const std::string& why) {
  invalid_input("cannot write " + quoted_path(requested) + ": " + why);
}

}  // namespace

fs::path follow_symlinks(const fs::path& requested) {
  fs::path p = requested;
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    if (hops == 40) refuse(requested, "too many levels of symbolic links (a loop?)");
    std::vector<char> buf(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 4095) + 1);
    const ssize_t n = ::readlink(p.c_str(), buf.data(), buf.size());
    if (n < 0) refuse(requested, std::string("cannot read the symbolic link ") + quoted_path(p) + ": " + std::strerror(errno));
    const fs::path next(std::string(buf.data(), static_cast<std::size_t>(n)));
    p = next.is_absolute() ? next : p.parent_path() / next;
  }
}

OutputTarget resolve_output_target(const fs::path& requested) {
  OutputTarget t;
  t.requested = requested;
  if (requested.native() == "-") {
    t.kind = OutputTarget::Kind::standard_output;
    t.path = requested;
    return t;
  }
  if (requested.empty()) invalid_input("an output path is empty");
  t.path = follow_symlinks(requested);
  struct stat st {};
  if (::stat(t.path.c_str(), &st) == 0) {
    if (S_ISREG(st.st_mode)) {
      t.exists = true;
    } else if (S_ISCHR(st.st_mode)) {
      t.kind = OutputTarget::Kind::character_device;
    } else if (S_ISFIFO(st.st_mode)) {
      t.kind = OutputTarget::Kind::fifo;
    } else if (S_ISSOCK(st.st_mode)) {
      t.kind = OutputTarget::Kind::socket;
    } else if (S_ISDIR(st.st_mode)) {
      refuse(requested, "it is a directory");
    } else if (S_ISBLK(st.st_mode)) {
      refuse(requested, "it is a block device (vibrissa writes regular files, FIFOs, character devices and sockets)");
    } else {
      refuse(requested, "it is neither a regular file nor a FIFO, character device or socket");
    }
    return t;
  }
  if (errno != ENOENT) refuse(requested, std::strerror(errno));
  // Nothing there (or a dangling link): a new file in the folder the path names.
  if (t.path.filename().empty() || t.path.filename() == "." || t.path.filename() == "..")
    refuse(requested, "the path names no file");
  const fs::path folder = t.path.parent_path().empty() ? fs::path(".") : t.path.parent_path();
  struct stat dir {};
  if (::stat(folder.c_str(), &dir) != 0)
    refuse(requested, "the folder " + quoted_path(folder) + " does not exist (" + std::strerror(errno) + ")");
  if (!S_ISDIR(dir.st_mode)) refuse(requested, quoted_path(folder) + " is not a folder");
  return t;
}

int open_direct_target(const OutputTarget& t) {
  const auto fail = [&](const char* doing) -> int {
    throw std::runtime_error("cannot write " + quoted_path(t.requested) + ": " + doing + ": " + std::strerror(errno));
  };
  switch (t.kind) {
    case OutputTarget::Kind::standard_output: {
      std::cout.flush();
      std::fflush(stdout);
      const int fd = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 0);
      return fd >= 0 ? fd : fail("standard output is closed");
    }
    case OutputTarget::Kind::character_device:
    case OutputTarget::Kind::fifo: {
      int fd;
      do fd = ::open(t.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);  // never O_CREAT or O_TRUNC
      while (fd < 0 && errno == EINTR);
      return fd >= 0 ? fd : fail("cannot open it");
    }
    case OutputTarget::Kind::socket: {
      sockaddr_un address{};
      address.sun_family = AF_UNIX;
      if (t.path.native().size() >= sizeof address.sun_path) {
        errno = ENAMETOOLONG;
        return fail("cannot connect to the socket");
      }
      std::memcpy(address.sun_path, t.path.c_str(), t.path.native().size() + 1);
      const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
      if (fd < 0) return fail("cannot create a socket");
      if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        const int err = errno;
        ::close(fd);
        errno = err;
        return fail("cannot connect to the socket");
      }
      return fd;
    }
    case OutputTarget::Kind::file: break;
  }
  throw std::logic_error("open_direct_target: " + quoted_path(t.requested) + " is a regular file");
}

void write_all(int fd, const char* data, std::size_t size, const fs::path& what) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error("cannot write " + quoted_path(what) + ": " + std::strerror(errno));
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void copy_file_to(const fs::path& from, int fd, const fs::path& what) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) throw std::runtime_error("cannot write " + quoted_path(what) + ": cannot read back its temporary " +
                                       quoted_path(from) + ": " + std::strerror(errno));
  std::vector<char> buf(1 << 16);
  for (;;) {
    const ssize_t n = ::read(in, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(in);
      throw std::runtime_error("cannot write " + quoted_path(what) + ": cannot read back its temporary: " +
                               std::strerror(err));
    }
    if (n == 0) break;
    try {
      write_all(fd, buf.data(), static_cast<std::size_t>(n), what);
    } catch (...) {
      ::close(in);
      throw;
    }
  }
  ::close(in);
}

void create_exclusively(const fs::path& path, const fs::path& target) {
  for (int attempt = 0;; ++attempt) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return;
    }
    const int err = errno;
    struct stat st {};
    if (err == EEXIST && attempt == 0 && ::lstat(path.c_str(), &st) == 0 && !S_ISDIR(st.st_mode) &&
        ::unlink(path.c_str()) == 0)
      continue;
    throw std::runtime_error("cannot write " + quoted_path(target) + ": cannot create its temporary " +
                             quoted_path(path) + " (outputs are written beside their target and renamed over it): " +
                             std::strerror(err));
  }
}

int sync_path(const fs::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return errno;
  const int rc = ::fsync(fd) == 0 || errno == EINVAL ? 0 : errno;
  ::close(fd);
  return rc;
}

void copy_permissions(const fs::path& path, const fs::path& model) {
  struct stat st {};
  if (::stat(model.c_str(), &st) != 0) return;
  if (::chown(path.c_str(), st.st_uid, st.st_gid) != 0) {
    [[maybe_unused]] const int group_only = ::chown(path.c_str(), static_cast<uid_t>(-1), st.st_gid);
  }
  ::chmod(path.c_str(), st.st_mode & 0777);  // permission bits only: never set-user-ID
}

void pause_if_test_hook_asks(const fs::path& temporary, const fs::path& target) {
  const char* name = std::getenv("VIBRISSA_TEST_PAUSE_BEFORE_COMMIT");
  if (name == nullptr || target.filename() != name) return;
  std::cerr << "vibrissa: test hook: paused before renaming " << temporary.string() << " to " << target.string()
            << std::endl;
  for (;;) ::pause();
}

}  // namespace vibrissa::io
