// `vibrissa modes` / `vibrissa dynamics` cases and outputs (include/vibrissa/io/dynamics_case.hpp).
#include "vibrissa/io/dynamics_case.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "csv_cells.hpp"
#include "vibrissa/core/chain.hpp"
#include "vibrissa/core/checks.hpp"
#include "vibrissa/dynamics/air_drag.hpp"
#include "vibrissa/io/array_config.hpp"
#include "vibrissa/io/atomic_file.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/io/json_file.hpp"
#include "vibrissa/io/json_input.hpp"
#include "vibrissa/io/object_json.hpp"
#include "vibrissa/io/output_folder.hpp"
#include "vibrissa/solve/whisker_frame_signals.hpp"

namespace vibrissa::io {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& msg) { throw std::invalid_argument(msg); }

void only_keys(const json& j, const std::string& where, const std::set<std::string>& known) {
  if (!j.is_object()) fail(where + " must be a JSON object, got " + describe(j));
  for (const auto& [key, value] : j.items())
    if (!known.count(key)) fail("unknown field " + (where.empty() ? "" : where + ".") + quote_text(key));
}

double number_or(const json& j, const char* key, const std::string& where, double fallback) {
  return j.contains(key) ? json_number(j.at(key), where.empty() ? std::string(key) : where + "." + key) : fallback;
}

}  // namespace

json contact_events_json(const std::vector<dynamics::ContactEvent>& list) {
  json events = json::array();
  for (const dynamics::ContactEvent& e : list)
    events.push_back({{"time", e.time}, {"type", std::string(to_string(e.type))}, {"object", e.object},
                      {"arc_length", e.arc_length}, {"point_W", {e.point_W.x(), e.point_W.y(), e.point_W.z()}},
                      {"force_W", {e.force_W.x(), e.force_W.y(), e.force_W.z()}}});
  return events;
}

dynamics::BaseTrajectory whisking_trajectory(const Pose& pose, const Whisking& w) {
  return dynamics::trajectory_from_placements([pose, w](double t) {
    const double d = w.protraction(t);
    return Placement(rotation_from_angles(pose.theta + d, pose.phi + w.k_phi * d, pose.zeta + w.k_zeta * d),
                     pose.p_W_base);
  });
}

dynamics::DynamicsProperties dynamics_properties_from_json(const json& d) {
  dynamics::DynamicsProperties props;
  only_keys(d, "dynamics", {"density", "damping_ratio", "joint_damping_time", "gravity", "air_drag", "air_density",
                            "air_kinematic_viscosity", "modes"});
  if (d.contains("modes")) {
    const json& m = d.at("modes");
    if (m.is_string()) {
      if (m.get<std::string>() != "all")
        fail("dynamics.modes must be \"all\" or a count >= 1, got " + quote_text(m.get<std::string>()));
    } else {
      props.modes = json_integer(m, "dynamics.modes", 1, 100000);
    }
  }
  if (d.contains("air_drag")) {
    if (!d.at("air_drag").is_boolean()) fail("dynamics.air_drag must be true or false, got " + describe(d.at("air_drag")));
    props.air_drag = d.at("air_drag").get<bool>();
  }
  props.air.density = number_or(d, "air_density", "dynamics", props.air.density);
  props.air.kinematic_viscosity =
      number_or(d, "air_kinematic_viscosity", "dynamics", props.air.kinematic_viscosity);
  props.density = number_or(d, "density", "dynamics", props.density);
  if (d.contains("damping_ratio") && d.contains("joint_damping_time"))
    fail("dynamics needs at most one of \"damping_ratio\" and \"joint_damping_time\"");
  props.damping_ratio = number_or(d, "damping_ratio", "dynamics", props.damping_ratio);
  if (d.contains("joint_damping_time"))
    props.joint_damping_time = json_number(d.at("joint_damping_time"), "dynamics.joint_damping_time");
  if (d.contains("gravity")) props.gravity_W = json_vec3(d.at("gravity"), "dynamics.gravity");
  dynamics::validate(props);
  return props;
}

