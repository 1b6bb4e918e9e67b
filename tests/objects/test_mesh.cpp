// Meshes: closest points against a brute-force loop over triangles, the sign inside a closed mesh, second-order
// convergence of a tessellated sphere to the sphere, files (OBJ, STL, PLY) through assimp, orientation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <Eigen/Geometry>

#include "shape_checks.hpp"
#include "vibrissa/objects/mesh.hpp"
#include "vibrissa/objects/sphere.hpp"

using namespace vibrissa;

namespace {

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5), the reference.
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double brute_distance(const Mesh& m, const Eigen::Vector3d& p) {
  double best = 1e300;
  for (const auto& t : m.triangles())
    best = std::min(best, (p - closest_on_triangle(p, m.vertices()[t[0]], m.vertices()[t[1]], m.vertices()[t[2]])).norm());
  return best;
}

// Inside a convex closed mesh: behind every face.
bool inside_convex(const Mesh& m, const Eigen::Vector3d& p) {
  for (const auto& t : m.triangles()) {
    const auto &a = m.vertices()[t[0]], &b = m.vertices()[t[1]], &c = m.vertices()[t[2]];
    if ((p - a).dot((b - a).cross(c - a)) > 0.0) return false;
  }
  return true;
}

std::filesystem::path temp_dir() {
  const auto d = std::filesystem::temp_directory_path() / ("vibrissa_mesh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

// A unit cube [0,1]^3 (8 vertices, 12 triangles, outward), for the file tests.
const std::vector<Eigen::Vector3d> kCube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const std::vector<std::array<int, 3>> kCubeFaces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                                    {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};

}  // namespace

TEST(Mesh, ClosestPointsMatchABruteForceLoop) {
  const Mesh ball(tessellated_sphere({0.01, 0.0, -0.002}, 0.003, 3));
  EXPECT_TRUE(ball.closed());
  EXPECT_EQ(ball.triangles().size(), 1280u);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.006, 0.006);
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d p = Eigen::Vector3d(0.01, 0.0, -0.002) + Eigen::Vector3d(u(rng), u(rng), u(rng));
    const SurfacePoint q = ball.nearest(p);
    const double d = brute_distance(ball, p);
    EXPECT_NEAR(std::abs(q.signed_distance), d, 1e-15) << i;
    EXPECT_EQ(q.signed_distance < 0.0, inside_convex(ball, p)) << i;
  }
}

TEST(Mesh, ALocalViewAnswersAsTheTree) {
  // A solve's view (Shape::local_view): queries wandering about a contact, near the surface, inside and up to
  // 2 mm away (beyond the gathered triangles: those go to the tree), some asked twice. Every answer is the tree's.
  const Mesh ball(tessellated_sphere(Eigen::Vector3d::Zero(), 0.003, 5));
  const std::unique_ptr<const Shape> view = ball.local_view(0.0001);
  ASSERT_NE(view, nullptr);
  EXPECT_EQ(view->type(), "mesh");
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Vector3d contact = Eigen::Vector3d(0.6, 0.8, 0.0) * 0.00305;
  int faces = 0;
  for (int i = 0; i < 600; ++i) {
    const double reach = i % 5 == 4 ? 0.002 : 0.0005;
    Eigen::Vector3d p = contact + reach * Eigen::Vector3d(u(rng), u(rng), u(rng));
    if (i % 7 == 3) p = contact;  // asked again
    if (i % 100 == 99) contact = contact.normalized() * 0.00305 + 0.0003 * Eigen::Vector3d(u(rng), u(rng), 0.0);
    const SurfacePoint a = view->nearest(p), b = ball.nearest(p);
    EXPECT_NEAR((a.closest - b.closest).norm(), 0.0, 1e-15) << i;
    EXPECT_NEAR(a.signed_distance, b.signed_distance, 1e-15) << i;
    EXPECT_NEAR((a.normal - b.normal).norm(), 0.0, 1e-12) << i;
    EXPECT_NEAR((a.normal_derivative - b.normal_derivative).norm() * 1e-4, 0.0, 1e-12) << i;
    EXPECT_EQ(a.feature, b.feature) << i;
    if (a.feature == SurfaceFeature::face) {
      EXPECT_EQ(a.feature_id, b.feature_id) << i;
      ++faces;
    }
    const SurfacePoint held = view->nearest_on_feature(p + Eigen::Vector3d(1e-5, 0.0, 0.0), a.feature_id);
    const SurfacePoint held_b = ball.nearest_on_feature(p + Eigen::Vector3d(1e-5, 0.0, 0.0), a.feature_id);
    EXPECT_EQ(held.closest, held_b.closest) << i;
    EXPECT_EQ(view->signed_distance(p), a.signed_distance) << i;
  }
  EXPECT_GT(faces, 300);
  EXPECT_EQ(view->bounds().lower, ball.bounds().lower);
  EXPECT_TRUE(view->needs_thickness());
}

TEST(Mesh, NormalsAndTheirDerivativesAgreeWithCentralDifferences) {
  const Mesh ball(tessellated_sphere(Eigen::Vector3d::Zero(), 0.003, 2));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.006, 0.006);
  int checked[3] = {0, 0, 0};
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const SurfacePoint q = ball.nearest(p);
    if (q.signed_distance < 1e-4) continue;  // outside, where the field is smooth within each feature's region
    ++checked[static_cast<int>(q.feature)];
    vibrissa::testing::expect_consistent_query(ball, p, 1e-5);
  }
  EXPECT_GT(checked[0], 10);
  EXPECT_GT(checked[1], 10);
  EXPECT_GT(checked[2], 3);
}

