#pragma once
// The inverse of force mode (docs/inverse.md): from the force and moment at the whisker's base, where along
// the whisker was it touched, how hard and in which direction. The unknowns are those of every contact solve
// (the normal follower force (F_y, F_z) in the loaded link's frame and the arc length s; f and angle zeta are
// derived); the equations are the chosen base signals in the whisker frame B (spec §2.4), fitted by weighted
// least squares with exact Jacobians (Dual<3>). Several starting arc lengths are tried; every distinct fit
// that explains the signals within the noise is reported, ranked.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/core/run_control.hpp"
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/solve/options.hpp"
#include "vibrissa/solve/solution.hpp"

namespace vibrissa {

/// The six base signals, components in frame B of the force and the moment about the base (spec §2.4).
enum class BaseSignal : std::uint8_t { Fx = 0, Fy = 1, Fz = 2, Mx = 3, My = 4, Mz = 5 };
std::string_view to_string(BaseSignal signal);

/// A subset of the base signals (always taken in the order Fx, Fy, Fz, Mx, My, Mz).
class SignalSet {
 public:
  constexpr SignalSet() = default;
  /// Presets: "all" (six), "bending" (My, Mz), "bending_axial" (Fx, My, Mz), "moments" (Mx, My, Mz),
  /// "moments_axial" (Fx, Mx, My, Mz); or a comma-separated list of names ("Fx,My,Mz"). Throws
  /// std::invalid_argument naming `field` for anything else or an empty set.
  static SignalSet parse(std::string_view text, const char* field = "signals");
  static SignalSet from_names(const std::vector<std::string>& names, const char* field = "signals");
  static constexpr SignalSet all() { return SignalSet(0x3F); }
  static constexpr SignalSet bending() { return SignalSet(0x30); }
  static constexpr SignalSet bending_axial() { return SignalSet(0x31); }

  [[nodiscard]] bool has(BaseSignal s) const { return (mask_ >> static_cast<int>(s)) & 1U; }
  [[nodiscard]] int size() const;
  [[nodiscard]] std::vector<BaseSignal> list() const;
  /// The preset name if there is one, else the comma-separated list.
  [[nodiscard]] std::string name() const;
  [[nodiscard]] std::uint8_t mask() const { return mask_; }
  friend bool operator==(SignalSet a, SignalSet b) { return a.mask_ == b.mask_; }