DynamicsCase dynamics_case_from_json(const json& j) {
  if (!j.is_object()) fail("the case must be a JSON object, got " + describe(j));
  if (!j.contains("whisker")) fail("the case needs a \"whisker\" object");
  return dynamics_case_from_json(j, whisker_from_json(j.at("whisker")));
}

DynamicsCase dynamics_case_from_json(const json& j, const Whisker& whisker) {
  only_keys(j, "", {"whisker", "dynamics", "whisking", "initial", "duration", "output_rate", "relative_tolerance",
                    "absolute_tolerance", "modes", "model", "objects", "contact", "load", "hold"});
  DynamicsCase c(whisker);
  if (j.contains("dynamics")) c.properties = dynamics_properties_from_json(j.at("dynamics"));
  dynamics::validate(c.properties);
  if (j.contains("whisking")) {
    const json& w = j.at("whisking");
    only_keys(w, "whisking", {"amplitude_deg", "frequency_Hz", "set_point_deg", "phase_deg", "series", "k_phi", "k_zeta"});
    Whisking wk;
    wk.protraction = protraction_from_json(w, "whisking");
    wk.k_phi = number_or(w, "k_phi", "whisking", 0.0);
    wk.k_zeta = number_or(w, "k_zeta", "whisking", 0.0);
    if (!std::isfinite(wk.k_phi)) fail("whisking.k_phi must be finite, got " + format_value(wk.k_phi));
    if (!std::isfinite(wk.k_zeta)) fail("whisking.k_zeta must be finite, got " + format_value(wk.k_zeta));
    c.whisking = wk;
  }
  if (j.contains("initial")) {
    const json& i = j.at("initial");
    only_keys(i, "initial", {"tip_force", "force", "arc_length"});
    if (i.contains("tip_force") && i.contains("force"))
      fail("initial needs at most one of \"tip_force\" and \"force\" (with \"arc_length\")");
    if (i.contains("arc_length") && !i.contains("force")) fail("initial.arc_length needs initial.force");
    if (i.contains("tip_force")) c.tip_force_B = json_vec3(i.at("tip_force"), "initial.tip_force");
    if (i.contains("force")) {
      c.tip_force_B = json_vec3(i.at("force"), "initial.force");
      if (i.contains("arc_length")) {
        const double s = json_number(i.at("arc_length"), "initial.arc_length");
        if (!(s > 0.0 && s <= c.whisker.length()))
          fail("initial.arc_length must be in (0, " + format_value(c.whisker.length()) + "] [m], got " + format_value(s));
        c.force_arc_length = s;
      }
    }
  }
  if (j.contains("model")) {
    const std::string m = json_string(j.at("model"), "model");
    if (m == "automatic") c.options.model = dynamics::ChainModel::automatic;
    else if (m == "linear") c.options.model = dynamics::ChainModel::linear;
    else if (m == "nonlinear") c.options.model = dynamics::ChainModel::nonlinear;
    else fail("model must be \"automatic\", \"linear\" or \"nonlinear\", got " + quote_text(m));
  }
  if (j.contains("objects")) {
    const json& list = j.at("objects");
    if (!list.is_array()) fail("objects must be an array, got " + describe(list));
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string where = "objects[" + std::to_string(k) + "]";
      const json& o = list[k];
      const std::string type = o.contains("type") ? json_string(o.at("type"), where + ".type") : "";
      if (type != "edge" && type != "peg") {
        // A surface (the objects of `vibrissa solve`: plane, sphere, cylinder, box, mesh; SI), with the whisker's
        // thickness by default.
        if (!o.is_object() || (type != "cylinder" && type != "plane" && type != "sphere" && type != "box" &&
                               type != "mesh"))
          fail(where + ".type must be \"edge\", \"peg\", \"cylinder\", \"plane\", \"sphere\", \"box\" or "
               "\"mesh\", got " + quote_text(type));
        // The shape's own checks name its field ("object.radius"): the message says which object too.
        std::shared_ptr<const Shape> shape;
        try {
          shape = shape_from_json(o, where, LengthKeys::metres, {}, {"thickness", "friction_coefficient"});
        } catch (const std::invalid_argument& e) {
          const std::string what = e.what();
          fail(what.rfind(where, 0) == 0 ? what : where + ": " + what);
        }
        const bool thickness = o.contains("thickness") ? json_bool(o.at("thickness"), where + ".thickness") : true;
        const double mu = number_or(o, "friction_coefficient", where, 0.0);
        if (!(mu >= 0.0)) fail(where + ".friction_coefficient must be >= 0, got " + format_value(mu));
        try {
          c.options.objects.push_back(dynamics::obstacle(shape, ObjectPose{}, thickness, mu));
        } catch (const std::invalid_argument& e) {
          fail(where + ": " + e.what());
        }
        continue;
      }
      only_keys(o, where, {"type", "point", "direction", "radius", "thickness", "friction_coefficient"});
      if (!o.contains("point")) fail(where + " needs \"point\" [m]");
      dynamics::LineObstacle ob;
      ob.point_W = json_vec3(o.at("point"), where + ".point");
      ob.direction_W = unit_direction(
          o.contains("direction") ? json_vec3(o.at("direction"), where + ".direction") : Eigen::Vector3d::UnitZ(),
          where + ".direction");
      if (type == "peg") {
        if (!o.contains("radius")) fail(where + " (a peg) needs \"radius\" [m]");
        ob.radius = json_number(o.at("radius"), where + ".radius");
        if (!(ob.radius >= 0.0)) fail(where + ".radius must be >= 0 [m], got " + format_value(ob.radius));
        ob.thickness = o.contains("thickness") ? json_bool(o.at("thickness"), where + ".thickness") : true;
      } else if (o.contains("radius") || o.contains("thickness")) {
        fail(where + ": an edge has no radius or thickness (its centre line touches the whisker's)");
      }
      ob.friction_coefficient = number_or(o, "friction_coefficient", where, 0.0);
      if (!(ob.friction_coefficient >= 0.0))
        fail(where + ".friction_coefficient must be >= 0, got " + format_value(ob.friction_coefficient));
      c.options.objects.push_back(ob);
    }
  }
  if (j.contains("contact")) {
    const json& k = j.at("contact");
    only_keys(k, "contact", {"stiffness", "tangential_stiffness", "damping_ratio"});
    c.options.contact.stiffness = number_or(k, "stiffness", "contact", c.options.contact.stiffness);
    c.options.contact.tangential_stiffness =
        number_or(k, "tangential_stiffness", "contact", c.options.contact.tangential_stiffness);
    c.options.contact.damping_ratio = number_or(k, "damping_ratio", "contact", c.options.contact.damping_ratio);
    dynamics::validate(c.options.contact);
  }
  if (c.options.model == dynamics::ChainModel::linear && !c.options.objects.empty())
    fail("model \"linear\" cannot touch objects: use \"nonlinear\" or leave \"model\" out");
  c.options.duration = number_or(j, "duration", "", c.options.duration);
  c.options.output_rate = number_or(j, "output_rate", "", c.options.output_rate);
  c.options.relative_tolerance = number_or(j, "relative_tolerance", "", c.options.relative_tolerance);
  c.options.absolute_tolerance = number_or(j, "absolute_tolerance", "", c.options.absolute_tolerance);
  c.options.modes = c.properties.modes;
  dynamics::validate(c.options);
  if (j.contains("modes")) c.mode_count = json_integer(j.at("modes"), "modes", 1, 100000);
  if (j.contains("load")) {
    c.load = load_from_json(j.at("load"));
    if (std::holds_alternative<BaseWrenchLoad>(*c.load))
      fail("load.mode \"base_wrench\" has no load to hold for modes: use force, dead_load, point, edge, "
           "frictional_edge or object");
  }
  if (j.contains("hold")) {
    if (!c.load) fail("\"hold\" needs a \"load\"");
    const std::string m = json_string(j.at("hold"), "hold");
    if (m == "stick") c.hold = dynamics::ContactModel::stick;
    else if (m == "slip") c.hold = dynamics::ContactModel::slip;
    else fail("hold must be \"stick\" or \"slip\", got " + quote_text(m));
  }
  return c;
}

