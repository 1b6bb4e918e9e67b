// The two-contact equilibrium of the object modes (docs/objects.md, "Two contacts"): the chain under two loads
// against the one-load walk, and a whisker pressed against an object at two places.
#include <gtest/gtest.h>

#include <vector>

#include "../../src/solve/two_contact.hpp"
#include "../core/test_helpers.hpp"
#include "vibrissa/core/chain.hpp"
#include "vibrissa/objects/clearance.hpp"
#include "vibrissa/objects/cylinder.hpp"
#include "vibrissa/solve/object_contact.hpp"

using namespace vibrissa;
using vibrissa::test::rat_whisker;

namespace {

LoadState load(double fx, double fy, double fz, double s) {
  LoadState l;
  l.force_x = fx;
  l.force_y = fy;
  l.force_z = fz;
  l.arc_length = s;
  return l;
}

}  // namespace

TEST(TwoContact, TwoLoadWalkIsTheOneLoadWalkWhereOneLoadIsZeroOrBothAreAtOnePoint) {
  const Whisker w = rat_whisker(60, Pose{});
  const double s1 = 0.0123, s2 = 0.0271;
  const LoadState a = load(1e-6, 2e-4, -1e-4, s1), b = load(0.0, -5e-5, 3e-4, s2);
  // A zero second load: the one-load walk (contact point, force, load frame axes, joint rotations).
  std::vector<Eigen::Vector3d> omega1(static_cast<std::size_t>(w.links())), omega2(omega1.size());
  FollowerVectors<double> follow{V3<double>(1, 0, 0), V3<double>(0, 1, 0)};
  const auto one = deflect<double, true>(w, V3<double>(a.force_x, a.force_y, a.force_z), V3<double>(0, 0, 0), s1,
                                         omega1.data(), &follow);
  const detail::TwoLoadKinematics two = detail::deflect_two_loads(w, {a, load(0.0, 0.0, 0.0, s2)}, omega2.data());
  EXPECT_LT((two.p_B[0] - to_eigen(one.p_contact_B)).norm(), 1e-15);
  EXPECT_LT((two.F_B[0] - to_eigen(one.force_B)).norm(), 1e-12 * to_eigen(one.force_B).norm());
  EXPECT_LT((two.t_B[0] - to_eigen(follow[0])).norm(), 1e-13);
  EXPECT_LT((two.y_B[0] - to_eigen(follow[1])).norm(), 1e-13);
  for (std::size_t j = 0; j < omega1.size(); ++j) EXPECT_LT((omega1[j] - omega2[j]).norm(), 1e-15) << j;
  // Both at one arc length: one load of their sum (the same load frame).
  const LoadState b_at_a = load(b.force_x, b.force_y, b.force_z, s1);
  const auto sum = deflect<double>(w, V3<double>(a.force_x + b.force_x, a.force_y + b.force_y, a.force_z + b.force_z),
                                   V3<double>(0, 0, 0), s1);
  const detail::TwoLoadKinematics both = detail::deflect_two_loads(w, {a, b_at_a});
  EXPECT_LT((both.p_B[0] - to_eigen(sum.p_contact_B)).norm(), 1e-15);
  EXPECT_LT((both.F_B[0] + both.F_B[1] - to_eigen(sum.force_B)).norm(), 1e-12 * to_eigen(sum.force_B).norm());
  // The order of the loads does not matter.
  const detail::TwoLoadKinematics ab = detail::deflect_two_loads(w, {a, b}), ba = detail::deflect_two_loads(w, {b, a});
  EXPECT_LT((ab.p_B[0] - ba.p_B[1]).norm(), 1e-16);
  EXPECT_LT((ab.p_B[1] - ba.p_B[0]).norm(), 1e-16);
}
