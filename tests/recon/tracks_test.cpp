#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "io/guarded_read.hpp"
#include "vibrissa/recon/reconstruct_files.hpp"
#include "vibrissa/recon/tracks.hpp"

using namespace vibrissa::recon;

namespace {
std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}
template <class T>
void put(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}
}  // namespace

TEST(PointsCsv, ReadsPointsInOrderAndSkipsUntracked) {
  const auto path = temp_file("p.csv", "frame,point,x_px,y_px,likelihood\n3,1,11,21,0.9\n3,0,10,20,1\n5,0,1,2,\n"
                                       "5,1,3,4,0.5\n7,0,nan,1,1\n");
  const Tracks2D t = read_points_csv(path);
  ASSERT_EQ(t.frames.size(), 2u);
  EXPECT_EQ(t.frames[0].frame, 3);
  EXPECT_EQ(t.frames[0].points_px[0], Eigen::Vector2d(10, 20));
  EXPECT_EQ(t.frames[0].likelihood[1], 0.9);
  EXPECT_EQ(t.frames[1].points_px.size(), 1u);  // the point without likelihood is untracked
  EXPECT_EQ(t.find(5), &t.frames[1]);
  EXPECT_EQ(t.find(4), nullptr);
}

TEST(PointsCsv, ErrorsNameFileLineAndField) {
  auto path = temp_file("bad.csv", "frame,point,x_px,y_px\n0,0,1,2\n0,1,abc,2\n");
  EXPECT_EQ(error_of([&] { read_points_csv(path); }), path + ": line 3, field 'x_px': 'abc' is not a finite number");
  path = temp_file("bad2.csv", "frame,point,x_px\n");
  EXPECT_EQ(error_of([&] { read_points_csv(path); }), path + ": line 1, field 'y_px': required column is missing");
  path = temp_file("bad3.csv", "frame,point,x_px,y_px,likelihood\n-1,0,1,2,1\n");
  EXPECT_EQ(error_of([&] { read_points_csv(path); }), path + ": line 2, field 'frame': '-1' is not a non-negative integer");
}

TEST(DeepLabCutCsv, ReadsKeypointsWithLikelihoodAndSelection) {
  const auto path = temp_file("dlc.csv",
                              "scorer,DLC_net,DLC_net,DLC_net,DLC_net,DLC_net,DLC_net\n"
                              "bodyparts,w0,w0,w0,w1,w1,w1\n"
                              "coords,x,y,likelihood,x,y,likelihood\n"
                              "0,1.5,2.5,0.99,3,4,0.2\n"
                              "1,,,,5,6,0.7\n");
  Tracks2D t = read_tracks(path);
  ASSERT_EQ(t.frames.size(), 2u);
  EXPECT_EQ(t.frames[0].points_px.size(), 2u);
  EXPECT_EQ(t.frames[0].points_px[0], Eigen::Vector2d(1.5, 2.5));
  EXPECT_EQ(t.frames[0].likelihood[1], 0.2);
  EXPECT_EQ(t.frames[1].points_px.size(), 1u);
  t = read_dlc_csv(path, {"w1", "w0"});
  EXPECT_EQ(t.frames[0].points_px[0], Eigen::Vector2d(3, 4));
  EXPECT_EQ(error_of([&] { read_dlc_csv(path, {"w2"}); }), path + ": field 'bodyparts': no x and y columns for bodypart 'w2'");
  const auto bad = temp_file("dlc_bad.csv", "scorer,a,a,a\nbodyparts,w0,w0,w0\ncoords,x,y,likelihood\n0,1,2,1.5\n");
  EXPECT_EQ(error_of([&] { read_dlc_csv(bad); }), bad + ": line 4, field 'w0.likelihood': frame 0: must lie in [0, 1]");
}

TEST(DeepLabCutCsv, MultiAnimalFilesNeedAnIndividual) {
  const auto path = temp_file("dlcma.csv",
                              "scorer,n,n,n,n,n,n\nindividuals,m1,m1,m1,m2,m2,m2\nbodyparts,w0,w0,w0,w0,w0,w0\n"
                              "coords,x,y,likelihood,x,y,likelihood\n0,1,2,1,7,8,1\n");
  EXPECT_NE(error_of([&] { read_dlc_csv(path); }).find("individuals"), std::string::npos);
  EXPECT_EQ(read_dlc_csv(path, {}, "m2").frames[0].points_px[0], Eigen::Vector2d(7, 8));
}

