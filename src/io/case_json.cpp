#include "vibrissa/io/case_json.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/core/plausibility.hpp"
#include "vibrissa/io/json_input.hpp"
#include "vibrissa/io/object_json.hpp"
#include "vibrissa/solve/object_contact.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& msg) { throw std::invalid_argument(msg); }

void reject_unknown(const json& j, const std::string& where, const std::set<std::string>& known) {
  if (!j.is_object()) fail(where + " must be a JSON object, got " + io::describe(j));
  for (const auto& [key, value] : j.items())
    if (!known.count(key)) fail("unknown field " + where + "." + quote_text(key));
}

double number(const json& j, const std::string& field) { return io::json_number(j, field); }

double number_or(const json& j, const char* key, const std::string& where, double fallback) {
  return j.contains(key) ? number(j.at(key), where + "." + key) : fallback;
}

Eigen::Vector3d vec3(const json& j, const std::string& field) { return io::json_vec3(j, field); }

std::vector<double> numbers(const json& j, const std::string& field) { return io::json_numbers(j, field); }

// A direction of any length: kept as given when the solvers can normalise it (bit-identical to the direct
// API), rescaled to unit length when its squared norm would under- or overflow.
Eigen::Vector3d direction(const json& j, const std::string& field) {
  const Eigen::Vector3d v = vec3(j, field);
  const Eigen::Vector3d unit = unit_direction(v, field);
  const double n2 = v.squaredNorm();
  return n2 >= std::numeric_limits<double>::min() && n2 <= std::numeric_limits<double>::max() ? v : unit;
}

Pose pose_from_json(const json& j) {
  reject_unknown(j, "whisker.pose", {"base", "theta", "phi", "zeta"});
  Pose p;
  if (j.contains("base")) p.p_W_base = vec3(j.at("base"), "whisker.pose.base");
  p.theta = number_or(j, "theta", "whisker.pose", 0.0);
  p.phi = number_or(j, "phi", "whisker.pose", 0.0);
  p.zeta = number_or(j, "zeta", "whisker.pose", 0.0);
  return p;
}

Edge edge_from_json(const json& j) {
  Edge e;
  if (!j.contains("point")) fail("load.point is required for an edge");
  if (!j.contains("direction")) fail("load.direction is required for an edge");
  e.point = vec3(j.at("point"), "load.point");
  e.direction = direction(j.at("direction"), "load.direction");
  return e;
}

SignalSet signals_from_json(const json& j) {
  if (j.is_string()) return SignalSet::parse(j.get<std::string>(), "load.signals");
  if (!j.is_array()) fail("load.signals must be a preset name or an array of signal names, got " + j.dump());
  std::vector<std::string> names;
  for (const auto& e : j) {
    if (!e.is_string()) fail("load.signals must hold signal names (Fx ... Mz), got " + e.dump());
    names.push_back(e.get<std::string>());
  }
  return SignalSet::from_names(names, "load.signals");
}

/// "noise": m standard deviations, or an m x m covariance (rows in signal order), SI.
Eigen::MatrixXd noise_from_json(const json& j, int m) {
  if (!j.is_array() || j.size() != static_cast<std::size_t>(m))
    fail("load.noise must hold " + std::to_string(m) + " standard deviations or " + std::to_string(m) +
         " covariance rows (one per signal), got " + j.dump());
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m, m);
  if (!j[0].is_array()) {
    const auto sd = numbers(j, "load.noise");
    for (int i = 0; i < m; ++i) {
      if (!(sd[static_cast<std::size_t>(i)] > 0.0))
        fail("load.noise[" + std::to_string(i) + "] must be positive, got " + std::to_string(sd[static_cast<std::size_t>(i)]));
      S(i, i) = sd[static_cast<std::size_t>(i)] * sd[static_cast<std::size_t>(i)];
    }
    return S;
  }
  for (int i = 0; i < m; ++i) {
    const std::string row = "load.noise[" + std::to_string(i) + "]";
    const auto r = numbers(j[static_cast<std::size_t>(i)], row);
    if (r.size() != static_cast<std::size_t>(m)) fail(row + " must hold " + std::to_string(m) + " numbers");
    for (int k = 0; k < m; ++k) S(i, k) = r[static_cast<std::size_t>(k)];
  }
  return S;
}

