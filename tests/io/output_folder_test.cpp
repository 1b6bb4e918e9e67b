// A run's outputs in one folder are published as one set (io/output_folder.hpp): after a failure or a kill at
// any moment, SIGKILL included, the folder holds the complete older set or the complete new one; files the run
// does not write stay, the figures of an older run go, links and special files among the outputs are written
// through, and the folder keeps its permissions.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

#include "fresh_dir.hpp"
#include "vibrissa/io/output_folder.hpp"
#include "vibrissa/io/temporary_files.hpp"

namespace fs = std::filesystem;
using vibrissa::test::fresh_dir;
using namespace vibrissa::io;

namespace {

const std::string_view kFigures[] = {"figure.png", "figures"};

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> names(const fs::path& d) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(d)) out.insert(e.path().filename().string());
  return out;
}

// Writes the set {a.txt, b.h5, c.json}, every file tagged with `run`; b.h5 through a path writer.
void publish(const fs::path& dir, int run, bool fail = false) {
  OutputFolder folder(dir, kFigures);
  const std::string tag = "run " + std::to_string(run) + "\n";
  folder.stage_text("a.txt", [&](std::ostream& out) { out << tag << std::string(20000, 'a'); });
  folder.stage("b.h5", [&](const std::string& tmp) { std::ofstream(tmp, std::ios::binary) << tag << "b"; });
  if (fail) throw std::runtime_error("the writer of c.json failed");
  folder.stage_text("c.json", [&](std::ostream& out) { out << tag; });
  folder.commit();
}

// The run whose set `dir` holds; fails the test unless every file of the set is there and of one run.
int run_of_set(const fs::path& dir) {
  const std::string a = contents(dir / "a.txt"), b = contents(dir / "b.h5"), c = contents(dir / "c.json");
  const std::string tag = c;
  EXPECT_FALSE(tag.empty()) << "c.json missing or empty";
  EXPECT_EQ(a.substr(0, tag.size()), tag) << "a.txt is of another run";
  EXPECT_EQ(a.size(), tag.size() + 20000) << "a.txt is partial";
  EXPECT_EQ(b, tag + "b") << "b.h5 is of another run";
  return tag.size() > 4 ? std::stoi(tag.substr(4)) : -1;
}

std::set<std::string> siblings_left(const fs::path& parent) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(parent))
    if (e.path().filename().string().rfind(".tmp-", 0) == 0) out.insert(e.path().filename().string());
  return out;
}

}  // namespace

TEST(OutputFolder, ANewFolderIsCreatedWithTheWholeSet) {
  const fs::path parent = fresh_dir("folder_new");
  publish(parent / "deeper" / "out", 1);
  EXPECT_EQ(run_of_set(parent / "deeper" / "out"), 1);
  EXPECT_EQ(names(parent / "deeper" / "out"), (std::set<std::string>{"a.txt", "b.h5", "c.json"}));
  EXPECT_TRUE(siblings_left(parent / "deeper").empty());
  EXPECT_EQ(live_temporaries(), 0u);
}

TEST(OutputFolder, FilesTheRunDoesNotWriteStayAndOlderFiguresGo) {
  const fs::path parent = fresh_dir("folder_keep");
  const fs::path out = parent / "out";
  publish(out, 1);
  std::ofstream(out / "notes.txt") << "mine";
  fs::create_directories(out / "analysis" / "deep");
  std::ofstream(out / "analysis" / "deep" / "x.csv") << "1,2";
  std::ofstream(out / "figure.png") << "old figure";
  fs::create_directories(out / "figures");
  std::ofstream(out / "figures" / "f.png") << "old figure";
  fs::create_symlink("notes.txt", out / "notes_link");
  struct stat before {};
  ::stat((out / "notes.txt").c_str(), &before);

  publish(out, 2);
  EXPECT_EQ(run_of_set(out), 2);
  EXPECT_EQ(names(out), (std::set<std::string>{"a.txt", "b.h5", "c.json", "notes.txt", "analysis", "notes_link"}));
  EXPECT_EQ(contents(out / "analysis" / "deep" / "x.csv"), "1,2");
  EXPECT_EQ(fs::read_symlink(out / "notes_link"), "notes.txt");
  struct stat after {};
  ::stat((out / "notes.txt").c_str(), &after);
  EXPECT_EQ(after.st_ino, before.st_ino) << "the user's file is the same file, not a copy";
  EXPECT_EQ(after.st_nlink, 1u);
  EXPECT_TRUE(siblings_left(parent).empty());
}

TEST(OutputFolder, AFailingWriterLeavesTheOlderSetAndNoTemporary) {
  const fs::path parent = fresh_dir("folder_fail");
  const fs::path out = parent / "out";
  publish(out, 1);
  std::ofstream(out / "figure.png") << "old figure";
  EXPECT_THROW(publish(out, 2, true), std::runtime_error);
  EXPECT_EQ(run_of_set(out), 1);
  EXPECT_TRUE(fs::exists(out / "figure.png"));
  EXPECT_TRUE(siblings_left(parent).empty());
  EXPECT_EQ(live_temporaries(), 0u);
}

