// Object modes: the peg of zero radius is edge mode, the force lies along the surface normal, the tip against a
// wall follows the tapered cantilever's closed form, no point of the deflected whisker is inside the object.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "../core/test_helpers.hpp"
#include "vibrissa/objects/box.hpp"
#include "vibrissa/objects/clearance.hpp"
#include "vibrissa/objects/cylinder.hpp"
#include "vibrissa/objects/mesh.hpp"
#include "vibrissa/objects/plane.hpp"
#include "vibrissa/objects/sphere.hpp"
#include "vibrissa/solve/object_contact.hpp"
#include "vibrissa/solve/solvers.hpp"

using namespace vibrissa;
using vibrissa::test::rat_whisker;
using vibrissa::test::tilted_pose;

namespace {

double relative(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm() / std::max(b.norm(), 1e-300); }

/// The smallest gap over the deflected whisker (nodes and links with their radii, or the centre line).
double whisker_clearance(const Whisker& w, const ObjectContact& o, const Solution& s) {
  const std::vector<double> none;
  return clearance(PlacedShape{o.shape, o.X_WO}, s.shape_W, w.node_arc_lengths(), o.thickness ? w.node_radii() : none)
      .gap;
}

}  // namespace

TEST(ObjectContact, PegOfZeroRadiusWithoutThicknessIsEdgeMode) {
  const Whisker w = rat_whisker(100, tilted_pose());
  for (const Eigen::Vector3d& at : {Eigen::Vector3d(0.02, 0.004, 0.0), Eigen::Vector3d(0.025, 0.009, 0.001)}) {
    const Edge edge{at, Eigen::Vector3d(0.1, -0.2, 1.0)};
    const Solution e = solve_edge(w, edge);
    ASSERT_EQ(e.status, Status::converged);
    for (double R : {0.0, 1e-13}) {
      const Cylinder peg(edge.point, edge.direction, R);
      const Solution c = solve_object(w, ObjectContact{&peg, {}, false});
      ASSERT_EQ(c.status, Status::converged) << c.message << " R = " << R << " at " << at.transpose();
      EXPECT_LT(relative(c.force_W, e.force_W), 1e-9) << R;
      EXPECT_LT(relative(c.moment_W, e.moment_W), 1e-9);
      EXPECT_LT(relative(c.contact_point_W, e.contact_point_W), 1e-9);
      EXPECT_NEAR(c.arc_length, e.arc_length, 1e-9 * e.arc_length);
      EXPECT_FALSE(c.surface->tip);
    }
  }
}

TEST(ObjectContact, FrictionlessForceIsAlongTheSurfaceNormal) {
  const Whisker w = rat_whisker(100, tilted_pose());
  const Eigen::Vector3d target = w.placement().to_world(w.rest_point_B(0.022));
  const Eigen::Vector3d push = w.placement().R_WB.col(1);  // toward the concave side
  const Sphere ball(target + 0.0025 * push + Eigen::Vector3d(0, 0, 0.0005), 0.003);
  const Cylinder peg(target + 0.0016 * push, Eigen::Vector3d(0.1, -0.2, 1.0), 0.002);
  // A wall on the whisker's convex side (normal across the whisker, toward its concave side), 0.4 mm in.
  const Eigen::Vector3d tangent = w.placement().R_WB * w.rest_link_frames_B()[55].col(0);
  const Eigen::Vector3d across = (push - push.dot(tangent) * tangent + Eigen::Vector3d(0.0, 0.0, 0.1)).normalized();
  const Plane wall(target + 0.0004 * across, across);
  const Box box(target + 0.0025 * push, Eigen::Vector3d(0.002, 0.003, 0.004),
                Eigen::Matrix3d(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())));
  for (const Shape* shape : std::initializer_list<const Shape*>{&ball, &peg, &wall, &box}) {
    SCOPED_TRACE(std::string(shape->type()));
    const ObjectContact o{shape, {}, true};
    const Solution s = solve_object(w, o);
    ASSERT_EQ(s.status, Status::converged) << s.message;
    ASSERT_TRUE(s.surface);
    // The normal at the contact (seen from just outside it: on an edge or vertex the surface has many).
    const Eigen::Vector3d n = shape->nearest(s.contact_point_W + 1e-7 * s.surface->normal_W).normal;
    EXPECT_NEAR(shape->signed_distance(s.contact_point_W), 0.0, 1e-12);
    EXPECT_LT(s.force_W.normalized().cross(n).norm(), 1e-9);
    EXPECT_GT(s.force_W.dot(n), 0.0);
    EXPECT_LT((s.surface->normal_W - n).norm(), 1e-9);
    EXPECT_GE(whisker_clearance(w, o, s), -1e-9);
  }
}