json matrix_to_json(const Eigen::Matrix3d& M) {
  json out = json::array();
  for (int i = 0; i < 3; ++i) out.push_back(json::array({M(i, 0), M(i, 1), M(i, 2)}));
  return out;
}

}  // namespace

json to_json(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

Whisker whisker_from_json(const json& j, std::vector<std::string>* warnings) {
  reject_unknown(j, "whisker",
                 {"points", "length", "curvature", "cubic", "pose", "links", "base_radius", "taper_ratio", "radii",
                  "youngs_modulus", "poisson_ratio", "base", "base_stiffness", "scheme"});
  WhiskerProperties p;
  if (j.contains("links")) {
    p.links = io::json_integer(j.at("links"), "whisker.links", 2, limits::max_links);
  }
  p.base_radius = number_or(j, "base_radius", "whisker", p.base_radius);
  p.taper_ratio = number_or(j, "taper_ratio", "whisker", p.taper_ratio);
  // A list given is a list used: an empty one is an error like a list of one (never "use the defaults").
  if (j.contains("radii")) {
    p.radii = numbers(j.at("radii"), "whisker.radii");
    if (p.radii.size() < 2) fail("whisker.radii needs at least 2 values, got " + std::to_string(p.radii.size()));
  }
  if (j.contains("youngs_modulus")) {
    if (j.at("youngs_modulus").is_array()) {
      p.youngs_moduli = numbers(j.at("youngs_modulus"), "whisker.youngs_modulus");
      if (p.youngs_moduli.size() < 2)
        fail("whisker.youngs_modulus as a list needs at least 2 values, got " + std::to_string(p.youngs_moduli.size()));
    } else {
      p.youngs_modulus = number(j.at("youngs_modulus"), "whisker.youngs_modulus");
    }
  }
  p.poisson_ratio = number_or(j, "poisson_ratio", "whisker", p.poisson_ratio);
  if (j.contains("base")) {
    const json& b = j.at("base");
    if (b == "elastic") p.base = BaseJoint::elastic;
    else if (b == "rigid") p.base = BaseJoint::rigid;
    else fail("whisker.base must be \"elastic\" or \"rigid\", got " + io::describe(b));
  }
  if (j.contains("base_stiffness")) p.base_stiffness = number(j.at("base_stiffness"), "whisker.base_stiffness");
  if (j.contains("scheme")) {
    const json& s = j.at("scheme");
    if (s == "paper") p.scheme = Scheme::paper;
    else if (s == "second_order") p.scheme = Scheme::second_order;
    else fail("whisker.scheme must be \"paper\" or \"second_order\", got " + io::describe(s));
  }
  std::optional<Pose> pose;
  if (j.contains("pose")) pose = pose_from_json(j.at("pose"));
  if (pose && warnings) *warnings = pose_warnings(*pose, "whisker.pose");

  const int shapes = int(j.contains("points")) + int(j.contains("length"));
  if (shapes != 1) fail("whisker needs exactly one of \"points\" or \"length\" (with \"curvature\" or \"cubic\")");
  if (j.contains("points")) {
    const json& pts = j.at("points");
    if (!pts.is_array()) fail("whisker.points must be an array of [x, y, z], got " + io::describe(pts));
    require_at_most(pts.size(), limits::max_shape_points, "whisker.points: number of points");
    std::vector<Eigen::Vector3d> points;
    for (std::size_t i = 0; i < pts.size(); ++i) points.push_back(vec3(pts[i], "whisker.points[" + std::to_string(i) + "]"));
    if (j.contains("curvature") || j.contains("cubic")) fail("whisker.curvature/cubic cannot be combined with points");
    // The paper scheme keeps the given points as its nodes (points.size() - 1 links): links cannot be honoured.
    if (p.scheme == Scheme::paper && j.contains("links") && p.links != int(points.size()) - 1)
      fail("whisker.links (" + std::to_string(p.links) + ") cannot be combined with \"scheme\": \"paper\" and points: " +
           "the paper scheme keeps the " + std::to_string(points.size()) + " points as its nodes (" +
           std::to_string(points.size() - 1) + " links); drop links, or use the second_order scheme to resample");
    return Whisker::from_points(points, p, pose);
  }
  const double length = number(j.at("length"), "whisker.length");
  if (!(length > 0.0)) fail("whisker.length must be positive, got " + format_value(length));
  if (j.contains("curvature") && j.contains("cubic")) fail("whisker has both curvature and cubic: give one");
  double A = 0.0, B = 0.0;
  if (j.contains("curvature")) B = number(j.at("curvature"), "whisker.curvature");
  if (j.contains("cubic")) {
    const auto c = numbers(j.at("cubic"), "whisker.cubic");
    if (c.size() != 2) fail("whisker.cubic must be [A, B], got " + io::describe(j.at("cubic")));
    A = c[0];
    B = c[1];
  }
  return Whisker::from_cubic(length, A, B, p, pose.value_or(Pose{}));
}

Load load_from_json(const json& j) {
  if (!j.is_object() || !j.contains("mode"))
    fail("load.mode is required (force, dead_load, point, edge, frictional_edge, base_wrench, object)");
  const json& mode = j.at("mode");
  if (mode == "force") {
    reject_unknown(j, "load", {"mode", "force", "arc_length", "angle"});
    if (!j.contains("force") || !j.contains("arc_length")) fail("load: force mode needs force and arc_length");
    return ForceLoad{number(j.at("force"), "load.force"), number(j.at("arc_length"), "load.arc_length"),
                     number_or(j, "angle", "load", 0.0)};
  }
  if (mode == "dead_load") {
    reject_unknown(j, "load", {"mode", "force", "arc_length"});
    if (!j.contains("force") || !j.contains("arc_length")) fail("load: dead_load mode needs force [3] and arc_length");
    return DeadLoad{vec3(j.at("force"), "load.force"), number(j.at("arc_length"), "load.arc_length")};
  }
  if (mode == "point") {
    reject_unknown(j, "load", {"mode", "point", "arc_length_hint", "edge_direction"});
    if (!j.contains("point")) fail("load.point is required in point mode");
    PointLoad l;
    l.point = vec3(j.at("point"), "load.point");
    if (j.contains("arc_length_hint")) l.arc_length_hint = number(j.at("arc_length_hint"), "load.arc_length_hint");
    if (j.contains("edge_direction"))
      l.edge_direction = direction(j.at("edge_direction"), "load.edge_direction");
    return l;
  }
  if (mode == "edge") {
    reject_unknown(j, "load", {"mode", "point", "direction", "arc_length_hint", "approach"});
    EdgeLoad l;
    l.edge = edge_from_json(j);
    if (j.contains("arc_length_hint")) l.arc_length_hint = number(j.at("arc_length_hint"), "load.arc_length_hint");
    if (j.contains("approach")) l.approach = vec3(j.at("approach"), "load.approach");
    return l;
  }
  if (mode == "frictional_edge") {
    reject_unknown(j, "load", {"mode", "point", "direction", "friction_coefficient", "previous_contact", "approach"});
    FrictionalEdgeLoad l;
    l.edge = edge_from_json(j);
    if (!j.contains("friction_coefficient")) fail("load.friction_coefficient is required in frictional_edge mode");
    if (!j.contains("previous_contact")) fail("load.previous_contact is required in frictional_edge mode");
    l.friction_coefficient = number(j.at("friction_coefficient"), "load.friction_coefficient");
    l.previous_contact = vec3(j.at("previous_contact"), "load.previous_contact");
    if (j.contains("approach")) l.approach = vec3(j.at("approach"), "load.approach");
    return l;
  }
  if (mode == "base_wrench") {
    reject_unknown(j, "load", {"mode", "force", "moment", "signals", "noise"});
    if (!j.contains("force") || !j.contains("moment")) fail("load: base_wrench mode needs force [3] and moment [3]");
    BaseWrenchLoad l;
    l.force = vec3(j.at("force"), "load.force");
    l.moment = vec3(j.at("moment"), "load.moment");
    if (j.contains("signals")) l.signals = signals_from_json(j.at("signals"));
    if (j.contains("noise")) l.noise_covariance = noise_from_json(j.at("noise"), l.signals.size());
    return l;
  }
  if (mode == "object") {
    reject_unknown(j, "load",
                   {"mode", "object", "thickness", "friction_coefficient", "previous_contact", "arc_length_hint", "approach"});
    if (!j.contains("object")) fail("load.object is required in object mode");
    ObjectLoad l;
    l.shape = io::shape_from_json(j.at("object"), "load.object", io::LengthKeys::metres);
    if (j.contains("thickness")) l.thickness = io::json_bool(j.at("thickness"), "load.thickness");
    if (j.contains("friction_coefficient")) {
      l.friction_coefficient = number(j.at("friction_coefficient"), "load.friction_coefficient");
      if (!j.contains("previous_contact"))
        fail("load.previous_contact is required with a friction_coefficient (where the contact was on the object)");
    }
    if (j.contains("previous_contact")) l.previous_contact = vec3(j.at("previous_contact"), "load.previous_contact");
    if (j.contains("arc_length_hint")) l.arc_length_hint = number(j.at("arc_length_hint"), "load.arc_length_hint");
    if (j.contains("approach")) l.approach = vec3(j.at("approach"), "load.approach");
    return l;
  }
  fail("load.mode must be one of force, dead_load, point, edge, frictional_edge, base_wrench, object; got " +
       io::describe(mode));
}

Case case_from_json(const json& j) {
  reject_unknown(j, "case", {"whisker", "load", "options"});
  if (!j.contains("whisker")) fail("case.whisker is required");
  if (!j.contains("load")) fail("case.load is required");
  SolveOptions o;
  o.find_other_roots = true;
  if (j.contains("options")) {
    const json& oj = j.at("options");
    reject_unknown(oj, "options", {"tolerance", "max_iterations", "find_other_roots", "compute_shape"});
    o.tolerance = number_or(oj, "tolerance", "options", o.tolerance);
    if (oj.contains("max_iterations"))
      o.max_iterations = io::json_integer(oj.at("max_iterations"), "options.max_iterations", 1, limits::max_iterations);
    if (oj.contains("find_other_roots")) o.find_other_roots = io::json_bool(oj.at("find_other_roots"), "options.find_other_roots");
    if (oj.contains("compute_shape")) o.compute_shape = io::json_bool(oj.at("compute_shape"), "options.compute_shape");
    validate(o);
  }
  std::vector<std::string> warnings;
  Whisker w = whisker_from_json(j.at("whisker"), &warnings);
  return Case{std::move(w), load_from_json(j.at("load")), o, std::move(warnings)};
}

std::vector<std::string> case_warnings(const Case& c) {
  std::vector<std::string> out = plausibility_warnings(c.whisker);
  out.insert(out.end(), c.input_warnings.begin(), c.input_warnings.end());
  const Eigen::Vector3d base = c.whisker.placement().p_W_base;
  const double L = c.whisker.length();
  auto add = [&](std::optional<std::string> m) {
    if (m) out.push_back(std::move(*m));
  };
  std::visit(
      [&](const auto& l) {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, ForceLoad>)
          add(force_warning("load.force", l.force));
        else if constexpr (std::is_same_v<T, DeadLoad> || std::is_same_v<T, BaseWrenchLoad>)
          add(force_warning("load.force", l.force.norm()));
        else if constexpr (std::is_same_v<T, PointLoad>)
          add(reach_warning("load.point", l.point, Eigen::Vector3d::Zero(), base, L));
        else if constexpr (std::is_same_v<T, EdgeLoad> || std::is_same_v<T, FrictionalEdgeLoad>)
          add(reach_warning("load edge (load.point, load.direction)", l.edge.point, l.edge.direction, base, L));
        else
          (void)l;  // objects: their own geometry (docs/objects.md)
      },
      c.load);
  return out;
}

