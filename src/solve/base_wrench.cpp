// The base-wrench inverse (docs/inverse.md): weighted least squares of the chosen base signals over the
// unknowns of every contact solve, u = (F_y, F_z) / (E I_0 / L²) and s / L, from several starting arc lengths.
#include "vibrissa/solve/base_wrench.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/SVD>

#include "contact_problem.hpp"
#include "vibrissa/core/plausibility.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {

namespace {

constexpr const char* kSignalNames[6] = {"Fx", "Fy", "Fz", "Mx", "My", "Mz"};

struct Preset {
  const char* name;
  std::uint8_t mask;
};
constexpr Preset kPresets[] = {
    {"all", 0x3F}, {"bending", 0x30}, {"bending_axial", 0x31}, {"moments", 0x38}, {"moments_axial", 0x39}};

/// The six signals in natural units (forces / (E I_0 / L²), moments about the base / (E I_0 / L)) and the
/// contact point in B [m], for scaled unknowns u.
template <class S>
struct Signals {
  std::array<S, 6> value;
  V3<S> p_B;
};

template <class S>
Signals<S> signals_at(const Whisker& w, const detail::Scales& sc, const std::array<S, 3>& u) {
  const auto c = detail::contact_at<S>(w, sc, u);
  const V3<S> M = cross(c.p_contact_B, c.force_B);
  const double fu = 1.0 / sc.force, mu = 1.0 / (sc.force * sc.length);
  return {{fu * c.force_B.x, fu * c.force_B.y, fu * c.force_B.z, mu * M.x, mu * M.y, mu * M.z}, c.p_contact_B};
}

/// The fitting problem: chosen signals, whitening, measured values (natural units).
struct Problem {
  const Whisker& w;
  detail::Scales sc;
  std::vector<int> index;   ///< chosen signals (0..5)
  Eigen::MatrixXd white;    ///< c · L_n^-1, Sigma_n = L_n L_n^T the noise covariance in natural units
  double c = 1.0;           ///< sqrt(mean variance in natural units): keeps the LM residual O(signal)
  Eigen::VectorXd measured; ///< chosen signals, natural units
  double tolerance = 0.0;   ///< absolute, on the LM residual
  Eigen::Vector3d force_B;  ///< measured base force in B [N] (used for starts when all of Fx, Fy, Fz are fitted)
  Eigen::Vector3d moment_B; ///< measured base moment in B [N·m] (for starts when all six are fitted)
  bool has_force = false;

