#include "vibrissa/recon/calibration_files.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <toml++/toml.h>
#include <yaml-cpp/yaml.h>

#include "text_cells.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::recon {

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw std::invalid_argument(where + ": " + message);
}

double unit_scale(const std::string& length_unit, const std::string& path, const char* format) {
  if (length_unit.empty())
    fail(path, std::string(format) + " files do not say their length unit: give it (--calibration-unit m, mm or "
                                     "um: the unit of the calibration board's square length)");
  return trial::length_scale(length_unit, path + ": length unit");
}

/// Numbers of a TOML array, flattened one level (a matrix is an array of rows).
std::vector<double> toml_numbers(const toml::node* node, const std::string& where) {
  if (!node || !node->is_array()) fail(where, "expected an array of numbers");
  std::vector<double> out;
  for (const toml::node& item : *node->as_array()) {
    if (item.is_array()) {
      for (const toml::node& x : *item.as_array()) {
        const auto v = x.value<double>();
        if (!v) fail(where, "expected numbers");
        out.push_back(*v);
      }
    } else {
      const auto v = item.value<double>();
      if (!v) fail(where, "expected numbers");
      out.push_back(*v);
    }
  }
  return out;
}

Camera camera_of(const std::vector<double>& K9, const std::vector<double>& dist, const std::vector<double>& rot,
                 const std::vector<double>& t3, double scale, const std::string& where) {
  if (K9.size() != 9) fail(where + " camera matrix", "expected 3x3 numbers, got " + std::to_string(K9.size()));
  if (t3.size() != 3) fail(where + " translation", "expected 3 numbers, got " + std::to_string(t3.size()));
  Eigen::Matrix3d K;
  K << K9[0], K9[1], K9[2], K9[3], K9[4], K9[5], K9[6], K9[7], K9[8];
  Eigen::Matrix3d R;
  if (rot.size() == 3) {
    R = rotation_from_rvec(Eigen::Vector3d(rot[0], rot[1], rot[2]));
  } else if (rot.size() == 9) {
    R << rot[0], rot[1], rot[2], rot[3], rot[4], rot[5], rot[6], rot[7], rot[8];
  } else {
    fail(where + " rotation", "expected a Rodrigues vector (3 numbers) or a 3x3 matrix, got " + std::to_string(rot.size()) +
                                  " numbers");
  }
  const Distortion d = dist.empty() ? Distortion{} : Distortion::from_opencv(dist, where + " distortion");
  try {
    return pinhole_camera(K, R, Eigen::Vector3d(t3[0], t3[1], t3[2]) * scale, d);
  } catch (const std::invalid_argument& e) {
    fail(where, e.what());
  }
}

/// Numbers of a FileStorage node: an opencv-matrix mapping (rows, cols, data) or a (nested) list.
std::vector<double> yaml_numbers(const YAML::Node& node, const std::string& where) {
  std::vector<double> out;
  try {
    if (node.IsMap()) {
      if (!node["data"]) fail(where, "expected an opencv-matrix with 'data'");
      out = yaml_numbers(node["data"], where);
      if (node["rows"] && node["cols"] && out.size() != node["rows"].as<std::size_t>() * node["cols"].as<std::size_t>())
        fail(where, "'data' does not hold rows x cols numbers");
      return out;
    }
    if (node.IsSequence()) {
      for (const auto& item : node) {
        if (item.IsSequence()) {
          for (const auto& x : item) out.push_back(x.as<double>());
        } else {
          out.push_back(item.as<double>());
        }
      }
      return out;
    }
  } catch (const YAML::Exception& e) {
    fail(where, std::string("expected numbers: ") + e.what());
  }
  fail(where, "expected a matrix (rows, cols, data) or a list of numbers");
}

std::optional<YAML::Node> first_of(const YAML::Node& doc, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (doc[k]) return doc[k];
  return std::nullopt;
}

std::string key_list(std::initializer_list<const char*> keys) {
  std::string s;
  for (const char* k : keys) s += (s.empty() ? "'" : ", '") + std::string(k) + "'";
  return s;
}

}  // namespace