Solution solve_case(const Case& c) {
  const Whisker& w = c.whisker;
  return std::visit(
      [&](const auto& l) -> Solution {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, ForceLoad>)
          return solve_force(w, l.force, l.arc_length, l.angle, c.options);
        else if constexpr (std::is_same_v<T, DeadLoad>)
          return solve_dead_load(w, l.force, l.arc_length, c.options);
        else if constexpr (std::is_same_v<T, PointLoad>)
          return solve_point(w, l.point, l.arc_length_hint, c.options, nullptr, l.edge_direction);
        else if constexpr (std::is_same_v<T, EdgeLoad>)
          return solve_edge(w, l.edge, l.arc_length_hint, c.options, nullptr, l.approach);
        else if constexpr (std::is_same_v<T, BaseWrenchLoad>)
          return solve_base_wrench(w, l.force, l.moment, base_wrench_options(l, c.options)).solution;
        else if constexpr (std::is_same_v<T, ObjectLoad>) {
          const ObjectContact o{l.shape.get(), {}, l.thickness};
          if (l.friction_coefficient)
            return solve_frictional_object(w, w.placement(), o, *l.friction_coefficient, *l.previous_contact, c.options,
                                           nullptr, l.approach);
          return solve_object(w, w.placement(), o, l.arc_length_hint, c.options, nullptr, l.approach);
        }
        else
          return solve_frictional_edge(w, l.edge, l.friction_coefficient, l.previous_contact, c.options, nullptr,
                                       l.approach);
      },
      c.load);
}