TEST(Janelia, ReadsBinaryAndTextWhiskersWithMeasurementIdentities) {
  // whiskbin1: 12-byte magic, records {int id, time, len; float x[len], y[len], thick[len], score[len]}, int count.
  std::string bin("bwhiskbin1\0\0", 12);
  auto segment = [&](int id, int frame, std::vector<float> x, std::vector<float> y) {
    put<std::int32_t>(bin, id);
    put<std::int32_t>(bin, frame);
    put<std::int32_t>(bin, std::int32_t(x.size()));
    for (auto* v : {&x, &y, &x, &y})
      for (float f : *v) put<float>(bin, f);
  };
  segment(0, 0, {100, 50, 10}, {1, 2, 3});  // stored tip first
  segment(1, 0, {5, 6, 7}, {9, 9, 9});
  segment(0, 1, {11, 60, 110}, {4, 5, 6});
  put<std::int32_t>(bin, 3);
  const auto whiskers = temp_file("w.whiskers", bin);
  const auto segs = read_whiskers(whiskers);
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[2].frame, 1);
  EXPECT_EQ(segs[2].x[2], 110.0f);
  // measv3: 8-byte magic, n_rows, n_measures, rows last first: 10 ints + char, data, velocity.
  std::string meas("measv3\0\0", 8);
  put<std::int32_t>(meas, 3);
  put<std::int32_t>(meas, 2);
  auto row = [&](int fid, int wid, int state) {
    for (int v : {0, fid, wid, state, 0, 0, 0, 1, 0, 2}) put<std::int32_t>(meas, v);
    meas.push_back('x');
    for (double v : {10.0, 2.0, 0.0, 0.0}) put<double>(meas, v);  // follicle (10, 2) in columns 0, 1
  };
  row(1, 0, 0);  // written last row first
  row(0, 1, -1);
  row(0, 0, 0);
  const auto measurements = temp_file("w.measurements", meas);
  const auto rows = read_measurements(measurements);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].frame, 0);
  EXPECT_EQ(rows[2].frame, 1);
  EXPECT_EQ(rows[1].identity, -1);
  const Tracks2D t = janelia_tracks(whiskers, measurements, 0);
  ASSERT_EQ(t.frames.size(), 2u);
  EXPECT_EQ(t.frames[0].points_px.front(), Eigen::Vector2d(10, 3));  // oriented follicle first
  EXPECT_EQ(t.frames[1].points_px.front(), Eigen::Vector2d(11, 4));
  // The text variant of the same segments.
  const auto text = temp_file("t.whiskers", "whisker1 (frame,id,time,n,x1,y1,thick1,score1...)\n"
                                            "0,0,0,3,100,1,1,1,50,2,1,1,10,3,1,1\n0,1,0,3,5,9,1,1,6,9,1,1,7,9,1,1\n"
                                            "1,0,1,3,11,4,1,1,60,5,1,1,110,6,1,1\n");
  const Tracks2D tt = janelia_tracks(text, measurements, 0);
  ASSERT_EQ(tt.frames.size(), 2u);
  EXPECT_EQ(tt.frames[0].points_px, t.frames[0].points_px);
  // Errors name file, frame/record and field.
  const auto cut = temp_file("cut.whiskers", bin.substr(0, 40) + bin.substr(bin.size() - 4));
  EXPECT_NE(error_of([&] { read_whiskers(cut); }).find(cut + ": segment 1 (frame 0), field 'len'"), std::string::npos);
  const auto badtext = temp_file("bad.whiskers", "whisker1 x\n0,0,0,2,1,1,1,1\n");
  EXPECT_EQ(error_of([&] { read_whiskers(badtext); }), badtext + ": line 2, field 'n': frame 0: n = 2 needs 12 cells, got 8");
  EXPECT_NE(error_of([&] { read_measurements(whiskers); }).find(whiskers + ": header"), std::string::npos);
  // A row count the file cannot hold is refused before anything is allocated (found by fuzz/janelia).
  std::string huge("measv3\0\0", 8);
  put<std::int32_t>(huge, 0x7fffffff);
  put<std::int32_t>(huge, 2);
  const auto huge_path = temp_file("huge.measurements", huge);
  EXPECT_EQ(error_of([&] { read_measurements(huge_path); }),
            huge_path + ": header, field 'n_rows': 2147483647 rows of 2 measures do not fit in the file (truncated?)");
}

namespace {
const std::string dlc_data = std::string(VIBRISSA_SOURCE_DIR) + "/tests/data/deeplabcut/";
void expect_same_tracks(const Tracks2D& a, const Tracks2D& b) {
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t i = 0; i < a.frames.size(); ++i) {
    EXPECT_EQ(a.frames[i].frame, b.frames[i].frame);
    EXPECT_EQ(a.frames[i].points_px, b.frames[i].points_px);
    EXPECT_EQ(a.frames[i].likelihood, b.frames[i].likelihood);
  }
}
}  // namespace

