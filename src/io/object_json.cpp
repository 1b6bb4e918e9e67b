#include "vibrissa/io/object_json.hpp"

#include <cmath>
#include <limits>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/io/json_input.hpp"
#include "vibrissa/objects/box.hpp"
#include "vibrissa/objects/cylinder.hpp"
#include "vibrissa/objects/mesh.hpp"
#include "vibrissa/objects/plane.hpp"
#include "vibrissa/objects/sphere.hpp"
#include "vibrissa/trial/format.hpp"

namespace vibrissa::io {

namespace {

using nlohmann::json;

struct Reader {
  const json& j;
  const std::string& where;
  LengthKeys keys;
  [[nodiscard]] std::string length_key(const char* name) const {
    return std::string(name) + (keys == LengthKeys::millimetres ? "_mm" : "");
  }
  [[nodiscard]] double scale() const { return keys == LengthKeys::millimetres ? 1e-3 : 1.0; }
  [[nodiscard]] std::string field(const std::string& key) const { return where + "." + key; }
  [[nodiscard]] const json& at(const std::string& key) const {
    if (!j.contains(key)) invalid_input(field(key) + " is required for a " + json_string(j.at("type"), where + ".type"));
    return j.at(key);
  }
  [[nodiscard]] Eigen::Vector3d point(const char* name) const { return scale() * json_vec3(at(length_key(name)), field(length_key(name))); }
  [[nodiscard]] double length(const char* name) const { return scale() * json_number(at(length_key(name)), field(length_key(name))); }
  [[nodiscard]] Eigen::Vector3d direction(const char* name) const { return json_vec3(at(name), field(name)); }
  [[nodiscard]] Eigen::Matrix3d rotation() const {
    if (!j.contains("rotation")) return Eigen::Matrix3d::Identity();
    const json& r = j.at("rotation");
    if (!r.is_array() || r.size() != 3) invalid_input(field("rotation") + " must hold 3 rows of 3 numbers, got " + describe(r));
    Eigen::Matrix3d R;
    for (int i = 0; i < 3; ++i) R.row(i) = json_vec3(r[static_cast<std::size_t>(i)], field("rotation") + "[" + std::to_string(i) + "]");
    return R;
  }
  void only(std::initializer_list<std::string> allowed, std::initializer_list<const char*> extra) const {
    for (const auto& [key, value] : j.items()) {
      bool ok = key == "type";
      for (const auto& a : allowed) ok = ok || key == a;
      for (const char* a : extra) ok = ok || key == a;
      if (!ok) invalid_input("unknown field " + where + "." + quote_text(key));
    }
  }
};

}  // namespace

std::shared_ptr<const Shape> shape_from_json(const json& j, const std::string& where, LengthKeys keys,
                                             const std::filesystem::path& base_dir,
                                             std::initializer_list<const char*> extra_keys) {
  if (!j.is_object()) invalid_input(where + " must be an object, got " + describe(j));
  if (!j.contains("type")) invalid_input(where + ".type is required (cylinder, plane, sphere, box, mesh)");
  const std::string type = json_string(j.at("type"), where + ".type");
  const Reader r{j, where, keys};
  auto L = [&](const char* name) { return r.length_key(name); };
  if (type == "cylinder") {
    r.only({L("point"), "axis", L("radius"), L("length")}, extra_keys);
    const double length = j.contains(L("length")) ? r.length("length") : std::numeric_limits<double>::infinity();
    return std::make_shared<Cylinder>(r.point("point"), r.direction("axis"), r.length("radius"), length);
  }
  if (type == "plane") {
    r.only({L("point"), "normal"}, extra_keys);
    return std::make_shared<Plane>(r.point("point"), r.direction("normal"));
  }
  if (type == "sphere") {
    r.only({L("centre"), L("radius")}, extra_keys);
    return std::make_shared<Sphere>(r.point("centre"), r.length("radius"));
  }
  if (type == "box") {
    r.only({L("centre"), L("half_extents"), "rotation"}, extra_keys);
    return std::make_shared<Box>(r.point("centre"), r.point("half_extents"), r.rotation());
  }
  if (type == "mesh") {
    r.only({"file", "file_unit", L("translation"), "rotation"}, extra_keys);
    std::filesystem::path file = json_string(r.at("file"), r.field("file"));
    if (!base_dir.empty()) file = resolve_input_path(file, base_dir);  // the rule of json_input.hpp
    const double unit =
        j.contains("file_unit") ? trial::length_scale(json_string(j.at("file_unit"), r.field("file_unit")), r.field("file_unit")) : 1.0;
    ObjectPose pose;
    pose.R_WO = r.rotation();
    require_rotation(pose.R_WO, r.field("rotation"));
    if (j.contains(L("translation"))) pose.p_WO = r.point("translation");
    return Mesh::from_file(file.string(), unit, pose);
  }
  invalid_input(where + ".type must be cylinder, plane, sphere, box or mesh, got " + describe(j.at("type")));
}

json shape_to_json(const Shape& shape) {
  const ShapeDescription d = shape.describe();
  json out;
  out["type"] = d.type;
  for (const auto& [name, values] : d.values) {
    if (name == "rotation") {
      out[name] = json::array({json::array({values[0], values[1], values[2]}), json::array({values[3], values[4], values[5]}),
                               json::array({values[6], values[7], values[8]})});
    } else if (values.size() == 1) {
      out[name] = values[0];
    } else {
      out[name] = values;
    }
  }
  if (!d.file.empty()) out["file"] = d.file;
  return out;
}

}  // namespace vibrissa::io