dynamics::BaseTrajectory base_trajectory(const DynamicsCase& c) {
  const Pose pose = c.whisker.placement().pose();
  if (c.whisking) return whisking_trajectory(pose, *c.whisking);
  return dynamics::fixed_base(c.whisker.placement());
}

dynamics::ExternalLoad external_load(const DynamicsCase& c) {
  if (!c.properties.air_drag) return {};
  return dynamics::air_drag_load(c.whisker, base_trajectory(c), c.properties.air);
}

dynamics::InitialState initial_state(const DynamicsCase& c, const dynamics::LinearModel& model) {
  dynamics::InitialState s;
  if (c.tip_force_B) {
    // Equilibrium under a force F (B axes) at arc length s on link k: K q = Q with Q_j = (x(s) - p_j) x F for
    // j <= k, i.e. Q = D(s)^T F with D(s) the displacement of the point, interpolated along link k between its
    // nodes (the link is rigid, so this is exact).
    const double arc = c.force_arc_length.value_or(c.whisker.length());
    int k = 0;
    double h = 0.0;
    c.whisker.locate(arc, k, h);
    const Eigen::Index a = static_cast<Eigen::Index>(3 * k);
    const double f = std::clamp(h / c.whisker.link_lengths()[static_cast<std::size_t>(k)], 0.0, 1.0);
    const Eigen::MatrixXd D = (1.0 - f) * model.node_displacement.middleRows<3>(a) +
                              f * model.node_displacement.middleRows<3>(a + 3);
    const Eigen::VectorXd Q = D.transpose() * *c.tip_force_B;
    s.q = model.stiffness.ldlt().solve(Q);
    s.q_dot = Eigen::VectorXd::Zero(s.q.size());
  }
  return s;
}