  Problem(const Whisker& whisker, const Eigen::Vector3d& F_B, const Eigen::Vector3d& M_B, const BaseWrenchOptions& o)
      : w(whisker), sc(whisker), force_B(F_B), moment_B(M_B) {
    for (BaseSignal s : o.signals.list()) index.push_back(static_cast<int>(s));
    has_force = o.signals.has(BaseSignal::Fx) && o.signals.has(BaseSignal::Fy) && o.signals.has(BaseSignal::Fz);
    const int m = static_cast<int>(index.size());
    Eigen::VectorXd unit(m);
    measured.resize(m);
    for (int i = 0; i < m; ++i) {
      const int k = index[static_cast<std::size_t>(i)];
      unit[i] = k < 3 ? sc.force : sc.force * sc.length;
      measured[i] = (k < 3 ? F_B[k] : M_B[k - 3]) / unit[i];
    }
    Eigen::MatrixXd sigma_n;
    if (o.noise_covariance.size() == 0)
      sigma_n = Eigen::MatrixXd::Identity(m, m) * (o.relative_noise * o.relative_noise);
    else
      sigma_n = unit.cwiseInverse().asDiagonal() * o.noise_covariance * unit.cwiseInverse().asDiagonal();
    c = std::sqrt(sigma_n.trace() / m);
    const Eigen::LLT<Eigen::MatrixXd> llt(sigma_n);
    white = c * llt.matrixL().solve(Eigen::MatrixXd::Identity(m, m));
    tolerance = o.solve.tolerance * std::max((white * measured).cwiseAbs().maxCoeff(), 1e-300);
  }
  [[nodiscard]] int m() const { return static_cast<int>(index.size()); }
  /// The same problem with the measured signals scaled by `lambda` (load continuation).
  [[nodiscard]] Problem scaled(double lambda) const {
    Problem q = *this;
    q.measured *= lambda;
    q.force_B *= lambda;
    q.tolerance *= lambda;
    return q;
  }
  [[nodiscard]] double chi2(double lm_cost) const { return lm_cost / (c * c); }
};

/// The LM residual c · L_n^-1 (signals(u) - measured) with M equations.
template <int M>
struct Residual {
  const Problem& p;
  template <class S>
  std::array<S, M> operator()(const std::array<S, 3>& u) const {
    const Signals<S> sig = signals_at<S>(p.w, p.sc, u);
    std::array<S, M> d, r;
    for (int i = 0; i < M; ++i)
      d[static_cast<std::size_t>(i)] =
          sig.value[static_cast<std::size_t>(p.index[static_cast<std::size_t>(i)])] - S(p.measured[i]);
    for (int i = 0; i < M; ++i) {  // white is lower triangular
      S acc(0.0);
      for (int j = 0; j <= i; ++j) acc += p.white(i, j) * d[static_cast<std::size_t>(j)];
      r[static_cast<std::size_t>(i)] = acc;
    }
    return r;
  }
};

detail::LMBounds fit_bounds() {
  detail::LMBounds b;
  b.lower[2] = 1e-9;
  b.upper[2] = 1.0;
  return b;
}

template <int M>
detail::LMResult fit_m(const Problem& p, const Eigen::Vector3d& u0, int max_iterations) {
  return detail::levenberg_marquardt(Residual<M>{p}, u0, fit_bounds(), p.tolerance, max_iterations);
}

detail::LMResult fit_raw(const Problem& p, const Eigen::Vector3d& u0, int max_iterations) {
  switch (p.m()) {
    case 1: return fit_m<1>(p, u0, max_iterations);
    case 2: return fit_m<2>(p, u0, max_iterations);
    case 3: return fit_m<3>(p, u0, max_iterations);
    case 4: return fit_m<4>(p, u0, max_iterations);
    case 5: return fit_m<5>(p, u0, max_iterations);
    default: return fit_m<6>(p, u0, max_iterations);
  }
}

/// A least-squares fit from u0. An over-determined fit also converges when its iteration stalls before the
/// limit: no step, however damped, lowers the squares, so u is a minimum to rounding. The objective is only
/// piecewise smooth in s (the loaded link changes at each node), and with noisy signals its minimum often
/// sits on such a kink, where the gradient does not vanish.
detail::LMResult fit(const Problem& p, const Eigen::Vector3d& u0, int max_iterations) {
  detail::LMResult lm = fit_raw(p, u0, max_iterations);
  if (!lm.converged && p.m() > 3 && lm.iterations < max_iterations && std::isfinite(lm.cost)) lm.converged = true;
  return lm;
}

/// Exact Jacobians at u: of the chosen signals (natural units, m x 3) and of the contact point in B (3 x 3).
void jacobians(const Problem& p, const Eigen::Vector3d& u, Eigen::MatrixXd& J_n, Eigen::Matrix3d& P_B) {
  using D = Dual<3>;
  const std::array<D, 3> x = {D::variable(u[0], 0), D::variable(u[1], 1), D::variable(u[2], 2)};
  const Signals<D> sig = signals_at<D>(p.w, p.sc, x);
  J_n.resize(p.m(), 3);
  for (int i = 0; i < p.m(); ++i)
    for (int j = 0; j < 3; ++j)
      J_n(i, j) = sig.value[static_cast<std::size_t>(p.index[static_cast<std::size_t>(i)])].d[static_cast<std::size_t>(j)];
  const D* pc[3] = {&sig.p_B.x, &sig.p_B.y, &sig.p_B.z};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P_B(i, j) = pc[i]->d[static_cast<std::size_t>(j)];
}

/// The starting force for arc length s0. With the whole base force measured: the follower load at s0 whose
/// base force it is (the dead-load solve, deflection included; its small axial part dropped). Otherwise, or
/// if that fails: the linear fit of the chosen signals about the unloaded whisker.
Eigen::Vector3d start_at(const Problem& p, double s0) {
  if (p.has_force) {
    SolveOptions o;
    o.compute_shape = false;
    const Solution d = solve_dead_load(p.w, Placement{}, p.force_B, s0 * p.sc.length, o);
    if (d.status == Status::converged) return {d.state.force_y / p.sc.force, d.state.force_z / p.sc.force, s0};
  }
  const Eigen::Vector3d u(0.0, 0.0, s0);
  Eigen::MatrixXd J_n;
  Eigen::Matrix3d P_B;
  jacobians(p, u, J_n, P_B);
  const Eigen::MatrixXd A = p.white * J_n.leftCols(2);
  const Eigen::Vector2d f = A.completeOrthogonalDecomposition().solve(p.white * p.measured);
  return {f.x(), f.y(), s0};
}

/// Extra starting arc lengths (scaled) when all six signals are fitted: the force's line of action
/// p = F x M / |F|^2 + t F passes through the contact, so the local minima along the rest whisker of the
/// distance to that line are good guesses of s while the deflection is moderate.
std::vector<double> line_of_action_starts(const Problem& p) {
  std::vector<double> out;
  if (p.m() != 6 || !(p.force_B.norm() > 0.0)) return out;
  const Eigen::Vector3d d = p.force_B.normalized();
  const Eigen::Vector3d q = p.force_B.cross(p.moment_B) / p.force_B.squaredNorm();
  const auto& nodes = p.w.rest_nodes_B();
  const auto& arc = p.w.node_arc_lengths();
  std::vector<double> dist(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3d r = nodes[i] - q;
    dist[i] = (r - r.dot(d) * d).norm();
  }
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const bool left = dist[i] <= dist[i - 1], right = i + 1 == nodes.size() || dist[i] <= dist[i + 1];
    if (left && right) out.push_back(std::min(arc[i] / p.sc.length, 1.0));
  }
  return out;
}

