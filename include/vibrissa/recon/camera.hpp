#pragma once
// Cameras of a tracked video (docs/reconstruction.md): a pinhole camera with OpenCV's distortion model (K, R_CW,
// t_C; k1 k2 p1 p2 k3 k4 k5 k6: radial, rational and tangential) or a DLT camera (11 parameters, Hartley &
// Zisserman §7.1 with P(2,3) = 1). World points are SI [m]; image points are pixels [px]. Both reduce to a 3x4 projection matrix P acting on *ideal* pixels
// (distortion removed), so triangulation and epipolar geometry are linear in every model.
#include <array>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace vibrissa::recon {

/// OpenCV's lens distortion of normalised coordinates n = (x, y), r² = x² + y² (cv::projectPoints):
/// n_d = n (1 + k1 r² + k2 r⁴ + k3 r⁶) / (1 + k4 r² + k5 r⁴ + k6 r⁶)
///       + (2 p1 x y + p2 (r² + 2 x²), p1 (r² + 2 y²) + 2 p2 x y).
struct Distortion {
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0, k4 = 0.0, k5 = 0.0, k6 = 0.0;
  [[nodiscard]] bool none() const;
  [[nodiscard]] Eigen::Vector2d apply(const Eigen::Vector2d& n) const;
  /// n with apply(n) = n_d (Newton from n_d); throws std::invalid_argument if it does not converge.
  [[nodiscard]] Eigen::Vector2d remove(const Eigen::Vector2d& n_d) const;
  /// From OpenCV's coefficient vector (k1, k2, p1, p2[, k3[, k4, k5, k6]]): 4, 5 or 8 numbers.
  static Distortion from_opencv(const std::vector<double>& coefficients, const std::string& where);
};

struct Camera {
  enum class Model { pinhole, dlt };
  Model model = Model::pinhole;
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();     ///< intrinsics [px] (pinhole)
  Eigen::Matrix3d R_CW = Eigen::Matrix3d::Identity();  ///< world -> camera rotation (pinhole)
  Eigen::Vector3d t_C = Eigen::Vector3d::Zero();       ///< p_C = R_CW p_W + t_C [m] (pinhole)
  Distortion distortion;                               ///< of normalised coordinates (pinhole)
  Eigen::Matrix<double, 3, 4> P = Eigen::Matrix<double, 3, 4>::Zero();  ///< ideal-pixel projection of [p_W; 1]

  /// Pixel of a world point (with distortion).
  [[nodiscard]] Eigen::Vector2d project(const Eigen::Vector3d& p_W) const;
  /// Ideal (undistorted) pixel of a measured pixel: the point P maps to. Identity for DLT cameras.
  [[nodiscard]] Eigen::Vector2d undistort(const Eigen::Vector2d& pixel) const;
  /// Camera centre in the world [m] (null vector of P).
  [[nodiscard]] Eigen::Vector3d centre() const;
};

/// Pinhole camera; throws std::invalid_argument unless K is upper triangular with positive focal lengths,
/// R_CW a rotation and everything finite.
Camera pinhole_camera(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R_CW, const Eigen::Vector3d& t_C,
                      const Distortion& distortion);
Camera pinhole_camera(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R_CW, const Eigen::Vector3d& t_C,
                      double k1 = 0.0, double k2 = 0.0);
/// Rotation of a Rodrigues vector (OpenCV's rvec: axis times angle [rad]).
Eigen::Matrix3d rotation_from_rvec(const Eigen::Vector3d& rvec);
/// DLT camera from its 11 parameters L1..L11 for world points in metres (u = (L1 X + L2 Y + L3 Z + L4) /
/// (L9 X + L10 Y + L11 Z + 1), v likewise with L5..L8).
Camera dlt_camera(const std::array<double, 11>& L);
/// The 11 DLT parameters of any camera without distortion (P scaled to P(2,3) = 1).
std::array<double, 11> dlt_parameters(const Camera& camera);

/// Named cameras of a calibration JSON file (docs/reconstruction.md, "Calibration file"):
///   {"length_unit": "mm", "cameras": {"top": {"model": "pinhole", "K": [[..],[..],[..]], "R": [[..]x3],
///    "t": [..], "k1": 0, "k2": 0}, "front": {"model": "dlt", "L": [11 numbers]}}}
/// Errors name the file and the field.
std::map<std::string, Camera> read_cameras_json(const std::string& path);
/// Writes cameras as that JSON (metres), with optional per-camera extra fields (e.g. RMS error).
void write_cameras_json(const std::string& path, const std::map<std::string, Camera>& cameras,
                        const std::map<std::string, double>& rms_reprojection_px = {});

}  // namespace vibrissa::recon