CaseModes case_modes(const DynamicsCase& c, int count) {
  CaseModes out;
  const Whisker& w = c.whisker;
  if (!c.load) {
    out.modes = dynamics::modes(w, c.properties, count);
    return out;
  }
  const Case sc{w, *c.load, SolveOptions{}, {}};
  out.solution = solve_case(sc);
  const Solution& sol = out.solution;
  if (sol.status != Status::converged || sol.contact_state != ContactState::contact)
    throw std::runtime_error("the load's quasi-static solve gave status " + std::string(to_string(sol.status)) +
                             ", contact " + std::string(to_string(sol.contact_state)) +
                             ": no equilibrium to take modes about");
  const Eigen::Matrix3d R_BW = w.placement().R_WB.transpose();
  dynamics::HeldLoad& h = out.held;
  h.arc_length = sol.arc_length;
  h.force_B = R_BW * sol.force_W;
  h.contact_point_B = R_BW * (sol.contact_point_W - w.placement().p_W_base);
  // How each load holds (docs/dynamics.md): forces keep their force; a point contact sticks; an edge or
  // object contact slips unless the frictional solve stuck; "hold" overrides.
  std::optional<Eigen::Vector3d> normal_W;
  std::visit(
      [&](const auto& l) {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, ForceLoad>) {
          h.follower = true;
        } else if constexpr (std::is_same_v<T, DeadLoad>) {
          h.follower = false;
        } else if constexpr (std::is_same_v<T, PointLoad>) {
          h.contact = dynamics::ContactModel::stick;
          normal_W = sol.force_W;
        } else if constexpr (std::is_same_v<T, EdgeLoad> || std::is_same_v<T, FrictionalEdgeLoad>) {
          h.contact = sol.friction == FrictionState::stick ? dynamics::ContactModel::stick : dynamics::ContactModel::slip;
          const Eigen::Vector3d e = l.edge.direction.normalized();
          normal_W = sol.force_W - sol.force_W.dot(e) * e;  // the edge's normal force
        } else if constexpr (std::is_same_v<T, ObjectLoad>) {
          h.contact = sol.friction == FrictionState::stick ? dynamics::ContactModel::stick : dynamics::ContactModel::slip;
          normal_W = sol.surface ? sol.surface->normal_W : sol.force_W;
        }
      },
      *c.load);
  if (c.hold) {
    if (h.contact == dynamics::ContactModel::none)
      throw std::invalid_argument("\"hold\" applies to contact loads (point, edge, frictional_edge, object), "
                                  "not to a force");
    h.contact = *c.hold;
  }
  if (normal_W) {
    if (!(normal_W->norm() > 0.0)) throw std::runtime_error("the contact force is zero: no contact normal for modes");
    h.normal_B = R_BW * normal_W->normalized();
  }
  // Start Newton from the quasi-static solve's joint rotations (rest axes).
  const std::size_t N = static_cast<std::size_t>(w.links());
  std::vector<Eigen::Vector3d> omega_link(N, Eigen::Vector3d::Zero());
  const LoadState& st = sol.state;
  deflect<double>(w, V3<double>(st.force_x, st.force_y, st.force_z), V3<double>(st.couple_x, st.couple_y, st.couple_z),
                  st.arc_length, omega_link.data());
  dynamics::JointRotations start(N);
  for (std::size_t j = 0; j < N; ++j) start[j] = w.rest_link_frames_B()[j] * omega_link[j];
  out.deflected = dynamics::deflected_modes(w, c.properties, h, start, count);
  out.modes = out.deflected->modes;
  return out;
}

