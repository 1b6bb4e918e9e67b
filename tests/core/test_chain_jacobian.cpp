// The analytic Jacobian of the chain (core/chain_jacobian.hpp) against the Dual<3> reference (to rounding)
// and central finite differences, and the series of the Rodrigues coefficients at their switch-over angle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "vibrissa/core/chain_jacobian.hpp"

namespace vibrissa {
namespace {

using D = Dual<3>;

/// A helix of radius 10 mm and pitch 60 mm: curved and twisted (torsion) rest shape, 40 mm long.
Whisker helix(const WhiskerProperties& props) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i <= 60; ++i) {
    const double a = 0.04 * i / 60.0 / 0.0117;  // ~ arc length / sqrt(r^2 + c^2)
    p.emplace_back(0.00955 * a, 0.01 * std::sin(a), 0.01 * (1.0 - std::cos(a)));
  }
  Pose pose;
  return Whisker::from_points(p, props, pose);
}

struct Case {
  std::string name;
  Whisker w;
};

std::vector<Case> whiskers() {
  std::vector<Case> out;
  WhiskerProperties props;
  out.push_back({"parabola", Whisker::from_parabola(0.04, 12.0, props)});
  WhiskerProperties coarse = props;
  coarse.links = 17;
  out.push_back({"cubic, 17 links", Whisker::from_cubic(0.03, -300.0, 20.0, coarse)});
  WhiskerProperties follicle = props;
  follicle.base_stiffness = 2e-5;
  out.push_back({"helix, follicle spring", helix(follicle)});
  WhiskerProperties rigid = props;
  rigid.base = BaseJoint::rigid;
  out.push_back({"helix, rigid base", helix(rigid)});
  WhiskerProperties paper = props;
  paper.scheme = Scheme::paper;
  paper.links = 30;
  out.push_back({"parabola, paper scheme", Whisker::from_parabola(0.04, 12.0, paper)});
  return out;
}

/// A load: force and couple in the loaded link's frame and the arc length as a fraction of L. The three
/// derivative directions are (force_L[dir0], force_L[dir1] or couple_L[dir1 - 3], s).
struct Load {
  Eigen::Vector3d force_L, couple_L;
  double s_over_L;
  int dir0, dir1;
};

std::vector<Load> loads() {
  return {
      {{0.0, 2e-4, 5e-5}, {0.0, 0.0, 0.0}, 0.6123, 1, 2},          // the solvers' case: (F_y, F_z, s)
      {{0.0, -1e-3, 4e-4}, {0.0, 0.0, 0.0}, 0.9071, 1, 2},         // large deflection near the tip
      {{0.0, 3e-4, -1e-4}, {0.0, 0.0, 0.0}, 0.0043, 1, 2},         // on the base link
      {{5e-5, 1e-4, 2e-4}, {1e-7, -2e-7, 3e-7}, 0.3377, 0, 4},     // axial force, couple (F_x, C_y, s)
      {{0.0, 2e-4, 0.0}, {0.0, 0.0, 0.0}, 0.2549, 1, 2},           // between nodes, planar force
  };
}

struct Evaluation {
  Eigen::Matrix<double, 9, 1> value;   // p, F, C in B
  Eigen::Matrix<double, 9, 3> jacobian;
};

Evaluation flatten(const ContactKinematics<D>& c) {
  Evaluation e;
  const V3<D>* out[3] = {&c.p_contact_B, &c.force_B, &c.couple_B};
  for (int o = 0; o < 3; ++o) {
    const D* comp[3] = {&out[o]->x, &out[o]->y, &out[o]->z};
    for (int i = 0; i < 3; ++i) {
      e.value[3 * o + i] = comp[i]->v;
      for (int j = 0; j < 3; ++j) e.jacobian(3 * o + i, j) = comp[i]->d[static_cast<std::size_t>(j)];
    }
  }
  return e;
}

/// Inputs of a load with the derivative directions seeded, shifted by `delta` along them (doubles only).
void seeded(const Whisker& w, const Load& l, const Eigen::Vector3d& delta, V3<D>& F, V3<D>& C, D& s) {
  Eigen::Vector3d f = l.force_L, c = l.couple_L;
  (l.dir1 < 3 ? f[l.dir1] : c[l.dir1 - 3]) += delta[1];
  f[l.dir0] += delta[0];
  F = V3<D>(D(f.x()), D(f.y()), D(f.z()));
  C = V3<D>(D(c.x()), D(c.y()), D(c.z()));
  D* fd[3] = {&F.x, &F.y, &F.z};
  D* cd[3] = {&C.x, &C.y, &C.z};
  fd[l.dir0]->d[0] = 1.0;
  (l.dir1 < 3 ? fd[l.dir1] : cd[l.dir1 - 3])->d[1] = 1.0;
  s = D::variable(l.s_over_L * w.length() + delta[2], 2);
}

