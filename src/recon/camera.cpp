#include "vibrissa/recon/camera.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "text_cells.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::recon {

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw std::invalid_argument(where + ": " + message);
}

}  // namespace

Eigen::Vector2d Camera::project(const Eigen::Vector3d& p_W) const {
  if (model == Model::dlt) {
    const Eigen::Vector3d x = P * p_W.homogeneous();
    return x.hnormalized();
  }
  const Eigen::Vector3d p_C = R_CW * p_W + t_C;
  return (K * distortion.apply(p_C.hnormalized()).homogeneous()).hnormalized();
}

Eigen::Vector2d Camera::undistort(const Eigen::Vector2d& pixel) const {
  if (model == Model::dlt || distortion.none()) return pixel;
  const Eigen::Vector2d d = (K.inverse() * pixel.homogeneous()).hnormalized();
  return (K * distortion.remove(d).homogeneous()).hnormalized();
}

bool Distortion::none() const {
  return k1 == 0.0 && k2 == 0.0 && p1 == 0.0 && p2 == 0.0 && k3 == 0.0 && k4 == 0.0 && k5 == 0.0 && k6 == 0.0;
}

Eigen::Vector2d Distortion::apply(const Eigen::Vector2d& n) const {
  const double x = n.x(), y = n.y(), r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
  const double radial = (1.0 + k1 * r2 + k2 * r4 + k3 * r6) / (1.0 + k4 * r2 + k5 * r4 + k6 * r6);
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Vector2d Distortion::remove(const Eigen::Vector2d& n_d) const {
  Eigen::Vector2d n = n_d;
  constexpr double h = 1e-7;
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector2d f = apply(n) - n_d;
    if (f.norm() <= 1e-15 * std::max(1.0, n_d.norm())) return n;
    Eigen::Matrix2d J;  // central differences: exact to ~1e-9, enough for Newton's quadratic convergence here
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d e = Eigen::Vector2d::Zero();
      e[k] = h;
      J.col(k) = (apply(n + e) - apply(n - e)) / (2.0 * h);
    }
    const Eigen::Vector2d step = J.partialPivLu().solve(f);
    if (!step.allFinite()) break;
    n -= step;
  }
  if ((apply(n) - n_d).norm() <= 1e-12 * std::max(1.0, n_d.norm())) return n;
  throw std::invalid_argument("distortion: cannot undistort the normalised point (" + std::to_string(n_d.x()) + ", " +
                              std::to_string(n_d.y()) + "): outside the range where the lens model is invertible");
}

Distortion Distortion::from_opencv(const std::vector<double>& c, const std::string& where) {
  if (c.size() != 4 && c.size() != 5 && c.size() != 8)
    fail(where, "expected 4, 5 or 8 distortion coefficients (k1, k2, p1, p2[, k3[, k4, k5, k6]]), got " +
                    std::to_string(c.size()) + " (thin-prism and tilt terms are not supported)");
  for (double v : c)
    if (!std::isfinite(v)) fail(where, "distortion coefficients must be finite");
  Distortion d;
  d.k1 = c[0];
  d.k2 = c[1];
  d.p1 = c[2];
  d.p2 = c[3];
  if (c.size() >= 5) d.k3 = c[4];
  if (c.size() == 8) {
    d.k4 = c[5];
    d.k5 = c[6];
    d.k6 = c[7];
  }
  return d;
}

Eigen::Matrix3d rotation_from_rvec(const Eigen::Vector3d& rvec) {
  const double angle = rvec.norm();
  if (!(angle > 0.0)) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rvec / angle).toRotationMatrix();
}

Eigen::Vector3d Camera::centre() const { return -P.leftCols<3>().inverse() * P.col(3); }

Camera pinhole_camera(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R_CW, const Eigen::Vector3d& t_C, double k1,
                      double k2) {
  Distortion d;
  d.k1 = k1;
  d.k2 = k2;
  return pinhole_camera(K, R_CW, t_C, d);
}

