// Output paths are written the way a Unix tool writes them (io/atomic_file.hpp): a regular file is replaced
// atomically, a symbolic link's target is replaced (never the link), "-", character devices, FIFOs and
// sockets are written to directly (never replaced), and anything else is an error naming the path before any
// writing. As root and as another user.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>

#include "fresh_dir.hpp"
#include "vibrissa/io/atomic_file.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/io/temporary_files.hpp"

namespace fs = std::filesystem;
using vibrissa::test::fresh_dir;
using namespace vibrissa::io;

namespace {

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

mode_t kind_of(const fs::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 ? (st.st_mode & S_IFMT) : 0;
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

void write_text(const fs::path& target, const std::string& text) {
  write_text_atomically(target, [&](std::ostream& out) { out << text; });
}

// A writer that needs a file name (as HDF5 and matio do).
void write_by_name(const fs::path& target, const std::string& text) {
  write_atomically(target, [&](const std::string& tmp) { std::ofstream(tmp, std::ios::binary) << text; });
}

// Reads everything a FIFO receives, on another thread.
std::future<std::string> read_fifo(const fs::path& fifo) {
  return std::async(std::launch::async, [fifo] { return contents(fifo); });
}

// Runs `body` in a child process (as user nobody when `as_nobody`); returns its exit status, or -signal.
template <class F>
int in_child(F&& body, bool as_nobody = false) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (as_nobody && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(90);
    int code = 0;
    try {
      body();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "child: %s\n", e.what());
      code = 1;
    }
    ::_exit(code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

}  // namespace

TEST(OutputPaths, ACharacterDeviceIsWrittenToNeverReplaced) {
  // As root, a private null device (so that a bug could never replace the machine's /dev/null); otherwise
  // /dev/null itself, which a normal user can write but not replace.
  const fs::path d = fresh_dir("chardev");
  fs::path device = "/dev/null";
  if (::geteuid() == 0) {
    device = d / "null";
    ASSERT_EQ(::mknod(device.c_str(), S_IFCHR | 0666, ::makedev(1, 3)), 0);
  }
  write_text(device, "a result\n");
  write_by_name(device, "an HDF5 file, say");
  write_json_file(device, nlohmann::json{{"a", 1}});
  EXPECT_EQ(kind_of(device), S_IFCHR);
  EXPECT_EQ(live_temporaries(), 0u);
  for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path(), device) << "left behind: " << e.path();
}

TEST(OutputPaths, DevNullWorksForAUserWhoCannotWriteDev) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to become another user";
  EXPECT_EQ(in_child([] {
              write_text("/dev/null", "x");
              write_by_name("/dev/null", "y");
            }, true),
            0);
  EXPECT_EQ(kind_of("/dev/null"), S_IFCHR);
}

TEST(OutputPaths, AFifoReceivesTheBytesAndStaysAFifo) {
  const fs::path d = fresh_dir("fifo");
  const fs::path fifo = d / "results.jsonl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto got = read_fifo(fifo);
  write_text(fifo, "line 1\nline 2\n");
  EXPECT_EQ(got.get(), "line 1\nline 2\n");
  got = read_fifo(fifo);
  write_by_name(fifo, "bytes written by name");
  EXPECT_EQ(got.get(), "bytes written by name");
  EXPECT_EQ(kind_of(fifo), S_IFIFO);
  EXPECT_EQ(live_temporaries(), 0u);
}

TEST(OutputPaths, TextReachesAFifoAsItIsFlushed) {
  // solve --jsonl -o FIFO: a reader sees each flushed line while the writer is still running.
  const fs::path d = fresh_dir("fifo_lines");
  const fs::path fifo = d / "lines";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::promise<std::string> first_line;
  std::thread reader([&] {
    std::ifstream in(fifo);
    std::string line;
    std::getline(in, line);
    first_line.set_value(line);
    std::string rest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  });
  write_text_atomically(fifo, [&](std::ostream& out) {
    out << "first" << std::endl;
    auto seen = first_line.get_future();
    EXPECT_EQ(seen.wait_for(std::chrono::seconds(20)), std::future_status::ready) << "the line did not arrive";
    EXPECT_EQ(seen.get(), "first");
    out << "second\n";
  });
  reader.join();
}