json solution_to_json(const Solution& s) {
  json j;
  j["status"] = std::string(to_string(s.status));
  j["message"] = std::string(s.message);
  j["contact_state"] = std::string(to_string(s.contact_state));
  j["friction"] = std::string(to_string(s.friction));
  j["fold"] = s.fold;
  j["force_magnitude"] = s.force_magnitude;
  j["arc_length"] = s.arc_length;
  j["angle"] = s.angle;
  j["contact_point_W"] = to_json(s.contact_point_W);
  j["force_W"] = to_json(s.force_W);
  j["moment_W"] = to_json(s.moment_W);
  // Deprecated keys without the frame suffix (docs/formats.md): same values, removed in 0.2.0.
  j["contact_point"] = j["contact_point_W"];
  j["force"] = j["force_W"];
  j["moment"] = j["moment_W"];
  const auto& wf = s.whisker_frame;
  j["whisker_frame"] = {{"force", to_json(wf.force)}, {"moment", to_json(wf.moment)}, {"Fx", wf.force.x()},
                        {"Mx", wf.moment.x()},       {"FT", wf.FT},                  {"MB", wf.MB},
                        {"FD", wf.FD},               {"MD", wf.MD}};
  j["normal_force"] = s.normal_force ? json(*s.normal_force) : json(nullptr);
  j["edge_force"] = s.edge_force ? json(*s.edge_force) : json(nullptr);
  j["other_root_arc_length"] = s.other_root_arc_length ? json(*s.other_root_arc_length) : json(nullptr);
  json roots = json::array();
  for (const Root& r : s.roots)
    roots.push_back({{"arc_length", r.arc_length}, {"force", r.force_magnitude}, {"residual", r.residual}});
  j["roots"] = std::move(roots);
  if (s.surface) {
    const SurfaceContact& c = *s.surface;
    j["surface"] = {{"normal_W", to_json(c.normal_W)},
                    {"friction_direction_W", to_json(c.friction_direction_W)},
                    {"tip", c.tip},
                    {"feature", std::string(to_string(c.feature))},
                    {"friction_force", c.friction_force},
                    {"clearance", c.clearance},
                    {"clearance_arc_length", c.clearance_arc_length}};
  } else {
    j["surface"] = nullptr;
  }
  j["second_contact_arc_length"] = s.second_contact_arc_length ? json(*s.second_contact_arc_length) : json(nullptr);
  if (s.second_contact) {  // two contacts solved together (docs/objects.md, "Two contacts")
    const SecondContact& c = *s.second_contact;
    j["second_contact"] = {{"arc_length", c.arc_length},
                           {"contact_point_W", to_json(c.contact_point_W)},
                           {"force_W", to_json(c.force_W)},
                           {"normal_W", to_json(c.normal_W)},
                           {"normal_force", c.normal_force},
                           {"feature", std::string(to_string(c.feature))}};
  } else {
    j["second_contact"] = nullptr;
  }
  j["residual"] = s.residual;
  j["iterations"] = s.iterations;
  json shape = json::array();
  for (const auto& p : s.shape_W) shape.push_back(to_json(p));
  j["shape_W"] = shape;
  j["shape"] = std::move(shape);  // deprecated, removed in 0.2.0
  return j;
}

