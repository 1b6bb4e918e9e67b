// Time integration of the chain (dynamics/simulate.hpp): energy, damping, frequency, base signals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "vibrissa/core/pose.hpp"
#include "vibrissa/core/whisker.hpp"
#include "vibrissa/dynamics/air_drag.hpp"
#include "vibrissa/dynamics/simulate.hpp"

namespace vibrissa::dynamics {
namespace {

Whisker curved_whisker(int links) {
  WhiskerProperties p;
  p.links = links;
  return Whisker::from_parabola(0.03, 15.0, p);
}

struct Peak {
  double time, value;
};

/// Local maxima of a sampled signal, refined by the parabola through the three samples around each.
std::vector<Peak> peaks(const std::vector<double>& t, const std::vector<double>& x) {
  std::vector<Peak> out;
  for (std::size_t i = 1; i + 1 < x.size(); ++i)
    if (x[i] > x[i - 1] && x[i] >= x[i + 1]) {
      const double a = 0.5 * (x[i - 1] - 2 * x[i] + x[i + 1]), b = 0.5 * (x[i + 1] - x[i - 1]);
      const double d = -b / (2 * a);
      out.push_back({t[i] + d * (t[i + 1] - t[i]), x[i] + b * d + a * d * d});
    }
  return out;
}

TEST(DynamicsSimulate, UndampedFreeVibrationKeepsItsEnergy) {
  const Whisker w = curved_whisker(40);
  DynamicsProperties dp;
  dp.damping_ratio = 0.0;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  InitialState init;
  init.q = 1e-3 * all.joint_shapes.col(0) + 5e-4 * all.joint_shapes.col(2) + 2e-4 * all.joint_shapes.col(5);
  SimulationOptions opt;
  opt.duration = 0.1;
  opt.output_rate = 2000;
  opt.relative_tolerance = 1e-5;
  const TimeSeries ts = simulate(w, model, all, fixed_base(Placement{}), dp.gravity_W, opt, init);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  const double E0 = ts.kinetic_energy[0] + ts.elastic_energy[0];
  double drift = 0.0;
  for (std::size_t i = 0; i < ts.time.size(); ++i)
    drift = std::max(drift, std::abs(ts.kinetic_energy[i] + ts.elastic_energy[i] - E0) / E0);
  // The trapezoidal rule conserves the quadratic energy of the undamped linear system exactly: rounding only.
  EXPECT_LT(drift, 1e-11);
  EXPECT_GT(ts.kinetic_energy[ts.time.size() / 3], 0.0);  // it does vibrate
}

TEST(DynamicsSimulate, LogDecrementRecoversTheDampingRatioAndThePeriodTheModalFrequency) {
  const Whisker w = curved_whisker(40);
  DynamicsProperties dp;
  dp.damping_ratio = 0.05;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  InitialState init;
  init.q = 1e-3 * all.joint_shapes.col(0);  // the first mode alone: the tip rings at its damped frequency
  SimulationOptions opt;
  opt.duration = 6.0 / all.frequency_hz(0);
  opt.output_rate = 400.0 * all.frequency_hz(0);
  opt.relative_tolerance = 1e-9;
  opt.record_nodes = false;
  const TimeSeries ts = simulate(w, model, all, fixed_base(Placement{}), dp.gravity_W, opt, init);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  // The tip's displacement along the mode's tip direction.
  const Eigen::Vector3d dir = ts.tip_displacement_B[0].normalized();
  std::vector<double> x;
  for (const auto& d : ts.tip_displacement_B) x.push_back(d.dot(dir));
  const auto pk = peaks(ts.time, x);
  ASSERT_GE(pk.size(), 4u);
  for (std::size_t i = 0; i + 1 < pk.size(); ++i) {
    const double delta = std::log(pk[i].value / pk[i + 1].value);
    const double zeta = delta / std::sqrt(4 * std::numbers::pi * std::numbers::pi + delta * delta);
    EXPECT_NEAR(zeta, 0.05, 2e-5);
    EXPECT_NEAR(1.0 / (pk[i + 1].time - pk[i].time) / all.damped_frequency_hz(0), 1.0, 2e-5);
  }
}

TEST(DynamicsSimulate, SteadyAccelerationOfTheBaseIsCarriedStatically) {
  // From equilibrium under a constant acceleration the whisker stays deflected and still; the follicle then
  // carries the whole inertial load: F = -m a, M = -(sum m c) x a (whisker frame, a in B).
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  const Eigen::Vector3d a_W(2.0, -5.0, 3.0);
  const BaseTrajectory base = [a_W](double t) {
    BaseMotion m;
    m.acceleration_W = a_W;
    m.velocity_W = a_W * t;
    m.p_W_base = 0.5 * a_W * t * t;
    return m;
  };
  SimulationOptions opt;
  opt.duration = 0.02;
  const TimeSeries ts = simulate(w, dp, base, opt);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  const auto links = link_inertias(w, dp.density);
  double mass = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (const auto& l : links) {
    mass += l.mass;
    first += l.mass * l.centroid_B;
  }
  const Eigen::Vector3d F = -mass * a_W;
  for (std::size_t i = 0; i < ts.time.size(); ++i) {
    EXPECT_LT((ts.force_B[i] - F).norm(), 1e-12 * F.norm());
    EXPECT_LT(ts.kinetic_energy[i], 1e-20 * ts.elastic_energy[i] + 1e-40);
    EXPECT_LT((ts.q.col(static_cast<Eigen::Index>(i)) - ts.q.col(0)).norm(), 1e-12 * ts.q.col(0).norm());
  }
  // Moment: the deflection is part of the centroids' lever arms only at second order; the rest lever arms.
  const Eigen::Vector3d M = -first.cross(a_W);
  EXPECT_LT((ts.moment_B.back() - M).norm(), 1e-3 * M.norm());
}

TEST(DynamicsSimulate, BaseMomentIsTheBaseJointsTorqueWhileWhisking) {
  // About the base, the follicle's moment balances the first joint's spring (undamped): M_base = K_0 theta_0.
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  dp.damping_ratio = 0.0;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  const BaseTrajectory base = trajectory_from_placements([](double t) {
    return Placement(rotation_from_angles(0.35 * std::sin(2 * std::numbers::pi * 8.0 * t), 0.0, 0.0),
                     Eigen::Vector3d::Zero());
  });
  SimulationOptions opt;
  opt.duration = 0.1;
  const TimeSeries ts = simulate(w, model, all, base, dp.gravity_W, opt);
  ASSERT_EQ(ts.status, SimulationStatus::completed);
  double largest = 0.0;
  for (const auto& m : ts.moment_B) largest = std::max(largest, m.norm());
  ASSERT_GT(largest, 0.0);
  for (std::size_t i = 0; i < ts.time.size(); ++i) {
    const Eigen::Vector3d torque =
        model.stiffness.topLeftCorner<3, 3>() * ts.q.col(static_cast<Eigen::Index>(i)).head<3>();
    EXPECT_LT((ts.moment_B[i] - torque).norm(), 1e-9 * largest) << "t = " << ts.time[i];
  }
}

/// Largest gaps between the base wrench (force_W, moment_W) and Newton's second law on the whole whisker
/// evaluated from the recorded shapes alone, relative to the law's peaks; also the drag's share of the force.
struct NewtonGaps {
  double force, moment, drag_share;
};

/// The follicle carries the air's drag minus the links' m a (force) and, about the moving base point, minus
/// their moments and their spin's rate of change. Each link is rigid along its chord, so its centroid is a fixed
/// mix of its nodes; the accelerations are 5-point central differences of the recorded nodes_W. The base turns
/// about two axes and translates near the first mode (elastic accelerations, not only rigid ones), with
/// amplitudes scaled by `scale`.
NewtonGaps newton_gaps(double scale) {
  const Whisker w = curved_whisker(20);
  DynamicsProperties dp;
  dp.air_drag = true;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  const double f1 = all.frequency_hz(0), two_pi = 2 * std::numbers::pi;
  const auto placement = [&](double t) {
    const double s = std::sin(two_pi * 0.8 * f1 * t), c = 1.0 - std::cos(two_pi * 0.5 * f1 * t);
    return Placement(rotation_from_angles(0.2 + scale * 2e-3 * s, 0.1 + scale * 1e-3 * c, 0.05),
                     scale * Eigen::Vector3d(1e-6 * c, -2e-6 * s, 1.5e-6 * std::sin(two_pi * 1.3 * f1 * t)));
  };
  const BaseTrajectory base = trajectory_from_placements(placement);
  SimulationOptions opt;
  opt.duration = 2.0 / f1;
  opt.output_rate = 400.0 * f1;
  opt.relative_tolerance = 1e-10;
  const ExternalLoad drag = air_drag_load(w, base, dp.air);
  const TimeSeries ts = simulate(w, model, all, base, dp.gravity_W, opt, {}, drag);
  EXPECT_EQ(ts.status, SimulationStatus::completed);

  // Per link: mass, where its centroid lies along its chord, and its inertia about the chord's normals.
  const auto links = link_inertias(w, dp.density);
  const auto& rest = w.rest_nodes_B();
  std::vector<double> along(links.size()), transverse(links.size());
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Eigen::Vector3d chord = rest[i + 1] - rest[i];
    along[i] = (links[i].centroid_B - rest[i]).dot(chord) / chord.squaredNorm();
    EXPECT_LT((links[i].centroid_B - rest[i] - along[i] * chord).norm(), 1e-12);  // on the chord
    const Eigen::Vector3d normal = chord.unitOrthogonal();
    transverse[i] = normal.dot(links[i].inertia_B * normal);
  }
  const double h = 1.0 / opt.output_rate;
  auto centroid = [&](std::size_t f, std::size_t i) {
    return ((1.0 - along[i]) * ts.nodes_W[f][i] + along[i] * ts.nodes_W[f][i + 1]).eval();
  };
  auto second = [&](auto x, std::size_t f) {  // O(h^4)
    return ((-x(f - 2) + 16.0 * x(f - 1) - 30.0 * x(f) + 16.0 * x(f + 1) - x(f + 2)) / (12.0 * h * h)).eval();
  };
  auto first = [&](auto x, std::size_t f) {
    return ((x(f - 2) - 8.0 * x(f - 1) + 8.0 * x(f + 1) - x(f + 2)) / (12.0 * h)).eval();
  };
  // A link's spin angular momentum: I_t d x d' / |d|^2 (the part about the chord, (r/l)^2 smaller, left out).
  auto spin = [&](std::size_t f, std::size_t i) {
    auto d = [&](std::size_t g) { return (ts.nodes_W[g][i + 1] - ts.nodes_W[g][i]).eval(); };
    const Eigen::Vector3d di = d(f);
    return (transverse[i] * di.cross(first(d, f)) / di.squaredNorm()).eval();
  };
  double peak_F = 0, peak_M = 0, gap_F = 0, gap_M = 0, peak_drag = 0;
  for (std::size_t f = 4; f + 4 < ts.time.size(); ++f) {
    Eigen::VectorXd unused = Eigen::VectorXd::Zero(model.mass.rows());
    Eigen::Matrix<double, 6, 1> drag_B = Eigen::Matrix<double, 6, 1>::Zero();
    drag(ts.time[f], unused, drag_B);
    const Eigen::Matrix3d& R = ts.placements[f].R_WB;
    const Eigen::Vector3d p_base = ts.placements[f].p_W_base;
    Eigen::Vector3d F = R * drag_B.head<3>(), M = R * drag_B.tail<3>();
    for (std::size_t i = 0; i < links.size(); ++i) {
      const Eigen::Vector3d a = second([&](std::size_t g) { return centroid(g, i); }, f);
      F -= links[i].mass * a;
      M -= (centroid(f, i) - p_base).cross(links[i].mass * a) + first([&](std::size_t g) { return spin(g, i); }, f);
    }
    gap_F = std::max(gap_F, (ts.force_W[f] - F).norm());
    gap_M = std::max(gap_M, (ts.moment_W[f] - M).norm());
    peak_F = std::max(peak_F, F.norm());
    peak_M = std::max(peak_M, M.norm());
    peak_drag = std::max(peak_drag, drag_B.head<3>().norm());
  }
  EXPECT_GT(peak_F, 0.0);
  return {gap_F / peak_F, gap_M / peak_M, peak_drag / peak_F};
}

TEST(DynamicsSimulate, BaseWrenchIsNewtonsSecondLawOnTheRecordedShapes) {
  // The linear model leaves out the products of the deflection with the base motion (docs/dynamics.md, "Scope"):
  // relative to the signals they grow with the amplitude; what does not is a missing or wrong term.
  const NewtonGaps large = newton_gaps(0.1), small = newton_gaps(0.01);
  std::printf("Newton gaps, force and moment: %.3g, %.3g (amplitude x 0.1), %.3g, %.3g (x 0.01); drag %.3g of F\n",
              large.force, large.moment, small.force, small.moment, small.drag_share);
  EXPECT_GT(small.drag_share, 5e-4);  // the drag is part of what is tested
  EXPECT_LT(small.force, 5e-5);
  EXPECT_LT(small.moment, 3e-5);
  EXPECT_GT(large.force, 8.0 * small.force);  // the products the model leaves out, first order in the amplitude
}

TEST(DynamicsSimulate, ErrorFallsWithTheTolerance) {
  const Whisker w = curved_whisker(30);
  DynamicsProperties dp;
  const LinearModel model = linear_model(w, dp);
  const Modes all = modes(model, w);
  const BaseTrajectory base = trajectory_from_placements([](double t) {
    return Placement(rotation_from_angles(0.35 * (1.0 - std::cos(2 * std::numbers::pi * 8.0 * t)), 0.0, 0.0),
                     Eigen::Vector3d::Zero());
  });
  auto run = [&](double rtol) {
    SimulationOptions opt;
    opt.duration = 0.125;
    opt.relative_tolerance = rtol;
    opt.record_nodes = false;
    return simulate(w, model, all, base, dp.gravity_W, opt);
  };
  const TimeSeries ref = run(1e-10);
  auto error = [&](const TimeSeries& ts) {
    double e = 0.0, big = 0.0;
    for (std::size_t i = 0; i < ts.time.size(); ++i) {
      e = std::max(e, (ts.moment_B[i] - ref.moment_B[i]).norm());
      big = std::max(big, ref.moment_B[i].norm());
    }
    return e / big;
  };
  const TimeSeries loose = run(1e-4), tight = run(1e-6);
  EXPECT_LT(error(tight), 1e-4);
  EXPECT_LT(error(tight), 0.2 * error(loose));
  EXPECT_GT(loose.steps, 0);
  EXPECT_GT(tight.steps, loose.steps);
}

}  // namespace
}  // namespace vibrissa::dynamics
