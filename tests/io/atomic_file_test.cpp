// Atomic outputs: a writer that fails midway leaves the old file byte-identical and no temporary; staged
// files replace their targets together; live temporaries are tracked for the signal handlers.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

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

std::size_t entries(const fs::path& d) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(d), fs::directory_iterator()));
}

}  // namespace

TEST(AtomicFile, WriterThatThrowsMidwayLeavesTheOldFileByteIdenticalAndNoTemporary) {
  const fs::path d = fresh_dir("throw");
  const fs::path target = d / "result.csv";
  const std::string old = "a,b\n1,2\n";
  std::ofstream(target, std::ios::binary) << old;
  std::string temporary_seen;
  EXPECT_THROW(write_text_atomically(target,
                                     [&](std::ostream& out) {
                                       out << "x,y\n3,";
                                       out.flush();
                                       temporary_seen = (d / (".tmp-" + std::to_string(::getpid()) + "-result.csv"))
                                                            .string();
                                       ASSERT_TRUE(fs::exists(temporary_seen)) << "written beside the target";
                                       throw std::runtime_error("interrupted");
                                     }),
               std::runtime_error);
  EXPECT_EQ(contents(target), old);
  EXPECT_FALSE(fs::exists(temporary_seen));
  EXPECT_EQ(entries(d), 1u);
  EXPECT_EQ(live_temporaries(), 0u);
}

TEST(AtomicFile, PathWriterThatThrowsLeavesNoFileWhereThereWasNone) {
  const fs::path d = fresh_dir("none");
  EXPECT_THROW(write_atomically(d / "out.h5",
                                [](const std::string& tmp) {
                                  std::ofstream(tmp) << "partial";
                                  throw std::runtime_error("interrupted");
                                }),
               std::runtime_error);
  EXPECT_EQ(entries(d), 0u);
}

TEST(AtomicFile, CommitReplacesTheTargetAndForgetsTheTemporary) {
  const fs::path d = fresh_dir("commit");
  const fs::path target = d / "summary.json";
  std::ofstream(target) << "old";
  write_json_file(target, nlohmann::json{{"a", 1.5}});
  EXPECT_EQ(contents(target), "{\n  \"a\": 1.5\n}\n");
  EXPECT_EQ(entries(d), 1u);
  EXPECT_EQ(live_temporaries(), 0u);
}

TEST(AtomicFile, WriterThatRemovesItsFileIsAnErrorNamingTheTarget) {
  const fs::path d = fresh_dir("nofile");
  try {
    write_atomically(d / "frames.h5", [](const std::string& tmp) { fs::remove(tmp); });
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("frames.h5"), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(d), 0u);
}

TEST(StagedFiles, NothingIsReplacedUntilEveryFileIsWritten) {
  const fs::path d = fresh_dir("staged");
  std::ofstream(d / "a.txt") << "old a";
  std::ofstream(d / "b.txt") << "old b";
  {
    StagedFiles files;
    files.stage_text(d / "a.txt", [](std::ostream& out) { out << "new a"; });
    EXPECT_EQ(live_temporaries(), 1u);
    EXPECT_THROW(files.stage_text(d / "b.txt",
                                  [](std::ostream& out) {
                                    out << "half of b";
                                    throw std::runtime_error("interrupted");
                                  }),
                 std::runtime_error);
  }
  EXPECT_EQ(contents(d / "a.txt"), "old a");
  EXPECT_EQ(contents(d / "b.txt"), "old b");
  EXPECT_EQ(entries(d), 2u);
  EXPECT_EQ(live_temporaries(), 0u);

  StagedFiles files;
  files.stage_text(d / "a.txt", [](std::ostream& out) { out << "new a"; });
  files.stage_text(d / "b.txt", [](std::ostream& out) { out << "new b"; });
  EXPECT_EQ(contents(d / "a.txt"), "old a");
  files.commit();
  EXPECT_EQ(contents(d / "a.txt"), "new a");
  EXPECT_EQ(contents(d / "b.txt"), "new b");
  EXPECT_EQ(entries(d), 2u);
}

TEST(TemporaryFiles, UnlinkLiveTemporariesRemovesExactlyTheLiveOnes) {
  const fs::path d = fresh_dir("registry");
  AtomicFile live(d / "live.csv");
  std::ofstream(live.temporary()) << "x";
  std::ofstream(d / "keep.csv") << "y";
  EXPECT_EQ(live_temporaries(), 1u);
  unlink_live_temporaries();  // what the signal handler does
  EXPECT_FALSE(fs::exists(live.temporary()));
  EXPECT_TRUE(fs::exists(d / "keep.csv"));
  live.discard();
  EXPECT_EQ(live_temporaries(), 0u);
}

TEST(TemporaryFiles, OverlongPathsAreRefusedNamingThePath) {
  const std::string name(kMaxTemporaryPath, 'x');
  try {
    register_temporary(fs::temp_directory_path() / name);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("xxxx"), std::string::npos);
  }
  try {
    AtomicFile f(fs::temp_directory_path() / name);  // too long for the file system: refused before any slot
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("xxxx"), std::string::npos);
  }
  EXPECT_EQ(live_temporaries(), 0u);
}
