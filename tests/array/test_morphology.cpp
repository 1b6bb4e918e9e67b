// Array morphology: the data sheet's check values (rat-array-data.md §1, §2), mirror symmetry, the mapping of
// the sources' angle convention onto vibrissa's whisker frame (user tables: tests/io/morphology_table_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <numbers>

#include <Eigen/Geometry>

#include "vibrissa/array/morphology.hpp"
#include "../core/test_helpers.hpp"

using namespace vibrissa;
using namespace vibrissa::array;

namespace {
constexpr double mm = 1e-3;
double rad(double d) { return d * std::numbers::pi / 180.0; }

const WhiskerSpec& find(const Morphology& m, const std::string& label) {
  for (const auto& s : m.whiskers)
    if (s.label() == label) return s;
  throw std::runtime_error("no whisker " + label);
}
}  // namespace

TEST(Morphology, TowalHas31WhiskersPerSideAnd62InAll) {
  EXPECT_EQ(towal2011(Sides::right).whiskers.size(), 31u);
  EXPECT_EQ(towal2011(Sides::left).whiskers.size(), 31u);
  const Morphology both = towal2011(Sides::both);
  ASSERT_EQ(both.whiskers.size(), 62u);
  EXPECT_NO_THROW(find(both, "A0R"));
  EXPECT_NO_THROW(find(both, "E6L"));
  EXPECT_NO_THROW(find(both, "D6R"));
  EXPECT_THROW(find(both, "E0R"), std::runtime_error);  // the E row starts at column 1
  EXPECT_THROW(find(both, "A5R"), std::runtime_error);
}

TEST(Morphology, TowalCheckValuesOfTheDataSheet) {
  const Morphology m = towal2011(Sides::right);
  const WhiskerSpec& a0 = find(m, "A0R");
  const WhiskerSpec& e6 = find(m, "E6R");
  // Data sheet §1: A0 (5.359, -10.331, -0.461) mm, S 46.402 mm; E6 (5.081, -1.764, -8.023) mm, S 7.705 mm.
  EXPECT_NEAR(a0.p_H_base.x() / mm, 5.359, 1e-3);
  EXPECT_NEAR(a0.p_H_base.y() / mm, -10.331, 1e-3);
  EXPECT_NEAR(a0.p_H_base.z() / mm, -0.461, 1e-3);
  EXPECT_NEAR(e6.p_H_base.x() / mm, 5.081, 1e-3);
  EXPECT_NEAR(e6.p_H_base.y() / mm, -1.764, 1e-3);
  EXPECT_NEAR(e6.p_H_base.z() / mm, -8.023, 1e-3);
  EXPECT_NEAR(a0.arc_length / mm, 46.402, 1e-3);
  EXPECT_NEAR(e6.arc_length / mm, 7.705, 1e-3);
  EXPECT_NEAR(a0.curvature * mm, 0.01175, 5e-6);
  // Angles of A0 (COL 1, ROW 1): theta = 10.6475 + 37.3178, zeta = 18.77 - 11.3485 - 4.9844 (deg); phi by the
  // default 'projection' method: atan(tan(phi_P) cos(90° - theta)) with phi_P = 1.0988 - 18.0334 + 50.6005;
  // by 'euler': -15.8761 + 47.3263.
  EXPECT_NEAR(a0.theta_rest, rad(47.9653), 1e-9);
  EXPECT_NEAR(a0.phi_rest, std::atan(std::tan(rad(33.6659)) * std::cos(rad(42.0347))), 1e-12);
  EXPECT_NEAR(find(towal2011(Sides::right, PhiMethod::euler), "A0R").phi_rest, rad(31.4502), 1e-9);
  EXPECT_NEAR(a0.zeta_rest, rad(2.4371), 1e-9);
}

