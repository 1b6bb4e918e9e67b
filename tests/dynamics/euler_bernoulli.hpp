#pragma once
// An independent reference for the modes: the Euler-Bernoulli cantilever with a varying section, discretised
// with Hermite cubic beam elements (consistent mass), written here without any of the library's chain code.
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace vibrissa::test {

/// Lowest `count` bending frequencies [Hz] of a straight clamped-free beam of length L whose radius falls
/// linearly from r0 to r1, modulus E, density rho, with `elements` elements (Gauss quadrature of degree 9, exact
/// for the polynomial EI(x) and rho A(x) of the cone). With `rotary`, the kinetic energy of the sections'
/// rotation, rho I w'^2 / 2, is included (Rayleigh's beam; the chain's links have it), which lowers the
/// frequencies by O((r/L)^2).
inline std::vector<double> euler_bernoulli_frequencies(double L, double r0, double r1, double E, double rho,
                                                       int elements, int count, bool rotary = true) {
  const int dofs = 2 * (elements + 1);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(dofs, dofs), M = Eigen::MatrixXd::Zero(dofs, dofs);
  const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                        0.2369268850561891};
  const double h = L / elements;
  for (int e = 0; e < elements; ++e) {
    Eigen::Matrix4d ke = Eigen::Matrix4d::Zero(), me = Eigen::Matrix4d::Zero();
    for (int g = 0; g < 5; ++g) {
      const double xi = 0.5 * (gx[g] + 1.0), x = (e + xi) * h;
      const double r = r0 + (r1 - r0) * x / L;
      const double EI = E * std::numbers::pi * std::pow(r, 4) / 4.0, rhoA = rho * std::numbers::pi * r * r;
      // Hermite shape functions on [0, 1] (w, w' h) and their second derivatives.
      const Eigen::Vector4d N(1 - 3 * xi * xi + 2 * xi * xi * xi, h * (xi - 2 * xi * xi + xi * xi * xi),
                              3 * xi * xi - 2 * xi * xi * xi, h * (-xi * xi + xi * xi * xi));
      const Eigen::Vector4d B = Eigen::Vector4d(-6 + 12 * xi, h * (-4 + 6 * xi), 6 - 12 * xi, h * (-2 + 6 * xi)) / (h * h);
      const Eigen::Vector4d D = Eigen::Vector4d(-6 * xi + 6 * xi * xi, h * (1 - 4 * xi + 3 * xi * xi),
                                                6 * xi - 6 * xi * xi, h * (-2 * xi + 3 * xi * xi)) / h;
      const double wq = 0.5 * gw[g] * h;
      ke += wq * EI * B * B.transpose();
      me += wq * rhoA * N * N.transpose();
      if (rotary) me += wq * (rho * std::numbers::pi * std::pow(r, 4) / 4.0) * D * D.transpose();
    }
    K.block<4, 4>(2 * e, 2 * e) += ke;
    M.block<4, 4>(2 * e, 2 * e) += me;
  }
  const int free = dofs - 2;  // clamped: w = w' = 0 at x = 0
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K.bottomRightCorner(free, free),
                                                                      M.bottomRightCorner(free, free),
                                                                      Eigen::EigenvaluesOnly);
  std::vector<double> f;
  for (int i = 0; i < count; ++i) f.push_back(std::sqrt(eig.eigenvalues()(i)) / (2.0 * std::numbers::pi));
  return f;
}

}  // namespace vibrissa::test
