// Inconsistent inputs are problems naming their likely cause (docs/reconstruction.md, step 9), and a lost end
// point costs little accuracy (step 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <array>
#include <iostream>
#include <functional>
#include <random>
#include <stdexcept>

#include "test_cameras.hpp"
#include "vibrissa/core/pose.hpp"
#include "vibrissa/recon/calibration_files.hpp"
#include "vibrissa/recon/geometry.hpp"
#include "vibrissa/recon/reconstruct.hpp"
#include "vibrissa/recon/tracks.hpp"

using namespace vibrissa;
using namespace vibrissa::recon;
using test_support::whisker_at;

namespace {

TrackFrame seen(std::int64_t frame, const Camera& cam, const std::vector<Eigen::Vector3d>& pts, std::mt19937& rng,
                double sigma) {
  std::normal_distribution<double> noise(0.0, sigma);
  TrackFrame f;
  f.frame = frame;
  for (const auto& p : pts) {
    f.points_px.push_back(cam.project(p) + Eigen::Vector2d(noise(rng), noise(rng)));
    f.likelihood.push_back(1.0);
  }
  return f;
}

const Camera top_cam = test_support::top_test_camera(-0.1, 0.0);
const Camera front_cam = test_support::front_test_camera();

/// `frames` frames; the front video starts `shift` frames later (its frame f shows frame f + shift).
void views(Tracks2D& top, Tracks2D& front, int frames, int shift = 0, double sigma = 0.5) {
  std::mt19937 rng(11);
  for (int i = 0; i < frames; ++i) top.frames.push_back(seen(i, top_cam, whisker_at(i), rng, sigma));
  for (int i = shift; i < frames; ++i) front.frames.push_back(seen(i - shift, front_cam, whisker_at(i), rng, sigma));
}

bool mentions(const Reconstruction& rec, const std::string& text) {
  return std::any_of(rec.problems.begin(), rec.problems.end(),
                     [&](const std::string& p) { return p.find(text) != std::string::npos; });
}
}  // namespace

TEST(InputChecks, ConsistentViewsHaveNoProblem) {
  Tracks2D top, front;
  views(top, front, 60);
  const Reconstruction rec = reconstruct(top, top_cam, front, front_cam, ReconstructOptions{});
  EXPECT_TRUE(rec.problems.empty()) << rec.problems.front();
  EXPECT_EQ(rec.frames_in_both, 60u);
  EXPECT_LT(rec.base_epipolar_px, 1.0);  // about the 0.5 px noise
}

TEST(InputChecks, ViewsOutOfStepAreAProblemUnlessTheOffsetIsGiven) {
  Tracks2D top, front;
  views(top, front, 80, 20);
  const Reconstruction rec = reconstruct(top, top_cam, front, front_cam, ReconstructOptions{});
  ASSERT_FALSE(rec.problems.empty());
  EXPECT_TRUE(mentions(rec, "out of step")) << rec.problems.front();
  EXPECT_TRUE(mentions(rec, "--front-frame-offset"));
  ReconstructOptions o;
  o.front_frame_offset = 20;
  const Reconstruction fixed = reconstruct(top, top_cam, front, front_cam, o);
  EXPECT_TRUE(fixed.problems.empty()) << fixed.problems.front();
  EXPECT_GE(fixed.count(FrameStatus::ok), 58u);
  EXPECT_LT(fixed.base_epipolar_px, 1.0);
}

TEST(InputChecks, SameFrameCountsOutOfStepDisagreeWithTheCalibration) {
  // Both files cover frames 0..59 but the front one shows frames 20..79 (cut differently): the moving base
  // leaves the epipolar lines.
  Tracks2D top, front;
  std::mt19937 rng(2);
  for (int i = 0; i < 60; ++i) {
    top.frames.push_back(seen(i, top_cam, whisker_at(i), rng, 0.5));
    front.frames.push_back(seen(i, front_cam, whisker_at(i + 20), rng, 0.5));
  }
  const Reconstruction rec = reconstruct(top, top_cam, front, front_cam, ReconstructOptions{});
  EXPECT_TRUE(mentions(rec, "do not agree with the calibration")) << (rec.problems.empty() ? "" : rec.problems[0]);
}

// Swapped views are only detectable when the exchange changes the epipolar geometry: two cameras alike, at
// right angles and equally far (the validation's pair), have a fundamental matrix that the exchange maps onto
// itself, and the swapped views reconstruct a mirrored whisker consistently. Here the front camera has a
// longer lens and another principal point.
TEST(InputChecks, SwappedViewsAreNamed) {
  Eigen::Matrix3d K;
  K << 3000, 0, 400, 0, 3000, 300, 0, 0, 1;
  const Camera front_long = pinhole_camera(K, front_cam.R_CW, front_cam.t_C);
  Tracks2D top, front;
  std::mt19937 rng(4);
  for (int i = 0; i < 40; ++i) {
    top.frames.push_back(seen(i, top_cam, whisker_at(i), rng, 0.5));
    front.frames.push_back(seen(i, front_long, whisker_at(i), rng, 0.5));
  }
  EXPECT_TRUE(reconstruct(top, top_cam, front, front_long, ReconstructOptions{}).problems.empty());
  const Reconstruction rec = reconstruct(front, top_cam, top, front_long, ReconstructOptions{});
  EXPECT_TRUE(mentions(rec, "the views are swapped")) << (rec.problems.empty() ? "" : rec.problems[0]);
}