// Fixtures written by pandas + PyTables (tests/data/deeplabcut/README.md): each .h5 and its .csv hold the
// same DataFrame.
TEST(DeepLabCutH5, SingleAnimalTableReadsLikeItsCsv) {
  const Tracks2D h5 = read_tracks(dlc_data + "single_animal.h5");
  expect_same_tracks(h5, read_dlc_csv(dlc_data + "single_animal.csv"));
  ASSERT_EQ(h5.frames.size(), 5u);
  EXPECT_EQ(h5.frames[3].frame, 4);  // frame 3 was not analysed
  ASSERT_EQ(h5.frames[1].points_px.size(), 2u);  // NaN tip in frame 1
  EXPECT_EQ(h5.frames[2].points_px[1], Eigen::Vector2d(141.0, 198.25));
  EXPECT_EQ(h5.frames[2].likelihood[1], 0.03125);
  EXPECT_EQ(h5.frames[0].points_px[2], Eigen::Vector2d(180.0, 192.0));
  expect_same_tracks(read_dlc_h5(dlc_data + "single_animal.h5", {"tip", "base"}),
                     read_dlc_csv(dlc_data + "single_animal.csv", {"tip", "base"}));
  // The deflated fuzz seed of the same table.
  expect_same_tracks(read_dlc_h5(std::string(VIBRISSA_SOURCE_DIR) + "/fuzz/corpus/dlc_h5/single_animal_zlib.h5"), h5);
}

TEST(DeepLabCutH5, MultiAnimalTableReadsLikeItsCsv) {
  const std::string h5 = dlc_data + "multi_animal.h5", csv = dlc_data + "multi_animal.csv";
  EXPECT_EQ(error_of([&] { read_dlc_h5(h5); }), h5 + ": field 'individuals': the file has 2 individuals: choose one");
  for (const char* who : {"mouse1", "mouse2"}) expect_same_tracks(read_dlc_h5(h5, {}, who), read_dlc_csv(csv, {}, who));
  const Tracks2D m2 = read_dlc_h5(h5, {}, "mouse2");
  EXPECT_EQ(m2.frames[0].points_px.size(), 2u);  // base untracked in frame 0
  EXPECT_EQ(m2.frames[1].points_px[0], Eigen::Vector2d(400.5, 200.125));
  EXPECT_EQ(error_of([&] { read_dlc_h5(h5, {}, "mouse3"); }), h5 + ": field 'individuals': no individual 'mouse3' in the file");
}

TEST(DeepLabCutH5, RejectsFilesThatAreNotPandasTables) {
  const auto empty = temp_file("x.h5", "");
  EXPECT_EQ(error_of([&] { read_tracks(empty); }), empty + ": cannot open as an HDF5 file");
  const std::string fixed = dlc_data + "fixed_format.h5";  // pandas' default to_hdf format
  EXPECT_EQ(error_of([&] { read_dlc_h5(fixed); }),
            fixed + ": group 'df_with_missing' attribute 'pandas_type': 'frame', expected 'frame_table' (write "
                    "with to_hdf(..., format=\"table\"))");
}

/// Whether read_dlc_h5 ends the process reading `path` with a signal (tried in a forked child).
bool read_dlc_h5_crashes(const std::string& path) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, SIG_DFL);
    try {
      (void)read_dlc_h5(path);
    } catch (...) {
    }
    ::_exit(0);
  }
  int status = 0;
  return pid > 0 && ::waitpid(pid, &status, 0) == pid && WIFSIGNALED(status);
}

TEST(DeepLabCutH5, AFileThatCrashesLibhdf5IsAnErrorNamingIt) {
  // libhdf5 1.10.8 divides by zero opening a dataset of this fuzzed file on x86 (tests/data/deeplabcut/README.md):
  // read through read_tracks, libhdf5 meets it in a child process first (src/io/guarded_read.hpp), and this
  // process survives with an error.
  if (!vibrissa::io::single_threaded()) GTEST_SKIP() << "this process runs other threads: the guard is off";
  const std::string crash = dlc_data + "libhdf5_crash_fpe.h5";
  if (!read_dlc_h5_crashes(crash)) GTEST_SKIP() << "this libhdf5 (or CPU) reads the file without crashing";
  const std::string message = error_of([&] { read_tracks(crash); });
  EXPECT_TRUE(message.starts_with(crash + ": libhdf5 crashed reading this file (")) << message;
  EXPECT_TRUE(message.ends_with("): it is corrupted, or not the format its extension says; nothing was read"))
      << message;
  EXPECT_THROW(read_tracks(crash), std::invalid_argument);
}

