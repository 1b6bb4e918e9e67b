#pragma once
// The `paper` scheme: Elastica3D v1's discretisation exactly (spec §2.1; docs/conventions.md). For a load at
// arc length s the published model re-meshes the whisker from the base to s: m nodes (m = the number of
// nodes at or before s, at least 3) at arc lengths k s / (m - 1) on MATLAB's spline through the nodes, with
// E and I splined through nodes 1..N (node 0 keeps its own). The load acts at the last new node, normal to
// the last new link, and follows it. Walking from the load to the base, joint j (at node j, distal link j)
// first twists about link j by M_x l_j / (G_j J_j) and then bends about the bending moment by
// |M_b| l_{j-1} / (E_j I_j) (l_{-1} = l_0; eqs. (1)-(3)); a rigid base has no joint 0.
// The walk is written in B with the rest geometry, so no link frames are needed; it is templated on the
// scalar so that dual numbers give exact Jacobians (the new nodes move with s).
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/contact_kinematics.hpp"
#include "vibrissa/core/rodrigues.hpp"
#include "vibrissa/core/whisker.hpp"

namespace vibrissa {

/// The three axes of a frame, as vectors in the frame they are expressed in.
template <class S>
struct Axes {
  V3<S> x, y, z;
  [[nodiscard]] V3<S> operator*(const V3<S>& v) const { return v.x * x + v.y * y + v.z * z; }
};

/// Elastica3D's frame of the loaded link, in which its force angle ζ is measured: the first link's
/// frame Rz(θ1) Ry(−φ1) (θ1, φ1 = azimuth and elevation of `first_link` in the reference frame), turned by
/// Rz(θ) Ry(−φ) with θ, φ the azimuth and elevation of `loaded_link` in that frame. The force of angle ζ is
/// f · (0, −cos ζ, −sin ζ) in it.
template <class S>
Axes<S> published_load_frame(const V3<S>& first_link, const V3<S>& loaded_link) {
  using std::sqrt;
  auto azimuth_axis = [](const V3<S>& d) {  // (−sin θ, cos θ, 0) for θ = atan2(d_y, d_x)
    const S h = sqrt(d.x * d.x + d.y * d.y);
    if (value_of(h) == 0.0) return V3<S>(S(0.0), S(1.0), S(0.0));
    return V3<S>(-d.y / h, d.x / h, S(0.0));
  };
  Axes<S> e0;
  e0.x = (S(1.0) / sqrt(dot(first_link, first_link))) * first_link;
  e0.y = azimuth_axis(e0.x);
  e0.z = cross(e0.x, e0.y);
  const V3<S> t = (S(1.0) / sqrt(dot(loaded_link, loaded_link))) * loaded_link;
  const V3<S> t_e0(dot(t, e0.x), dot(t, e0.y), dot(t, e0.z));
  Axes<S> c;
  c.x = t;
  c.y = e0 * azimuth_axis(t_e0);
  c.z = cross(c.x, c.y);
  return c;
}

/// Number of nodes of the re-meshed chain for a load at s (Elastica3D: nodes at or before s, at least 3).
int published_node_count(const Whisker& w, double s);

/// The load frame of deflect_published() for a load at s on the undeflected whisker (axes in B): a start
/// force F_B has components (0, F_B . y, F_B . z) in it.
Axes<double> published_rest_load_frame(const Whisker& w, double s);

/// Elastica3D's roll δ of its load frame taken with W as the reference frame (R_WB: B axes in W) relative
/// to the one taken with B: a force of Elastica3D angle ζ has components f (0, −cos(ζ+δ), −sin(ζ+δ)) in
/// the load frame of deflect_published().
double published_angle_offset(const Whisker& w, const Eigen::Matrix3d& R_WB, double s);

/// Optional record of a walk (doubles): rest node and rotation of each joint of the re-meshed chain.
struct PublishedJoints {
  std::vector<Eigen::Vector3d> node_B;
  std::vector<Eigen::Matrix3d> rotation_B;
};

/// Deflects the published chain under a follower force and couple at s (components in the frame
/// published_load_frame(first new link, loaded link) taken with B as the reference frame). `followers`, if
/// given, are vectors in that frame, turned with the load and returned in B (contact_kinematics.hpp).
template <class S>
ContactKinematics<S> deflect_published(const Whisker& w, const V3<S>& force_L, const V3<S>& couple_L, const S& s,
                                       PublishedJoints* record = nullptr, FollowerVectors<S>* followers = nullptr) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Whisker::PublishedRemesh& remesh = w.published_remesh();
  const int m = published_node_count(w, value_of(s));
  // Elastica3D moves a load at s <= 0 to the end of the first link.
  const S step = (value_of(s) > 0.0 ? s : S(w.node_arc_lengths()[1])) / double(m - 1);
  const double L = w.length(), nu = w.properties().poisson_ratio;
  const bool rigid_base = w.properties().base == BaseJoint::rigid;
  auto node = [&](int k) {
    const S t = double(k) * step;
    return V3<S>(remesh.node_B[0](t), remesh.node_B[1](t), remesh.node_B[2](t));
  };
  auto norm = [](const V3<S>& v) { return sqrt(dot(v, v)); };
  auto val = [](const V3<S>& v) { return Eigen::Vector3d(value_of(v.x), value_of(v.y), value_of(v.z)); };

