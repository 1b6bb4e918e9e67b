#pragma once
// Two-view geometry (Hartley & Zisserman): linear triangulation refined to minimum ideal-pixel reprojection
// error, the fundamental matrix of two cameras, and DLT calibration from 3D-2D correspondences.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/recon/camera.hpp"

namespace vibrissa::recon {

struct Triangulated {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  ///< [m]
  double reprojection_px = 0.0;                   ///< RMS over the views, with distortion [px]
  bool ok = false;                                ///< false if the rays are parallel or the point is behind a camera
};

/// Point seen at `pixels[k]` by `cameras[k]` (>= 2 views): homogeneous DLT (H&Z §12.2, SVD) on ideal pixels,
/// then Gauss-Newton on the ideal-pixel reprojection error.
Triangulated triangulate(const std::vector<const Camera*>& cameras, const std::vector<Eigen::Vector2d>& pixels);

/// F with x2^T F x1 = 0 for ideal pixels x1 of camera 1 and x2 of camera 2 (H&Z eq. 9.1).
Eigen::Matrix3d fundamental_matrix(const Camera& camera1, const Camera& camera2);

struct Calibration {
  Camera camera;                        ///< DLT camera
  std::vector<double> residuals_px;     ///< reprojection error of each correspondence [px]
  double rms_px = 0.0;
};
/// DLT calibration (H&Z §7.1, normalised, algorithm 7.1) from >= 6 correspondences not all coplanar;
/// throws std::invalid_argument for fewer points, non-finite values or a degenerate configuration.
Calibration calibrate_dlt(const std::vector<Eigen::Vector3d>& points_W, const std::vector<Eigen::Vector2d>& pixels);

}  // namespace vibrissa::recon

namespace vibrissa::recon {

/// Known 3D points and their pixels in one camera, for calibrate_dlt.
struct Correspondences {
  std::vector<Eigen::Vector3d> points_W;  ///< [m]
  std::vector<Eigen::Vector2d> pixels;    ///< [px]
};
/// CSV with header `x,y,z,u_px,v_px` (x, y, z in `length_unit`: m, mm or um); errors name file, line, field.
Correspondences read_correspondences_csv(const std::string& path, const std::string& length_unit);

}  // namespace vibrissa::recon
