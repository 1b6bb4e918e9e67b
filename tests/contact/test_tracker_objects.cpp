// The contact tracker against objects (docs/objects.md, "Tracking"): a whisker protracting into a sphere and a
// tessellation of it: onset, contact frames with the force along the normal and no point inside, the same
// contacts on the mesh as on the sphere (to its tessellation's accuracy), release on retraction.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/objects/clearance.hpp"
#include "vibrissa/objects/mesh.hpp"
#include "vibrissa/objects/sphere.hpp"
#include "vibrissa/solve/solvers.hpp"

using namespace vibrissa;

namespace {

struct Frame {
  ContactState state;
  Status status;
  bool solved;
  Eigen::Vector3d force;
  double arc_length;
};

// Protraction from -20 to +25 deg and back over 120 frames, against `shape`.
std::vector<Frame> protract(const Whisker& w, const Shape& shape) {
  TrackerOptions o;
  ContactTracker tracker(w, o);
  const PlacedShape placed{&shape, {}};
  std::vector<Frame> out;
  for (int k = 0; k < 120; ++k) {
    const double phase = k < 60 ? k / 59.0 : (119 - k) / 59.0;
    Pose pose;
    pose.theta = (-20.0 + 45.0 * phase) * std::numbers::pi / 180.0;
    const Placement X(pose);
    const TrackedFrame& f = tracker.step(X, std::span<const PlacedShape>(&placed, 1));
    out.push_back({f.state, f.solution.status, f.solved, f.solution.force_W, f.solution.arc_length});
    if (f.state == ContactState::contact && f.solution.status == Status::converged) {
      const Solution& s = f.solution;
      EXPECT_LT(s.force_W.normalized().cross(s.surface->normal_W).norm(), 1e-9) << k;
      std::vector<Eigen::Vector3d> nodes;
      deflected_shape(w, X, s.state, nodes);
      EXPECT_GE(clearance(placed, nodes, w.node_arc_lengths(), w.node_radii()).gap, -1e-9) << k;
    }
  }
  return out;
}

}  // namespace

TEST(TrackerObjects, ProtractionIntoASphereAndItsMesh) {
  WhiskerProperties p;
  p.links = 60;
  const Whisker w = Whisker::from_parabola(0.030, 10.0, p);
  // A 2 mm sphere at 20 mm from the base, at 10 deg azimuth, in the plane of the whisk.
  const Eigen::Vector3d centre(0.020 * std::cos(0.17), 0.020 * std::sin(0.17), 0.0);
  const Sphere ball(centre, 0.002);
  const Mesh mesh(tessellated_sphere(centre, 0.002, 4));
  const std::vector<Frame> a = protract(w, ball), b = protract(w, mesh);
  int onset = -1, contacts = 0, both = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (a[k].state == ContactState::contact && onset < 0) onset = static_cast<int>(k);
    if (a[k].state == ContactState::contact) ++contacts;
    // Protraction (the whisker pressing in): the mesh's contacts are the sphere's. (On retraction the two part:
    // the frictionless contact slides along the surface, and the mesh's rounded edges stall its solves more often:
    // docs/objects.md, "Speed".)
    if (k < 60 && a[k].state == ContactState::contact && b[k].state == ContactState::contact &&
        a[k].status == Status::converged && b[k].status == Status::converged) {
      ++both;
      // The mesh's vertices lie on the sphere; its faces are within 2 um of it (5,120 triangles).
      EXPECT_LT((a[k].force - b[k].force).norm(), 0.05 * a[k].force.norm()) << k;
      EXPECT_NEAR(a[k].arc_length, b[k].arc_length, 2e-4) << k;
    }
  }
  EXPECT_GT(onset, 0);         // not at the first frame
  EXPECT_GT(contacts, 5);      // a run of contact frames
  EXPECT_GE(both, 3);  // measured: 3 of the sphere's protraction contact frames also converge on the mesh
  EXPECT_EQ(a.back().state, ContactState::free);  // released on retraction
}

// Whiskers whisking against small meshes (a 1,280-triangle sphere, a 64-facet cylinder) through the tracker, as
// `vibrissa array` runs them (issue 24): at every frame in contact no point of the deflected whisker is inside the
// mesh (>= -1e-9 m), or the frame's status is typed and says where (second_contact with the arc length at which
// the whisker is inside; slipped_off: pushed past).
TEST(TrackerObjects, WhiskingAgainstMeshesNeverPenetratesSilently) {
  const Eigen::Vector3d centre(0.018, 0.006, 0.0);
  const Mesh ball(tessellated_sphere(centre, 0.002, 3));
  const Mesh peg(tessellated_cylinder(centre - Eigen::Vector3d(0.0, 0.0, 0.01), 0.0015, 0.02, 64, 8));
  int contact = 0, converged = 0, two = 0, second = 0, slipped = 0;
  for (const Mesh* mesh : {&ball, &peg}) {
    const PlacedShape placed{mesh, {}};
    for (int whisker = 0; whisker < 4; ++whisker) {
      WhiskerProperties p;
      p.links = 60;
      const Whisker w = Whisker::from_parabola(0.026 + 0.004 * whisker, 8.0 + 3.0 * whisker, p);
      TrackerOptions o;
      o.solve.compute_shape = true;
      ContactTracker tracker(w, o);
      for (int k = 0; k < 80; ++k) {  // protraction from -10 to +40 deg and back, at elevation and roll
        const double phase = k < 40 ? k / 39.0 : (79 - k) / 39.0;
        Pose pose;
        pose.theta = (-10.0 + 50.0 * phase) * std::numbers::pi / 180.0;
        pose.phi = (-6.0 + 4.0 * whisker) * std::numbers::pi / 180.0;
        pose.zeta = 0.3 * whisker;
        const Placement X(pose);
        const TrackedFrame& f = tracker.step(X, std::span<const PlacedShape>(&placed, 1));
        if (f.state == ContactState::pushed_past) ++slipped;
        if (f.state != ContactState::contact) continue;
        ++contact;
        const Solution& s = f.solution;
        std::vector<Eigen::Vector3d> nodes = s.shape_W;
        if (nodes.empty()) deflected_shape(w, X, s.state, nodes);
        const Clearance c = clearance(placed, nodes, w.node_arc_lengths(), w.node_radii());
        if (s.status == Status::converged) {
          ++converged;
          if (s.second_contact) ++two;
          EXPECT_GE(c.gap, -1e-9) << "whisker " << whisker << " frame " << k;
        } else if (s.status == Status::second_contact) {
          ++second;
          ASSERT_TRUE(s.second_contact_arc_length);
          EXPECT_LT(c.gap, -1e-9);
          EXPECT_NEAR(c.arc_length, *s.second_contact_arc_length, 1e-12);
        } else {
          ADD_FAILURE() << "frame " << k << " in contact with status " << to_string(s.status);
        }
      }
    }
  }
  std::printf("whisking against meshes: %d frames in contact, %d converged (%d with two contacts), %d second "
              "contacts, %d frames pushed past\n", contact, converged, two, second, slipped);
  EXPECT_GT(contact, 100);
  EXPECT_LE(second, contact / 20);
}
