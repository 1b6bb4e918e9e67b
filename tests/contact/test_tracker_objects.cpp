// The contact tracker against objects (docs/objects.md, "Tracking"): a whisker protracting into a sphere and a
// tessellation of it: onset, contact frames with the force along the normal and no point inside, the same
// contacts on the mesh as on the sphere (to its tessellation's accuracy), release on retraction.
#include <gtest/gtest.h>

#include <cmath>
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