TEST(ObjectContact, TipAgainstAWallFollowsTheTaperedCantilever) {
  // A straight tapered whisker along x; a wall whose normal n is tilted from the whisker by 60 deg moved into its
  // tip by d0 along n. Linear theory: the tip moves transversely by c F_perp, c = int (L - x)^2 / (E I(x)) dx
  // (the chain is inextensible), and F = f n: f = d0 / (c n_perp^2).
  const double L = 0.03, E = 3.3e9, r_base = 100e-6, ratio = 15.0;
  const double a = r_base, b = r_base / ratio, k = (a - b) / L;
  const double c = 4.0 / (std::numbers::pi * E) / (k * k * k) * (-1.0 / a + b / (a * a) - b * b / (3 * a * a * a) + 1.0 / (3 * b));
  const double angle = test::deg(60), d0 = 2e-8;  // small: the axial force's moment on the deflection is O(d0 / L)
  SolveOptions options;
  options.tolerance = 1e-16;
  const Eigen::Vector3d n(-std::cos(angle), std::sin(angle), 0.0);  // outward from the wall, toward the whisker
  double previous_error = 0.0;
  for (int links : {50, 100, 200}) {
    WhiskerProperties p;
    p.links = links;
    p.base = BaseJoint::rigid;
    const Whisker w = Whisker::from_parabola(L, 0.0, p);
    const Eigen::Vector3d tip(L, 0.0, 0.0);
    const Plane wall(tip - (b - d0) * n, n);  // the tip's cap (radius b) is d0 inside the wall
    const ObjectContact o{&wall, {}, true};
    const Solution s = solve_object(w, o, std::nullopt, options);
    ASSERT_EQ(s.status, Status::converged) << s.message;
    ASSERT_TRUE(s.surface->tip);
    EXPECT_EQ(s.arc_length, w.length());  // the tip, which is at s = L to round-off (links of L / N)
    EXPECT_NEAR(s.arc_length, L, 1e-12 * L);
    EXPECT_LT(s.force_W.normalized().cross(n).norm(), 1e-9);
    const double f = d0 / (c * (1.0 - n.x() * n.x()));
    const double error = std::abs(s.force_magnitude - f) / f;
    EXPECT_LT(error, 2e-3) << links;
    std::cout << links << " links: f = " << s.force_magnitude << " N, closed form " << f << " N, error " << error << "\n";
    if (previous_error > 0.0) {
      EXPECT_GT(previous_error / error, 3.0) << "second order in the links";
    }
    previous_error = error;
  }
}

TEST(ObjectContact, NoPointOfTheWhiskerIsInsideOverRandomPosesAndObjects) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Mesh ball_mesh(tessellated_sphere(Eigen::Vector3d::Zero(), 0.003, 3));
  int converged = 0, second = 0, checked = 0, valid = 0, two = 0;
  for (int i = 0; i < 300; ++i) {
    Pose pose;
    pose.theta = 0.6 * (u(rng) - 0.5);
    pose.phi = 0.6 * (u(rng) - 0.5);
    pose.zeta = 2.0 * std::numbers::pi * u(rng);
    const Whisker w = rat_whisker(60, pose);
    const double s0 = 0.01 + 0.028 * u(rng);
    const Eigen::Vector3d at = w.placement().to_world(w.rest_point_B(s0));
    const double theta = 2.0 * std::numbers::pi * u(rng);
    const Eigen::Vector3d dir = w.placement().R_WB * Eigen::Vector3d(0.0, std::cos(theta), std::sin(theta));
    const double depth = 0.0015 * u(rng);
    std::unique_ptr<Shape> shape;
    ObjectPose X;
    switch (i % 5) {
      case 0: shape = std::make_unique<Sphere>(at + (0.002 - depth) * dir, 0.002); break;
      case 1: {  // a wall on the whisker's convex side (on its concave side a curved whisker meets it twice)
        const Eigen::Vector3d d = dir.dot(w.placement().R_WB.col(1)) > 0.0 ? Eigen::Vector3d(-dir) : dir;
        shape = std::make_unique<Plane>(at - depth * d, -d);
        break;
      }
      case 2: shape = std::make_unique<Cylinder>(at + (0.001 - depth) * dir, dir.cross(Eigen::Vector3d(u(rng), u(rng), 1.0)), 0.001); break;
      case 3: shape = std::make_unique<Box>(at + (0.002 - depth) * dir, Eigen::Vector3d(0.002, 0.002, 0.002),
                                            Eigen::Matrix3d(Eigen::AngleAxisd(6.0 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized())));
        break;
      default: X.p_WO = at + (0.003 - depth) * dir; break;
    }
    const ObjectContact o{shape ? shape.get() : &ball_mesh, X, true};
    // Objects that reach the base (half of the first millimetre) are not whisker contacts: drawn again.
    if (o.shape->signed_distance(o.X_WO.to_object(w.placement().to_world(w.rest_point_B(0.001)))) < 0.0005) continue;
    ++valid;
    const Solution s = solve_object(w, o);
    if (s.status == Status::second_contact) ++second;
    if (s.status != Status::converged) continue;
    ++converged;
    ++checked;
    const Eigen::Vector3d n = o.shape->nearest(o.X_WO.to_object(s.contact_point_W + 1e-7 * s.surface->normal_W)).normal;
    // Two contacts: each force along its own normal (the first's is the total less the second's).
    const Eigen::Vector3d first = s.second_contact ? Eigen::Vector3d(s.force_W - s.second_contact->force_W) : s.force_W;
    // At a crease the normal is a cone: a contact held on a mesh's edge whose load point lies just outside the
    // edge's region (its chord touches the edge) has its force along the edge's normal at the load point, off the
    // cone's face by an angle whose penetration r a^2 / 2 is below the 1e-9 m clearance (docs/objects.md).
    const double crease_cone = s.surface->feature == SurfaceFeature::edge ? 1e-2 : 1e-9;
    EXPECT_LT(first.normalized().cross(o.X_WO.R_WO * n).norm(), crease_cone) << i;
    if (s.second_contact) {
      ++two;
      const Eigen::Vector3d n2 =
          o.shape->nearest(o.X_WO.to_object(s.second_contact->contact_point_W + 1e-7 * s.second_contact->normal_W)).normal;
      EXPECT_LT(s.second_contact->force_W.normalized().cross(o.X_WO.R_WO * n2).norm(), 1e-9) << i;
      EXPECT_GT(s.second_contact->normal_force, 0.0) << i;
    }
    EXPECT_GE(whisker_clearance(w, o, s), -1e-9) << i << " " << o.shape->type();
  }
  EXPECT_GT(converged, 0.85 * valid);
  std::cout << "converged " << converged << " (two contacts " << two << "), second contact " << second << " of " << valid
            << "\n";
}