json equilibrium_to_json(const CaseModes& m, const Whisker& w) {
  if (!m.deflected) return nullptr;
  const dynamics::DeflectedModes& d = *m.deflected;
  const auto vec = [](const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); };
  json j;
  j["arc_length"] = m.held.arc_length;
  j["load"] = m.held.contact == dynamics::ContactModel::none ? (m.held.follower ? "follower" : "dead") : "contact";
  j["contact"] = std::string(dynamics::to_string(m.held.contact));
  if (m.held.contact == dynamics::ContactModel::slip) j["normal_B"] = vec(m.held.normal_B);
  j["constraints"] = d.constraints;
  j["force_B"] = vec(d.equilibrium.force_B);
  j["contact_point_B"] = vec(d.equilibrium.contact_B);
  j["quasi_static_force_B"] = vec(w.placement().R_WB.transpose() * m.solution.force_W);
  j["tip_B"] = vec(dynamics::chain_nodes_B(w, d.equilibrium.omega).back());
  j["newton_iterations"] = d.equilibrium.iterations;
  j["relative_residual"] = d.equilibrium.residual;
  j["stiffness_asymmetry"] = d.asymmetry;
  j["largest_imaginary"] = d.largest_imaginary;
  return j;
}

json modes_to_json(const dynamics::Modes& m, const Whisker& w, const DynamicsCase& c) {
  json out;
  out["density"] = c.properties.density;
  out["joint_damping_time"] = m.damping_time;
  out["links"] = w.links();
  out["length"] = w.length();
  json list = json::array();
  for (int i = 0; i < m.count(); ++i) {
    json mode;
    mode["frequency"] = m.frequency_hz(i);
    mode["damped_frequency"] = m.damped_frequency_hz(i);
    mode["damping_ratio"] = m.damping_ratio(i);
    mode["torsion_fraction"] = m.torsion_fraction(i);
    json nodes = json::array();
    for (int k = 0; k <= w.links(); ++k) {
      const Eigen::Vector3d v = m.node_shapes.col(i).segment<3>(3 * k);
      nodes.push_back(json::array({v.x(), v.y(), v.z()}));
    }
    mode["node_shape_B"] = std::move(nodes);
    list.push_back(std::move(mode));
  }
  out["modes"] = std::move(list);
  return out;
}