BaseWrenchOptions base_wrench_options(const BaseWrenchLoad& load, const SolveOptions& options) {
  BaseWrenchOptions o;
  o.signals = load.signals;
  o.noise_covariance = load.noise_covariance;
  o.solve = options;
  return o;
}

json base_wrench_to_json(const BaseWrenchResult& r) {
  json j = solution_to_json(r.solution);
  json roots = json::array();
  for (const auto& q : r.roots)
    roots.push_back({{"arc_length", q.arc_length}, {"force_magnitude", q.force_magnitude}, {"angle", q.angle},
                     {"contact_point_W", to_json(q.contact_point_W)},
                     {"contact_point", to_json(q.contact_point_W)},  // deprecated, removed in 0.2.0
                     {"chi2", q.chi2}});
  const auto& id = r.identifiability;
  j["base_wrench"] = {
      {"signals", r.signals.name()},
      {"chi2", r.chi2},
      {"roots", std::move(roots)},
      {"identifiability",
       {{"signals", id.signals},
        {"identifiable", id.identifiable},
        {"condition_number", std::isfinite(id.condition_number) ? json(id.condition_number) : json(nullptr)},
        {"null_direction", to_json(id.null_direction)},
        {"covariance", matrix_to_json(id.covariance)},
        {"contact_point_covariance", matrix_to_json(id.contact_point_covariance_W)}}}};
  return j;
}

json case_result_to_json(const Case& c, const Solution& s) {
  json j = solution_to_json(s);
  if (const auto* l = std::get_if<ObjectLoad>(&c.load)) j["object"] = io::shape_to_json(*l->shape);
  j["warnings"] = case_warnings(c);
  return j;
}

json solve_case_to_json(const Case& c) {
  if (const auto* l = std::get_if<BaseWrenchLoad>(&c.load)) {
    const BaseWrenchResult r =
        solve_base_wrench(c.whisker, l->force, l->moment, base_wrench_options(*l, c.options));
    json j = base_wrench_to_json(r);
    std::vector<std::string> warnings = base_wrench_warnings(r);  // first: the numbers are not the contact
    for (std::string& w : case_warnings(c)) warnings.push_back(std::move(w));
    j["warnings"] = std::move(warnings);
    return j;
  }
  return case_result_to_json(c, solve_case(c));
}

json read_json_file(const std::string& path) { return io::read_json_input(path); }

}  // namespace vibrissa
