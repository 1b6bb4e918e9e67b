#include "vibrissa/recon/geometry.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

namespace vibrissa::recon {

namespace {

using Matrix34 = Eigen::Matrix<double, 3, 4>;

/// Ideal-pixel projection of X by P and its 2x3 Jacobian.
Eigen::Vector2d project_ideal(const Matrix34& P, const Eigen::Vector3d& X, Eigen::Matrix<double, 2, 3>* J) {
  const Eigen::Vector3d h = P * X.homogeneous();
  const Eigen::Vector2d x(h(0) / h(2), h(1) / h(2));
  if (J) {
    J->row(0) = (P.block<1, 3>(0, 0) - x(0) * P.block<1, 3>(2, 0)) / h(2);
    J->row(1) = (P.block<1, 3>(1, 0) - x(1) * P.block<1, 3>(2, 0)) / h(2);
  }
  return x;
}

/// Depth sign of X in a camera (H&Z §6.2.3): positive in front.
double depth(const Matrix34& P, const Eigen::Vector3d& X) {
  const double w = (P.row(2) * X.homogeneous())(0);
  return P.leftCols<3>().determinant() > 0.0 ? w : -w;
}

/// Similarity T (dim+1 square) moving the centroid to the origin and the mean distance to sqrt(dim).
template <int D>
Eigen::Matrix<double, D + 1, D + 1> normalising_transform(const std::vector<Eigen::Matrix<double, D, 1>>& pts) {
  Eigen::Matrix<double, D, 1> c = Eigen::Matrix<double, D, 1>::Zero();
  for (const auto& p : pts) c += p;
  c /= double(pts.size());
  double mean = 0.0;
  for (const auto& p : pts) mean += (p - c).norm();
  mean /= double(pts.size());
  const double s = mean > 0.0 ? std::sqrt(double(D)) / mean : 1.0;
  Eigen::Matrix<double, D + 1, D + 1> T = Eigen::Matrix<double, D + 1, D + 1>::Identity() * s;
  T(D, D) = 1.0;
  T.template topRightCorner<D, 1>() = -s * c;
  return T;
}

}  // namespace

Triangulated triangulate(const std::vector<const Camera*>& cameras, const std::vector<Eigen::Vector2d>& pixels) {
  if (cameras.size() != pixels.size() || cameras.size() < 2)
    throw std::invalid_argument("triangulate: needs one pixel per camera and at least two views");
  const std::size_t n = cameras.size();
  std::vector<Eigen::Vector2d> ideal(n);
  Eigen::MatrixXd A(2 * n, 4);
  for (std::size_t k = 0; k < n; ++k) {
    ideal[k] = cameras[k]->undistort(pixels[k]);
    const Matrix34& P = cameras[k]->P;
    A.row(Eigen::Index(2 * k)) = ideal[k].x() * P.row(2) - P.row(0);
    A.row(Eigen::Index(2 * k + 1)) = ideal[k].y() * P.row(2) - P.row(1);
  }
  for (Eigen::Index r = 0; r < A.rows(); ++r) A.row(r).normalize();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d h = svd.matrixV().col(3);
  Triangulated out;
  const Eigen::Vector4d sv = svd.singularValues();
  if (!(std::abs(h(3)) > 1e-12 * h.head<3>().norm()) || !(sv(2) > 1e-12 * sv(0))) return out;  // rays parallel
  Eigen::Vector3d X = h.head<3>() / h(3);
  // Gauss-Newton on the ideal-pixel reprojection error (the linear solution minimises an algebraic error).
  for (int it = 0; it < 10; ++it) {
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < n; ++k) {
      Eigen::Matrix<double, 2, 3> J;
      const Eigen::Vector2d r = project_ideal(cameras[k]->P, X, &J) - ideal[k];
      JtJ += J.transpose() * J;
      Jtr += J.transpose() * r;
    }
    const Eigen::Vector3d step = JtJ.ldlt().solve(-Jtr);
    if (!step.allFinite()) break;
    X += step;
    if (step.norm() <= 1e-15 * std::max(1.0, X.norm())) break;
  }
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (!(depth(cameras[k]->P, X) > 0.0)) return out;
    sum += (cameras[k]->project(X) - pixels[k]).squaredNorm();
  }
  out.p_W = X;
  out.reprojection_px = std::sqrt(sum / double(n));
  out.ok = X.allFinite();
  return out;
}

Eigen::Matrix3d fundamental_matrix(const Camera& c1, const Camera& c2) {
  const Eigen::Vector4d C1 = c1.centre().homogeneous();
  const Eigen::Vector3d e2 = c2.P * C1;
  Eigen::Matrix3d ex;
  ex << 0, -e2(2), e2(1), e2(2), 0, -e2(0), -e2(1), e2(0), 0;
  const Eigen::Matrix<double, 4, 3> P1plus = c1.P.transpose() * (c1.P * c1.P.transpose()).inverse();
  return ex * c2.P * P1plus;
}