/// A fit from starting arc length s0 (scaled) by continuation in the load from the unloaded whisker (the
/// signals scaled by lambda = 0 -> 1): large deflections leave the direct start far off.
detail::LMResult fit_by_continuation(const Problem& p, double s0, int max_iterations) {
  auto solve_at = [&](double lambda, const Eigen::Vector3d& u, bool first) {
    const Problem q = p.scaled(lambda);
    return fit(q, first ? start_at(q, s0) : u, max_iterations);
  };
  return detail::load_continuation(solve_at, Eigen::Vector3d(0.0, 0.0, s0), 1.0 / 64.0);
}

BaseWrenchRoot root_of(const Problem& p, const Placement& X, const detail::LMResult& lm) {
  BaseWrenchRoot r;
  r.state = detail::state_from_unknowns(lm.u, p.sc);
  r.arc_length = r.state.arc_length;
  r.force_magnitude = std::hypot(r.state.force_y, r.state.force_z);
  r.angle = std::atan2(r.state.force_z, r.state.force_y);
  const std::array<double, 3> u = {lm.u[0], lm.u[1], lm.u[2]};
  r.contact_point_W = X.to_world(to_eigen(signals_at<double>(p.w, p.sc, u).p_B));
  r.chi2 = p.chi2(lm.cost);
  return r;
}