TEST(ObjectContact, FrictionZeroIsFrictionlessInfiniteSticksAndSlipMeetsTheCone) {
  const Whisker w = rat_whisker(100, tilted_pose());
  const Eigen::Vector3d target = w.placement().to_world(w.rest_point_B(0.022));
  const Eigen::Vector3d push = w.placement().R_WB.col(1);
  const Cylinder peg(target + 0.0015 * push, Eigen::Vector3d(0.3, -0.2, 1.0), 0.002);
  const ObjectContact o{&peg, {}, true};
  const Solution free = solve_object(w, o);
  ASSERT_EQ(free.status, Status::converged);
  // A previous contact 0.3 mm along the peg's axis from the frictionless one (on the surface).
  const Eigen::Vector3d previous = free.contact_point_W + 0.0003 * peg.axis();
  const Solution zero = solve_frictional_object(w, w.placement(), o, 0.0, previous);
  ASSERT_EQ(zero.status, Status::converged);
  EXPECT_EQ(zero.friction, FrictionState::slip);
  EXPECT_LT(relative(zero.force_W, free.force_W), 1e-12);
  const Solution stuck = solve_frictional_object(w, w.placement(), o, 1e9, previous);
  ASSERT_EQ(stuck.status, Status::converged) << stuck.message;
  EXPECT_EQ(stuck.friction, FrictionState::stick);
  // Stuck: the contact did not move across the whisker (along b) from the previous point.
  EXPECT_NEAR((stuck.contact_point_W - previous).dot(stuck.surface->friction_direction_W), 0.0, 1e-12);
  const double needed = std::abs(stuck.surface->friction_force) / *stuck.normal_force;
  ASSERT_GT(needed, 0.01);
  const double mu = 0.5 * needed;  // less than sticking needs: it slips, to the cone's edge
  const Solution slip = solve_frictional_object(w, w.placement(), o, mu, previous);
  ASSERT_EQ(slip.status, Status::converged) << slip.message;
  EXPECT_EQ(slip.friction, FrictionState::slip);
  EXPECT_NEAR(std::abs(slip.surface->friction_force), mu * *slip.normal_force, 1e-9 * *slip.normal_force);
  // The force has no part along the whisker in the tangent plane: F = F_n n + F_b b.
  const Eigen::Vector3d rest = slip.force_W - *slip.normal_force * slip.surface->normal_W -
                               slip.surface->friction_force * slip.surface->friction_direction_W;
  EXPECT_LT(rest.norm(), 1e-9 * slip.force_magnitude);
  // Between the previous point and the frictionless one (spec §3.1).
  const double from = (slip.contact_point_W - previous).dot(slip.surface->friction_direction_W);
  const double to = (free.contact_point_W - previous).dot(slip.surface->friction_direction_W);
  EXPECT_GT(slip.surface->friction_force * stuck.surface->friction_force, 0.0);  // opposing the same slip
  EXPECT_GT(from / to, 0.0);
  EXPECT_LT(from / to, 1.0);
}