Evaluation analytic(const Whisker& w, const Load& l) {
  V3<D> F, C;
  D s;
  seeded(w, l, Eigen::Vector3d::Zero(), F, C, s);
  return flatten(deflect_analytic(w, F, C, s));
}

/// One build of the analytic walk (detail::analytic_builds()).
Evaluation built(const detail::AnalyticBuild& b, const Whisker& w, const Load& l) {
  V3<D> F, C;
  D s;
  seeded(w, l, Eigen::Vector3d::Zero(), F, C, s);
  return flatten(b.walk(w, F, C, s));
}

Evaluation reference(const Whisker& w, const Load& l, const Eigen::Vector3d& delta = Eigen::Vector3d::Zero()) {
  V3<D> F, C;
  D s;
  seeded(w, l, delta, F, C, s);
  if (w.properties().scheme == Scheme::paper) return flatten(deflect_published<D>(w, F, C, s));
  return flatten(deflect<D>(w, F, C, s));
}

/// Scale of each block of 3 outputs (p, F, C) for relative comparisons.
double block_scale(const Eigen::Matrix<double, 9, 1>& v, const Eigen::Matrix<double, 9, 3>& J, int row) {
  const int b = row / 3;
  return std::max(v.segment<3>(3 * b).norm(), J.middleRows<3>(3 * b).norm()) + 1e-300;
}

TEST(ChainJacobian, AnalyticEqualsDualReference) {
  for (const auto& c : whiskers())
    for (const auto& l : loads()) {
      const Evaluation a = analytic(c.w, l), r = reference(c.w, l);
      for (int i = 0; i < 9; ++i) {
        const double scale = block_scale(r.value, r.jacobian, i);
        EXPECT_NEAR(a.value[i], r.value[i], 1e-13 * scale) << c.name << ", s/L " << l.s_over_L << ", row " << i;
        for (int j = 0; j < 3; ++j)
          EXPECT_NEAR(a.jacobian(i, j), r.jacobian(i, j), 1e-12 * scale)
              << c.name << ", s/L " << l.s_over_L << ", row " << i << ", column " << j;
      }
    }
}

