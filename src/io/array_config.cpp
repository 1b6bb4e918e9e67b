#include "vibrissa/io/array_config.hpp"
#include "vibrissa/io/dynamics_case.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "../array/array_util.hpp"  // the array layer's message and unit helpers
#include "vibrissa/core/checks.hpp"
#include "vibrissa/io/json_input.hpp"
#include "vibrissa/io/morphology_table.hpp"
#include "vibrissa/io/object_json.hpp"

namespace vibrissa::io {

using namespace vibrissa::array;

namespace {

using nlohmann::json;
constexpr double mm = 1e-3;

// Refuses keys other than `allowed` in object `j` at `where`.
void only_keys(const json& j, const std::string& where, std::initializer_list<const char*> allowed) {
  if (!j.is_object()) fail(where + " must be an object");
  for (const auto& [key, value] : j.items()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      fail(where + (where.empty() ? "" : ".") + quote_text(key) + ": unknown key (expected one of: " + list + ")");
    }
  }
}

std::string path_of(const std::string& where, const std::string& key) { return where.empty() ? key : where + "." + key; }

double number(const json& j, const std::string& where, const std::string& key, double fallback) {
  if (!j.contains(key)) return fallback;
  const json& v = j.at(key);
  if (v.is_string() && (v.get<std::string>() == "nan" || v.get<std::string>() == "NaN"))
    fail(path_of(where, key) + " must be finite, got NaN");
  return io::json_number(v, path_of(where, key));
}

int integer(const json& j, const std::string& where, const std::string& key, int fallback, int lo, int hi) {
  if (!j.contains(key)) return fallback;
  return io::json_integer(j.at(key), path_of(where, key), lo, hi);
}

std::string text(const json& j, const std::string& where, const std::string& key, const std::string& fallback) {
  if (!j.contains(key)) return fallback;
  return io::json_string(j.at(key), path_of(where, key));
}

std::vector<double> numbers(const json& j, const std::string& where, const std::string& key) {
  if (!j.contains(key)) return {};
  return io::json_numbers(j.at(key), path_of(where, key));
}

Eigen::Vector3d vec3(const json& j, const std::string& where, const std::string& key, const Eigen::Vector3d& fallback) {
  if (!j.contains(key)) return fallback;
  const std::vector<double> v = numbers(j, where, key);
  if (v.size() != 3) fail(path_of(where, key) + " must hold 3 numbers, got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

Protraction protraction_from(const json& j, const std::string& where, const Protraction& base) {
  Protraction p = base;
  p.amplitude = deg(number(j, where, "amplitude_deg", to_deg(base.amplitude)));
  p.frequency = number(j, where, "frequency_Hz", base.frequency);
  p.set_point = deg(number(j, where, "set_point_deg", to_deg(base.set_point)));
  p.phase = deg(number(j, where, "phase_deg", to_deg(base.phase)));
  if (j.contains("series")) {
    const json& s = j.at("series");
    const std::string at = path_of(where, "series");
    only_keys(s, at, {"time_s", "dtheta_deg"});
    p.series_time = numbers(s, at, "time_s");
    p.series_dtheta = numbers(s, at, "dtheta_deg");
    for (double& d : p.series_dtheta) d = deg(d);
  }
  validate(p, where);
  return p;
}

SceneObject object_from(const json& o, const std::string& where, const std::filesystem::path& base_dir) {
  if (!o.is_object()) fail(where + " must be an object");
  const std::string type = text(o, where, "type", "");
  const ObjectFrame frame = object_frame_from_string(text(o, where, "frame", "world"), (where + ".frame").c_str());
  const double inf = std::numeric_limits<double>::infinity();
  if (type == "peg") {
    only_keys(o, where, {"type", "frame", "point_mm", "height_mm"});
    if (!o.contains("point_mm")) fail(where + ".point_mm is missing");
    return make_peg(vec3(o, where, "point_mm", Eigen::Vector3d::Zero()) * mm, o.contains("height_mm") ? number(o, where, "height_mm", 0) * mm : inf,
                    frame, where);
  }
  if (type == "edge") {
    only_keys(o, where, {"type", "frame", "point_mm", "direction", "length_mm"});
    if (!o.contains("point_mm")) fail(where + ".point_mm is missing");
    if (!o.contains("direction")) fail(where + ".direction is missing");
    return make_edge(vec3(o, where, "point_mm", Eigen::Vector3d::Zero()) * mm, vec3(o, where, "direction", Eigen::Vector3d::Zero()),
                     o.contains("length_mm") ? number(o, where, "length_mm", 0) * mm : inf, frame, where);
  }
  if (type == "prism") {
    only_keys(o, where, {"type", "frame", "vertices_mm", "axis", "length_mm"});
    if (!o.contains("vertices_mm") || !o.at("vertices_mm").is_array())
      fail(where + ".vertices_mm must be a list of 3 points");
    std::vector<Eigen::Vector3d> v;
    const json& vs = o.at("vertices_mm");
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const std::string at = where + ".vertices_mm[" + std::to_string(i) + "]";
      json wrap = json::object();
      wrap["p"] = vs[i];
      v.push_back(vec3(wrap, at, "p", Eigen::Vector3d::Zero()) * mm);
    }
    if (!o.contains("length_mm")) fail(where + ".length_mm is missing");
    return make_prism(v, vec3(o, where, "axis", Eigen::Vector3d::UnitZ()), number(o, where, "length_mm", 0) * mm,
                      frame, where);
  }
  if (type == "cylinder" || type == "plane" || type == "sphere" || type == "box" || type == "mesh") {
    SceneObject s{type, frame, {}, shape_from_json(o, where, LengthKeys::millimetres, base_dir, {"frame"})};
    return s;
  }
  fail(where + ".type must be 'peg', 'edge', 'prism', 'cylinder', 'plane', 'sphere', 'box' or 'mesh', got '" + type + "'");
}

}  // namespace

Protraction protraction_from_json(const json& j, const std::string& where, const Protraction& base) {
  return protraction_from(j, where, base);
}

nlohmann::json default_array_config_json() {
  return json::parse(R"({
    "morphology": {"source": "towal2011", "sides": "right"},
    "whisking": {"amplitude_deg": 30, "set_point_deg": 10, "frequency_Hz": 8, "slopes": "knutsen2008"},
    "time": {"start_s": 0, "end_s": 0.0625, "frames": 250},
    "head": {"pitch_deg": 0, "pitches_deg": [0]},
    "objects": [{"type": "peg", "frame": "world", "point_mm": [20, -8, -3]}],
    "solver": {"mode": "edge", "mu": 0.48, "links": 100},
    "output": {"render_count": 50}
  })");
}