  V3<S> n_next = node(m - 1), n_j = node(m - 2);
  const V3<S> loaded = n_next - n_j;
  const Axes<S> frame = published_load_frame(node(1) - node(0), loaded);
  // v[0] = contact point relative to node j, v[1] = F, v[2] = C, then the follower vectors if any.
  V3<S> v[5] = {n_next - n_j, frame * force_L, frame * couple_L, V3<S>(), V3<S>()};
  const int carried = followers ? 5 : 3;
  if (followers) {
    v[3] = frame * (*followers)[0];
    v[4] = frame * (*followers)[1];
  }
  if (record) {
    record->node_B.assign(static_cast<std::size_t>(m - 1), Eigen::Vector3d::Zero());
    record->rotation_B.assign(static_cast<std::size_t>(m - 1), Eigen::Matrix3d::Identity());
  }
  for (int j = m - 2; j >= 0; --j) {
    const V3<S> d = n_next - n_j;
    const S l_j = norm(d);
    const V3<S> t = (S(1.0) / l_j) * d;
    const V3<S> n_prev = j > 0 ? node(j - 1) : n_j;
    const S l_prev = j > 0 ? norm(n_j - n_prev) : l_j;
    if (record) record->node_B[static_cast<std::size_t>(j)] = val(n_j);
    if (!(j == 0 && rigid_base)) {
      S E, I;
      if (j == 0) {
        E = S(w.node_youngs_moduli().front());
        I = S(std::numbers::pi / 4.0 * std::pow(w.node_radii().front(), 4));
      } else {
        const S sj = value_of(double(j) * step) > L ? S(L) : double(j) * step;  // spline only up to the tip
        E = remesh.youngs(sj);
        I = remesh.inertia(sj);
      }
      const S G = E / (2.0 * (1.0 + nu)), J = 2.0 * I;
      const V3<S> M = cross(v[0], v[1]) + v[2];
      const S Mt = dot(M, t);
      const S twist = Mt * l_j / (G * J);
      V3<S> bend = (l_prev / (E * I)) * (M - Mt * t);
      if (j == 0 && w.base_extra_compliance() > 0.0) bend += S(w.base_extra_compliance()) * (M - Mt * t);
      const S ct = cos(twist), st = sin(twist);
      S a, b;
      detail::rodrigues_coefficients(dot(bend, bend), a, b);
      auto turn = [&](const V3<S>& x) {  // twist about t, then bend (Elastica3D's order)
        const V3<S> twisted = ct * x + st * cross(t, x) + ((S(1.0) - ct) * dot(t, x)) * t;
        return detail::rotate(bend, a, b, twisted);
      };
      for (int i = 0; i < carried; ++i) v[i] = turn(v[i]);
      if (record) {
        Eigen::Matrix3d R;
        for (int c = 0; c < 3; ++c) R.col(c) = val(turn(V3<S>(Eigen::Vector3d(Eigen::Vector3d::Unit(c)))));
        record->rotation_B[static_cast<std::size_t>(j)] = R;
      }
    }
    v[0] += n_j - n_prev;  // the contact point relative to node j - 1
    n_next = n_j;
    n_j = n_prev;
  }
  if (followers) *followers = {v[3], v[4]};
  return {v[0], v[1], v[2]};
}

/// Nodes (N+1) of the deflected whisker in B: each original node moves with the link of the re-meshed
/// chain that holds its arc length (nodes past s with the loaded link).
void published_nodes_B(const Whisker& w, const V3<double>& force_L, const V3<double>& couple_L, double s,
                       std::vector<Eigen::Vector3d>& nodes_B);

}  // namespace vibrissa
