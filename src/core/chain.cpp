#include "vibrissa/core/chain.hpp"

namespace vibrissa {

template ContactKinematics<double> deflect<double>(const Whisker&, const V3<double>&, const V3<double>&, const double&,
                                                   Eigen::Vector3d*, FollowerVectors<double>*);
template ContactKinematics<Dual<3>> deflect<Dual<3>>(const Whisker&, const V3<Dual<3>>&, const V3<Dual<3>>&,
                                                     const Dual<3>&, Eigen::Vector3d*, FollowerVectors<Dual<3>>*);
template ContactKinematics<double> deflect<double, true>(const Whisker&, const V3<double>&, const V3<double>&,
                                                         const double&, Eigen::Vector3d*, FollowerVectors<double>*);
template ContactKinematics<Dual<3>> deflect<Dual<3>, true>(const Whisker&, const V3<Dual<3>>&, const V3<Dual<3>>&,
                                                           const Dual<3>&, Eigen::Vector3d*,
                                                           FollowerVectors<Dual<3>>*);

Eigen::Matrix3d joint_rotation_matrix(const Eigen::Vector3d& omega) {
  const V3<double> w(omega);
  double a, b;
  detail::rodrigues_coefficients(dot(w, w), a, b);
  const Mat3<double> E = detail::rotation_matrix(w, a, b);
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = E.m[3 * i + j];
  return R;
}

void deflected_nodes_B(const Whisker& w, const Eigen::Vector3d* omega, std::vector<Eigen::Vector3d>& nodes_B) {
  const int N = w.links();
  nodes_B.resize(static_cast<std::size_t>(N) + 1);
  nodes_B[0].setZero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (int i = 0; i < N; ++i) {
    const std::size_t u = static_cast<std::size_t>(i);
    R = R * w.rest_joint_rotations()[u];
    if (!omega[i].isZero(0.0)) R = R * joint_rotation_matrix(omega[i]);
    nodes_B[u + 1] = nodes_B[u] + w.link_lengths()[u] * R.col(0);
  }
}

}  // namespace vibrissa
