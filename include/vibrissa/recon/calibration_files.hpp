#pragma once
// The calibrations users have (docs/formats.md, "Camera calibrations"): vibrissa's own JSON, anipose's
// calibration.toml (toml++) and one camera per OpenCV FileStorage file, YAML or JSON (yaml-cpp). All give
// pinhole cameras with OpenCV's distortion model (recon/camera.hpp), world coordinates in metres.
#include <map>
#include <string>

#include "vibrissa/recon/camera.hpp"

namespace vibrissa::recon {

/// anipose calibration.toml: one table per camera ([cam_0], ...) with `name`, `matrix` (3x3), `distortions`
/// (OpenCV's 4, 5 or 8 coefficients), `rotation` (Rodrigues vector), `translation` (in the unit of the board's
/// square length, `length_unit`); other tables ([metadata]) are skipped. Cameras are named by `name`.
std::map<std::string, Camera> read_anipose_toml(const std::string& path, const std::string& length_unit);

/// One camera of an OpenCV FileStorage file (.yml/.yaml, with or without the `%YAML:1.0` line, or .json):
/// the camera matrix (`camera_matrix`, `cameraMatrix`, `K`, `M` or `mtx`), distortion (`distortion_coefficients`,
/// `dist_coeffs`, `distCoeffs`, `D` or `dist`; absent: none), rotation (`rvec`: 3 numbers, or `R`: 3x3) and
/// translation (`tvec`, `T` or `t`, in `length_unit`); each an `!!opencv-matrix` (rows, cols, data) or a list.
Camera read_opencv_storage(const std::string& path, const std::string& length_unit);

/// A calibration argument: `FILE.json` (vibrissa's JSON, docs/reconstruction.md), `FILE.toml` (anipose), or
/// `NAME=FILE` (one camera in an OpenCV FileStorage .yml/.yaml/.json file). `length_unit` (m, mm, um) is
/// required for anipose and OpenCV files, which do not say their unit; vibrissa's JSON says its own.
std::map<std::string, Camera> read_calibration(const std::string& spec, const std::string& length_unit);

}  // namespace vibrissa::recon