Camera pinhole_camera(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R_CW, const Eigen::Vector3d& t_C,
                      const Distortion& d) {
  if (!K.allFinite() || !R_CW.allFinite() || !t_C.allFinite() ||
      !Eigen::Matrix<double, 8, 1>(d.k1, d.k2, d.p1, d.p2, d.k3, d.k4, d.k5, d.k6).allFinite())
    throw std::invalid_argument("pinhole camera: K, R, t and the distortion coefficients must be finite");
  if (!(K(0, 0) > 0.0 && K(1, 1) > 0.0) || K(1, 0) != 0.0 || K(2, 0) != 0.0 || K(2, 1) != 0.0 || K(2, 2) != 1.0)
    throw std::invalid_argument("pinhole camera: K must be [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with fx, fy > 0");
  if (!(R_CW.transpose() * R_CW - Eigen::Matrix3d::Identity()).isZero(1e-6) || !(R_CW.determinant() > 0.0))
    throw std::invalid_argument("pinhole camera: R must be a rotation (orthonormal, determinant +1)");
  Camera c;
  c.model = Camera::Model::pinhole;
  c.K = K;
  c.R_CW = R_CW;
  c.t_C = t_C;
  c.distortion = d;
  c.P.leftCols<3>() = K * R_CW;
  c.P.col(3) = K * t_C;
  return c;
}

Camera dlt_camera(const std::array<double, 11>& L) {
  for (double v : L)
    if (!std::isfinite(v)) throw std::invalid_argument("DLT camera: the 11 parameters must be finite");
  Camera c;
  c.model = Camera::Model::dlt;
  c.P << L[0], L[1], L[2], L[3], L[4], L[5], L[6], L[7], L[8], L[9], L[10], 1.0;
  if (!(std::abs(c.P.leftCols<3>().determinant()) > 0.0))
    throw std::invalid_argument("DLT camera: the parameters are degenerate (left 3x3 block is singular)");
  return c;
}

std::array<double, 11> dlt_parameters(const Camera& c) {
  const Eigen::Matrix<double, 3, 4> P = c.P / c.P(2, 3);
  return {P(0, 0), P(0, 1), P(0, 2), P(0, 3), P(1, 0), P(1, 1), P(1, 2), P(1, 3), P(2, 0), P(2, 1), P(2, 2)};
}

namespace {

using nlohmann::json;

double number(const json& j, const std::string& where) {
  if (!j.is_number()) fail(where, "expected a number, got " + j.dump());
  return j.get<double>();
}
Eigen::MatrixXd matrix(const json& j, int rows, int cols, const std::string& where) {
  if (!j.is_array() || int(j.size()) != rows) fail(where, "expected " + std::to_string(rows) + " rows");
  Eigen::MatrixXd m(rows, cols);
  for (int r = 0; r < rows; ++r) {
    const json& row = cols == 1 ? json::array({j[std::size_t(r)]}) : j[std::size_t(r)];
    if (!row.is_array() || int(row.size()) != cols)
      fail(where, "row " + std::to_string(r + 1) + ": expected " + std::to_string(cols) + " numbers");
    for (int c = 0; c < cols; ++c) m(r, c) = number(row[std::size_t(c)], where);
  }
  return m;
}

}  // namespace

