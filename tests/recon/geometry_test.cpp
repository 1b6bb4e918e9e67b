#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <random>

#include "test_cameras.hpp"
#include "vibrissa/recon/geometry.hpp"

using namespace vibrissa::recon;
using test_support::front_test_camera;
using test_support::top_test_camera;

namespace {
std::vector<Eigen::Vector3d> random_points(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.02, 0.04);
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng), 0.5 * u(rng));
  return p;
}
}  // namespace

TEST(Camera, UndistortInvertsTheDistortionOfProject) {
  const Camera c = top_test_camera(-0.3, 0.2);
  for (const auto& p : random_points(50, 1)) {
    const Eigen::Vector2d ideal = (c.P * p.homogeneous()).hnormalized();
    EXPECT_LT((c.undistort(c.project(p)) - ideal).norm(), 1e-9);
    EXPECT_GT((c.project(p) - ideal).norm(), 1e-3);  // the distortion is not negligible
  }
}

TEST(Camera, DltParametersRoundTripAndReproduceThePinholeProjection) {
  const Camera pin = top_test_camera();
  const Camera dlt = dlt_camera(dlt_parameters(pin));
  const auto L = dlt_parameters(dlt);
  const auto L0 = dlt_parameters(pin);
  for (std::size_t k = 0; k < 11; ++k) EXPECT_DOUBLE_EQ(L[k], L0[k]);
  for (const auto& p : random_points(20, 2)) EXPECT_LT((dlt.project(p) - pin.project(p)).norm(), 1e-9);
  EXPECT_LT((dlt.centre() - Eigen::Vector3d(0.015, 0.01, 0.3)).norm(), 1e-12);
}