json read_array_config_json(const std::filesystem::path& path) {
  try {
    return io::read_json_input(path, true);
  } catch (const std::invalid_argument& e) {
    fail(std::string("config: ") + e.what());
  }
}

SimulationConfig load_array_config(const std::filesystem::path& path) {
  return array_config_from_json(read_array_config_json(path), path.parent_path());
}

SimulationConfig array_config_from_json(const json& input, const std::filesystem::path& base_dir) {
  const json j = io::resolve_input_paths(input, base_dir);  // files named relative to base_dir (json_input.hpp)
  only_keys(j, "", {"morphology", "whisking", "time", "head", "objects", "solver", "output", "threads", "comment",
                    "dynamics"});
  SimulationConfig c;
  if (j.contains("dynamics")) c.dynamics = dynamics_properties_from_json(j.at("dynamics"));

  // --- morphology ---
  const json m = j.value("morphology", json::object());
  only_keys(m, "morphology", {"source", "sides", "phi_method", "whiskers", "taper_ratio", "youngs_modulus_GPa",
                                  "base_radius_scale"});
  const std::string source = text(m, "morphology", "source", "towal2011");
  const Sides sides = sides_from_string(text(m, "morphology", "sides", "right"));
  const PhiMethod phi_method = phi_method_from_string(text(m, "morphology", "phi_method", "projection"));
  if (m.contains("phi_method") && source != "towal2011" && source != "towal")
    fail("morphology.phi_method applies only to source 'towal2011', got source '" + quote_text(source) + "'");
  if (source.size() > 4 && (source.ends_with(".csv") || source.ends_with(".json"))) {
    c.morphology = read_morphology_table(std::filesystem::path(source));  // made absolute above
  } else {
    c.morphology = morphology_by_name(source, sides, phi_method);
  }
  if (m.contains("whiskers")) {
    if (!m.at("whiskers").is_array()) fail("morphology.whiskers must be a list of names");
    std::vector<std::string> names;
    for (const auto& n : m.at("whiskers")) {
      if (!n.is_string()) fail("morphology.whiskers must be a list of names, got " + io::describe(n));
      names.push_back(n.get<std::string>());
    }
    c.morphology = select_whiskers(c.morphology, names);
  }
  const double taper = number(m, "morphology", "taper_ratio", 0.0);
  const double E = number(m, "morphology", "youngs_modulus_GPa", 0.0);
  const double scale = number(m, "morphology", "base_radius_scale", 1.0);
  if (m.contains("taper_ratio") && !(taper > 1.0)) fail("morphology.taper_ratio must be > 1, got " + fmt(taper));
  if (m.contains("youngs_modulus_GPa") && !(E > 0.0)) fail("morphology.youngs_modulus_GPa must be > 0, got " + fmt(E));
  if (!(scale > 0.0)) fail("morphology.base_radius_scale must be > 0, got " + fmt(scale));
  for (WhiskerSpec& s : c.morphology.whiskers) {
    if (m.contains("taper_ratio")) s.taper_ratio = taper;
    if (m.contains("youngs_modulus_GPa")) s.youngs_modulus = E * 1e9;
    s.base_radius *= scale;
  }

  // --- whisking ---
  const json w = j.value("whisking", json::object());
  only_keys(w, "whisking",
            {"amplitude_deg", "frequency_Hz", "set_point_deg", "phase_deg", "series", "slopes", "per_whisker"});
  c.whisking.slopes = slope_set_from_string(text(w, "whisking", "slopes", "knutsen2008"));
  Protraction default_whisk;  // the built-in default whisk: Δθ from -20° to +40° at 8 Hz
  default_whisk.amplitude = deg(30.0);
  default_whisk.set_point = deg(10.0);
  default_whisk.frequency = 8.0;
  c.whisking.protraction = protraction_from(w, "whisking", default_whisk);
  if (w.contains("per_whisker")) {
    const json& pw = w.at("per_whisker");
    if (!pw.is_object()) fail("whisking.per_whisker must map whisker names to settings");
    for (const auto& [name, settings] : pw.items()) {
      const std::string at = "whisking.per_whisker." + name;
      only_keys(settings, at, {"amplitude_deg", "frequency_Hz", "set_point_deg", "phase_deg", "series"});
      c.whisking.per_whisker[name] = protraction_from(settings, at, c.whisking.protraction);
    }
  }

  // --- time ---
  const json t = j.value("time", json::object());
  only_keys(t, "time", {"start_s", "end_s", "frames", "times_s"});
  if (t.contains("times_s")) {
    c.times = numbers(t, "time", "times_s");
  } else {
    c.times = uniform_times(number(t, "time", "start_s", 0.0), number(t, "time", "end_s", 0.0625),
                            integer(t, "time", "frames", 250, 2, static_cast<int>(limits::max_array_frames)));
  }

  // --- head ---
  const json h = j.value("head", json::object());
  only_keys(h, "head", {"position_mm", "velocity_mm_per_s", "yaw_deg", "pitch_deg", "roll_deg", "yaw_rate_deg_per_s",
                        "pitch_rate_deg_per_s", "roll_rate_deg_per_s", "pitches_deg", "series"});
  c.head.p_W_head = vec3(h, "head", "position_mm", Eigen::Vector3d::Zero()) * mm;
  c.head.v_W_head = vec3(h, "head", "velocity_mm_per_s", Eigen::Vector3d::Zero()) * mm;
  c.head.yaw = deg(number(h, "head", "yaw_deg", 0.0));
  c.head.pitch = deg(number(h, "head", "pitch_deg", 0.0));
  c.head.roll = deg(number(h, "head", "roll_deg", 0.0));
  c.head.yaw_rate = deg(number(h, "head", "yaw_rate_deg_per_s", 0.0));
  c.head.pitch_rate = deg(number(h, "head", "pitch_rate_deg_per_s", 0.0));
  c.head.roll_rate = deg(number(h, "head", "roll_rate_deg_per_s", 0.0));
  if (h.contains("series")) {
    const json& s = h.at("series");
    only_keys(s, "head.series", {"time_s", "position_mm", "yaw_deg", "pitch_deg", "roll_deg"});
    const std::vector<double> ts = numbers(s, "head.series", "time_s");
    auto column = [&](const char* key) {
      std::vector<double> v = numbers(s, "head.series", key);
      if (!s.contains(key)) v.assign(ts.size(), 0.0);
      if (v.size() != ts.size())
        fail(std::string("head.series.") + key + " has " + std::to_string(v.size()) + " values, time_s has " +
             std::to_string(ts.size()));
      return v;
    };
    const auto yaw = column("yaw_deg"), pitch = column("pitch_deg"), roll = column("roll_deg");
    std::vector<Eigen::Vector3d> pos(ts.size(), Eigen::Vector3d::Zero());
    if (s.contains("position_mm")) {
      const json& ps = s.at("position_mm");
      if (!ps.is_array() || ps.size() != ts.size())
        fail("head.series.position_mm must hold one [x, y, z] per time_s");
      for (std::size_t i = 0; i < ts.size(); ++i) {
        json wrap = json::object();
        wrap["p"] = ps[i];
        pos[i] = vec3(wrap, "head.series.position_mm[" + std::to_string(i) + "]", "p", Eigen::Vector3d::Zero()) * mm;
      }
    }
    for (std::size_t i = 0; i < ts.size(); ++i)
      c.head.series.push_back(HeadSample{ts[i], pos[i], deg(yaw[i]), deg(pitch[i]), deg(roll[i])});
  }
  c.pitches = h.contains("pitches_deg") ? numbers(h, "head", "pitches_deg") : std::vector<double>{0.0};
  for (double& p : c.pitches) p = deg(p);

  // --- objects ---
  if (!j.contains("objects")) fail("objects is missing: the scene needs at least one peg, edge or prism");
  const json& objs = j.at("objects");
  if (!objs.is_array() || objs.empty()) fail("objects must be a non-empty list");
  require_at_most(objs.size(), limits::max_edges, "objects: number of objects");
  for (std::size_t i = 0; i < objs.size(); ++i)
    c.objects.push_back(object_from(objs[i], "objects[" + std::to_string(i) + "]", base_dir));

  // --- solver ---
  const json s = j.value("solver", json::object());
  only_keys(s, "solver", {"mode", "mu", "links", "tolerance_m", "max_iterations", "thickness"});
  if (s.contains("thickness")) c.thickness = io::json_bool(s.at("thickness"), "solver.thickness");
  c.mode = contact_mode_from_string(text(s, "solver", "mode", "edge"), "solver.mode");
  c.mu = number(s, "solver", "mu", 0.48);
  c.links = integer(s, "solver", "links", 100, 2, limits::max_links);
  c.tolerance = number(s, "solver", "tolerance_m", 1e-10);
  c.max_iterations = integer(s, "solver", "max_iterations", 100, 1, limits::max_iterations);

  // --- output (what the simulation keeps for the animation) ---
  const json o = j.value("output", json::object());
  only_keys(o, "output", {"render_count", "render_pitch_index"});
  const int render = integer(o, "output", "render_count", 50, 0, static_cast<int>(limits::max_array_frames));
  const int F = static_cast<int>(c.times.size());
  const int n = std::min(render, F);
  for (int i = 0; i < n; ++i) {
    const int f = n == 1 ? F - 1 : static_cast<int>(std::lround(double(i) * (F - 1) / (n - 1)));
    if (c.render_frames.empty() || c.render_frames.back() != f) c.render_frames.push_back(f);
  }
  c.render_pitch = integer(o, "output", "render_pitch_index", 0, 0, static_cast<int>(limits::max_list_length));
  c.threads = integer(j, "", "threads", 0, 0, limits::max_threads);
  validate(c);
  return c;
}

}  // namespace vibrissa::io
