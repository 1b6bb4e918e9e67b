"""Calibrations users have (docs/formats.md, "Camera calibrations"): the full OpenCV pinhole model (K, k1 k2 p1
p2 k3 [k4 k5 k6], rvec or R, tvec) in vibrissa's JSON, anipose's calibration.toml and OpenCV FileStorage
YAML/JSON project world points exactly as OpenCV's own cv2.projectPoints does (to 1e-9 px)."""

import json

import cv2
import numpy as np
import pytest

from vibrissa import _vibrissa

RVEC = np.array([0.31, -0.42, 0.17])
TVEC = np.array([12.0, -7.5, 310.0])  # mm
K = np.array([[2410.5, 0.0, 655.25], [0.0, 2398.75, 498.5], [0.0, 0.0, 1.0]])
DISTORTIONS = {
    "5": np.array([-0.21, 0.13, 0.0012, -0.0008, -0.05]),
    "8": np.array([-0.21, 0.13, 0.0012, -0.0008, -0.05, 0.02, -0.01, 0.004]),
    "4": np.array([-0.11, 0.0, 0.002, 0.001]),
}


def points_mm():
    rng = np.random.default_rng(4)
    return rng.uniform([-40, -30, -20], [40, 30, 20], (200, 3))  # up to ~0.2 of the image's half-width


def cv2_pixels(dist, P_mm):
    px, _ = cv2.projectPoints(P_mm.reshape(-1, 1, 3), RVEC, TVEC, K, dist)
    return px.reshape(-1, 2)


def ours(spec, camera, P_mm, unit="mm"):
    return np.array(_vibrissa._project_points(spec, camera, (P_mm * 1e-3).tolist(), unit))


@pytest.mark.parametrize("n", sorted(DISTORTIONS))
def test_vibrissa_json_with_rvec_and_dist_matches_opencv(tmp_path, n):
    R, _ = cv2.Rodrigues(RVEC)
    for rot in ({"rvec": RVEC.tolist()}, {"R": R.tolist()}):
        cam = {"model": "pinhole", "K": K.tolist(), "t": TVEC.tolist(), "dist": DISTORTIONS[n].tolist(), **rot}
        path = tmp_path / "cams.json"
        path.write_text(json.dumps({"length_unit": "mm", "cameras": {"a": cam}}))
        P = points_mm()
        err = np.abs(ours(str(path), "a", P, "") - cv2_pixels(DISTORTIONS[n], P)).max()
        assert err < 1e-9, (n, list(rot), err)


def test_anipose_toml_matches_opencv(tmp_path):
    toml = ["[cam_0]", 'name = "top"', "size = [ 1280, 1024,]",
            "matrix = [ " + ", ".join("[ " + ", ".join(repr(float(v)) for v in row) + ",]" for row in K) + ",]",
            "distortions = [ " + ", ".join(repr(float(v)) for v in DISTORTIONS["5"]) + ",]",
            "rotation = [ " + ", ".join(repr(float(v)) for v in RVEC) + ",]",
            "translation = [ " + ", ".join(repr(float(v)) for v in TVEC) + ",]", "",
            "[metadata]", "adjusted = false", "error = 0.42"]
    path = tmp_path / "calibration.toml"
    path.write_text("\n".join(toml) + "\n")
    P = points_mm()
    assert np.abs(ours(str(path), "top", P) - cv2_pixels(DISTORTIONS["5"], P)).max() < 1e-9
    with pytest.raises(ValueError, match="length unit"):
        ours(str(path), "top", P, "")


@pytest.mark.parametrize("ext", ["yml", "json"])
def test_opencv_filestorage_matches_opencv(tmp_path, ext):
    path = tmp_path / f"front.{ext}"
    fs = cv2.FileStorage(str(path), cv2.FILE_STORAGE_WRITE)
    fs.write("camera_matrix", K)
    fs.write("distortion_coefficients", DISTORTIONS["8"].reshape(1, -1))
    fs.write("rvec", RVEC.reshape(3, 1))
    fs.write("tvec", TVEC.reshape(3, 1))
    fs.release()
    P = points_mm()
    err = np.abs(ours(f"front={path}", "front", P) - cv2_pixels(DISTORTIONS["8"], P)).max()
    assert err < 1e-9, err


def test_opencv_filestorage_without_pose_is_refused(tmp_path):
    path = tmp_path / "intrinsics.yml"
    fs = cv2.FileStorage(str(path), cv2.FILE_STORAGE_WRITE)
    fs.write("camera_matrix", K)
    fs.release()
    with pytest.raises(ValueError, match="no rotation"):
        ours(f"cam={path}", "cam", points_mm())