std::map<std::string, Camera> read_anipose_toml(const std::string& path, const std::string& length_unit) {
  toml::table doc;
  try {
    doc = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "not valid TOML: " << e.description() << " (line " << e.source().begin.line << ")";
    fail(path, msg.str());
  }
  const double scale = unit_scale(length_unit, path, "anipose calibration.toml");
  std::map<std::string, Camera> out;
  for (auto&& [key, node] : doc) {
    const std::string table(key.str());
    if (table == "metadata" || !node.is_table()) continue;
    const toml::table& cam = *node.as_table();
    const std::string where = path + ": table [" + table + "]";
    const auto name = cam["name"].value<std::string>();
    if (!name) fail(where + ", field 'name'", "expected the camera's name (a string)");
    if (const auto type = cam["type"].value<std::string>(); type && *type != "pinhole" && *type != "")
      fail(where + ", field 'type'", "'" + *type + "' cameras are not supported (pinhole only)");
    for (const char* field : {"matrix", "rotation", "translation"})
      if (!cam[field]) fail(where + ", field '" + field + "'", "required field is missing");
    const std::vector<double> dist =
        cam["distortions"] ? toml_numbers(cam["distortions"].node(), where + ", field 'distortions'") : std::vector<double>{};
    Camera c = camera_of(toml_numbers(cam["matrix"].node(), where + ", field 'matrix'"), dist,
                         toml_numbers(cam["rotation"].node(), where + ", field 'rotation'"),
                         toml_numbers(cam["translation"].node(), where + ", field 'translation'"), scale, where);
    if (!out.emplace(*name, c).second) fail(where + ", field 'name'", "camera '" + *name + "' appears twice");
  }
  if (out.empty()) fail(path, "no camera table ([cam_0], ...) found");
  return out;
}

Camera read_opencv_storage(const std::string& path, const std::string& length_unit) {
  std::ifstream in = open_input(path, "calibration file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  // OpenCV writes "%YAML:1.0" (not a YAML 1.2 directive) and "---"; drop the directive line.
  if (text.rfind("%YAML", 0) == 0) text.erase(0, text.find('\n') == std::string::npos ? text.size() : text.find('\n') + 1);
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    fail(path, std::string("not a valid OpenCV FileStorage file (YAML or JSON): ") + e.what());
  }
  if (!doc.IsMap()) fail(path, "expected a mapping of named matrices");
  const double scale = unit_scale(length_unit, path, "OpenCV FileStorage");
  const auto K_keys = {"camera_matrix", "cameraMatrix", "K", "M", "mtx"};
  const auto D_keys = {"distortion_coefficients", "dist_coeffs", "distCoeffs", "D", "dist"};
  const auto R_keys = {"rvec", "R", "rotation"};
  const auto T_keys = {"tvec", "T", "t", "translation"};
  const auto K = first_of(doc, K_keys), D = first_of(doc, D_keys), R = first_of(doc, R_keys),
             T = first_of(doc, T_keys);
  if (!K) fail(path, "no camera matrix (" + key_list(K_keys) + ")");
  if (!R) fail(path, "no rotation (" + key_list(R_keys) + "): the camera's pose is needed to triangulate");
  if (!T) fail(path, "no translation (" + key_list(T_keys) + "): the camera's pose is needed to triangulate");
  std::vector<double> dist = D ? yaml_numbers(*D, path + ": distortion") : std::vector<double>{};
  // OpenCV may write 14 coefficients (with thin-prism and tilt terms); zeros beyond the 8th are accepted.
  if (dist.size() == 12 || dist.size() == 14) {
    for (std::size_t k = 8; k < dist.size(); ++k)
      if (dist[k] != 0.0) fail(path + ": distortion", "thin-prism and tilt coefficients (s1..s4, tx, ty) are not supported");
    dist.resize(8);
  }
  return camera_of(yaml_numbers(*K, path + ": camera matrix"), dist, yaml_numbers(*R, path + ": rotation"),
                   yaml_numbers(*T, path + ": translation"), scale, path + ":");
}

std::map<std::string, Camera> read_calibration(const std::string& spec, const std::string& length_unit) {
  const auto eq = spec.find('=');
  if (!std::filesystem::exists(spec) && eq != std::string::npos && eq > 0) {
    const std::string name = spec.substr(0, eq), path = spec.substr(eq + 1);
    return {{name, read_opencv_storage(path, length_unit)}};
  }
  const std::string ext = std::filesystem::path(spec).extension().string();
  if (ext == ".toml") return read_anipose_toml(spec, length_unit);
  if (ext == ".yml" || ext == ".yaml")
    fail(spec, "an OpenCV FileStorage file holds one camera: give it as NAME=" + spec);
  return read_cameras_json(spec);
}

}  // namespace vibrissa::recon