TEST(OutputPaths, ASocketIsConnectedToAndReceivesTheBytes) {
  const fs::path d = fresh_dir("socket");
  const fs::path path = d / "s";
  const int server = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::snprintf(address.sun_path, sizeof address.sun_path, "%s", path.c_str());
  ASSERT_EQ(::bind(server, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::listen(server, 1), 0);
  auto got = std::async(std::launch::async, [server] {
    const int c = ::accept(server, nullptr, nullptr);
    std::string text;
    char buf[256];
    for (ssize_t n; (n = ::read(c, buf, sizeof buf)) > 0;) text.append(buf, static_cast<std::size_t>(n));
    ::close(c);
    return text;
  });
  write_by_name(path, "over a socket");
  EXPECT_EQ(got.get(), "over a socket");
  EXPECT_EQ(kind_of(path), S_IFSOCK);
  ::close(server);
}

TEST(OutputPaths, DashIsStandardOutput) {
  const fs::path d = fresh_dir("stdout");
  const fs::path captured = d / "captured";
  EXPECT_EQ(in_child([&] {
              const int fd = ::open(captured.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
              ::dup2(fd, STDOUT_FILENO);
              write_text("-", "to standard output\n");
              write_by_name("-", "by name\n");
            }),
            0);
  EXPECT_EQ(contents(captured), "to standard output\nby name\n");
  EXPECT_FALSE(fs::exists("-"));
}

TEST(OutputPaths, ASymlinkChainIsFollowedAndOnlyItsFinalTargetReplaced) {
  const fs::path d = fresh_dir("links");
  fs::create_directories(d / "data");
  std::ofstream(d / "data" / "result.json") << "old";
  fs::create_symlink("data/result.json", d / "b.json");  // relative, to the folder of the link
  fs::create_symlink(d / "b.json", d / "a.json");         // a -> b -> data/result.json
  write_text(d / "a.json", "new");
  EXPECT_EQ(kind_of(d / "a.json"), S_IFLNK);
  EXPECT_EQ(kind_of(d / "b.json"), S_IFLNK);
  EXPECT_EQ(fs::read_symlink(d / "b.json"), "data/result.json");
  EXPECT_EQ(contents(d / "data" / "result.json"), "new");
  // The temporary was beside the final target, and nothing is left.
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "data"), fs::directory_iterator()), 1);
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 3);
}

TEST(OutputPaths, ADanglingSymlinkGetsTheFileItNames) {
  const fs::path d = fresh_dir("dangling");
  fs::create_symlink("made.json", d / "link.json");
  write_by_name(d / "link.json", "created");
  EXPECT_EQ(kind_of(d / "link.json"), S_IFLNK);
  EXPECT_EQ(contents(d / "made.json"), "created");
}

TEST(OutputPaths, ALinkLoopADirectoryAndAMissingFolderAreErrorsNamingThePath) {
  const fs::path d = fresh_dir("refused");
  fs::create_symlink("loop2", d / "loop1");
  fs::create_symlink("loop1", d / "loop2");
  EXPECT_NE(error_of([&] { write_text(d / "loop1", "x"); }).find("loop1': too many levels of symbolic links"),
            std::string::npos);
  EXPECT_THROW(write_text(d / "loop1", "x"), std::invalid_argument);
  EXPECT_NE(error_of([&] { write_by_name(d, "x"); }).find("': it is a directory"), std::string::npos);
  EXPECT_NE(error_of([&] { write_text(d / "no" / "such.json", "x"); }).find("no' does not exist"), std::string::npos);
  if (::geteuid() == 0) {
    ASSERT_EQ(::mknod((d / "block").c_str(), S_IFBLK | 0600, ::makedev(7, 200)), 0);
    EXPECT_NE(error_of([&] { write_text(d / "block", "x"); }).find("block': it is a block device"), std::string::npos);
    EXPECT_EQ(kind_of(d / "block"), S_IFBLK);
  }
  EXPECT_EQ(live_temporaries(), 0u);
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), ::geteuid() == 0 ? 3 : 2);
}

TEST(OutputPaths, AReplacedFileKeepsItsPermissions) {
  const fs::path d = fresh_dir("mode");
  const fs::path target = d / "private.json";
  std::ofstream(target) << "old";
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write);
  write_json_file(target, nlohmann::json{{"new", true}});
  EXPECT_EQ(fs::status(target).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
}

TEST(OutputPaths, ALinkPlantedAtTheTemporaryNameIsNotFollowed) {
  // Someone who can write the folder (say /tmp) places a link at the predictable temporary name.
  const fs::path d = fresh_dir("planted");
  const fs::path victim = d / "victim";
  std::ofstream(victim) << "precious";
  fs::create_symlink(victim, d / (".tmp-" + std::to_string(::getpid()) + "-out.json"));
  write_text(d / "out.json", "result");
  EXPECT_EQ(contents(victim), "precious");
  EXPECT_EQ(contents(d / "out.json"), "result");
}

TEST(OutputPaths, TextThatIsNotUtf8IsWrittenAsUtf8Json) {
  const fs::path d = fresh_dir("utf8");
  write_json_file(d / "r.json", nlohmann::json{{"error", std::string("bad \xff byte")}});
  EXPECT_EQ(contents(d / "r.json"), "{\n  \"error\": \"bad \xEF\xBF\xBD byte\"\n}\n");
}