std::map<std::string, Camera> read_cameras_json(const std::string& path) {
  std::ifstream in = open_input(path, "calibration file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::parse_error& e) {
    fail(path, std::string("not valid JSON: ") + e.what());
  }
  if (!doc.is_object()) fail(path, "expected a JSON object");
  for (const auto& [key, value] : doc.items()) {
    (void)value;
    if (key != "length_unit" && key != "cameras") fail(path + ": field '" + key + "'", "unknown field");
  }
  const std::string unit = doc.value("length_unit", std::string("m"));
  const double Ls = trial::length_scale(unit, path + ": field 'length_unit'");
  if (!doc.contains("cameras") || !doc["cameras"].is_object() || doc["cameras"].empty())
    fail(path + ": field 'cameras'", "expected an object of named cameras");
  std::map<std::string, Camera> out;
  for (const auto& [name, cj] : doc["cameras"].items()) {
    const std::string where = path + ": field 'cameras." + name;
    if (!cj.is_object()) fail(where + "'", "expected an object");
    const std::string model = cj.value("model", std::string());
    try {
      if (model == "pinhole") {
        for (const auto& [key, v] : cj.items()) {
          (void)v;
          if (key != "model" && key != "K" && key != "R" && key != "rvec" && key != "t" && key != "dist" &&
              key != "k1" && key != "k2" && key != "p1" && key != "p2" && key != "k3" && key != "k4" && key != "k5" &&
              key != "k6" && key != "rms_reprojection_px")
            fail(where + "." + key + "'", "unknown field for a pinhole camera");
        }
        for (const char* key : {"K", "t"})
          if (!cj.contains(key)) fail(where + "." + key + "'", "required field is missing");
        if (cj.contains("R") == cj.contains("rvec")) fail(where + ".R'", "give exactly one of 'R' (3x3) and 'rvec' (3)");
        const Eigen::Matrix3d K = matrix(cj["K"], 3, 3, where + ".K'");
        const Eigen::Matrix3d R = cj.contains("R") ? Eigen::Matrix3d(matrix(cj["R"], 3, 3, where + ".R'"))
                                                   : rotation_from_rvec(matrix(cj["rvec"], 3, 1, where + ".rvec'"));
        const Eigen::Vector3d t = matrix(cj["t"], 3, 1, where + ".t'") * Ls;
        Distortion d;
        if (cj.contains("dist")) {
          for (const char* key : {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"})
            if (cj.contains(key)) fail(where + "." + key + "'", "give the distortion either as 'dist' or by name, not both");
          if (!cj["dist"].is_array()) fail(where + ".dist'", "expected an array of 4, 5 or 8 numbers");
          std::vector<double> c;
          for (const auto& v : cj["dist"]) c.push_back(number(v, where + ".dist'"));
          d = Distortion::from_opencv(c, where + ".dist'");
        } else {
          const std::array<std::pair<const char*, double*>, 8> named{{{"k1", &d.k1}, {"k2", &d.k2}, {"p1", &d.p1},
                                                                       {"p2", &d.p2}, {"k3", &d.k3}, {"k4", &d.k4},
                                                                       {"k5", &d.k5}, {"k6", &d.k6}}};
          for (const auto& [key, value] : named)
            if (cj.contains(key)) *value = number(cj[key], where + "." + key + "'");
        }
        out.emplace(name, pinhole_camera(K, R, t, d));
      } else if (model == "dlt") {
        for (const auto& [key, v] : cj.items()) {
          (void)v;
          if (key != "model" && key != "L" && key != "rms_reprojection_px")
            fail(where + "." + key + "'", "unknown field for a DLT camera");
        }
        if (!cj.contains("L") || !cj["L"].is_array() || cj["L"].size() != 11)
          fail(where + ".L'", "expected 11 numbers");
        std::array<double, 11> L{};
        for (std::size_t k = 0; k < 11; ++k) L[k] = number(cj["L"][k], where + ".L'");
        // Parameters given per length unit: P acts on X[unit] = X[m] / Ls.
        for (std::size_t k : {0u, 1u, 2u, 4u, 5u, 6u, 8u, 9u, 10u}) L[k] /= Ls;
        out.emplace(name, dlt_camera(L));
      } else {
        fail(where + ".model'", "expected \"pinhole\" or \"dlt\", got \"" + model + "\"");
      }
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      if (what.rfind(path, 0) == 0) throw;
      fail(where + "'", what);
    }
  }
  return out;
}

void write_cameras_json(const std::string& path, const std::map<std::string, Camera>& cameras,
                        const std::map<std::string, double>& rms_reprojection_px) {
  json doc;
  doc["length_unit"] = "m";
  json& cj = doc["cameras"];
  cj = json::object();
  for (const auto& [name, c] : cameras) {
    json j;
    if (c.model == Camera::Model::pinhole) {
      j["model"] = "pinhole";
      auto rows = [](const Eigen::Matrix3d& m) {
        return json::array({{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}});
      };
      j["K"] = rows(c.K);
      j["R"] = rows(c.R_CW);
      j["t"] = {c.t_C.x(), c.t_C.y(), c.t_C.z()};
      const Distortion& d = c.distortion;
      j["dist"] = {d.k1, d.k2, d.p1, d.p2, d.k3, d.k4, d.k5, d.k6};
    } else {
      j["model"] = "dlt";
      j["L"] = dlt_parameters(c);
    }
    if (auto it = rms_reprojection_px.find(name); it != rms_reprojection_px.end()) j["rms_reprojection_px"] = it->second;
    cj[name] = j;
  }
  io::write_json_file(path, doc);
}

}  // namespace vibrissa::recon
