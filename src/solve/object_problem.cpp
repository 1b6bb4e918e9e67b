#include "object_problem.hpp"

#include "newton_line_search.hpp"
#include "vibrissa/solve/solvers.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <Eigen/Geometry>

namespace vibrissa::detail {

namespace {

template <class S>
struct SurfaceAt {
  S distance;
  V3<S> normal, closest;
  SurfacePoint value;  ///< the query itself (doubles)
};

/// The query at c with its derivatives: d distance = n . dc, d n = (dn/dp) dc, closest = c - distance n.
template <class S>
SurfaceAt<S> surface_at(const ObjectGeometryB& g, const V3<S>& c) {
  const Eigen::Vector3d cv(value_of(c.x), value_of(c.y), value_of(c.z));
  const SurfacePoint q = g.query(cv);
  SurfaceAt<S> out;
  out.value = q;
  if constexpr (std::is_same_v<S, double>) {
    out.distance = q.signed_distance;
    out.normal = V3<double>(q.normal);
  } else {
    const V3<S> dc = c - V3<S>(cv);  // derivatives only
    out.distance = S(q.signed_distance) + dot(V3<S>(q.normal), dc);
    out.normal = V3<S>(q.normal) + mul(q.normal_derivative, dc);
  }
  out.closest = c - out.distance * out.normal;
  return out;
}

/// r(s) and r'(s) of the whisker's linear taper between nodes (the last link's beyond the tip).
template <class S>
S radius_at(const Whisker& w, const S& s, double& slope) {
  int k;
  double h;
  w.locate(value_of(s), k, h);
  k = std::clamp(k, 0, w.links() - 1);
  const auto& r = w.node_radii();
  const auto& arc = w.node_arc_lengths();
  const auto uk = static_cast<std::size_t>(k);
  slope = (r[uk + 1] - r[uk]) / (arc[uk + 1] - arc[uk]);
  return S(r[uk]) + slope * (s - S(arc[uk]));
}

template <class S>
V3<S> unit(const V3<S>& v) {
  using std::sqrt;
  return (S(1.0) / sqrt(dot(v, v))) * v;
}

/// The load in the load frame from the force components normal to the whisker (side contacts): the axial part
/// makes the force normal to the tapered surface (frictionless: F_x = r' F_T / sqrt(1 - r'^2); frictional:
/// F . t_tangent = 0 with the law's normal); frictional contacts with thickness add friction's couple about the
/// centre line, C = -r n x F.
template <class S>
void side_load(const FrictionLaw& law, bool thickness, const S& Fy, const S& Fz, const S& r, double slope, V3<S>& F_L,
               V3<S>& C_L) {
  using std::sqrt;
  S Fx;
  if (law.kind == FrictionLaw::Kind::frictionless) {
    Fx = (slope / std::sqrt(1.0 - slope * slope)) * sqrt(Fy * Fy + Fz * Fz + S(1e-300));
  } else {
    const Eigen::Vector3d& k = law.normal_L;
    Fx = (slope / (1.0 - slope * k.x())) * (Fy * k.y() + Fz * k.z());
  }
  F_L = V3<S>(Fx, Fy, Fz);
  C_L = V3<S>(S(0.0), S(0.0), S(0.0));
  if (law.kind != FrictionLaw::Kind::frictionless && thickness) C_L = (S(0.0) - r) * cross(V3<S>(law.normal_L), F_L);
}

template <class S>
S smaller(const S& a, const S& b) {
  return value_of(b) < value_of(a) ? b : a;
}

/// The gap of a piece of the loaded link around the load point c (second-order scheme; docs/objects.md, "The
/// chain's chords"): the chain is its chords, and the load frame's x axis t (the smooth tangent) is tilted from
/// the link's chord u by (h - l/2) kappa, so with the gap at c zero and the tangency on t, the chord or its end
/// nodes could cross the surface by up to l^2 kappa / 16. The distance equation holds for the link's lowest
/// piece: c itself, its start or end node, or the chord's own nearest point (a Newton step along u from c's
/// query). Solves keep one piece (a smooth system) and change it where another is lower (attempt_side).
template <class S>
S piece_gap(ClearancePiece piece, const Whisker& w, const ObjectGeometryB& g, const S& s, const V3<S>& c,
            const FollowerVectors<S>& f, const S& gap_c, const SurfacePoint& at_c) {
  if (piece == ClearancePiece::centre) return gap_c;
  int k;
  double h0;
  w.locate(value_of(s), k, h0);
  k = std::clamp(k, 0, w.links() - 1);
  const auto uk = static_cast<std::size_t>(k);
  const double l = w.link_lengths()[uk];
  const S h = s - S(w.node_arc_lengths()[uk]);
  // The chord in the load frame: exp(-[psi]x) e_x, psi = (h - l/2) kappa (chain.hpp), then in B.
  const V3<S> psi = (h - S(0.5 * l)) * V3<S>(w.load_frame_curvature()[uk]);
  S a, b;
  rodrigues_coefficients(dot(psi, psi), a, b);
  const V3<S> v = rotate(S(-1.0) * psi, a, b, V3<S>(S(1.0), S(0.0), S(0.0)));
  const V3<S> u = v.x * f[0] + v.y * f[1] + v.z * cross(f[0], f[1]);
  const double r0 = g.thickness ? w.node_radii()[uk] : 0.0, r1 = g.thickness ? w.node_radii()[uk + 1] : 0.0;
  if (piece == ClearancePiece::start_node) return surface_at(g, c - h * u).distance - S(r0);
  if (piece == ClearancePiece::end_node) return surface_at(g, c + (S(l) - h) * u).distance - S(r1);
  // The chord's nearest point: a Newton step along u from c (the gap's slope and curvature there).
  const Eigen::Vector3d uv(value_of(u.x), value_of(u.y), value_of(u.z));
  const double slope = at_c.normal.dot(uv) - (r1 - r0) / l, curvature = uv.dot(at_c.normal_derivative * uv);
  const double tau = curvature > 0.0 ? std::clamp(-slope / curvature, -value_of(h), l - value_of(h)) : 0.0;
  const S r_tau = g.thickness ? S(r0) + (h + tau) * ((r1 - r0) / l) : S(0.0);
  return surface_at(g, c + tau * u).distance - r_tau;
}

/// The whisker deflected by `state` with the load frame's axes (through the geometry's record of the last one).
const ObjectGeometryB::Deflected& deflected_at(const Whisker& w, const ObjectGeometryB& g, const LoadState& state) {
  FollowerVectors<double> follow{V3<double>(1, 0, 0), V3<double>(0, 1, 0)};
  (void)walk_deflected<double>(w, g, V3<double>(state.force_x, state.force_y, state.force_z),
                               V3<double>(state.couple_x, state.couple_y, state.couple_z), state.arc_length, follow);
  return *g.last_deflected;
}

/// Whether a piece of the link can be lower than c: never on a line without radius or in the paper scheme (its
/// load frame is the loaded link's chord).
bool pieces_apply(const Whisker& w, const ObjectGeometryB& g) {
  return w.properties().scheme != Scheme::paper && !(g.core_B && g.core_B->radius == 0.0 && !g.thickness);
}

/// The walk's inputs of a side contact at scaled unknowns u (force and couple in the load frame, s, and r(s)).
template <class S>
void side_walk_inputs(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                      const std::array<S, 3>& u, V3<S>& F_L, V3<S>& C_L, S& s, S& r, double& slope) {
  s = sc.length * u[2];
  slope = 0.0;
  r = g.thickness ? radius_at(w, s, slope) : S(0.0);
  side_load(law, g.thickness, S(sc.force * u[0]), S(sc.force * u[1]), r, slope, F_L, C_L);
}

LMBounds side_bounds() {
  LMBounds b;
  b.lower[2] = 1e-9;
  b.upper[2] = 1.0;
  return b;
}

/// Whether the Jacobian of the geometry's record is an estimate (adopted from a warm state), and dropping it.
class RecordedEstimate final : public JacobianEstimates {
 public:
  explicit RecordedEstimate(const ObjectGeometryB& g) : g_(g) {}
  [[nodiscard]] bool estimated() const override { return g_.last_jacobian && g_.last_jacobian->estimated; }
  void forget_estimate() override {
    if (estimated()) g_.last_jacobian.reset();
  }