TEST(Morphology, TowalBasePointsLieOnThePadEllipsoid) {
  const Eigen::Vector3d centre(1.9128, -7.6549, -5.4439), radii(9.5304, 5.5393, 6.9745);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(rad(106.51), Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(rad(-2.5211), Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(rad(-19.5401), Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  for (const WhiskerSpec& s : towal2011(Sides::right).whiskers) {
    const Eigen::Vector3d local = R.transpose() * (s.p_H_base / mm - centre);
    EXPECT_NEAR(local.cwiseQuotient(radii).norm(), 1.0, 1e-12) << s.name;
  }
}

TEST(Morphology, LeftSideIsTheMirrorImageOfTheRight) {
  const Morphology both = towal2011(Sides::both);
  for (const std::string name : {"A0", "C2", "E6"}) {
    const WhiskerSpec& r = find(both, name + "R");
    const WhiskerSpec& l = find(both, name + "L");
    EXPECT_DOUBLE_EQ(l.p_H_base.x(), -r.p_H_base.x());
    EXPECT_DOUBLE_EQ(l.p_H_base.y(), r.p_H_base.y());
    EXPECT_DOUBLE_EQ(l.p_H_base.z(), r.p_H_base.z());
    const Whisker rest = make_rest_whisker(r, 20);
    const Eigen::Matrix3d Rr = R_HB(Side::right, r.theta_rest, r.phi_rest, r.zeta_rest);
    const Eigen::Matrix3d Rl = R_HB(Side::left, l.theta_rest, l.phi_rest, l.zeta_rest);
    EXPECT_NEAR(Rl.determinant(), 1.0, 1e-12);
    for (const Eigen::Vector3d& n : rest.rest_nodes_B()) {
      const Eigen::Vector3d pr = r.p_H_base + Rr * n, pl = l.p_H_base + Rl * n;
      EXPECT_NEAR(pl.x(), -pr.x(), 1e-15);
      EXPECT_NEAR(pl.y(), pr.y(), 1e-15);
      EXPECT_NEAR(pl.z(), pr.z(), 1e-15);
    }
  }
}

TEST(Morphology, SourceConventionMapsOntoTheWhiskerFrame) {
  // Data sheet §2: the source draws the whisker as (x, 0, -A x^2) and places it by Rz(theta - 90°)·Ry(-phi)·Rx(zeta).
  // vibrissa draws (x, A x^2, 0) in B; every node must land on the same point. Built here independently with
  // Eigen's AngleAxis.
  for (const WhiskerSpec& s : belli2018(Sides::right).whiskers) {
    const Eigen::Matrix3d R_src = (Eigen::AngleAxisd(s.theta_rest - rad(90), Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(-s.phi_rest, Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(s.zeta_rest, Eigen::Vector3d::UnitX()))
                                      .toRotationMatrix();
    const Eigen::Matrix3d R = R_HB(s.side, s.theta_rest, s.phi_rest, s.zeta_rest);
    const Whisker rest = make_rest_whisker(s, 30);
    for (const Eigen::Vector3d& n : rest.rest_nodes_B()) {
      EXPECT_NEAR(n.y(), s.curvature * n.x() * n.x(), 1e-12);  // vibrissa's parabola, concave toward +y
      const Eigen::Vector3d src = R_src * Eigen::Vector3d(n.x(), 0.0, -s.curvature * n.x() * n.x());
      EXPECT_NEAR((R * n - src).norm(), 0.0, 1e-14) << s.name;
    }
  }
}

TEST(Morphology, RightSideWhiskersPointOutwardAndDorsalRowsPointUp) {
  // The rest whiskers of the right side emerge laterally (+x of the head); row A (dorsal) points above row E.
  const Morphology m = towal2011(Sides::right);
  for (const WhiskerSpec& s : m.whiskers) {
    const Eigen::Vector3d x_H = R_HB(s.side, s.theta_rest, s.phi_rest, s.zeta_rest).col(0);
    EXPECT_GT(x_H.x(), 0.0) << s.name;
  }
  const auto up = [&](const std::string& l) {
    const WhiskerSpec& s = find(m, l);
    return R_HB(s.side, s.theta_rest, s.phi_rest, s.zeta_rest).col(0).z();
  };
  EXPECT_GT(up("A1R"), up("C1R"));
  EXPECT_GT(up("C1R"), up("E1R"));
}

TEST(Morphology, BelliTableAndBaseRadiusModel) {
  const Morphology m = belli2018(Sides::both);
  ASSERT_EQ(m.whiskers.size(), 54u);
  const WhiskerSpec& c1 = find(m, "C1R");
  EXPECT_NEAR(c1.arc_length / mm, 52.8, 1e-12);
  EXPECT_NEAR(c1.curvature * mm, 0.00694, 1e-12);
  EXPECT_NEAR(c1.zeta_rest, rad(-20.8), 1e-12);
  // d_base = 0.041 + 0.002 S + 0.011 row - 0.0039 col [mm] (data sheet §2): C1 -> 0.041 + 0.1056 + 0.033 - 0.0039.
  EXPECT_NEAR(belli_base_diameter_mm(52.8, 3, 1), 0.1757, 1e-12);
  EXPECT_NEAR(c1.base_radius, 0.5 * 0.1757 * mm, 1e-15);
  EXPECT_EQ(c1.taper_ratio, 15.0);
  EXPECT_EQ(find(m, "C1L").p_H_base.x(), -c1.p_H_base.x());
}

TEST(Morphology, BelliAndTowalAgreeOnTheRelativeLayout) {
  // The data sheet warns the Belli base-point mapping uses another origin: differences between two whiskers
  // must still agree with Towal's to ~1.5 mm.
  const Morphology t = towal2011(Sides::right), b = belli2018(Sides::right);
  const Eigen::Vector3d dt = find(t, "C1R").p_H_base - find(t, "C4R").p_H_base;
  const Eigen::Vector3d db = find(b, "C1R").p_H_base - find(b, "C4R").p_H_base;
  EXPECT_LT((dt - db).norm(), 1.5 * mm);
}

TEST(Morphology, ByNameAndUnknownNamesAreErrorsNamingTheField) {
  EXPECT_EQ(morphology_by_name("belli2018").whiskers.size(), 27u);
  try {
    morphology_by_name("towal2012");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("morphology.source"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("towal2012"), std::string::npos);
  }
  try {
    select_whiskers(towal2011(Sides::right), {"C2", "Z9"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("morphology.whiskers"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("Z9"), std::string::npos);
  }
  const Morphology sel = select_whiskers(towal2011(Sides::both), {"C2", "D1R"});
  EXPECT_EQ(sel.whiskers.size(), 3u);
}

// --- RatMap Toolbox v1.1 (tests/data/ratmap/README.md): placement and φ of every whisker, each TGL_PHI method ---
namespace {

struct RatMapRow {
  std::map<std::string, std::string> cell;
  [[nodiscard]] double num(const std::string& key) const { return std::stod(cell.at(key)); }
  /// "LA0" (toolbox) -> "A0L" (vibrissa's label).
  [[nodiscard]] std::string label() const {
    const std::string& w = cell.at("whisker");
    return w.substr(1) + w.substr(0, 1);
  }
};

std::vector<RatMapRow> read_ratmap(const std::string& file) {
  std::ifstream in(std::string(VIBRISSA_SOURCE_DIR) + "/tests/data/ratmap/" + file);
  if (!in) throw std::runtime_error("missing fixture " + file);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) header.push_back(c);
  std::vector<RatMapRow> rows;
  while (std::getline(in, line)) {
    RatMapRow r;
    std::stringstream ls(line);
    std::size_t i = 0;
    for (std::string c; std::getline(ls, c, ',');) r.cell[header.at(i++)] = c;
    rows.push_back(r);
  }
  return rows;
}

PhiMethod toolbox_method(const std::string& tgl_phi) {
  if (tgl_phi == "proj") return PhiMethod::projection;
  if (tgl_phi == "proj_phi_only") return PhiMethod::projection_phi_only;
  if (tgl_phi == "euler") return PhiMethod::euler;
  throw std::runtime_error("unknown TGL_PHI " + tgl_phi);
}

/// Toolbox point k of a whisker as vibrissa places it: the parabola point at the toolbox's x, mapped by
/// vibrissa's base point and R_HB.
Eigen::Vector3d placed_toolbox_point(const WhiskerSpec& s, const RatMapRow& r, int k, int points) {
  const double x = k * r.num("x_tip_mm") / (points - 1) * mm;
  return s.p_H_base + R_HB(s.side, s.theta_rest, s.phi_rest, s.zeta_rest) *
                          Eigen::Vector3d(x, s.curvature * x * x, 0.0);
}

}  // namespace

TEST(Morphology, TowalReproducesTheRatMapToolboxForEachPhiMethod) {
  // Every whisker of both sides, every point the toolbox returns, within 1 µm (measured: < 1e-13 m).
  const std::vector<RatMapRow> rows = read_ratmap("ratmap_v1_1.csv");
  ASSERT_EQ(rows.size(), 3u * 62u);
  constexpr int points = 4;
  std::map<std::string, double> worst;
  for (const RatMapRow& r : rows) {
    const std::string tgl = r.cell.at("method");
    const Morphology m = towal2011(Sides::both, toolbox_method(tgl));
    const WhiskerSpec& s = find(m, r.label());
    EXPECT_NEAR(s.arc_length / mm, r.num("s_mm"), 1e-12) << r.label();
    EXPECT_NEAR(s.curvature * mm, r.num("a_per_mm"), 1e-15) << r.label();
    EXPECT_NEAR(s.phi_rest, -r.num("phi_rad"), 1e-14) << tgl << " " << r.label();  // toolbox rotates by Ry(C_phi)
    for (int k = 0; k < points; ++k) {
      const std::string n = std::to_string(k);
      const Eigen::Vector3d ref(r.num("x" + n + "_mm"), r.num("y" + n + "_mm"), r.num("z" + n + "_mm"));
      const double error = (placed_toolbox_point(s, r, k, points) - ref * mm).norm();
      worst[tgl] = std::max(worst[tgl], error);
      EXPECT_LT(error, 1e-6) << tgl << " " << r.label() << " point " << k;
    }
  }
  for (const auto& [tgl, e] : worst) {
    std::cout << "RatMap " << tgl << ": worst point error " << e << " m\n";
    EXPECT_LT(e, 1e-12) << tgl;
  }
}

TEST(Morphology, TowalDefaultIsTheToolboxDefaultProjection) {
  // The default reproduces 'proj'; 'euler' moves the tip of A0 by millimetres (the reason for the option).
  const std::vector<RatMapRow> rows = read_ratmap("ratmap_v1_1.csv");
  const Morphology def = towal2011(Sides::right);
  const Morphology proj = towal2011(Sides::right, PhiMethod::projection);
  const Morphology euler = towal2011(Sides::right, PhiMethod::euler);
  for (std::size_t i = 0; i < def.whiskers.size(); ++i) EXPECT_EQ(def.whiskers[i].phi_rest, proj.whiskers[i].phi_rest);
  for (const RatMapRow& r : rows) {
    if (r.cell.at("method") != "proj" || r.label() != "A0R") continue;
    const double tip_shift = (placed_toolbox_point(find(proj, "A0R"), r, 3, 4) -
                              placed_toolbox_point(find(euler, "A0R"), r, 3, 4)).norm();
    EXPECT_GT(tip_shift, 3e-3);
    EXPECT_LT(tip_shift, 4e-3);
  }
}

TEST(Morphology, TowalElevationTakesTheToolboxBranchesForAnyProjectionTheta) {
  // 'W_th' overrides from 5° to 175° send both sides through every quadrant branch of 'proj' and 'proj_phi_only'.
  const std::vector<RatMapRow> rows = read_ratmap("ratmap_v1_1_phi_branches.csv");
  ASSERT_EQ(rows.size(), 2u * 8u * 62u);
  for (const RatMapRow& r : rows) {
    const std::string& w = r.cell.at("whisker");
    int row = 0, column = 0;
    parse_whisker_name(w.substr(1), row, column, "fixture");
    const Side side = w[0] == 'R' ? Side::right : Side::left;
    const double phi = towal_elevation(toolbox_method(r.cell.at("method")), side, r.num("theta_projection_deg"),
                                       column + 1, row);
    EXPECT_NEAR(phi, -r.num("phi_rad"), 1e-14) << r.cell.at("method") << " " << w << " " << r.cell.at("theta_projection_deg");
  }
  EXPECT_THROW(towal_elevation(PhiMethod::projection, Side::right, 181.0, 1, 1), std::invalid_argument);
}

TEST(Morphology, PhiMethodNamesAndUnknownOnesAreErrorsNamingTheField) {
  for (const PhiMethod m : {PhiMethod::projection, PhiMethod::projection_phi_only, PhiMethod::euler})
    EXPECT_EQ(phi_method_from_string(to_string(m)), m);
  EXPECT_EQ(test::invalid_message([] { phi_method_from_string("proj"); }),
            "morphology.phi_method must be 'projection', 'projection_phi_only' or 'euler', got 'proj'");
}