Calibration calibrate_dlt(const std::vector<Eigen::Vector3d>& X, const std::vector<Eigen::Vector2d>& x) {
  if (X.size() != x.size())
    throw std::invalid_argument("calibration: " + std::to_string(X.size()) + " world points but " +
                                std::to_string(x.size()) + " image points");
  if (X.size() < 6)
    throw std::invalid_argument("calibration: needs at least 6 correspondences, got " + std::to_string(X.size()));
  for (std::size_t i = 0; i < X.size(); ++i)
    if (!X[i].allFinite() || !x[i].allFinite())
      throw std::invalid_argument("calibration: correspondence " + std::to_string(i + 1) + " is not finite");
  const std::size_t n = X.size();
  // Non-coplanar points are needed (a plane leaves P undetermined).
  Eigen::MatrixXd Q(n, 3);
  for (std::size_t i = 0; i < n; ++i) Q.row(Eigen::Index(i)) = X[i].transpose();
  Q.rowwise() -= Q.colwise().mean();
  const Eigen::Vector3d qs = Eigen::JacobiSVD<Eigen::MatrixXd>(Q).singularValues();
  if (!(qs(2) > 1e-9 * qs(0)))
    throw std::invalid_argument("calibration: the world points are coplanar or collinear; DLT needs 3D spread");
  const Eigen::Matrix4d T = normalising_transform<3>(X);
  const Eigen::Matrix3d U = normalising_transform<2>(x);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(Eigen::Index(2 * n), 12);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::RowVector4d Xn = (T * X[i].homogeneous()).transpose();
    const Eigen::Vector3d xn = U * x[i].homogeneous();
    const Eigen::Index r = Eigen::Index(2 * i);
    A.block<1, 4>(r, 4) = -xn(2) * Xn;
    A.block<1, 4>(r, 8) = xn(1) * Xn;
    A.block<1, 4>(r + 1, 0) = xn(2) * Xn;
    A.block<1, 4>(r + 1, 8) = -xn(0) * Xn;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd s = svd.singularValues();
  if (!(s(10) > 1e-12 * s(0))) throw std::invalid_argument("calibration: degenerate configuration (rank < 11)");
  const Eigen::VectorXd p = svd.matrixV().col(11);
  Matrix34 Pn;
  Pn << p(0), p(1), p(2), p(3), p(4), p(5), p(6), p(7), p(8), p(9), p(10), p(11);
  Matrix34 P = U.inverse() * Pn * T;
  if (!(std::abs(P(2, 3)) > 1e-300)) throw std::invalid_argument("calibration: P(3,4) is zero; move the origin");
  P /= P(2, 3);
  // Gauss-Newton / Levenberg-Marquardt on the geometric error over the 11 free entries (H&Z algorithm 7.1 (iii)).
  auto residuals = [&](const Matrix34& M) {
    Eigen::VectorXd r(Eigen::Index(2 * n));
    for (std::size_t i = 0; i < n; ++i)
      r.segment<2>(Eigen::Index(2 * i)) = (M * X[i].homogeneous()).hnormalized() - x[i];
    return r;
  };
  double lambda = 1e-3;
  Eigen::VectorXd r = residuals(P);
  for (int it = 0; it < 50; ++it) {
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(Eigen::Index(2 * n), 11);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector4d Xh = X[i].homogeneous();
      const Eigen::Vector3d h = P * Xh;
      const Eigen::Vector2d u = h.head<2>() / h(2);
      const Eigen::Index row = Eigen::Index(2 * i);
      J.block<1, 4>(row, 0) = Xh.transpose() / h(2);
      J.block<1, 4>(row + 1, 4) = Xh.transpose() / h(2);
      for (int k = 0; k < 2; ++k) J.block<1, 3>(row + k, 8) = -u(k) * Xh.head<3>().transpose() / h(2);
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    Eigen::MatrixXd H = JtJ;
    H.diagonal() *= 1.0 + lambda;
    const Eigen::VectorXd step = H.ldlt().solve(-g);
    Matrix34 trial = P;
    for (int k = 0; k < 11; ++k) trial(k / 4, k % 4) += step(k);
    const Eigen::VectorXd rt = residuals(trial);
    if (rt.allFinite() && rt.squaredNorm() < r.squaredNorm()) {
      const bool converged = r.squaredNorm() - rt.squaredNorm() <= 1e-14 * r.squaredNorm();
      P = trial;
      r = rt;
      lambda *= 0.1;
      if (converged) break;
    } else {
      lambda *= 10.0;
      if (lambda > 1e10) break;
    }
  }
  Calibration out;
  std::array<double, 11> L{};
  for (int k = 0; k < 11; ++k) L[std::size_t(k)] = P(k / 4, k % 4);
  out.camera = dlt_camera(L);
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    out.residuals_px.push_back((out.camera.project(X[i]) - x[i]).norm());
    sum += out.residuals_px.back() * out.residuals_px.back();
  }
  out.rms_px = std::sqrt(sum / double(n));
  return out;
}

}  // namespace vibrissa::recon