TEST(Mesh, TessellatedSphereConvergesAtSecondOrder) {
  // Signed distance at points 1 mm outside a 3 mm sphere: the mesh's error is the sagitta of its triangles,
  // O(h^2) in the edge length h, so each subdivision (h / 2) divides it by ~4.
  const Sphere exact(Eigen::Vector3d::Zero(), 0.003);
  std::mt19937_64 rng(2);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 200; ++i) points.push_back(0.004 * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
  std::vector<double> error, edge;
  for (int n = 2; n <= 5; ++n) {
    const Mesh m(tessellated_sphere(Eigen::Vector3d::Zero(), 0.003, n));
    double e = 0.0;
    for (const auto& p : points) e = std::max(e, std::abs(m.signed_distance(p) - exact.signed_distance(p)));
    error.push_back(e);
    edge.push_back(m.longest_edge());
  }
  for (std::size_t i = 1; i < error.size(); ++i) {
    const double order = std::log(error[i - 1] / error[i]) / std::log(edge[i - 1] / edge[i]);
    EXPECT_NEAR(order, 2.0, 0.25) << "subdivision " << i + 2;
  }
}

TEST(Mesh, ReadsObjStlAndPlyAndOrientsClosedMeshesOutward) {
  const auto dir = temp_dir();
  {  // OBJ with two faces flipped: oriented consistently and outward on reading
    std::ofstream f(dir / "cube.obj");
    for (const auto& v : kCube) f << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (std::size_t i = 0; i < kCubeFaces.size(); ++i) {
      auto t = kCubeFaces[i];
      if (i == 3 || i == 8) std::swap(t[1], t[2]);
      f << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    }
  }
  {  // ASCII STL, every face inward: the whole mesh is turned outward
    std::ofstream f(dir / "cube.stl");
    f << "solid cube\n";
    for (const auto& t : kCubeFaces) {
      f << " facet normal 0 0 0\n  outer loop\n";
      for (int k : {t[0], t[2], t[1]}) f << "   vertex " << kCube[k].x() << ' ' << kCube[k].y() << ' ' << kCube[k].z() << '\n';
      f << "  endloop\n endfacet\n";
    }
    f << "endsolid cube\n";
  }
  {  // ASCII PLY
    std::ofstream f(dir / "cube.ply");
    f << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& v : kCube) f << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto& t : kCubeFaces) f << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  }
  for (const char* name : {"cube.obj", "cube.stl", "cube.ply"}) {
    SCOPED_TRACE(name);
    ObjectPose pose;
    pose.p_WO = {0.01, 0.0, 0.0};
    const auto m = Mesh::from_file((dir / name).string(), 1e-3, pose);  // a 1 mm cube at x = 10 mm
    EXPECT_EQ(m->vertices().size(), 8u);
    EXPECT_EQ(m->triangles().size(), 12u);
    EXPECT_TRUE(m->closed());
    EXPECT_NEAR(m->signed_distance({0.0105, 0.0005, 0.0005}), -0.0005, 1e-15);
    EXPECT_NEAR(m->signed_distance({0.0105, 0.0005, 0.0025}), 0.0015, 1e-15);
    const SurfacePoint corner = m->nearest({0.012, 0.002, 0.002});
    EXPECT_EQ(corner.feature, SurfaceFeature::vertex);
    EXPECT_NEAR(corner.signed_distance, std::sqrt(3.0) * 0.001, 1e-15);
    const SurfacePoint edge = m->nearest({0.012, 0.002, 0.0005});
    EXPECT_EQ(edge.feature, SurfaceFeature::edge);
    EXPECT_NEAR(edge.signed_distance, std::sqrt(2.0) * 0.001, 1e-15);
    EXPECT_EQ(m->describe().file, (dir / name).string());
  }
  std::filesystem::remove_all(dir);
}

TEST(Mesh, AnOpenSurfaceIsSignedByTheSideItsNormalsFace) {
  TriangleSoup square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  const Mesh sheet(square);
  EXPECT_FALSE(sheet.closed());
  EXPECT_NEAR(sheet.signed_distance({0.5, 0.5, 0.25}), 0.25, 1e-15);
  EXPECT_NEAR(sheet.signed_distance({0.5, 0.5, -0.25}), -0.25, 1e-15);
}

TEST(Mesh, BadInputIsAnErrorNamingIt) {
  EXPECT_THROW(Mesh(TriangleSoup{{{0, 0, 0}, {1, 0, 0}}, {{0, 1, 2}}}), std::invalid_argument);
  EXPECT_THROW(Mesh(TriangleSoup{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}}), std::invalid_argument);  // no area
  try {
    (void)Mesh::from_file("/nonexistent/thing.stl");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/thing.stl"), std::string::npos);
  }
  const auto dir = temp_dir();
  { std::ofstream(dir / "bad.obj") << "this is not a mesh\n"; }
  EXPECT_THROW((void)Mesh::from_file((dir / "bad.obj").string()), std::invalid_argument);
  std::filesystem::remove_all(dir);
}