TEST(Camera, RejectsBadIntrinsicsAndRotations) {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  K(0, 0) = -1.0;
  EXPECT_THROW(pinhole_camera(K, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(pinhole_camera(Eigen::Matrix3d::Identity(), 2.0 * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
               std::invalid_argument);
}

TEST(Triangulation, ExactProjectionsRecoverPointsTo1e9WithDistortion) {
  const Camera a = top_test_camera(-0.2, 0.05), b = front_test_camera(0.1, -0.02);
  for (const auto& p : random_points(100, 3)) {
    const Triangulated t = triangulate({&a, &b}, {a.project(p), b.project(p)});
    ASSERT_TRUE(t.ok);
    EXPECT_LT((t.p_W - p).norm(), 1e-9);
    EXPECT_LT(t.reprojection_px, 1e-6);
  }
}

TEST(Triangulation, PointBehindACameraIsNotOk) {
  const Camera a = top_test_camera(), b = front_test_camera();
  const Eigen::Vector3d behind(0.015, 0.01, 0.5);  // above the top camera
  const Triangulated t = triangulate({&a, &b}, {a.project(behind), b.project(behind)});
  EXPECT_FALSE(t.ok);
}

TEST(Triangulation, FundamentalMatrixSatisfiesTheEpipolarConstraint) {
  const Camera a = top_test_camera(), b = dlt_camera(dlt_parameters(front_test_camera()));
  const Eigen::Matrix3d F = fundamental_matrix(a, b);
  for (const auto& p : random_points(30, 4)) {
    Eigen::Vector3d l = F * a.project(p).homogeneous();
    l /= l.head<2>().norm();
    EXPECT_LT(std::abs(l.dot(b.project(p).homogeneous())), 1e-9);  // distance to the epipolar line [px]
  }
}

TEST(Calibration, RecoversAKnownCameraFromExactCorrespondences) {
  const Camera truth = front_test_camera();
  const auto X = random_points(8, 5);
  std::vector<Eigen::Vector2d> x;
  for (const auto& p : X) x.push_back(truth.project(p));
  const Calibration cal = calibrate_dlt(X, x);
  EXPECT_LT(cal.rms_px, 1e-8);
  const auto L = dlt_parameters(cal.camera), L0 = dlt_parameters(truth);
  for (std::size_t k = 0; k < 11; ++k) EXPECT_NEAR(L[k], L0[k], 1e-7 * (1.0 + std::abs(L0[k])));
  for (const auto& p : random_points(20, 6)) EXPECT_LT((cal.camera.project(p) - truth.project(p)).norm(), 1e-6);
}

TEST(Calibration, NoisyCorrespondencesReportTheirReprojectionError) {
  const Camera truth = top_test_camera();
  const auto X = random_points(40, 7);
  std::mt19937 rng(8);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::vector<Eigen::Vector2d> x;
  for (const auto& p : X) x.push_back(truth.project(p) + Eigen::Vector2d(noise(rng), noise(rng)));
  const Calibration cal = calibrate_dlt(X, x);
  EXPECT_GT(cal.rms_px, 0.2);
  EXPECT_LT(cal.rms_px, 0.8);
  ASSERT_EQ(cal.residuals_px.size(), X.size());
}

TEST(Calibration, RejectsTooFewAndCoplanarPoints) {
  const Camera truth = top_test_camera();
  auto X = random_points(5, 9);
  std::vector<Eigen::Vector2d> x;
  for (const auto& p : X) x.push_back(truth.project(p));
  EXPECT_THROW(calibrate_dlt(X, x), std::invalid_argument);
  X = random_points(10, 10);
  x.clear();
  for (auto& p : X) {
    p.z() = 0.0;
    x.push_back(truth.project(p));
  }
  EXPECT_THROW(calibrate_dlt(X, x), std::invalid_argument);
}

TEST(CalibrationFile, RoundTripsAndNamesFileAndFieldInErrors) {
  const std::string path = ::testing::TempDir() + "cams.json";
  write_cameras_json(path, {{"top", top_test_camera(-0.1, 0.01)}, {"front", dlt_camera(dlt_parameters(front_test_camera()))}});
  const auto cams = read_cameras_json(path);
  ASSERT_EQ(cams.size(), 2u);
  for (const auto& p : random_points(10, 11)) {
    EXPECT_LT((cams.at("top").project(p) - top_test_camera(-0.1, 0.01).project(p)).norm(), 1e-9);
    EXPECT_LT((cams.at("front").project(p) - front_test_camera().project(p)).norm(), 1e-9);
  }
  // DLT parameters per millimetre give the same camera.
  const auto L = dlt_parameters(front_test_camera());
  std::ofstream(path) << std::setprecision(17) << "{\"length_unit\": \"mm\", \"cameras\": {\"f\": {\"model\": \"dlt\", \"L\": [" << L[0] / 1e3
                      << "," << L[1] / 1e3 << "," << L[2] / 1e3 << "," << L[3] << "," << L[4] / 1e3 << "," << L[5] / 1e3
                      << "," << L[6] / 1e3 << "," << L[7] << "," << L[8] / 1e3 << "," << L[9] / 1e3 << ","
                      << L[10] / 1e3 << "]}}}";
  const Eigen::Vector3d p(0.01, 0.002, 0.003);
  EXPECT_LT((read_cameras_json(path).at("f").project(p) - front_test_camera().project(p)).norm(), 1e-6);
  std::ofstream(path) << R"({"cameras": {"top": {"model": "pinhole", "K": [[1,0,0],[0,1,0]], "R": [], "t": [0,0,0]}}})";
  try {
    read_cameras_json(path);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": field 'cameras.top.K'"), std::string::npos) << e.what();
  }
  std::ofstream(path) << R"({"cameras": {"top": {"model": "pinhole", "K": [[1,0,0],[0,1,0],[0,0,1]], "R": [[1,0,0],[0,1,0],[0,0,1]], "t": [0,0,1], "k7": 0}}})";
  try {
    read_cameras_json(path);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field 'cameras.top.k7'"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

// OpenCV's distortion model (radial, rational, tangential): undistorting a distorted point gives it back,
// and a pinhole camera built from an rvec equals the one built from its rotation matrix.
TEST(Camera, FullOpenCvDistortionRoundTripsAndRvecIsRodrigues) {
  Distortion d;
  d.k1 = -0.21;
  d.k2 = 0.13;
  d.p1 = 0.0012;
  d.p2 = -0.0008;
  d.k3 = -0.05;
  d.k4 = 0.02;
  d.k5 = -0.01;
  d.k6 = 0.004;
  for (double x : {-0.3, -0.05, 0.0, 0.12, 0.28})
    for (double y : {-0.25, 0.0, 0.07, 0.3}) {
      const Eigen::Vector2d n(x, y);
      EXPECT_LT((d.remove(d.apply(n)) - n).norm(), 1e-13) << x << " " << y;
    }
  const Eigen::Vector3d rvec(0.31, -0.42, 0.17);
  const Eigen::Matrix3d R = rotation_from_rvec(rvec);
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LT((R * rvec - rvec).norm(), 1e-15);  // the axis is fixed
  EXPECT_NEAR(std::acos((R.trace() - 1.0) / 2.0), rvec.norm(), 1e-12);
  Eigen::Matrix3d K;
  K << 2400, 0, 640, 0, 2390, 480, 0, 0, 1;
  const Camera c = pinhole_camera(K, R, Eigen::Vector3d(0.01, -0.02, 0.3), d);
  const Eigen::Vector3d p_W(0.004, 0.003, -0.002);
  EXPECT_LT((c.project(c.centre() + 1e-3 * (p_W - c.centre())) - c.project(p_W)).norm(), 1e-9);  // same ray
  EXPECT_LT((c.undistort(c.project(p_W)) - (c.P * p_W.homogeneous()).hnormalized()).norm(), 1e-9);
}
