// The paper scheme against Elastica3D v1 itself: force mode to 1e-9 relative, contact-point and peg
// modes to Elastica3D's own convergence (numbers and how they were made: tests/data/elastica3d/README.md).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vibrissa/core/cubic_spline.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa {
namespace {

const nlohmann::json& fixtures() {
  static const nlohmann::json j = [] {
    std::ifstream in(std::string(VIBRISSA_SOURCE_DIR) + "/tests/data/elastica3d/elastica3d_v1.json");
    return nlohmann::json::parse(in);
  }();
  return j;
}

Eigen::Vector3d vec(const nlohmann::json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

Whisker fixture_whisker(const std::string& name, const std::string& base) {
  std::vector<Eigen::Vector3d> nodes;
  for (const auto& p : fixtures()["whiskers"][name]) nodes.push_back(vec(p));
  WhiskerProperties props;  // E = 3.3 GPa, nu = 0.38, r 100 um -> 100/15 um linear in arc length, as given to Elastica3D
  props.scheme = Scheme::paper;
  props.base = base == "rigid" ? BaseJoint::rigid : BaseJoint::elastic;
  return Whisker::from_points(nodes, props);
}

void expect_close(const Eigen::Vector3d& got, const Eigen::Vector3d& want, double rel, const std::string& what) {
  EXPECT_LE((got - want).norm(), rel * want.norm()) << what << ": got " << got.transpose() << ", want "
                                                    << want.transpose();
}

TEST(CubicSpline, MatchesMatlabNotAKnot) {
  // Octave 7.3: spline(0:5, (0:5).^4, [-0.5 2.5 5.5]) = -5 39.0625 910 (a quartic is not reproduced).
  const CubicSpline sp = CubicSpline::not_a_knot({0, 1, 2, 3, 4, 5}, {0, 1, 16, 81, 256, 625});
  EXPECT_NEAR(sp(-0.5), -5.0, 1e-12);
  EXPECT_NEAR(sp(5.5), 910.0, 1e-10);
  EXPECT_NEAR(sp(3.0), 81.0, 1e-12);
  const CubicSpline cubic = CubicSpline::not_a_knot({0, 0.5, 2, 3, 7}, {0, 0.125, 8, 27, 343});  // exact for cubics
  EXPECT_NEAR(cubic(1.5), 3.375, 1e-12);
  EXPECT_NEAR(cubic(8.0), 512.0, 1e-9);
}

TEST(Elastica3D, ForceModeAgreesToRoundOff) {
  int n = 0;
  for (const auto& c : fixtures()["force_mode"]) {
    const Whisker w = fixture_whisker(c["whisker"], c["base"]);
    const double zeta = c["zeta"];
    const Solution s = solve_force(w, c["force"].get<double>(), c["arc_length"].get<double>(), zeta);
    const std::string what = std::string(c["whisker"]) + " f=" + c["force"].dump() + " s=" + c["arc_length"].dump() +
                             " zeta=" + c["zeta"].dump();
    expect_close(s.force_W, vec(c["force_W"]), 1e-9, what + " force");
    expect_close(s.moment_W, vec(c["moment_W"]), 1e-9, what + " moment");
    expect_close(s.contact_point_W, vec(c["contact_W"]), 1e-9, what + " contact");
    EXPECT_NEAR(std::remainder(s.angle - zeta, 2 * std::numbers::pi), 0.0, 1e-12) << what;
    ++n;
  }
  EXPECT_EQ(n, 15);
}

TEST(Elastica3D, ContactModesReturnItsRoots) {
  for (const auto& c : fixtures()["contact_modes"]) {
    const Whisker w = fixture_whisker(c["whisker"], "elastic");
    const auto& ref = c["elastica3d"];
    const double s_ref = ref["arc_length"];
    const std::string what = std::string(c["mode"]) + " " + std::string(c["whisker"]) + " s=" + ref["arc_length"].dump();
    const Solution s = c["mode"] == "point" ? solve_point(w, vec(c["point_W"]), s_ref)
                                            : solve_edge(w, Edge{vec(c["point_W"]), vec(c["direction_W"])}, s_ref);
    ASSERT_EQ(s.status, Status::converged) << what;
    EXPECT_NEAR(s.arc_length, s_ref, 1e-10 * w.length()) << what;
    expect_close(s.force_W, vec(ref["force_W"]), 1e-8, what + " force");
    expect_close(s.moment_W, vec(ref["moment_W"]), 1e-8, what + " moment");
    expect_close(s.contact_point_W, vec(ref["contact_W"]), 1e-9, what + " contact");
  }
}

TEST(Elastica3D, PointModeThroughAForceModeContactReturnsThatLoad) {
  // Its Nelder-Mead found another root for these points; hinted at the load's s, vibrissa returns the load,
  // and lists Elastica3D's root among the roots it found. (The 2 mN load at 21 mm: the next test.)
  for (const auto& c : fixtures()["contact_modes"]) {
    if (c["mode"] != "point" || c["made_by"]["force"].get<double>() > 1e-3) continue;
    const Whisker w = fixture_whisker(c["whisker"], "elastic");
    const auto& made = c["made_by"];
    const double f = made["force"], s_made = made["arc_length"];
    const Solution s = solve_point(w, vec(c["point_W"]), s_made);
    const std::string what = std::string(c["whisker"]) + " f=" + made["force"].dump() + " s=" + made["arc_length"].dump();
    ASSERT_EQ(s.status, Status::converged) << what;
    const Solution forward = solve_force(w, f, s_made, made["zeta"].get<double>());
    // A load exactly at a node is a root of the re-mesh at that node (s within round-off of it).
    EXPECT_NEAR(s.arc_length, s_made, 1e-10 * w.length()) << what;
    expect_close(s.force_W, forward.force_W, 1e-8, what + " force");
    const double s_elastica = c["elastica3d"]["arc_length"];
    bool listed = false;
    for (const Root& r : s.roots) listed = listed || std::abs(r.arc_length - s_elastica) < 1e-9 * w.length();
    EXPECT_TRUE(listed || std::abs(s_elastica - s_made) < 1e-9) << what << ": Elastica3D's root s=" << s_elastica;
  }
}

TEST(Elastica3D, HintedPointModeReturnsTheLoadJustPastARestNode) {
  // The 2 mN load at 21 mm (zeta 2.5), ~0.9 um past a rest node: a neighbouring root lies 7 um before it
  // (|F| 1.25 mN) and Elastica3D's at 17.3 mm. The load is ~7 E I_0 / L^2, out of reach of the fixed-s start
  // from zero force, so the scan used to return the neighbour; hinted at the load's s, point mode must return
  // the force-mode load itself and still list Elastica3D's root.
  int n = 0;
  for (const auto& c : fixtures()["contact_modes"]) {
    if (c["mode"] != "point" || c["made_by"]["force"].get<double>() < 1.5e-3) continue;
    const Whisker w = fixture_whisker(c["whisker"], "elastic");
    const auto& made = c["made_by"];
    const double f = made["force"], s_made = made["arc_length"];
    const Solution forward = solve_force(w, f, s_made, made["zeta"].get<double>());
    const Solution s = solve_point(w, vec(c["point_W"]), s_made);
    ASSERT_EQ(s.status, Status::converged);
    EXPECT_NEAR(s.arc_length, s_made, 1e-10 * w.length());
    EXPECT_NEAR(s.force_magnitude, f, 1e-8 * f);
    expect_close(s.force_W, forward.force_W, 1e-8, "force");
    expect_close(s.contact_point_W, forward.contact_point_W, 1e-9, "contact");
    const double s_elastica = c["elastica3d"]["arc_length"];
    bool neighbour = false, elastica = false;
    for (const Root& r : s.roots) {
      neighbour = neighbour || (std::abs(r.arc_length - s_made) > 1e-6 && std::abs(r.arc_length - s_made) < 1e-5);
      elastica = elastica || std::abs(r.arc_length - s_elastica) < 1e-9 * w.length();
    }
    EXPECT_TRUE(neighbour) << "the neighbouring root 7 um before the load is a real root";
    EXPECT_TRUE(elastica) << "Elastica3D's root s=" << s_elastica;
    ++n;
  }
  EXPECT_EQ(n, 1);
}

}  // namespace
}  // namespace vibrissa
