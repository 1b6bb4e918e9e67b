#include "vibrissa/recon/camera.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "vibrissa/io/json_file.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::recon {

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw std::invalid_argument(where + ": " + message);
}

/// r_ideal with r_ideal (1 + k1 r^2 + k2 r^4) = r_distorted (Newton from r_distorted).
double undistort_radius(double r_d, double k1, double k2) {
  double r = r_d;
  for (int it = 0; it < 100; ++it) {
    const double r2 = r * r;
    const double f = r * (1.0 + k1 * r2 + k2 * r2 * r2) - r_d;
    const double df = 1.0 + 3.0 * k1 * r2 + 5.0 * k2 * r2 * r2;
    const double step = f / df;
    r -= step;
    if (std::abs(step) <= 1e-16 * std::max(1.0, r)) break;
  }
  return r;
}

}  // namespace

Eigen::Vector2d Camera::project(const Eigen::Vector3d& p_W) const {
  if (model == Model::dlt) {
    const Eigen::Vector3d x = P * p_W.homogeneous();
    return x.hnormalized();
  }
  const Eigen::Vector3d p_C = R_CW * p_W + t_C;
  Eigen::Vector2d n = p_C.hnormalized();
  const double r2 = n.squaredNorm();
  n *= 1.0 + k1 * r2 + k2 * r2 * r2;
  return (K * n.homogeneous()).hnormalized();
}

Eigen::Vector2d Camera::undistort(const Eigen::Vector2d& pixel) const {
  if (model == Model::dlt || (k1 == 0.0 && k2 == 0.0)) return pixel;
  const Eigen::Vector2d d = (K.inverse() * pixel.homogeneous()).hnormalized();
  const double r_d = d.norm();
  if (r_d == 0.0) return pixel;
  const Eigen::Vector2d n = d * (undistort_radius(r_d, k1, k2) / r_d);
  return (K * n.homogeneous()).hnormalized();
}

Eigen::Vector3d Camera::centre() const { return -P.leftCols<3>().inverse() * P.col(3); }

Camera pinhole_camera(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R_CW, const Eigen::Vector3d& t_C, double k1,
                      double k2) {
  if (!K.allFinite() || !R_CW.allFinite() || !t_C.allFinite() || !std::isfinite(k1) || !std::isfinite(k2))
    throw std::invalid_argument("pinhole camera: K, R, t, k1 and k2 must be finite");
  if (!(K(0, 0) > 0.0 && K(1, 1) > 0.0) || K(1, 0) != 0.0 || K(2, 0) != 0.0 || K(2, 1) != 0.0 || K(2, 2) != 1.0)
    throw std::invalid_argument("pinhole camera: K must be [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with fx, fy > 0");
  if (!(R_CW.transpose() * R_CW - Eigen::Matrix3d::Identity()).isZero(1e-6) || !(R_CW.determinant() > 0.0))
    throw std::invalid_argument("pinhole camera: R must be a rotation (orthonormal, determinant +1)");
  Camera c;
  c.model = Camera::Model::pinhole;
  c.K = K;
  c.R_CW = R_CW;
  c.t_C = t_C;
  c.k1 = k1;
  c.k2 = k2;
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
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open calibration file");
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
          if (key != "model" && key != "K" && key != "R" && key != "t" && key != "k1" && key != "k2" &&
              key != "rms_reprojection_px")
            fail(where + "." + key + "'", "unknown field for a pinhole camera");
        }
        for (const char* key : {"K", "R", "t"})
          if (!cj.contains(key)) fail(where + "." + key + "'", "required field is missing");
        const Eigen::Matrix3d K = matrix(cj["K"], 3, 3, where + ".K'");
        const Eigen::Matrix3d R = matrix(cj["R"], 3, 3, where + ".R'");
        const Eigen::Vector3d t = matrix(cj["t"], 3, 1, where + ".t'") * Ls;
        const double k1 = cj.contains("k1") ? number(cj["k1"], where + ".k1'") : 0.0;
        const double k2 = cj.contains("k2") ? number(cj["k2"], where + ".k2'") : 0.0;
        out.emplace(name, pinhole_camera(K, R, t, k1, k2));
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
      j["k1"] = c.k1;
      j["k2"] = c.k2;
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