 private:
  const ObjectGeometryB& g_;
};

/// The nine kinematic quantities and the two follower vectors of a walk (const or not), in LoadSensitivity's order.
template <class Kinematics, class Follow>
auto components(Kinematics& k, Follow& f) {
  return std::array{&k.p_contact_B.x, &k.p_contact_B.y, &k.p_contact_B.z, &k.force_B.x, &k.force_B.y,
                    &k.force_B.z,     &k.couple_B.x,    &k.couple_B.y,    &k.couple_B.z, &f[0].x,
                    &f[0].y,          &f[0].z,          &f[1].x,          &f[1].y,       &f[1].z};
}

std::array<double, 7> load_of(const LoadState& s) {
  return {s.force_x, s.force_y, s.force_z, s.couple_x, s.couple_y, s.couple_z, s.arc_length};
}

}  // namespace

template <class S>
ContactKinematics<S> walk_deflected(const Whisker& w, const ObjectGeometryB& g, const V3<S>& F_L, const V3<S>& C_L,
                                    const S& s, FollowerVectors<S>& follow) {
  const std::array<double, 7> load{value_of(F_L.x), value_of(F_L.y), value_of(F_L.z), value_of(C_L.x),
                                   value_of(C_L.y), value_of(C_L.z), value_of(s)};
  if constexpr (std::is_same_v<S, double>) {
    if (g.last_deflected && g.last_deflected->load == load) {
      follow = g.last_deflected->follow;
      return g.last_deflected->k;
    }
    if (!g.last_deflected) g.last_deflected = ObjectGeometryB::Deflected{};
    ObjectGeometryB::Deflected& d = *g.last_deflected;
    d.load = load;
    const bool second_order = w.properties().scheme != Scheme::paper;
    d.omega.resize(second_order ? static_cast<std::size_t>(w.links()) : 0);
    d.k = deflect<double, true>(w, F_L, C_L, s, second_order ? d.omega.data() : nullptr, &follow);
    d.follow = follow;
    return d.k;
  } else {
    const std::array<Dual<3>, 7> input{F_L.x, F_L.y, F_L.z, C_L.x, C_L.y, C_L.z, s};
    auto same = [](const std::array<Dual<3>, 7>& a, const std::array<Dual<3>, 7>& b) {
      for (std::size_t i = 0; i < 7; ++i)
        if (a[i].v != b[i].v || a[i].d != b[i].d) return false;
      return true;
    };
    if (g.last_jacobian && same(g.last_jacobian->input, input)) {
      follow = g.last_jacobian->follow;
      return g.last_jacobian->k;
    }
    const ContactKinematics<S> k = deflect_for_solve<S>(w, F_L, C_L, s, follow);
    g.last_jacobian = ObjectGeometryB::DeflectedJacobian{input, k, follow, std::nullopt, false};
    if (!g.last_deflected) g.last_deflected = ObjectGeometryB::Deflected{};
    ObjectGeometryB::Deflected& d = *g.last_deflected;
    auto v = [](const V3<S>& x) { return V3<double>(value_of(x.x), value_of(x.y), value_of(x.z)); };
    d.load = load;
    d.k = {v(k.p_contact_B), v(k.force_B), v(k.couple_B)};
    d.follow = {v(follow[0]), v(follow[1])};
    d.omega.clear();
    return k;
  }
}
template ContactKinematics<double> walk_deflected<double>(const Whisker&, const ObjectGeometryB&, const V3<double>&,
                                                          const V3<double>&, const double&, FollowerVectors<double>&);
template ContactKinematics<Dual<3>> walk_deflected<Dual<3>>(const Whisker&, const ObjectGeometryB&,
                                                            const V3<Dual<3>>&, const V3<Dual<3>>&, const Dual<3>&,
                                                            FollowerVectors<Dual<3>>&);

LoadState start_side_load(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                          const Eigen::Vector3d& u0) {
  using D = Dual<3>;
  const LMBounds b = side_bounds();
  const Eigen::Vector3d u = u0.cwiseMax(b.lower).cwiseMin(b.upper);  // as newton_line_search() starts
  const std::array<D, 3> x = {D::variable(u[0], 0), D::variable(u[1], 1), D::variable(u[2], 2)};
  V3<D> F_L, C_L;
  D s, r;
  double slope;
  side_walk_inputs<D>(w, sc, g, law, x, F_L, C_L, s, r, slope);
  FollowerVectors<D> follow{V3<D>(D(1.0), D(0.0), D(0.0)), V3<D>(D(0.0), D(1.0), D(0.0))};
  (void)walk_deflected<D>(w, g, F_L, C_L, s, follow);
  LoadState state;
  state.force_x = F_L.x.v;
  state.force_y = F_L.y.v;
  state.force_z = F_L.z.v;
  state.couple_x = C_L.x.v;
  state.couple_y = C_L.y.v;
  state.couple_z = C_L.z.v;
  state.arc_length = s.v;
  return state;
}

std::optional<Eigen::Vector3d> adopt_side_sensitivity(const Whisker& w, const Scales& sc, const ObjectGeometryB& g,
                                                      const FrictionLaw& law, const LoadState& warm) {
  using D = Dual<3>;
  const LoadSensitivity& c = warm.sensitivity;
  if (!c.object || c.whisker == 0 || c.whisker != w.mechanics_fingerprint() ||
      law.kind != FrictionLaw::Kind::frictionless)
    return std::nullopt;
  const Eigen::Vector3d u(c.unknowns[0], c.unknowns[1], c.unknowns[2]);
  const LMBounds b = side_bounds();
  if (u != u.cwiseMax(b.lower).cwiseMin(b.upper)) return std::nullopt;
  const std::array<D, 3> x = {D::variable(u[0], 0), D::variable(u[1], 1), D::variable(u[2], 2)};
  V3<D> F_L, C_L;
  D s, r;
  double slope;
  side_walk_inputs<D>(w, sc, g, law, x, F_L, C_L, s, r, slope);
  const std::array<D, 7> input{F_L.x, F_L.y, F_L.z, C_L.x, C_L.y, C_L.z, s};
  std::array<double, 7> load{};
  for (std::size_t i = 0; i < 7; ++i) load[i] = input[i].v;
  if (load != load_of(warm)) return std::nullopt;  // the record is not of this load (or of another law)
  ObjectGeometryB::DeflectedJacobian J{input, {}, {}, u, true};
  ObjectGeometryB::Deflected d;
  d.load = load;
  const auto to = components(J.k, J.follow);
  const auto values = components(d.k, d.follow);
  for (std::size_t i = 0; i < to.size(); ++i) {
    const double* from = i < 9 ? &c.kinematics[4 * i] : &c.followers[4 * (i - 9)];
    to[i]->v = *values[i] = from[0];
    for (std::size_t j = 0; j < 3; ++j) to[i]->d[j] = from[1 + j];
  }
  g.last_jacobian = J;
  g.last_deflected = d;
  return u;
}

LoadSensitivity side_sensitivity(const Whisker& w, const ObjectGeometryB& g, const Eigen::Vector3d& u,
                                 const LoadState& state) {
  LoadSensitivity out;
  const std::array<double, 7> load = load_of(state);
  if (!g.last_deflected || g.last_deflected->load != load || !g.last_jacobian || !g.last_jacobian->side_u) return out;
  const ObjectGeometryB::DeflectedJacobian& J = *g.last_jacobian;
  ObjectGeometryB::Deflected values = *g.last_deflected;
  const auto from = components(J.k, J.follow);
  const auto value = components(values.k, values.follow);
  // Broyden's update of K = dk/du from the record's unknowns u_J to u: K + (k(u) - k(u_J) - K s) s^T / (s^T s).
  const Eigen::Vector3d step = u - *J.side_u;
  const double ss = step.squaredNorm();
  for (std::size_t i = 0; i < from.size(); ++i) {
    const Dual<3>& k = *from[i];
    const double predicted = k.d[0] * step[0] + k.d[1] * step[1] + k.d[2] * step[2];
    const double c = ss > 0.0 ? (*value[i] - k.v - predicted) / ss : 0.0;
    double* to = i < 9 ? &out.kinematics[4 * i] : &out.followers[4 * (i - 9)];
    to[0] = *value[i];
    for (std::size_t j = 0; j < 3; ++j) {
      to[1 + j] = k.d[j] + c * step[static_cast<Eigen::Index>(j)];
      if (!std::isfinite(to[1 + j])) return LoadSensitivity{};
    }
  }
  out.unknowns = {u[0], u[1], u[2]};
  out.whisker = w.mechanics_fingerprint();
  out.object = true;
  return out;
}

ContactKinematics<double> kinematics_at(const Whisker& w, const ObjectGeometryB& g, const LoadState& state) {
  return deflected_at(w, g, state).k;
}

void deflected_nodes(const Whisker& w, const ObjectGeometryB& g, const Placement& X, const LoadState& state,
                     std::vector<Eigen::Vector3d>& nodes) {
  if (w.properties().scheme == Scheme::paper) {
    deflected_shape(w, X, state, nodes);
    return;
  }
  const std::array<double, 7> load{state.force_x,  state.force_y,  state.force_z,   state.couple_x,
                                   state.couple_y, state.couple_z, state.arc_length};
  if (!g.last_deflected || g.last_deflected->load != load || g.last_deflected->omega.empty()) g.last_deflected.reset();
  const ObjectGeometryB::Deflected& d = deflected_at(w, g, state);  // (walked again only for the joint rotations)
  deflected_nodes_B(w, d.omega.data(), nodes);
  for (auto& p : nodes) p = X.to_world(p);
}

double whisker_radius_at(const Whisker& w, double s, double& slope) { return radius_at(w, s, slope); }

double piece_gap_at(ClearancePiece piece, const Whisker& w, const ObjectGeometryB& g, double s,
                    const Eigen::Vector3d& c_B, const Eigen::Vector3d& t_B, const Eigen::Vector3d& y_B) {
  const V3<double> c(c_B);
  const FollowerVectors<double> follow{V3<double>(t_B), V3<double>(y_B)};
  const SurfacePoint at_c = g.query(c_B);
  double slope = 0.0;
  const double gap_c = at_c.signed_distance - (g.thickness ? radius_at(w, s, slope) : 0.0);
  return piece_gap(piece, w, g, s, c, follow, gap_c, at_c);
}

bool contact_pieces_apply(const Whisker& w, const ObjectGeometryB& g) { return pieces_apply(w, g); }

LoadState side_load_state(const Whisker& w, const ObjectGeometryB& g, double force_y, double force_z, double s) {
  double slope = 0.0;
  const double r = g.thickness ? radius_at(w, s, slope) : 0.0;
  V3<double> F_L, C_L;
  side_load(FrictionLaw{}, g.thickness, force_y, force_z, r, slope, F_L, C_L);
  LoadState state;
  state.force_x = F_L.x;
  state.force_y = F_L.y;
  state.force_z = F_L.z;
  state.arc_length = s;
  return state;
}

SurfacePoint ObjectGeometryB::query(const Eigen::Vector3d& c_B) const {
  const Eigen::Vector3d p_O = R_BO.transpose() * (c_B - offset_B - p_BO);
  SurfacePoint q = held_feature >= 0 ? shape->nearest_on_feature(p_O, held_feature) : shape->nearest(p_O);
  q.closest = R_BO * q.closest + p_BO + offset_B;
  q.normal = R_BO * q.normal;
  q.normal_derivative = R_BO * q.normal_derivative * R_BO.transpose();
  q.edge_direction = R_BO * q.edge_direction;
  return q;
}

ObjectGeometryB object_in_body(const Placement& X, const ObjectContact& o) {
  ObjectGeometryB g;
  g.shape = o.shape;
  g.thickness = o.thickness;
  g.R_BO = X.R_WB.transpose() * o.X_WO.R_WO;
  g.p_BO = X.R_WB.transpose() * (o.X_WO.p_WO - X.p_W_base);
  if (const auto core = o.shape->line_core())
    g.core_B = LineCore{g.R_BO * core->point + g.p_BO, (g.R_BO * core->direction).normalized(), core->radius};
  return g;
}

Eigen::Vector3d ObjectContactPoint::normal_in_load_frame() const {
  const Eigen::Vector3d z = t_B.cross(y_B);
  return {normal_B.dot(t_B), normal_B.dot(y_B), normal_B.dot(z)};
}

double core_side(const ObjectGeometryB& g, const Eigen::Vector3d& c, const Eigen::Vector3d& t) {
  if (!g.core_B) return 1.0;
  const Eigen::Vector3d d = c - g.core_B->point - g.offset_B;
  return d.dot(g.core_B->direction.cross(t)) < 0.0 ? -1.0 : 1.0;
}

ObjectAttempt attempt_side(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                           double sigma, const Eigen::Vector3d& u0, const SolveOptions& options,
                           ClearancePiece piece, std::optional<double> pinned) {
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY();
  if (g.core_B) normal_basis(g.core_B->direction, e1, e2);  // as edge mode (edge_problem.cpp)
  auto residual = [&](const auto& u) {
    using S = std::decay_t<decltype(u[0])>;
    S s, r;
    double slope;
    V3<S> F_L, C_L;
    side_walk_inputs<S>(w, sc, g, law, u, F_L, C_L, s, r, slope);
    FollowerVectors<S> follow{V3<S>(S(1.0), S(0.0), S(0.0)), V3<S>(S(0.0), S(1.0), S(0.0))};
    const auto k = walk_deflected<S>(w, g, F_L, C_L, s, follow);
    if constexpr (!std::is_same_v<S, double>)  // the record's derivatives are these unknowns' (side_sensitivity)
      g.last_jacobian->side_u = Eigen::Vector3d(u[0].v, u[1].v, u[2].v);
    const V3<S>& c = k.p_contact_B;
    const V3<S>& t = follow[0];
    const V3<S> F((S(1.0) / sc.force) * k.force_B.x, (S(1.0) / sc.force) * k.force_B.y,
                  (S(1.0) / sc.force) * k.force_B.z);
    const double inv_L = 1.0 / sc.length;
    const SurfaceAt<S> q = surface_at(g, c);
    // The gap equation holds for the loaded link's closest point (link_clearance), which is c itself on a line.
    const S gap_c = q.distance - r;
    const S deficit = gap_c - piece_gap(piece, w, g, s, c, follow, gap_c, q.value);
    if (g.core_B) {  // the line's terms: (c - axis) = (R + r) u, u . t = r', u normal to the axis
      using std::sqrt;
      const V3<S> a(g.core_B->direction);
      const V3<S> d = c - V3<S>(Eigen::Vector3d(g.core_B->point + g.offset_B));
      const V3<S> radial = d - dot(d, a) * a;
      const V3<S> across = cross(a, t);
      const S sin_b = sqrt(dot(across, across));
      const V3<S> t_perp = t - dot(t, a) * a;
      const S sin_g = slope / sin_b;
      const S cos_g = sqrt(S(1.0) - sin_g * sin_g);
      const V3<S> n = (sigma * cos_g / sin_b) * across + (sin_g / sin_b) * t_perp;
      const V3<S> e = radial - (S(g.core_B->radius) + r + deficit) * n;
      S third;
      if (law.kind == FrictionLaw::Kind::frictionless) {
        third = dot(F, a);
      } else {
        const V3<S> b = unit(cross(n, t));
        if (law.kind == FrictionLaw::Kind::stick) {
          const V3<S> on_surface = c - radial + S(g.core_B->radius) * n;
          third = inv_L * dot(on_surface - V3<S>(law.previous_B), b);
        } else {
          third = dot(F, b) + law.sigma_mu * dot(F, n);
        }
      }
      if (pinned) return std::array<S, 3>{inv_L * (gap_c - deficit), u[2] - *pinned / sc.length, third};
      return std::array<S, 3>{inv_L * dot(e, V3<S>(e1)), inv_L * dot(e, V3<S>(e2)), third};
    }
    const V3<S> b = unit(cross(q.normal, t));
    S third;
    if (law.kind == FrictionLaw::Kind::frictionless) third = dot(F, b);
    else if (law.kind == FrictionLaw::Kind::stick) third = inv_L * dot(q.closest - V3<S>(law.previous_B), b);
    else third = dot(F, b) + law.sigma_mu * dot(F, q.normal);
    if (pinned) return std::array<S, 3>{inv_L * (gap_c - deficit), u[2] - *pinned / sc.length, third};
    return std::array<S, 3>{inv_L * (gap_c - deficit), dot(q.normal, t) - slope, third};
  };
  ObjectAttempt a;
  RecordedEstimate estimate(g);
  a.lm = newton_line_search(residual, u0, side_bounds(), options.tolerance / sc.length, options.max_iterations,
                            &estimate);
  if (a.lm.converged) a.status = Status::converged;
  else a.status = a.lm.at_upper_bound ? Status::slipped_off : Status::not_converged;
  // The state: the load at the solved unknowns (the same numbers the residual gave the walk).
  const double s = sc.length * a.lm.u[2];
  double slope = 0.0;
  const double r = g.thickness ? radius_at(w, s, slope) : 0.0;
  V3<double> F_L, C_L;
  side_load(law, g.thickness, sc.force * a.lm.u[0], sc.force * a.lm.u[1], r, slope, F_L, C_L);
  a.state.force_x = F_L.x;
  a.state.force_y = F_L.y;
  a.state.force_z = F_L.z;
  a.state.couple_x = C_L.x;
  a.state.couple_y = C_L.y;
  a.state.couple_z = C_L.z;
  a.state.arc_length = s;
  return a;
}

ObjectAttempt attempt_tip(const Whisker& w, const Scales& sc, const ObjectGeometryB& g, const FrictionLaw& law,
                          const Eigen::Vector3d& u0, const SolveOptions& options, ClearancePiece piece) {
  const double L = w.length();
  const double r_tip = g.thickness ? w.node_radii().back() : 0.0;
  // A fixed pair of directions in the tangent plane, continuous near the start's normal.
  const Eigen::Vector3d reference = [&] {
    const V3<double> F0(sc.force * u0[0], sc.force * u0[1], sc.force * u0[2]);
    const auto k = deflect<double>(w, F0, V3<double>(0, 0, 0), L);
    const Eigen::Vector3d n = g.query(to_eigen(k.p_contact_B)).normal;
    const Eigen::Vector3d helper = std::abs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    return Eigen::Vector3d((helper - helper.dot(n) * n).normalized());
  }();
  auto residual = [&](const auto& u) {
    using S = std::decay_t<decltype(u[0])>;
    const V3<S> F_L(sc.force * u[0], sc.force * u[1], sc.force * u[2]);
    V3<S> C_L(S(0.0), S(0.0), S(0.0));
    if (law.kind != FrictionLaw::Kind::frictionless && g.thickness)
      C_L = S(-r_tip) * cross(V3<S>(law.normal_L), F_L);
    FollowerVectors<S> follow{V3<S>(S(1.0), S(0.0), S(0.0)), V3<S>(S(0.0), S(1.0), S(0.0))};
    const auto k = walk_deflected<S>(w, g, F_L, C_L, S(L), follow);
    const SurfaceAt<S> q = surface_at(g, k.p_contact_B);
    const S gap_c = q.distance - S(r_tip);
    const S gap = piece_gap(piece, w, g, S(L), k.p_contact_B, follow, gap_c, q.value);
    const V3<S> e1 = unit(V3<S>(reference) - dot(V3<S>(reference), q.normal) * q.normal);
    const V3<S> e2 = cross(q.normal, e1);
    const V3<S> F((S(1.0) / sc.force) * k.force_B.x, (S(1.0) / sc.force) * k.force_B.y,
                  (S(1.0) / sc.force) * k.force_B.z);
    const double inv_L = 1.0 / sc.length;
    V3<S> tangential;
    if (law.kind == FrictionLaw::Kind::frictionless) {
      tangential = F;
    } else if (law.kind == FrictionLaw::Kind::stick) {
      tangential = inv_L * (q.closest - V3<S>(law.previous_B));
    } else {
      const S Fn = dot(F, q.normal);
      tangential = F - Fn * q.normal + (law.sigma_mu * Fn) * V3<S>(law.slip_B);
    }
    return std::array<S, 3>{inv_L * gap, dot(tangential, e1), dot(tangential, e2)};
  };
  ObjectAttempt a;
  a.tip = true;
  a.lm = newton_line_search(residual, u0, LMBounds{}, options.tolerance / sc.length, options.max_iterations);
  a.status = a.lm.converged ? Status::converged : Status::not_converged;
  a.state.force_x = sc.force * a.lm.u[0];
  a.state.force_y = sc.force * a.lm.u[1];
  a.state.force_z = sc.force * a.lm.u[2];
  if (law.kind != FrictionLaw::Kind::frictionless && g.thickness) {
    const Eigen::Vector3d C = -r_tip * law.normal_L.cross(Eigen::Vector3d(a.state.force_x, a.state.force_y, a.state.force_z));
    a.state.couple_x = C.x();
    a.state.couple_y = C.y();
    a.state.couple_z = C.z();
  }
  a.state.arc_length = L;
  return a;
}

ClearancePiece lowest_piece(const Whisker& w, const ObjectGeometryB& g, const LoadState& state) {
  if (!pieces_apply(w, g)) return ClearancePiece::centre;
  const double s = state.arc_length;
  const ObjectGeometryB::Deflected& d = deflected_at(w, g, state);
  const auto& k = d.k;
  const FollowerVectors<double>& follow = d.follow;
  const SurfacePoint at_c = g.query(to_eigen(k.p_contact_B));
  double slope = 0.0;
  const double gap_c = at_c.signed_distance - (g.thickness ? radius_at(w, s, slope) : 0.0);
  ClearancePiece best = ClearancePiece::centre;
  double lowest = gap_c;
  for (ClearancePiece p : {ClearancePiece::start_node, ClearancePiece::end_node, ClearancePiece::chord}) {
    const double gap = piece_gap(p, w, g, s, k.p_contact_B, follow, gap_c, at_c);
    if (gap < lowest - 1e-15 * w.length()) {
      lowest = gap;
      best = p;
    }
  }
  return best;
}

ObjectContactPoint contact_point_at(const Whisker& w, const ObjectGeometryB& g, const LoadState& state, bool tip,
                                    double sigma) {
  ObjectContactPoint p;
  const ObjectGeometryB::Deflected& d = deflected_at(w, g, state);
  const auto& k = d.k;
  const FollowerVectors<double>& follow = d.follow;
  p.c_B = to_eigen(k.p_contact_B);
  p.F_B = to_eigen(k.force_B);
  p.t_B = to_eigen(follow[0]);
  p.y_B = to_eigen(follow[1]);
  p.surface = g.query(p.c_B);
  if (g.thickness) p.radius = radius_at(w, state.arc_length, p.slope);
  p.normal_B = p.surface.normal;
  if (g.core_B && !tip) {  // the line's normal u (regular where the centre line is on the axis: edge mode)
    const Eigen::Vector3d a = g.core_B->direction, across = a.cross(p.t_B), t_perp = p.t_B - p.t_B.dot(a) * a;
    const double sin_b = across.norm(), sin_g = p.slope / sin_b;
    // The side: the solve's; where the centre line is on the axis (zero radius, thickness off) the force's.
    const double side = g.core_B->radius + p.radius > 0.0 ? sigma : p.F_B.dot(across);
    p.normal_B = (side < 0.0 ? -1.0 : 1.0) * std::sqrt(1.0 - sin_g * sin_g) / sin_b * across + sin_g / sin_b * t_perp;
  }
  p.point_B = p.surface.closest;
  if (tip) {
    const Eigen::Vector3d tangential = p.F_B - p.F_B.dot(p.normal_B) * p.normal_B;
    p.friction_B = tangential.norm() > 0.0 ? Eigen::Vector3d(tangential.normalized()) : Eigen::Vector3d::Zero();
  } else {
    p.friction_B = p.normal_B.cross(p.t_B).normalized();
  }
  return p;
}

DeepestPoint deepest_rest_point(const Whisker& w, const ObjectGeometryB& g) {
  const auto& nodes = w.rest_nodes_B();
  const auto& arc = w.node_arc_lengths();
  const auto& radii = w.node_radii();
  auto gap_at = [&](double s) {
    double slope = 0.0;
    const double r = g.thickness ? radius_at(w, s, slope) : 0.0;
    return g.query(w.rest_point_B(s)).signed_distance - r;
  };
  std::size_t best = 0;
  double best_gap = 1e300;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double gap = g.query(nodes[i]).signed_distance - (g.thickness ? radii[i] : 0.0);
    if (gap < best_gap) {
      best_gap = gap;
      best = i;
    }
  }
  // Golden-section search over the two links about the deepest node.
  double lo = arc[best > 0 ? best - 1 : 0], hi = arc[std::min(best + 1, nodes.size() - 1)];
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo), f1 = gap_at(x1), f2 = gap_at(x2);
  for (int it = 0; it < 60 && hi - lo > 1e-12 * w.length(); ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - phi * (hi - lo);
      f1 = gap_at(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + phi * (hi - lo);
      f2 = gap_at(x2);
    }
  }
  DeepestPoint d;
  d.arc_length = arc[best];
  d.gap = best_gap;
  const double s = 0.5 * (lo + hi), gs = gap_at(s);
  if (gs < best_gap) {
    d.arc_length = s;
    d.gap = gs;
  }
  d.normal_B = g.query(w.rest_point_B(d.arc_length)).normal;
  return d;
}

}  // namespace vibrissa::detail