TEST(OutputFolder, AFolderGivenAsALinkIsFilledAndTheLinkStays) {
  const fs::path parent = fresh_dir("folder_link");
  fs::create_directories(parent / "disk" / "results");
  fs::create_symlink("disk/results", parent / "out");
  publish(parent / "out", 1);
  EXPECT_EQ(fs::read_symlink(parent / "out"), "disk/results");
  EXPECT_EQ(run_of_set(parent / "disk" / "results"), 1);
  publish(parent / "out", 2);
  EXPECT_EQ(run_of_set(parent / "out"), 2);
  EXPECT_TRUE(siblings_left(parent / "disk").empty());
}

TEST(OutputFolder, OutputsThatAreLinksOrFifosInTheFolderAreWrittenThrough) {
  const fs::path parent = fresh_dir("folder_through");
  const fs::path out = parent / "out";
  fs::create_directories(out);
  fs::create_directories(parent / "elsewhere");
  fs::create_symlink(parent / "elsewhere" / "a.txt", out / "a.txt");  // dangling: created
  ASSERT_EQ(::mkfifo((out / "c.json").c_str(), 0600), 0);
  auto fifo = std::async(std::launch::async, [&] { return contents(out / "c.json"); });
  publish(out, 1);
  EXPECT_EQ(fifo.get(), "run 1\n");
  EXPECT_TRUE(fs::is_symlink(out / "a.txt"));
  EXPECT_EQ(contents(parent / "elsewhere" / "a.txt").substr(0, 6), "run 1\n");
  struct stat st {};
  ASSERT_EQ(::lstat((out / "c.json").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(contents(out / "b.h5"), "run 1\nb");
  EXPECT_EQ(names(out), (std::set<std::string>{"a.txt", "b.h5", "c.json"}));
}

TEST(OutputFolder, AnOutputNameThatIsAFolderIsAnErrorBeforeAnythingChanges) {
  const fs::path parent = fresh_dir("folder_dir");
  const fs::path out = parent / "out";
  publish(out, 1);
  fs::remove(out / "c.json");
  fs::create_directories(out / "c.json");
  try {
    publish(out, 2);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("c.json': it is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(contents(out / "a.txt").substr(0, 6), "run 1\n");
  EXPECT_TRUE(siblings_left(parent).empty());
}

TEST(OutputFolder, KeepsTheFolderPermissionsAndTheWorkingDirectory) {
  const fs::path parent = fresh_dir("folder_mode");
  const fs::path out = parent / "out";
  fs::create_directories(out);
  fs::permissions(out, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
  const fs::path cwd = fs::current_path();
  fs::current_path(out);
  publish(".", 1);  // the working directory itself
  EXPECT_EQ(fs::current_path(), out);
  EXPECT_EQ(run_of_set("."), 1);  // the new folder, seen through the working directory
  fs::current_path(cwd);
  EXPECT_EQ(fs::status(out).permissions() & fs::perms::all,
            fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
}

TEST(OutputFolder, AParentFolderThatCannotBeWrittenPublishesInPlace) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to become another user";
  const fs::path parent = fresh_dir("folder_in_place");
  const fs::path out = parent / "out";
  fs::create_directories(out);
  ASSERT_EQ(::chown(out.c_str(), 65534, 65534), 0);
  fs::permissions(parent, fs::perms::owner_all | fs::perms::others_read | fs::perms::others_exec);
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(90);
    try {
      publish(out, 1);
      publish(out, 2);
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(run_of_set(out), 2);
  EXPECT_EQ(names(out), (std::set<std::string>{"a.txt", "b.h5", "c.json"}));
}

TEST(OutputFolder, AKillAtAnyMomentLeavesOneCompleteSet) {
  // Property test: a child publishes sets in a loop; SIGKILL at random moments (seeded); after each kill the
  // folder holds one complete set, and the user's file is still there.
  const fs::path parent = fresh_dir("folder_kill");
  const fs::path out = parent / "out";
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < 5; ++i) publish(out, 0);
  const auto publish_us = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0) / 5;
  std::ofstream(out / "notes.txt") << "mine";
  std::mt19937 random(20231125);
  // Kills from the child's start up to about four of its publications: every phase is hit.
  std::uniform_int_distribution<long> delay_us(0, 500 + 3 * publish_us.count());
  int last = 0, kills = 0, k = 0;
  std::set<int> seen;
  // At least 25 kills; on a loaded machine a child may be killed before it publishes anything, so the kills go
  // on (up to 400) until they have landed between more than 5 different runs: the test is never vacuous.
  for (; k < 400 && (k < 25 || seen.size() <= 5); ++k) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      try {
        for (int run = (k + 1) * 1000;; ++run) publish(out, run);
      } catch (...) {
        ::_exit(1);
      }
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(random) * (1 + k / 25)));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    kills += WIFSIGNALED(status) ? 1 : 0;
    EXPECT_TRUE(WIFSIGNALED(status)) << "kill " << k << ": the child ended by itself, exit status "
                                     << (WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    const int run = run_of_set(out);
    if (::testing::Test::HasFailure()) FAIL() << "after kill " << k << ": the folder mixes runs";
    EXPECT_TRUE(run == last || run >= (k + 1) * 1000) << "kill " << k << ": set of run " << run;
    last = run;
    seen.insert(run);
    EXPECT_EQ(contents(out / "notes.txt"), "mine") << "kill " << k;
    for (const std::string& n : siblings_left(parent)) fs::remove_all(parent / n);  // as a user may
  }
  EXPECT_EQ(kills, k);
  EXPECT_GT(seen.size(), 5u) << "the kills should land between different runs (" << k << " kills)";
}