TEST(ChainJacobian, EveryBuildGivesThePortableNumbers) {
  // On a CPU with AVX2 (or AVX-512) deflect_analytic() carries the three directions in vector lanes; the
  // portable build (one vector per direction) must give the same numbers bit for bit, derivatives included,
  // and deflect_analytic() must be the last build listed.
  const auto builds = detail::analytic_builds();
  ASSERT_FALSE(builds.empty());
  EXPECT_STREQ(builds.front().name, "portable");
  if (builds.size() == 1) GTEST_SKIP() << "this CPU runs the portable build only";
  int compared = 0;
  for (const auto& c : whiskers()) {
    if (c.w.properties().scheme == Scheme::paper) continue;  // the builds are the second-order walk's
    for (const auto& l : loads()) {
      const Evaluation one_by_one = built(builds.front(), c.w, l), dispatched = analytic(c.w, l),
                       last = built(builds.back(), c.w, l);
      EXPECT_EQ(dispatched.value, last.value) << c.name << ", s/L " << l.s_over_L;
      EXPECT_EQ(dispatched.jacobian, last.jacobian) << c.name << ", s/L " << l.s_over_L;
      for (std::size_t b = 1; b < builds.size(); ++b) {
        const Evaluation lanes = built(builds[b], c.w, l);
        EXPECT_EQ(lanes.value, one_by_one.value) << builds[b].name << ", " << c.name << ", s/L " << l.s_over_L;
        EXPECT_EQ(lanes.jacobian, one_by_one.jacobian) << builds[b].name << ", " << c.name << ", s/L " << l.s_over_L;
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, 20);
}

TEST(ChainJacobian, AnalyticMatchesCentralDifferences) {
  for (const auto& c : whiskers())
    for (const auto& l : loads()) {
      const Evaluation a = analytic(c.w, l);
      const double force_scale = l.force_L.norm(), couple_scale = std::max(l.couple_L.norm(), 1e-7);
      const Eigen::Vector3d step(1e-5 * force_scale, 1e-5 * (l.dir1 < 3 ? force_scale : couple_scale),
                                 1e-7 * c.w.length());
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d e = step[j] * Eigen::Vector3d::Unit(j);
        const Eigen::Matrix<double, 9, 1> fd = (reference(c.w, l, e).value - reference(c.w, l, -e).value) / (2.0 * step[j]);
        for (int i = 0; i < 9; ++i)
          EXPECT_NEAR(a.jacobian(i, j), fd[i], 1e-6 * block_scale(a.value, a.jacobian, i))
              << c.name << ", s/L " << l.s_over_L << ", row " << i << ", column " << j;
      }
    }
}

TEST(ChainJacobian, SolverDispatchIsTheAnalyticJacobian) {
  const Whisker w = Whisker::from_parabola(0.04, 12.0, WhiskerProperties{});
  const V3<D> F(D(0.0), D::variable(1e-4, 0), D::variable(3e-5, 1)), C(D(0.0), D(0.0), D(0.0));
  const D s = D::variable(0.025, 2);
  const auto a = flatten(deflect_for_solve<D>(w, F, C, s)), b = flatten(deflect_analytic(w, F, C, s));
  EXPECT_EQ(a.value, b.value);
  EXPECT_EQ(a.jacobian, b.jacobian);
  const auto v = deflect_for_solve<double>(w, V3<double>(0.0, 1e-4, 3e-5), V3<double>(0, 0, 0), 0.025);
  EXPECT_NEAR(v.p_contact_B.x, a.value[0], 1e-15 * w.length());
}

// Dual<3> arithmetic forms its values exactly as doubles do, division included: the Dual<3> walk (the
// reference, and the paper scheme's Jacobian in the solvers) gives deflect<double>'s numbers. (The analytic
// walk turns its values by the joint's matrix: equal to rounding, AnalyticEqualsDualReference.)
TEST(Dual, ValuesAreComputedExactlyAsOnDoubles) {
  const double a = 0.3, b = 0.7, k = 0.7;
  EXPECT_NE(a * (1.0 / b), a / b);  // the case that needs care
  EXPECT_EQ((D::variable(a, 0) / D::variable(b, 1)).v, a / b);
  EXPECT_EQ((D::variable(a, 0) / k).v, a / k);
  const D q = D::variable(a, 0) / D::variable(b, 1);
  EXPECT_DOUBLE_EQ(q.d[0], 1.0 / b);
  EXPECT_DOUBLE_EQ(q.d[1], -a / (b * b));
  // every branch of the walk: short and Estrin series, follicle spring, couple, the loaded joint alone
  for (const auto& c : whiskers())
    for (const auto& l : loads()) {
      V3<D> F, C;
      D s;
      seeded(c.w, l, Eigen::Vector3d::Zero(), F, C, s);
      const auto dual = flatten(deflect<D>(c.w, F, C, s));
      const auto plain = deflect<double>(c.w, V3<double>(l.force_L), V3<double>(l.couple_L), s.v);
      const double p[9] = {plain.p_contact_B.x, plain.p_contact_B.y, plain.p_contact_B.z,
                           plain.force_B.x,     plain.force_B.y,     plain.force_B.z,
                           plain.couple_B.x,    plain.couple_B.y,    plain.couple_B.z};
      for (int i = 0; i < 9; ++i) EXPECT_EQ(dual.value[i], p[i]) << c.name << ", s/L " << l.s_over_L << ", output " << i;
    }
}

// The walk carries its vectors in rest axes. Here is the walk in link frames, as it was first written:
// v_{j-1} = Q_j exp([omega_j]x) v_j, omega_j = K_j (M + (K_j M) x M / 2) with K_j the compliance in link j's
// frame, M = w_j (r x F + C), the follicle spring on the y and z components of link 0's frame. The two are the
// same map (R_{j-1} Q_j = R_j); they must agree to rounding, joint rotations included.
ContactKinematics<double> link_frame_walk(const Whisker& w, const V3<double>& force_L, const V3<double>& couple_L,
                                          double s, Eigen::Vector3d* omega_out) {
  int k;
  double h;
  w.locate(s, k, h);
  const auto uk = static_cast<std::size_t>(k);
  V3<double> v[3] = {V3<double>(h, 0.0, 0.0), force_L, couple_L};
  const Eigen::Vector3d& kappa = w.load_frame_curvature()[uk];
  const V3<double> psi((h - 0.5 * w.link_lengths()[uk]) * Eigen::Vector3d(kappa));
  const Eigen::Matrix3d E = joint_rotation_matrix(to_eigen(psi));
  v[1] = V3<double>(Eigen::Vector3d(E * to_eigen(v[1])));
  v[2] = V3<double>(Eigen::Vector3d(E * to_eigen(v[2])));
  for (int j = w.links() - 1; j > k; --j) omega_out[j].setZero();
  for (int j = k; j >= 0; --j) {
    const auto u = static_cast<std::size_t>(j);
    const V3<double> rxF = cross(v[0], v[1]);
    const double wf = j == k ? w.loaded_joint_weight_base(j) + w.loaded_joint_weight_slope() * h : w.joint_weight()[u];
    const double wc = j == k ? w.loaded_joint_weight_base(j) + h : w.joint_weight()[u];
    const Eigen::Vector3d M = wf * to_eigen(rxF) + wc * to_eigen(v[2]);
    const Eigen::Matrix3d& K = w.joint_compliance_link()[u];
    const Eigen::Vector3d P = K * M;
    Eigen::Vector3d omega = K * (M + 0.5 * P.cross(M));
    if (j == 0) {
      const Eigen::Vector3d Mb = to_eigen(rxF + v[2]);
      omega.y() += w.base_extra_compliance() * Mb.y();
      omega.z() += w.base_extra_compliance() * Mb.z();
    }
    omega_out[j] = omega;
    const Eigen::Matrix3d G = w.rest_joint_rotations()[u] * joint_rotation_matrix(omega);
    for (auto& x : v) x = V3<double>(Eigen::Vector3d(G * to_eigen(x)));
    if (j > 0) v[0].x += w.link_lengths()[u - 1];
  }
  return {v[0], v[1], v[2]};
}

TEST(Chain, RestAxesWalkIsTheLinkFrameWalk) {
  int compared = 0, past_short_series = 0;
  for (const auto& c : whiskers()) {
    if (c.w.properties().scheme == Scheme::paper) continue;
    const auto N = static_cast<std::size_t>(c.w.links());
    for (const auto& l : loads())
      for (const double scale : {1.0, 8.0}) {  // and loads that bend joints past the short series
        std::vector<Eigen::Vector3d> omega(N), omega_ref(N);
        const V3<double> F(Eigen::Vector3d(scale * l.force_L)), C(Eigen::Vector3d(scale * l.couple_L));
        const double s = l.s_over_L * c.w.length();
        const auto r = link_frame_walk(c.w, F, C, s, omega_ref.data());
        double largest = 0.0;
        for (const auto& o : omega_ref) largest = std::max(largest, o.norm());
        // A joint turned past a right angle is outside what a chain of this N represents, and there the walk
        // amplifies rounding (joints of 14 to 47 rad differ by 1e-9): not compared.
        if (largest > 0.5 * std::numbers::pi) continue;
        ++compared;
        past_short_series += largest > std::sqrt(detail::rodrigues_short_series_limit) ? 1 : 0;
        const auto a = deflect<double>(c.w, F, C, s, omega.data());
        const std::string where = c.name + ", s/L " + std::to_string(l.s_over_L) + ", x" + std::to_string(scale);
        EXPECT_LT((to_eigen(a.p_contact_B) - to_eigen(r.p_contact_B)).norm(), 1e-12 * c.w.length()) << where;
        EXPECT_LT((to_eigen(a.force_B) - to_eigen(r.force_B)).norm(), 1e-12 * to_eigen(F).norm()) << where;
        EXPECT_LE((to_eigen(a.couple_B) - to_eigen(r.couple_B)).norm(), 1e-12 * to_eigen(C).norm()) << where;
        double worst = 0.0;
        for (std::size_t j = 0; j < N; ++j) worst = std::max(worst, (omega[j] - omega_ref[j]).norm());
        EXPECT_GT(largest, 0.0) << where;
        EXPECT_LT(worst, 1e-12 * largest) << where;
      }
  }
  EXPECT_GE(compared, 30);
  EXPECT_GE(past_short_series, 10);
}

// The Rodrigues coefficients switch from series to closed form at t^2 = rodrigues_series_limit: both sides
// agree to rounding there, and the series is exact to rounding (against long double closed forms).
TEST(Rodrigues, SeriesMatchesClosedFormAtSwitchOver) {
  const double t2 = detail::rodrigues_series_limit;
  const double below = std::nextafter(t2, 0.0);
  double a_s, b_s, a_c, b_c;
  detail::rodrigues_coefficients(below, a_s, b_s);
  detail::rodrigues_coefficients(t2, a_c, b_c);
  const long double t = std::sqrt(static_cast<long double>(below));
  const long double a_exact = std::sin(t) / t, b_exact = (1.0L - std::cos(t)) / (t * t),
                    c_exact = (t - std::sin(t)) / (t * t * t);
  EXPECT_NEAR(a_s, static_cast<double>(a_exact), 2e-16);
  EXPECT_NEAR(b_s, static_cast<double>(b_exact), 2e-16 * 0.5);
  EXPECT_NEAR(a_s, a_c, 4e-16);
  EXPECT_NEAR(b_s, b_c, 4e-16 * 0.5);
  const double c_s = detail::right_jacobian_coefficient(below, a_s), c_c = detail::right_jacobian_coefficient(t2, a_c);
  EXPECT_NEAR(c_s, static_cast<double>(c_exact), 2e-16 / 6.0);
  EXPECT_NEAR(c_s, c_c, 1e-13);  // the closed form (1 - a)/t^2 loses ~3 digits to cancellation here
}

// Below rodrigues_short_series_limit four terms are used: on both sides of that switch the coefficients are
// exact to rounding (a dropped fifth term would show as 2e-19 at most; a dropped fourth as 1.6e-14 for a).
TEST(Rodrigues, ShortSeriesIsExactBelowItsLimit) {
  for (const double t2 : {std::nextafter(detail::rodrigues_short_series_limit, 0.0), detail::rodrigues_short_series_limit,
                          1e-6, 1e-10}) {
    double a, b;
    detail::rodrigues_coefficients(t2, a, b);
    const long double t = std::sqrt(static_cast<long double>(t2));
    EXPECT_NEAR(a, static_cast<double>(std::sin(t) / t), 1.2e-16) << t2;
    const long double half = std::sin(0.5L * t) / t;  // (1 - cos t)/t^2 = 2 sin^2(t/2)/t^2, free of cancellation
    EXPECT_NEAR(b, static_cast<double>(2.0L * half * half), 0.6e-16) << t2;
  }
}

// The split form deflect() turns its vectors with equals the matrix form to rounding.
TEST(Rodrigues, SplitFormIsTheRotation) {
  for (const double angle : {1e-9, 0.01, 0.1, 0.3, 1.3}) {
    const V3<double> w(angle * 0.48, -angle * 0.6, angle * 0.64), v(0.3, -1.1, 0.7), offset(0.01, 0.02, -0.03);
    const double t2 = dot(w, w);
    double a, b;
    detail::rodrigues_coefficients(t2, a, b);
    const V3<double> m = detail::rotation_matrix(w, a, b) * v + offset;
    const V3<double> split = detail::RotationTerms<double>(w, t2, v).turned(a, b, offset);
    EXPECT_NEAR(split.x, m.x, 1e-15);
    EXPECT_NEAR(split.y, m.y, 1e-15);
    EXPECT_NEAR(split.z, m.z, 1e-15);
  }
}

TEST(Rodrigues, MatrixFormIsTheRotationOfRotate) {
  for (const double angle : {1e-9, 0.1, 0.19999, 0.2000001, 1.3}) {
    const V3<double> w(angle * 0.48, -angle * 0.6, angle * 0.64);
    double a, b;
    detail::rodrigues_coefficients(dot(w, w), a, b);
    const Mat3<double> R = detail::rotation_matrix(w, a, b);
    const V3<double> v(0.3, -1.1, 0.7);
    const V3<double> x = R * v, y = detail::rotate(w, a, b, v);
    EXPECT_NEAR(x.x, y.x, 1e-15);
    EXPECT_NEAR(x.y, y.y, 1e-15);
    EXPECT_NEAR(x.z, y.z, 1e-15);
    EXPECT_NEAR(dot(x, x), dot(v, v), 1e-14);
  }
}

}  // namespace
}  // namespace vibrissa
