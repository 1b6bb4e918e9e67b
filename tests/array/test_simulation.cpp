// Full-array simulation: contact onset from the sweep, push-past and release, mirror symmetry, invariance to
// a rigid motion of head + object, eq. (7), and config errors that name the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>

#include "vibrissa/array/error_bound.hpp"
#include "vibrissa/array/morphology.hpp"
#include "vibrissa/array/sweep.hpp"
#include "vibrissa/core/pose.hpp"
#include "vibrissa/io/array_config.hpp"

using namespace vibrissa;
using namespace vibrissa::array;
using nlohmann::json;

namespace {
double rad(double d) { return d * std::numbers::pi / 180.0; }

json base_config() {
  json j = io::default_array_config_json();
  j["output"]["render_count"] = 0;
  return j;
}

std::size_t whisker_index(const ArrayResult& r, const std::string& label) {
  for (std::size_t w = 0; w < r.labels.size(); ++w)
    if (r.labels[w] == label) return w;
  throw std::runtime_error("no " + label);
}

int first_frame(const ArrayResult& r, std::size_t w, ContactState s, std::size_t p = 0) {
  for (std::size_t f = 0; f < r.n_frames; ++f)
    if (r.state_at(p, w, f) == s) return static_cast<int>(f);
  return -1;
}

void expect_config_error(const json& j, const std::string& field) {
  try {
    io::array_config_from_json(j);
    FAIL() << "no error for " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(ArraySimulation, DefaultSceneTouchesSeveralWhiskersAndSomePushPast) {
  const ArrayResult r = simulate_array(io::array_config_from_json(base_config()));
  const auto summary = summarize_pitches(r);
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_GE(summary[0].whiskers_touching, 5u);
  EXPECT_GE(summary[0].whiskers_pushed_past, 1u);
  EXPECT_GT(summary[0].peak_MB, 1e-7);  // µN·m scale (spec Fig. 3)
  EXPECT_LT(summary[0].peak_MB, 1e-4);
}

TEST(ArraySimulation, ContactBeginsInTheFrameInWhichTheRestWhiskerCrossesThePeg) {
  json j = base_config();
  j["morphology"]["whiskers"] = {"C2"};
  j["time"]["frames"] = 2000;
  const SimulationConfig c = io::array_config_from_json(j);
  const ArrayResult r = simulate_array(c);
  const int on = first_frame(r, 0, ContactState::contact);
  ASSERT_GT(on, 0);
  // Independent check on the rest whisker: seen from above (the peg is vertical), the peg's (x, y) changes side
  // of the whisker between frames on-1 and on, at a node distance along the whisker within its length.
  const WhiskerSpec& s = c.morphology.whiskers[0];
  const Whisker rest = make_rest_whisker(s, c.links);
  const Eigen::Vector2d peg(0.020, -0.008);
  auto side_and_reach = [&](int f, double& reach) {
    const WhiskerAngles a = angles_at(s, c.whisking, c.times[static_cast<std::size_t>(f)]);
    const Eigen::Matrix3d R = R_HB(s.side, a.theta, a.phi, a.zeta);
    double best = 1e9, sgn = 0.0;
    const auto& n = rest.rest_nodes_B();
    for (std::size_t i = 0; i + 1 < n.size(); ++i) {
      const Eigen::Vector3d p0 = s.p_H_base + R * n[i], p1 = s.p_H_base + R * n[i + 1];
      const Eigen::Vector2d a2 = p0.head<2>(), t = (p1 - p0).head<2>();
      const double u = std::clamp((peg - a2).dot(t) / t.squaredNorm(), 0.0, 1.0);
      const double d = (a2 + u * t - peg).norm();
      if (d < best) {
        best = d;
        sgn = t.x() * (peg - a2).y() - t.y() * (peg - a2).x();
        reach = u;
      }
    }
    return sgn;
  };
  double reach0 = 0, reach1 = 0;
  EXPECT_LT(side_and_reach(on - 1, reach0) * side_and_reach(on, reach1), 0.0);
  EXPECT_EQ(r.state_at(0, 0, static_cast<std::size_t>(on - 1)), ContactState::free);
  // At onset the whisker has barely bent: the contact lies on the peg at the rest whisker's crossing height.
  const std::size_t k = r.index(0, 0, static_cast<std::size_t>(on));
  EXPECT_NEAR(r.contact_W[3 * k], 0.020, 1e-9);
  EXPECT_NEAR(r.contact_W[3 * k + 1], -0.008, 1e-9);
  EXPECT_LT(r.FT[k], 1e-6);
  // A coarser time grid finds the onset within one of its frame steps.
  j["time"]["frames"] = 200;
  const ArrayResult coarse = simulate_array(io::array_config_from_json(j));
  const int on_coarse = first_frame(coarse, 0, ContactState::contact);
  ASSERT_GT(on_coarse, 0);
  EXPECT_LE(coarse.times[static_cast<std::size_t>(on_coarse - 1)], r.times[static_cast<std::size_t>(on)]);
  EXPECT_GE(coarse.times[static_cast<std::size_t>(on_coarse)], r.times[static_cast<std::size_t>(on - 1)]);
}

TEST(ArraySimulation, PushPastThenReleaseOnRetraction) {
  json j = base_config();
  j["time"]["end_s"] = 0.125;  // a whole whisk: protraction then retraction
  j["time"]["frames"] = 500;
  const ArrayResult r = simulate_array(io::array_config_from_json(j));
  int pushed_whiskers = 0;
  for (std::size_t w = 0; w < r.n_whiskers; ++w) {
    const int pp = first_frame(r, w, ContactState::pushed_past);
    if (pp < 0) continue;
    ++pushed_whiskers;
    // Pushed past only out of contact, and it lasts until the rest whisker crosses back on retraction.
    EXPECT_EQ(r.state_at(0, w, static_cast<std::size_t>(pp - 1)), ContactState::contact) << r.labels[w];
    std::size_t f = static_cast<std::size_t>(pp);
    while (f < r.n_frames && r.state_at(0, w, f) == ContactState::pushed_past) ++f;
    ASSERT_LT(f, r.n_frames) << r.labels[w] << " never released";
    EXPECT_EQ(r.state_at(0, w, f), ContactState::free) << r.labels[w];
    EXPECT_GT(r.times[f], 0.0625) << r.labels[w] << " released before retraction began";
    EXPECT_EQ(r.state_at(0, w, r.n_frames - 1), ContactState::free) << r.labels[w];
  }
  EXPECT_GE(pushed_whiskers, 1);
}

TEST(ArraySimulation, LeftAndRightSignalsMirrorInASymmetricScene) {
  json j = base_config();
  j["morphology"]["sides"] = "both";
  j["morphology"]["whiskers"] = {"B2", "C1", "C2", "C3", "D1", "D2"};
  j["objects"] = json::array({json{{"type", "peg"}, {"point_mm", {20, -8, -3}}},
                              json{{"type", "peg"}, {"point_mm", {-20, -8, -3}}}});
  const ArrayResult r = simulate_array(io::array_config_from_json(j));
  int touched = 0;
  for (const std::string name : {"B2", "C1", "C2", "C3", "D1", "D2"}) {
    const std::size_t R = whisker_index(r, name + "R"), L = whisker_index(r, name + "L");
    for (std::size_t f = 0; f < r.n_frames; ++f) {
      ASSERT_EQ(r.state_at(0, R, f), r.state_at(0, L, f)) << name << " frame " << f;
      if (r.state_at(0, R, f) != ContactState::contact) continue;
      ++touched;
      const std::size_t kr = r.index(0, R, f), kl = r.index(0, L, f);
      EXPECT_NEAR(r.MB[kl], r.MB[kr], 1e-9 * r.MB[kr] + 1e-15);
      EXPECT_NEAR(r.FT[kl], r.FT[kr], 1e-9 * r.FT[kr] + 1e-12);
      EXPECT_NEAR(r.s_applied[kl], r.s_applied[kr], 1e-10);
      const Eigen::Vector3d flip(-1, 1, 1);
      EXPECT_NEAR((r.vec(r.contact_W, 0, L, f) - flip.cwiseProduct(r.vec(r.contact_W, 0, R, f))).norm(), 0.0, 1e-10);
      EXPECT_NEAR((r.vec(r.force_W, 0, L, f) - flip.cwiseProduct(r.vec(r.force_W, 0, R, f))).norm(), 0.0,
                  1e-9 * r.FT[kr] + 1e-12);
      // In the whisker frame the mirror flips z_B only: (Fx, Fy, -Fz).
      const Eigen::Vector3d flip_z(1, 1, -1);
      EXPECT_NEAR((r.vec(r.force_B, 0, L, f) - flip_z.cwiseProduct(r.vec(r.force_B, 0, R, f))).norm(), 0.0,
                  1e-9 * r.FT[kr] + 1e-12);
    }
  }
  EXPECT_GT(touched, 50);
}

TEST(ArraySimulation, RigidMotionOfHeadAndObjectTogetherChangesNothingButTheFrame) {
  json a = base_config();
  a["morphology"]["whiskers"] = {"B2", "C2", "C3", "D2"};
  a["objects"] = json::array({json{{"type", "edge"}, {"point_mm", {20, -8, -3}}, {"direction", {0.1, 0.2, 1.0}}}});
  json b = a;
  const Eigen::Matrix3d R = rotation_z(rad(25)) * rotation_x(rad(-15)) * rotation_y(rad(10));
  const Eigen::Vector3d t(0.004, -0.012, 0.007);
  b["head"]["position_mm"] = {t.x() * 1e3, t.y() * 1e3, t.z() * 1e3};
  b["head"]["yaw_deg"] = 25;
  b["head"]["pitch_deg"] = -15;
  b["head"]["roll_deg"] = 10;
  const Eigen::Vector3d p = R * Eigen::Vector3d(0.020, -0.008, -0.003) + t;
  const Eigen::Vector3d d = R * Eigen::Vector3d(0.1, 0.2, 1.0);
  b["objects"][0]["point_mm"] = {p.x() * 1e3, p.y() * 1e3, p.z() * 1e3};
  b["objects"][0]["direction"] = {d.x(), d.y(), d.z()};
  const ArrayResult ra = simulate_array(io::array_config_from_json(a)), rb = simulate_array(io::array_config_from_json(b));
  int contacts = 0;
  for (std::size_t w = 0; w < ra.n_whiskers; ++w)
    for (std::size_t f = 0; f < ra.n_frames; ++f) {
      ASSERT_EQ(ra.state_at(0, w, f), rb.state_at(0, w, f)) << ra.labels[w] << " frame " << f;
      if (ra.state_at(0, w, f) != ContactState::contact) continue;
      ++contacts;
      const std::size_t k = ra.index(0, w, f);
      EXPECT_NEAR(rb.MB[k], ra.MB[k], 1e-7 * ra.MB[k] + 1e-15);
      EXPECT_NEAR(rb.s_applied[k], ra.s_applied[k], 1e-9);
      EXPECT_NEAR((rb.vec(rb.force_B, 0, w, f) - ra.vec(ra.force_B, 0, w, f)).norm(), 0.0, 1e-7 * ra.FT[k] + 1e-12);
      EXPECT_NEAR((rb.vec(rb.contact_W, 0, w, f) - (R * ra.vec(ra.contact_W, 0, w, f) + t)).norm(), 0.0, 1e-9);
      EXPECT_NEAR((rb.vec(rb.force_W, 0, w, f) - R * ra.vec(ra.force_W, 0, w, f)).norm(), 0.0, 1e-7 * ra.FT[k] + 1e-12);
    }
  EXPECT_GT(contacts, 20);
}

TEST(ArraySimulation, HeadPitchSweepChangesTheSignalsButAHeadFixedPegDoesNot) {
  json j = base_config();
  j["morphology"]["whiskers"] = {"C1", "C2", "D1", "D2"};
  j["head"]["pitches_deg"] = {-10, 0, 15};
  const ArrayResult world = simulate_array(io::array_config_from_json(j));
  const auto s = summarize_pitches(world);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NE(s[0].peak_MB, s[2].peak_MB);
  j["objects"][0]["frame"] = "head";
  const ArrayResult head = simulate_array(io::array_config_from_json(j));
  const auto h = summarize_pitches(head);
  EXPECT_NEAR(h[0].peak_MB, h[2].peak_MB, 1e-9 * h[0].peak_MB);
}

TEST(ArraySimulation, PrismContactIsWithWhicheverEdgeTheWhiskerReaches) {
  json j = base_config();
  j["morphology"]["whiskers"] = {"C1", "C2", "C3", "D2", "B2"};
  j["objects"] = json::array({json{{"type", "prism"},
                                   {"vertices_mm", {{20, -8, -15}, {26, -10, -15}, {24, -2, -15}}},
                                   {"axis", {0, 0, 1}},
                                   {"length_mm", 30}}});
  const ArrayResult r = simulate_array(io::array_config_from_json(j));
  std::set<int> edges;
  for (std::size_t i = 0; i < r.state.size(); ++i)
    if (r.state[i] == static_cast<std::int8_t>(ContactState::contact)) edges.insert(r.edge[i]);
  ASSERT_FALSE(edges.empty());
  for (int e : edges) EXPECT_TRUE(e >= 0 && e < 3);
}

TEST(ErrorBound, EquationSevenAndFive) {
  // eq. (5): L = R_base / (R_base - R_tip) S = 15/14 S for a taper of 15.
  EXPECT_NEAR(cone_length(0.03, 15.0), 0.03 * 15.0 / 14.0, 1e-15);
  const double L = 0.03 * 15.0 / 14.0, s = 0.01, E = 3.3e9, R = 100e-6, mu = 0.48, FN = 1e-3;
  const double expected = 4.0 * L / (3.0 * E * std::numbers::pi * std::pow(R, 4)) * mu * FN * s * s * s / (L - s);
  EXPECT_NEAR(contact_error_bound(+0.5, mu, FN, s, 0.03, R, 15.0, E), expected, 1e-12 * expected);
  EXPECT_NEAR(contact_error_bound(-0.5, mu, FN, s, 0.03, R, 15.0, E), -expected, 1e-12 * expected);
  EXPECT_EQ(contact_error_bound(0.0, mu, FN, s, 0.03, R, 15.0, E), 0.0);
  EXPECT_EQ(contact_error_bound(1.0, 0.0, FN, s, 0.03, R, 15.0, E), 0.0);
  // About 1 mm for a 1 mN normal force at 1 cm on a 3 cm whisker (the scale of Fig. 4b).
  EXPECT_GT(expected, 1e-4);
  EXPECT_LT(expected, 1e-2);
}

TEST(ArrayConfig, InvalidConfigsNameTheField) {
  json j = base_config();
  j["morphology"]["whiskers"] = {"C2", "X7"};
  expect_config_error(j, "morphology.whiskers");
  j = base_config();
  j["objects"] = json::array({json{{"type", "edge"}, {"point_mm", {1, 2, 3}}, {"direction", {0, 0, 1}}, {"length_mm", 0}}});
  expect_config_error(j, "objects[0].length_mm");
  j = base_config();
  j["objects"][0]["type"] = "edge";
  j["objects"][0]["direction"] = {0, 0, 0};
  expect_config_error(j, "objects[0].direction");
  j = base_config();
  j["whisking"]["amplitude_deg"] = "nan";
  expect_config_error(j, "whisking.amplitude_deg");
  j = base_config();
  j["head"]["pitches_deg"] = {0, "NaN"};
  expect_config_error(j, "head.pitches_deg[1]");
  j = base_config();
  j["head"]["pitches_deg"] = {-180, 1e300};  // --pitches=1e300 ran a meaningless pose before
  expect_config_error(j, "head.pitches_deg[1] must lie in [-180, 180], got 1e+300");
  j = base_config();
  j["head"]["pich_deg"] = 5;
  expect_config_error(j, "head.pich_deg");
  j = base_config();
  j["whisking"]["slopes"] = "towal";
  expect_config_error(j, "whisking.slopes");
  j = base_config();
  j["time"]["frames"] = 1;
  expect_config_error(j, "time.frames");
  j = base_config();
  j["morphology"]["source"] = "missing_table.csv";
  expect_config_error(j, "morphology.source");
  j = base_config();
  j["morphology"]["phi_method"] = "proj";  // the toolbox's spelling is not vibrissa's
  expect_config_error(j, "morphology.phi_method must be 'projection', 'projection_phi_only' or 'euler', got 'proj'");
  j = base_config();
  j["morphology"]["source"] = "belli2018";
  j["morphology"]["phi_method"] = "euler";  // Belli's table gives φ directly
  expect_config_error(j, "morphology.phi_method applies only to source 'towal2011', got source 'belli2018'");
}

TEST(ArrayConfig, PhiMethodSelectsTheTowalElevation) {
  json j = base_config();
  j["morphology"]["whiskers"] = {"E1"};
  const double projection = io::array_config_from_json(j).morphology.whiskers.at(0).phi_rest;
  j["morphology"]["phi_method"] = "euler";
  const double euler = io::array_config_from_json(j).morphology.whiskers.at(0).phi_rest;
  EXPECT_EQ(projection,
            array::select_whiskers(array::towal2011(array::Sides::right), {"E1"}).whiskers.at(0).phi_rest);
  EXPECT_GT(std::abs(projection - euler), 0.01);
  EXPECT_NEAR(euler, (-15.8761 * 5 + 47.3263) * std::numbers::pi / 180.0, 1e-12);  // Euler-φ regression, ROW 5
}

// `vibrissa array --dynamics` (docs/dynamics.md): the bases follow the array's kinematics exactly as in the
// quasi-static run (time offset and head pitch included), a whisking whisker carries inertial base signals, a
// still one none, and the config's "dynamics" is checked.
TEST(ArrayDynamics, BasesFollowTheArrayKinematicsAndStillWhiskersCarryNothing) {
  json j = base_config();
  j["morphology"]["whiskers"] = json::array({"C1", "D2"});
  j["objects"] = json::array({{{"type", "peg"}, {"point_mm", {200.0, -8.0, -3.0}}}});  // out of reach: in air
  j["time"] = {{"start_s", 0.03}, {"end_s", 0.0925}, {"frames", 126}};
  j["head"]["pitches_deg"] = json::array({0.0, 10.0});
  j["solver"]["links"] = 40;
  const ArrayResult quasi = simulate_array(io::array_config_from_json(j));
  j["dynamics"] = json::object();
  const ArrayResult dyn = simulate_array(io::array_config_from_json(j));
  ASSERT_EQ(dyn.base_W.size(), quasi.base_W.size());
  for (std::size_t i = 0; i < dyn.base_W.size(); ++i) EXPECT_NEAR(dyn.base_W[i], quasi.base_W[i], 1e-12);
  EXPECT_EQ(dyn.theta, quasi.theta);
  ASSERT_EQ(dyn.tip_displacement_B.size(), dyn.force_B.size());
  double peak = 0.0;
  for (std::size_t k = 0; k < dyn.MB.size(); ++k) {
    EXPECT_EQ(dyn.state[k], 0);  // in air
    peak = std::max(peak, dyn.MB[k]);
  }
  EXPECT_GT(peak, 1e-9);  // tens of nN m: a whisk's inertia
  EXPECT_GT(dyn.dynamics_steps, 0u);
  ASSERT_EQ(array_warnings(dyn).size(), 1u);  // nothing touched: the scene is out of reach (as without dynamics)
  // No whisking and a still head: the follicle carries nothing (to rounding).
  j["whisking"]["amplitude_deg"] = 0.0;
  const ArrayResult still = simulate_array(io::array_config_from_json(j));
  for (double m : still.MB) EXPECT_LT(m, 1e-16);  // rounding of the differentiated placements, 1e-8 of a whisk
  j["dynamics"] = {{"density", -1.0}};
  expect_config_error(j, "dynamics.density");
  j["dynamics"] = {{"modes", 0}};  // "all" or a count >= 1
  expect_config_error(j, "dynamics.modes");
  j["dynamics"] = {{"modes", "some"}};
  expect_config_error(j, "dynamics.modes");
  j["dynamics"] = {{"modes", "all"}};
  EXPECT_EQ(io::array_config_from_json(j).dynamics->modes, 0);
  j["dynamics"] = {{"modes", 40}};
  EXPECT_EQ(io::array_config_from_json(j).dynamics->modes, 40);
}

namespace vibrissa::array {
namespace {

// `vibrissa array --dynamics` against the array's objects (docs/dynamics.md, "vibrissa array --dynamics"): C2
// whisks into the default peg (an infinite edge, world-fixed); the integrator touches it where the quasi-static
// run does (onset within a frame), the frames in contact carry the contact (edge, arc length, point on the edge)
// and the base moment peaks within 2 % of the quasi-static peak (8 Hz whisking: inertia and the joint dampers
// add little to a contact moment); the events are recorded per whisker.
TEST(ArrayDynamics, AWhiskerWhiskingIntoThePegTouchesItAsTheQuasiStaticRunDoes) {
  json j = base_config();
  j["morphology"]["whiskers"] = json::array({"C2"});
  j["solver"]["links"] = 40;
  j["time"] = {{"start_s", 0.0}, {"end_s", 0.0625}, {"frames", 126}};
  const ArrayResult quasi = simulate_array(io::array_config_from_json(j));
  j["dynamics"] = json::object();
  const ArrayResult dyn = simulate_array(io::array_config_from_json(j));
  const int onset = first_frame(quasi, 0, ContactState::contact);
  ASSERT_GE(onset, 0);
  ASSERT_EQ(dyn.contact_events.size(), 1u);
  const auto& events = dyn.contact_events[0];
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front().type, dynamics::ContactEventType::touch);
  const double frame = dyn.times[1] - dyn.times[0];
  EXPECT_LE(events.front().time, quasi.times[static_cast<std::size_t>(onset)]);
  EXPECT_GT(events.front().time, quasi.times[static_cast<std::size_t>(onset)] - frame);
  double peak_quasi = 0.0, peak_dyn = 0.0;
  int both = 0;
  for (std::size_t f = 0; f < dyn.n_frames; ++f) {
    peak_quasi = std::max(peak_quasi, quasi.MB[f]);
    peak_dyn = std::max(peak_dyn, dyn.MB[f]);
    if (dyn.state_at(0, 0, f) != ContactState::contact) continue;
    EXPECT_EQ(dyn.edge[f], 0);
    EXPECT_GT(dyn.s_applied[f], 0.0);
    // The contact point lies on the peg's line (x = 20 mm, y = -8 mm), to the penalty's penetration.
    EXPECT_NEAR(dyn.contact_W[3 * f], 0.020, 1e-6);
    EXPECT_NEAR(dyn.contact_W[3 * f + 1], -0.008, 1e-6);
    if (quasi.state_at(0, 0, f) == ContactState::contact) ++both;
  }
  EXPECT_GT(both, 20);
  EXPECT_NEAR(peak_dyn, peak_quasi, 0.02 * peak_quasi);
  std::printf("C2 into the peg: touch at %.4f s (quasi-static onset frame %.4f s), peak M_B %.4g vs %.4g N m\n",
              events.front().time, quasi.times[static_cast<std::size_t>(onset)], peak_dyn, peak_quasi);
}

// Events are contact episodes: D3 slides off the peg's line across the nodes between its links, and each node
// let the penalty contact go for 1-100 us (every 0.1-0.4 ms; 419 events in 1 s before such releases were merged):
// touch, release, touch, then one release as it slides off (0.127 s), not a touch/release pair per node.
TEST(ArrayDynamics, AContactSlidingAcrossTheNodesIsOneEpisode) {
  json j = base_config();
  j["morphology"]["whiskers"] = json::array({"D3"});
  j["time"] = {{"start_s", 0.0}, {"end_s", 0.13}, {"frames", 131}};
  j["dynamics"] = json::object();
  const ArrayResult dyn = simulate_array(io::array_config_from_json(j));
  ASSERT_EQ(dyn.contact_events.size(), 1u);
  const auto& events = dyn.contact_events[0];
  std::string types;
  for (const auto& e : events) types += std::string(dynamics::to_string(e.type)) + " ";
  EXPECT_EQ(types, "touch release touch release ") << events.size() << " events";
}

// With friction (frictional_edge, mu 0.25, N = 20) D3 slides off the peg across the nodes between its links;
// TR-BDF2 alone flipped the elastic-plastic state at each slip -> stick transition there (1,140 slip onsets in this
// 0.13 s, 2,391 in 1 s): stick and slip onsets count for the flicker switch (SDIRK2 with step doubling while the
// contact flickers), which leaves 42.
TEST(ArrayDynamics, AFrictionalContactSlidingAcrossTheNodesDoesNotChatter) {
  json j = base_config();
  j["morphology"]["whiskers"] = json::array({"D3"});
  j["time"] = {{"start_s", 0.0}, {"end_s", 0.13}, {"frames", 131}};
  j["solver"]["links"] = 20;
  j["solver"]["mode"] = "frictional_edge";
  j["solver"]["mu"] = 0.25;
  j["dynamics"] = json::object();
  const ArrayResult dyn = simulate_array(io::array_config_from_json(j));
  ASSERT_EQ(dyn.contact_events.size(), 1u);
  std::size_t touches = 0, slips = 0;
  for (const auto& e : dyn.contact_events[0]) {
    touches += e.type == dynamics::ContactEventType::touch;
    slips += e.type == dynamics::ContactEventType::slip;
  }
  EXPECT_GE(touches, 1u);
  EXPECT_GE(slips, 1u);
  EXPECT_LE(slips, 60u) << dyn.contact_events[0].size() << " events";
  std::printf("D3 (N = 20, mu 0.25) sliding off the peg: %zu touches, %zu slip onsets, %zu events\n", touches, slips,
              dyn.contact_events[0].size());
}

}  // namespace
}  // namespace vibrissa::array