namespace {

struct Column {
  std::string name;
  std::vector<double> values;
  std::string units, long_name;
};

std::vector<Column> scalar_columns(const dynamics::TimeSeries& ts) {
  const std::size_t n = ts.time.size();
  std::vector<Column> cols;
  cols.push_back({"time", ts.time, "s", "time"});
  std::vector<double> th(n), ph(n), ze(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Pose p = ts.placements[i].pose();
    th[i] = p.theta;
    ph[i] = p.phi;
    ze[i] = p.zeta;
  }
  cols.push_back({"theta", th, "rad", "protraction angle of the base"});
  cols.push_back({"phi", ph, "rad", "elevation angle of the base"});
  cols.push_back({"zeta", ze, "rad", "roll angle of the base"});
  auto vec = [&](const std::vector<Eigen::Vector3d>& v, const std::string& prefix, const std::string& suffix,
                 const std::string& units, const std::string& what) {
    const char* axes[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      std::vector<double> x(n);
      for (std::size_t i = 0; i < n; ++i) x[i] = v[i](a);
      cols.push_back({prefix + axes[a] + suffix, std::move(x), units, what + ", " + axes[a] + " component"});
    }
  };
  vec(ts.force_B, "F", "_B", "N", "force on the follicle, whisker frame");
  vec(ts.moment_B, "M", "_B", "N m", "moment on the follicle about the base, whisker frame");
  vec(ts.force_W, "F", "_W", "N", "force on the follicle, world frame");
  vec(ts.moment_W, "M", "_W", "N m", "moment on the follicle about the base, world frame");
  std::vector<double> FT(n), MB(n), FD(n), MD(n);
  for (std::size_t i = 0; i < n; ++i) {
    const WhiskerFrameSignals sig = whisker_frame_signals(ts.force_B[i], ts.moment_B[i]);
    FT[i] = sig.FT;
    MB[i] = sig.MB;
    FD[i] = sig.FD;
    MD[i] = sig.MD;
  }
  cols.push_back({"FT", FT, "N", "transverse force at the base"});
  cols.push_back({"MB", MB, "N m", "bending moment at the base"});
  cols.push_back({"FD", FD, "rad", "direction of the transverse force, atan2(Fz, Fy)"});
  cols.push_back({"MD", MD, "rad", "direction of the bending moment, atan2(Mz, My)"});
  vec(ts.tip_displacement_B, "tip_", "_B", "m", "tip displacement from its rest position, whisker frame");
  cols.push_back({"kinetic_energy", ts.kinetic_energy, "J", "kinetic energy relative to the base frame"});
  cols.push_back({"elastic_energy", ts.elastic_energy, "J", "elastic energy of the joints"});
  for (std::size_t o = 0; o < ts.contacts.size(); ++o) {
    const dynamics::ContactChannels& ch = ts.contacts[o];
    const std::string p = "contact" + std::to_string(o) + "_", who = "object " + std::to_string(o);
    std::vector<double> state(n);
    for (std::size_t i = 0; i < n; ++i) state[i] = static_cast<double>(static_cast<int>(ch.state[i]));
    cols.push_back({p + "state", std::move(state), "1", who + ": contact state, 0 none, 1 stick, 2 slip"});
    cols.push_back({p + "s", ch.arc_length, "m", who + ": arc length of the whisker's nearest point"});
    cols.push_back({p + "gap", ch.gap, "m", who + ": gap to the surface (< 0: penetration)"});
    vec(ch.point_W, p, "_W", "m", who + ": whisker's nearest point, world frame");
    vec(ch.force_W, p + "F", "_W", "N", who + ": contact force on the whisker, world frame");
  }
  return cols;
}

}  // namespace

LabelledData dynamics_data(const dynamics::TimeSeries& ts) {
  LabelledData d;
  const std::size_t n = ts.time.size();
  for (Column& c : scalar_columns(ts)) {
    LabelledVariable v{.name = c.name, .dims = {"time"}, .shape = {n}, .units = c.units, .long_name = c.long_name};
    d.add_owned(std::move(v), std::move(c.values));
  }
  if (!ts.nodes_W.empty()) {
    const std::size_t nodes = ts.nodes_W.front().size();
    std::vector<double> xyz;
    xyz.reserve(n * nodes * 3);
    for (const auto& frame : ts.nodes_W)
      for (const auto& p : frame) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    d.add_owned({.name = "nodes_W", .dims = {"time", "node", "component"}, .shape = {n, nodes, 3}, .units = "m",
                 .long_name = "whisker nodes, world frame", .compress = true},
                std::move(xyz));
    d.add_index_coordinate("", "node", nodes, "node index from the base");
    d.add_component_coordinate();
  }
  d.attributes = {{"", "format", "vibrissa-dynamics"}, {"", "format_version", 1.0},
                  {"", "status", std::string(to_string(ts.status))}};
  return d;
}