BaseWrenchIdentifiability identify(const Problem& p, const Placement& X, const Eigen::Vector3d& u) {
  BaseWrenchIdentifiability id;
  id.signals = p.m();
  Eigen::MatrixXd J_n;
  Eigen::Matrix3d P_B;
  jacobians(p, u, J_n, P_B);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J_n, Eigen::ComputeFullV);
  const Eigen::VectorXd sv = svd.singularValues();
  const double smax = sv.size() > 0 ? sv[0] : 0.0;
  const double smin = p.m() >= 3 ? sv[2] : 0.0;
  id.condition_number = smin > 0.0 ? smax / smin : std::numeric_limits<double>::infinity();
  const double rho = std::hypot(u[0], u[1]);
  // d(s/L, f/F_unit, zeta)/du; f and zeta are undefined at zero force.
  Eigen::Matrix3d T_n = Eigen::Matrix3d::Zero();
  T_n(0, 2) = 1.0;
  if (rho > 0.0) {
    T_n(1, 0) = u[0] / rho;
    T_n(1, 1) = u[1] / rho;
    T_n(2, 0) = -u[1] / (rho * rho);
    T_n(2, 1) = u[0] / (rho * rho);
  }
  id.identifiable = p.m() >= 3 && id.condition_number < 1e12 && rho > 0.0;
  if (!id.identifiable) {
    const Eigen::Vector3d v = T_n * svd.matrixV().col(2);
    id.null_direction = v.norm() > 0.0 ? Eigen::Vector3d(v.normalized()) : Eigen::Vector3d::UnitX();
    return id;
  }
  // Covariance of u: (J^T Sigma_n^-1 J)^-1 with the whitening (white / c = L_n^-1).
  const Eigen::MatrixXd J_w = (p.white / p.c) * J_n;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd_w(J_w, Eigen::ComputeFullV);
  const Eigen::Vector3d inv_sv2 = svd_w.singularValues().head<3>().array().square().inverse();
  const Eigen::Matrix3d V = svd_w.matrixV();
  const Eigen::Matrix3d C_u = V * inv_sv2.asDiagonal() * V.transpose();
  const Eigen::Matrix3d T = Eigen::Vector3d(p.sc.length, p.sc.force, 1.0).asDiagonal() * T_n;
  id.covariance = T * C_u * T.transpose();
  const Eigen::Matrix3d P_W = X.R_WB * P_B;
  id.contact_point_covariance_W = P_W * C_u * P_W.transpose();
  return id;
}

bool same_fit(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).cwiseAbs().maxCoeff() <= 1e-6 * std::max(1.0, a.cwiseAbs().maxCoeff());
}

}  // namespace

std::string_view to_string(BaseSignal signal) { return kSignalNames[static_cast<int>(signal)]; }

int SignalSet::size() const {
  int n = 0;
  for (int i = 0; i < 6; ++i) n += (mask_ >> i) & 1;
  return n;
}

std::vector<BaseSignal> SignalSet::list() const {
  std::vector<BaseSignal> out;
  for (int i = 0; i < 6; ++i)
    if ((mask_ >> i) & 1U) out.push_back(static_cast<BaseSignal>(i));
  return out;
}

std::string SignalSet::name() const {
  for (const Preset& p : kPresets)
    if (p.mask == mask_) return p.name;
  std::string out;
  for (BaseSignal s : list()) {
    if (!out.empty()) out += ',';
    out += to_string(s);
  }
  return out;
}

SignalSet SignalSet::from_names(const std::vector<std::string>& names, const char* field) {
  std::uint8_t mask = 0;
  for (const std::string& n : names) {
    int k = -1;
    for (int i = 0; i < 6; ++i)
      if (n == kSignalNames[i]) k = i;
    if (k < 0)
      throw std::invalid_argument(std::string(field) + ": unknown signal \"" + n +
                                  "\" (expected Fx, Fy, Fz, Mx, My, Mz or a preset)");
    const auto bit = static_cast<std::uint8_t>(1U << k);
    if (mask & bit) throw std::invalid_argument(std::string(field) + ": signal \"" + n + "\" given twice");
    mask = static_cast<std::uint8_t>(mask | bit);
  }
  if (mask == 0) throw std::invalid_argument(std::string(field) + " must name at least one signal");
  return SignalSet(mask);
}

SignalSet SignalSet::parse(std::string_view text, const char* field) {
  for (const Preset& p : kPresets)
    if (text == p.name) return SignalSet(p.mask);
  std::vector<std::string> names;
  std::string cur;
  for (char ch : text) {
    if (ch == ',') {
      names.push_back(cur);
      cur.clear();
    } else if (ch != ' ') {
      cur += ch;
    }
  }
  names.push_back(cur);
  return from_names(names, field);
}

