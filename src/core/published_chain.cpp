#include "vibrissa/core/published_chain.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vibrissa {

int published_node_count(const Whisker& w, double s) {
  const auto& arc = w.node_arc_lengths();
  const int at_or_before = static_cast<int>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin());
  return std::max(at_or_before, 3);
}

namespace {
/// The first and the loaded link of the rest chain re-meshed for a load at s (as deflect_published() meshes).
std::pair<Eigen::Vector3d, Eigen::Vector3d> rest_first_and_loaded_links(const Whisker& w, double s) {
  const auto& remesh = w.published_remesh();
  const int m = published_node_count(w, s);
  const double step = (s > 0.0 ? s : w.node_arc_lengths()[1]) / double(m - 1);
  auto node = [&](int k) {
    const double t = double(k) * step;
    return Eigen::Vector3d(remesh.node_B[0](t), remesh.node_B[1](t), remesh.node_B[2](t));
  };
  return {node(1) - node(0), node(m - 1) - node(m - 2)};
}
}  // namespace

Axes<double> published_rest_load_frame(const Whisker& w, double s) {
  const auto [first, loaded] = rest_first_and_loaded_links(w, s);
  return published_load_frame<double>(first, loaded);
}

double published_angle_offset(const Whisker& w, const Eigen::Matrix3d& R_WB, double s) {
  const auto [first, loaded] = rest_first_and_loaded_links(w, s);
  const Axes<double> in_B = published_load_frame<double>(first, loaded);
  const Axes<double> in_W = published_load_frame<double>(Eigen::Vector3d(R_WB * first), Eigen::Vector3d(R_WB * loaded));
  const Eigen::Vector3d y_B = R_WB * to_eigen(in_B.y), z_B = R_WB * to_eigen(in_B.z), y_W = to_eigen(in_W.y);
  return std::atan2(y_W.dot(z_B), y_W.dot(y_B));
}

void published_nodes_B(const Whisker& w, const V3<double>& force_L, const V3<double>& couple_L, double s,
                       std::vector<Eigen::Vector3d>& nodes_B) {
  thread_local PublishedJoints joints;
  deflect_published<double>(w, force_L, couple_L, s, &joints);
  const std::size_t links = joints.node_B.size();
  // A point on new link k moves by T_0 ∘ ... ∘ T_k, T_j(x) = n_j + R_j (x - n_j): compose from the base.
  thread_local std::vector<Eigen::Matrix3d> R;
  thread_local std::vector<Eigen::Vector3d> b;
  R.resize(links);
  b.resize(links);
  Eigen::Matrix3d R_acc = Eigen::Matrix3d::Identity();
  Eigen::Vector3d b_acc = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < links; ++k) {
    const Eigen::Vector3d& n = joints.node_B[k];
    b_acc += R_acc * (n - joints.rotation_B[k] * n);
    R_acc = R_acc * joints.rotation_B[k];
    R[k] = R_acc;
    b[k] = b_acc;
  }
  const auto& rest = w.rest_nodes_B();
  const auto& arc = w.node_arc_lengths();
  const double step = (s > 0.0 ? s : arc[1]) / double(links);
  nodes_B.resize(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    std::size_t k = links - 1;
    if (arc[i] <= s && step > 0.0) k = std::min(static_cast<std::size_t>(arc[i] / step), links - 1);
    nodes_B[i] = R[k] * rest[i] + b[k];
  }
}

}  // namespace vibrissa