// Files written by the Janelia Whisker Tracker itself (tests/data/janelia/README.md): `trace` of a synthetic
// video of one dark quadratic whisker, x = 40 + s, y = 100 + 3 f + (-0.2 + 0.04 f) s + 0.0012 s^2 px (frame f,
// 0 <= s <= 220), `measure` + `classify` (identity 0 for the whisker, -1 for the stray segments), and
// `whisker_convert` to the text format.
TEST(Janelia, ReadsWhatTheTrackerWroteForASyntheticVideo) {
  const std::string dir = std::string(VIBRISSA_SOURCE_DIR) + "/tests/data/janelia/";
  const auto binary = read_whiskers(dir + "synth.whiskers");
  const auto text = read_whiskers(dir + "synth_text.whiskers");
  ASSERT_EQ(binary.size(), 14u);
  ASSERT_EQ(text.size(), binary.size());
  std::vector<int> per_frame(6, 0);
  for (std::size_t i = 0; i < binary.size(); ++i) {
    ASSERT_LT(binary[i].frame, 6);
    ++per_frame[std::size_t(binary[i].frame)];
    EXPECT_EQ(text[i].frame, binary[i].frame);
    EXPECT_EQ(text[i].id, binary[i].id);
    ASSERT_EQ(text[i].x.size(), binary[i].x.size());
    for (std::size_t k = 0; k < binary[i].x.size(); ++k) {  // the text file has 6 significant digits
      EXPECT_NEAR(text[i].x[k], binary[i].x[k], 1e-3f);
      EXPECT_NEAR(text[i].y[k], binary[i].y[k], 1e-3f);
    }
  }
  EXPECT_EQ(per_frame, (std::vector<int>{3, 3, 2, 3, 2, 1}));
  const auto rows = read_measurements(dir + "synth.measurements");
  ASSERT_EQ(rows.size(), binary.size());
  int whiskers = 0;
  for (const auto& r : rows) {
    EXPECT_TRUE(r.identity == 0 || r.identity == -1);
    if (r.identity == 0) {
      ++whiskers;
      EXPECT_EQ(r.segment, 0);  // the long trace of each frame
    }
  }
  EXPECT_EQ(whiskers, 6);
  for (const std::string file : {"synth.whiskers", "synth_text.whiskers"}) {
    SCOPED_TRACE(file);
    const Tracks2D t = janelia_tracks(dir + file, dir + "synth.measurements", 0);
    ASSERT_EQ(t.frames.size(), 6u);
    for (const auto& f : t.frames) {
      const double y0 = 100.0 + 3.0 * double(f.frame), slope = -0.2 + 0.04 * double(f.frame);
      // Oriented from the follicle: the tracer starts at the face edge (x ~ 30) and runs to the tip.
      EXPECT_NEAR(f.points_px.front().x(), 30.0, 0.1);
      EXPECT_GT(f.points_px.back().x(), 260.0);
      EXPECT_EQ(f.likelihood, std::vector<double>(f.points_px.size(), 1.0));
      std::size_t inside = 0;
      for (const auto& p : f.points_px) {
        if (p.x() < 45.0 || p.x() > 255.0) continue;  // away from the face edge and the tapered tip
        ++inside;
        double d = 1e9;  // distance to the drawn centre line
        for (double s = 0.0; s <= 220.0; s += 0.01)
          d = std::min(d, std::hypot(p.x() - 40.0 - s, p.y() - y0 - slope * s - 0.0012 * s * s));
        EXPECT_LT(d, 1.0) << "frame " << f.frame << " point (" << p.x() << ", " << p.y() << ")";
      }
      EXPECT_GT(inside, 180u);
    }
  }
}

// --whisker NAME=SPEC (docs/reconstruction.md, "Many whiskers per video"): a number is a Janelia label, else
// DeepLabCut keypoints base to tip.
TEST(Whiskers, ParsesLabelsAndKeypointsAndNamesBadArguments) {
  const WhiskerSelection c2 = parse_whisker("C2=c2_0,c2_1,c2_2");
  EXPECT_EQ(c2.name, "C2");
  EXPECT_EQ(c2.bodyparts, (std::vector<std::string>{"c2_0", "c2_1", "c2_2"}));
  EXPECT_EQ(c2.identity, -1);
  const WhiskerSelection c1 = parse_whisker("C1=7");
  EXPECT_EQ(c1.identity, 7);
  EXPECT_TRUE(c1.bodyparts.empty());
  EXPECT_NE(error_of([] { parse_whisker("C2"); }).find("--whisker expects NAME="), std::string::npos);
  EXPECT_NE(error_of([] { parse_whisker("C3=c3_0"); }).find("--whisker C3: 'c3_0' names 1 keypoint"), std::string::npos);
}