void validate(const BaseWrenchOptions& o) {
  const int m = o.signals.size();
  if (m < 1) throw std::invalid_argument("signals must name at least one signal");
  if (!(o.starts >= 1 && o.starts <= 10000))
    throw std::invalid_argument("starts must be in [1, 10000], got " + std::to_string(o.starts));
  if (!(std::isfinite(o.relative_noise) && o.relative_noise > 0.0))
    throw std::invalid_argument("relative_noise must be positive and finite, got " + std::to_string(o.relative_noise));
  if (!(std::isfinite(o.root_chi2) && o.root_chi2 >= 0.0))
    throw std::invalid_argument("root_chi2 must be >= 0 and finite, got " + std::to_string(o.root_chi2));
  if (!(o.solve.tolerance > 0.0 && std::isfinite(o.solve.tolerance)))
    throw std::invalid_argument("options.tolerance must be positive, got " + std::to_string(o.solve.tolerance));
  if (o.solve.max_iterations < 1)
    throw std::invalid_argument("options.max_iterations must be >= 1, got " + std::to_string(o.solve.max_iterations));
  const Eigen::MatrixXd& S = o.noise_covariance;
  if (S.size() == 0) return;
  if (S.rows() != m || S.cols() != m)
    throw std::invalid_argument("noise must be " + std::to_string(m) + " x " + std::to_string(m) + " for signals " +
                                o.signals.name() + ", got " + std::to_string(S.rows()) + " x " +
                                std::to_string(S.cols()));
  if (!S.allFinite()) throw std::invalid_argument("noise must be finite");
  if (!(S - S.transpose()).isZero(1e-12 * S.cwiseAbs().maxCoeff()))
    throw std::invalid_argument("noise covariance must be symmetric");
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success || !(S.diagonal().array() > 0.0).all())
    throw std::invalid_argument("noise covariance must be positive definite");
}

BaseWrenchResult solve_base_wrench(const Whisker& w, const Placement& X, const Eigen::Vector3d& F_base_W,
                                   const Eigen::Vector3d& M_base_W, const BaseWrenchOptions& options,
                                   const LoadState* warm) {
  require_finite(F_base_W, "force");
  require_finite(M_base_W, "moment");
  validate(options);
  BaseWrenchResult out;
  out.signals = options.signals;
  const Problem p(w, X.R_WB.transpose() * F_base_W, X.R_WB.transpose() * M_base_W, options);
  out.identifiability.signals = p.m();
  if (p.measured.cwiseAbs().maxCoeff() == 0.0) {
    out.solution = detail::unloaded_solution(w, X, Status::no_contact, "the base signals are zero: no contact",
                                             options.solve);
    return out;
  }

  std::vector<detail::LMResult> fits;
  int iterations = 0;
  const int m_over = std::max(p.m() - 3, 0);
  if (warm) {
    const detail::LMResult lm = fit(p, detail::unknowns_from_state(*warm, p.sc), options.solve.max_iterations);
    iterations += lm.iterations;
    if (lm.converged && p.chi2(lm.cost) <= m_over + options.root_chi2) fits.push_back(lm);
  }
  detail::LMResult best_failed;
  best_failed.cost = std::numeric_limits<double>::infinity();
  // Direct fits from every start; if none explains the signals, again by load continuation.
  auto explains = [&] {
    for (const auto& f : fits)
      if (p.chi2(f.cost) <= m_over + options.root_chi2) return true;
    return false;
  };
  std::vector<double> starts = line_of_action_starts(p);
  for (int i = 0; i < options.starts; ++i) starts.push_back((i + 0.5) / options.starts);
  for (int pass = 0; pass < 2 && !explains(); ++pass) {
    for (const double s0 : starts) {
      const detail::LMResult lm = pass == 0 ? fit(p, start_at(p, s0), options.solve.max_iterations)
                                            : fit_by_continuation(p, s0, options.solve.max_iterations);
      iterations += lm.iterations;
      if (lm.converged)
        fits.push_back(lm);
      else if (std::isfinite(lm.cost) && lm.cost < best_failed.cost)
        best_failed = lm;
    }
  }
  if (fits.empty()) {
    if (!std::isfinite(best_failed.cost)) best_failed.u = Eigen::Vector3d(0.0, 0.0, 1.0);
    detail::fill_solution(w, X, detail::state_from_unknowns(best_failed.u, p.sc), options.solve, std::nullopt,
                          out.solution);
    out.chi2 = std::isfinite(best_failed.cost) ? p.chi2(best_failed.cost) : 0.0;
    out.solution.residual = std::sqrt(out.chi2);
    out.solution.iterations = iterations;
    detail::set_status(out.solution, Status::not_converged,
                       "base wrench: no start reached a least-squares optimum within the iteration limit");
    out.identifiability = identify(p, X, best_failed.u);
    return out;
  }

  // Rank: chi2, then among fits tied with the best (1e-9), the smaller arc length; drop repeats.
  std::sort(fits.begin(), fits.end(), [](const auto& a, const auto& b) { return a.cost < b.cost; });
  const double best_cost = fits.front().cost;
  const auto tie_end = std::find_if(fits.begin(), fits.end(), [&](const auto& f) {
    return p.chi2(f.cost) > p.chi2(best_cost) + 1e-9;
  });
  std::stable_sort(fits.begin(), tie_end, [](const auto& a, const auto& b) { return a.u[2] < b.u[2]; });
  std::vector<const detail::LMResult*> kept;
  for (const auto& f : fits) {
    if (p.chi2(f.cost) > p.chi2(best_cost) + options.root_chi2) break;
    bool repeat = false;
    for (const auto* k : kept) repeat = repeat || same_fit(k->u, f.u);
    if (!repeat) kept.push_back(&f);
  }
  for (const auto* k : kept) out.roots.push_back(root_of(p, X, *k));

  const detail::LMResult& best = *kept.front();
  detail::fill_solution(w, X, detail::state_from_unknowns(best.u, p.sc), options.solve, std::nullopt, out.solution);
  out.chi2 = out.roots.front().chi2;
  out.solution.residual = std::sqrt(out.chi2);
  out.solution.iterations = iterations;
  if (kept.size() > 1) out.solution.other_root_arc_length = out.roots[1].arc_length;
  out.identifiability = identify(p, X, best.u);
  if (!explains()) {  // an optimum, but the signals differ from it by more than their noise: not this contact
    detail::set_status(out.solution, Status::not_converged,
                       "base wrench: the best fit leaves chi2 above what the signals' noise explains (a local "
                       "optimum): no contact found that explains the signals");
    return out;
  }
  if (out.identifiability.identifiable)
    detail::set_status(out.solution, Status::converged,
                       "base wrench: least-squares fit of the base signals (residual = sqrt(chi2))");
  else
    detail::set_status(out.solution, Status::underdetermined,
                       "base wrench: the signals do not determine the contact (s, f, angle): this fit is one "
                       "of a family along identifiability.null_direction");
  return out;
}