json dynamics_summary(const dynamics::TimeSeries& ts, const dynamics::Modes& modes, const DynamicsCase& c) {
  json j;
  j["status"] = std::string(to_string(ts.status));
  j["frames"] = ts.time.size();
  j["steps"] = ts.steps;
  j["rejected_steps"] = ts.rejected_steps;
  j["smallest_step_s"] = ts.smallest_step;
  j["largest_step_s"] = ts.largest_step;
  double FT = 0.0, MB = 0.0, tip = 0.0;
  for (std::size_t i = 0; i < ts.time.size(); ++i) {
    FT = std::max(FT, std::hypot(ts.force_B[i].y(), ts.force_B[i].z()));
    MB = std::max(MB, std::hypot(ts.moment_B[i].y(), ts.moment_B[i].z()));
    tip = std::max(tip, ts.tip_displacement_B[i].norm());
  }
  j["peak_FT_uN"] = FT * 1e6;
  j["peak_MB_uNm"] = MB * 1e6;
  j["peak_tip_displacement_mm"] = tip * 1e3;
  j["model"] = std::string(to_string(ts.model));
  j["max_penetration_m"] = ts.max_penetration;
  j["events"] = contact_events_json(ts.events);
  // The linear model holds about the rest shape (docs/dynamics.md): say so when the deflection leaves that range.
  json warnings = json::array();
  const double L = c.whisker.length();
  if (ts.model == dynamics::ChainModel::linear && tip > 0.05 * L)
    warnings.push_back("the tip moved up to " + format_value(tip * 1e3) + " mm from rest, " +
                       format_value(std::round(1000.0 * tip / L) / 10.0) +
                       " % of the whisker's length: beyond the small deflections the linearised model assumes "
                       "(docs/dynamics.md, 5 % used here)");
  j["warnings"] = std::move(warnings);
  json f = json::array(), z = json::array();
  for (int i = 0; i < std::min(c.mode_count, modes.count()); ++i) {
    f.push_back(modes.frequency_hz(i));
    z.push_back(modes.damping_ratio(i));
  }
  j["mode_frequencies_Hz"] = f;
  j["mode_damping_ratios"] = z;
  return j;
}

void write_dynamics_outputs(const dynamics::TimeSeries& ts, const json& summary, const std::filesystem::path& dir) {
  const std::vector<Column> cols = scalar_columns(ts);
  OutputFolder folder(dir);
  folder.stage_text("dynamics.csv", [&](std::ostream& out) {
    for (std::size_t k = 0; k < cols.size(); ++k) out << (k ? "," : "") << cols[k].name;
    out << "\n";
    for (std::size_t i = 0; i < ts.time.size(); ++i) {
      for (std::size_t k = 0; k < cols.size(); ++k) out << (k ? "," : "") << csv::cell(cols[k].values[i]);
      out << "\n";
    }
  });
  if (!ts.contacts.empty())
    folder.stage_text("events.csv", [&](std::ostream& out) {
      out << "time,type,object,arc_length,x_W,y_W,z_W,Fx_W,Fy_W,Fz_W\n";
      for (const dynamics::ContactEvent& e : ts.events) {
        out << csv::cell(e.time) << "," << to_string(e.type) << "," << e.object << "," << csv::cell(e.arc_length);
        for (int a = 0; a < 3; ++a) out << "," << csv::cell(e.point_W(a));
        for (int a = 0; a < 3; ++a) out << "," << csv::cell(e.force_W(a));
        out << "\n";
      }
    });
  const LabelledData data = dynamics_data(ts);
  folder.stage("dynamics.h5", [&](const std::string& tmp) { write_labelled_h5(data, tmp); });
  stage_json_file(folder, "summary.json", summary);
  folder.commit();
}

}  // namespace vibrissa::io