 private:
  constexpr explicit SignalSet(std::uint8_t mask) : mask_(mask) {}
  std::uint8_t mask_ = 0x3F;
};

struct BaseWrenchOptions {
  SignalSet signals = SignalSet::all();
  /// Sensor-noise covariance of the chosen signals in frame B, SI (N², N²·m, N²·m²), rows in signal order
  /// (size m x m, symmetric positive definite). Empty: every signal independent with standard deviation
  /// `relative_noise` times its natural unit (forces E I_0 / L², moments E I_0 / L).
  Eigen::MatrixXd noise_covariance;
  double relative_noise = 1e-6;
  /// Starting arc lengths, evenly spread over the whisker (s/L = (i + 1/2) / starts).
  int starts = 16;
  /// A fit is listed in `roots` if its chi-square is within this of the best fit's.
  double root_chi2 = 9.0;
  /// tolerance: on the whitened signals, relative to their largest magnitude (dimensionless);
  /// max_iterations per start; compute_shape; find_other_roots is not used.
  SolveOptions solve;
};

/// One fit of the signals (a candidate contact), SI units.
struct BaseWrenchRoot {
  double arc_length = 0.0;       ///< s [m]
  double force_magnitude = 0.0;  ///< f [N]
  double angle = 0.0;            ///< zeta = atan2(F_z, F_y) of the loaded link [rad]
  Eigen::Vector3d contact_point_W = Eigen::Vector3d::Zero();  ///< [m]
  double chi2 = 0.0;             ///< whitened squared residual
  LoadState state;               ///< the fitted unknowns
};

/// Identifiability of (s, f, zeta) from the chosen signals at the returned fit (linearised).
struct BaseWrenchIdentifiability {
  int signals = 0;              ///< number of equations m
  bool identifiable = false;    ///< m >= 3 and the whitened Jacobian has full rank (condition < 1e12)
  /// Ratio of the largest to the smallest singular value of the Jacobian of the signals in natural units
  /// with respect to (F_y, F_z) / (E I_0 / L²) and s / L; +infinity when rank-deficient.
  double condition_number = 0.0;
  /// Unit null direction of that Jacobian in (ds / L, df / (E I_0 / L²), dzeta) when not identifiable; else 0.
  Eigen::Vector3d null_direction = Eigen::Vector3d::Zero();
  /// Linearised covariance (J^T Sigma^-1 J)^-1 of (s [m], f [N], zeta [rad]) for the noise covariance used;
  /// zero when not identifiable.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  /// Covariance of the contact point, world [m²] (through the exact d p / d unknowns); zero when not identifiable.
  Eigen::Matrix3d contact_point_covariance_W = Eigen::Matrix3d::Zero();
};

struct BaseWrenchResult {
  /// The returned fit (roots[0]) as a force-mode Solution: status, contact point, arc length, force,
  /// angle, base signals, shape. status converged: the least-squares optimum was reached (signals fitted to
  /// tolerance, or the gradient of the squares vanished for an over-determined set); residual = sqrt(chi2).
  Solution solution;
  double chi2 = 0.0;  ///< whitened squared residual of the returned fit (~ m - 3 for noisy signals)
  /// Every distinct converged fit with chi2 <= best + root_chi2, best first (ties within 1e-9 in chi2: the
  /// smaller arc length first). Empty unless converged.
  std::vector<BaseWrenchRoot> roots;
  BaseWrenchIdentifiability identifiability;
  SignalSet signals;
};

/// Fits (s, f, zeta) to the base force `F_base_W` [N] and moment `M_base_W` [N·m] (world frame, moment about
/// the base point): exactly Solution::force_W and Solution::moment_W of a solve at `X_WB`. Components outside
/// options.signals (after rotation into B) are ignored. All signals zero: status no_contact. `warm`, if
/// given, is tried first; when its fit converges no scan is made (roots then holds that fit only).
BaseWrenchResult solve_base_wrench(const Whisker& whisker, const Placement& X_WB, const Eigen::Vector3d& F_base_W,
                                   const Eigen::Vector3d& M_base_W, const BaseWrenchOptions& options = {},
                                   const LoadState* warm = nullptr);
inline BaseWrenchResult solve_base_wrench(const Whisker& w, const Eigen::Vector3d& F_base_W,
                                          const Eigen::Vector3d& M_base_W, const BaseWrenchOptions& options = {}) {
  return solve_base_wrench(w, w.placement(), F_base_W, M_base_W, options);
}

/// A time series of base wrenches, each frame warm-started from the previous converged fit (a cold scan
/// when there is none or it fails). Polls `control` between frames.
std::vector<BaseWrenchResult> solve_base_wrench_series(const Whisker& whisker, const Placement& X_WB,
                                                       const std::vector<Eigen::Vector3d>& F_base_W,
                                                       const std::vector<Eigen::Vector3d>& M_base_W,
                                                       const BaseWrenchOptions& options = {},
                                                       const RunControl& control = {});

void validate(const BaseWrenchOptions& options);

/// What a user must read before the numbers (docs/inverse.md): for status underdetermined, one sentence
/// naming the signals, the fitted arc length and the null direction; empty otherwise. `vibrissa solve` puts
/// these first in "warnings" (and on standard error), Python raises them with warnings.warn.
std::vector<std::string> base_wrench_warnings(const BaseWrenchResult& result);

}  // namespace vibrissa