TEST(InputChecks, AWrongCalibrationIsAProblem) {
  Tracks2D top, front;
  views(top, front, 40);
  // The front camera moved 3 mm sideways after calibrating (about 24 px at 0.3 m), across the epipolar lines
  // (a move along them, here vertical, only changes the depth of the reconstruction and cannot be seen).
  const Camera moved = pinhole_camera(front_cam.K, front_cam.R_CW, front_cam.t_C + Eigen::Vector3d(0.003, 0.0, 0.0));
  const Reconstruction rec = reconstruct(top, top_cam, front, moved, ReconstructOptions{});
  EXPECT_TRUE(mentions(rec, "do not agree with the calibration")) << (rec.problems.empty() ? "" : rec.problems[0]);
}

TEST(InputChecks, LowYieldIsAProblemUnlessAccepted) {
  Tracks2D top, front;
  views(top, front, 40);
  for (std::size_t i = 0; i < 25; ++i)
    for (auto& l : front.frames[i].likelihood) l = 0.2;  // the front tracker lost the whisker
  const Reconstruction rec = reconstruct(top, top_cam, front, front_cam, ReconstructOptions{});
  EXPECT_TRUE(mentions(rec, "only 15 of the 40 frames")) << (rec.problems.empty() ? "" : rec.problems[0]);
  ReconstructOptions o;
  o.min_yield = 0.0;
  EXPECT_TRUE(reconstruct(top, top_cam, front, front_cam, o).problems.empty());
}

// A base point lost in one view (low likelihood) is recovered from the other view along the end fit; at 0.5 px
// the base of such frames must be within 1.5x the error of intact frames (measured 1.36x and 1.29x). Two lost
// base points are not extrapolated (3.3x when they were): those frames are flagged, never off by a spacing.
TEST(InputChecks, FramesMissingAnEndAreNearlyAsGoodAsIntactOnes) {
  std::mt19937 rng(5);
  Tracks2D top, front;
  const int n = 240;
  for (int i = 0; i < n; ++i) {
    top.frames.push_back(seen(i, top_cam, whisker_at(i), rng, 0.5));
    front.frames.push_back(seen(i, front_cam, whisker_at(i), rng, 0.5));
    const int kind = i % 4;  // 0 intact; 1 top base lost; 2 front base lost; 3 front base and next lost
    if (kind == 1) top.frames.back().likelihood[0] = 0.1;
    if (kind >= 2) front.frames.back().likelihood[0] = 0.1;
    if (kind == 3) front.frames.back().likelihood[1] = 0.1;
  }
  ReconstructOptions o;
  o.base_jump = 2e-3;  // the base moves up to 1.6 mm within the identity check's window here
  const Reconstruction rec = reconstruct(top, top_cam, front, front_cam, o);
  std::array<std::vector<double>, 4> err;
  for (int i = 0; i < n; ++i) {
    const auto& f = rec.frames[std::size_t(i)];
    if (i % 4 == 3) {
      EXPECT_TRUE(!f.ok() || (f.base_W - whisker_at(i)[0]).norm() < 0.6e-3) << i;  // flagged, or not a spacing off
      continue;
    }
    ASSERT_TRUE(f.ok()) << i << " " << frame_status_name(f.status);
    err[std::size_t(i % 4)].push_back((f.base_W - whisker_at(i)[0]).norm());
  }
  auto rms = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x * x;
    return std::sqrt(s / double(v.size()));
  };
  for (std::size_t kind = 1; kind < 3; ++kind) {
    EXPECT_LT(rms(err[kind]), 1.5 * rms(err[0])) << kind;
  }
}

// A directory given for an input file opens as an empty stream on Linux: the readers said "the file is empty" or
// leaked "basic_filebuf::underflow"; each now names the path and says it is a directory.
TEST(InputFiles, ADirectoryIsNamedAsSuch) {
  const std::string dir = ::testing::TempDir();
  auto expect_directory_error = [&](const std::function<void()>& read, const std::string& what) {
    try {
      read();
      ADD_FAILURE() << "no error for a directory as " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not a " + what);
    }
  };
  expect_directory_error([&] { read_cameras_json(dir); }, "calibration file");
  expect_directory_error([&] { read_calibration("top=" + dir, "mm"); }, "calibration file");
  expect_directory_error([&] { read_correspondences_csv(dir, "mm"); }, "correspondence file");
  expect_directory_error([&] { read_points_csv(dir); }, "track file");
  expect_directory_error([&] { read_dlc_csv(dir); }, "track file");
  expect_directory_error([&] { read_whiskers(dir); }, "track file");
}