std::vector<BaseWrenchResult> solve_base_wrench_series(const Whisker& w, const Placement& X,
                                                       const std::vector<Eigen::Vector3d>& F_base_W,
                                                       const std::vector<Eigen::Vector3d>& M_base_W,
                                                       const BaseWrenchOptions& options, const RunControl& control) {
  if (F_base_W.size() != M_base_W.size())
    throw std::invalid_argument("force and moment series must have the same length, got " +
                                std::to_string(F_base_W.size()) + " and " + std::to_string(M_base_W.size()));
  validate(options);
  ProgressCounter counter(control, F_base_W.size());
  std::vector<BaseWrenchResult> out;
  out.reserve(F_base_W.size());
  const LoadState* warm = nullptr;
  for (std::size_t k = 0; k < F_base_W.size(); ++k) {
    counter.check();
    out.push_back(solve_base_wrench(w, X, F_base_W[k], M_base_W[k], options, warm));
    const Solution& s = out.back().solution;
    warm = s.status == Status::converged || s.status == Status::underdetermined ? &s.state : nullptr;
    counter.advance();
  }
  return out;
}

std::vector<std::string> base_wrench_warnings(const BaseWrenchResult& r) {
  if (r.solution.status != Status::underdetermined) return {};
  const Eigen::Vector3d& n = r.identifiability.null_direction;
  return {"underdetermined: the signals " + r.signals.name() + " (" + std::to_string(r.identifiability.signals) +
          " equations) cannot determine the contact (s, f, angle); the fit at s = " +
          format_significant(r.solution.arc_length * 1e3) + " mm is one of a family (null direction ds/L " +
          format_significant(n.x(), 2) + ", df/F0 " + format_significant(n.y(), 2) + ", dangle " +
          format_significant(n.z(), 2) +
          "), not the contact: fit more signals (Fx or Mx with My, Mz; docs/inverse.md)"};
}

}  // namespace vibrissa
