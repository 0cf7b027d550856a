#include "facecap/refine/mesh_hierarchy.hpp"

#include <gtest/gtest.h>

#include <map>

#include "test_support.hpp"

namespace facecap {

namespace {

// An n x n grid of quads on the plane z = 50 cm, 1 cm apart, facing the camera.
void grid(int n, std::vector<Polygon>& polys, Positions& p) {
  p.resize(3, (n + 1) * (n + 1));
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) p.col(y * (n + 1) + x) = Vec3f(float(x) - n / 2.0f, float(y) - n / 2.0f, 50.0f);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      Polygon q;
      const int a = y * (n + 1) + x;
      q.v = {a, a + n + 1, a + n + 2, a + 1};  // counter-clockwise seen from the camera (y down)
      polys.push_back(q);
    }
  }
}

// No cracks: every edge is used by two triangles, except edges on the domain boundary.
void expect_conforming(const MeshLevel& level, const Positions& p, float extent) {
  std::map<std::pair<int, int>, int> uses;
  for (const Triangle& t : level.triangles)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  for (const auto& [e, count] : uses) {
    ASSERT_LE(count, 2);
    if (count == 1) {
      // Both ends on the same side of the square.
      const Vec3f a = p.col(e.first), b = p.col(e.second);
      const bool on_side = (std::abs(a.x() - b.x()) < 1e-5f && std::abs(std::abs(a.x()) - extent) < 1e-4f) ||
                           (std::abs(a.y() - b.y()) < 1e-5f && std::abs(std::abs(a.y()) - extent) < 1e-4f);
      EXPECT_TRUE(on_side) << "crack at edge " << e.first << "-" << e.second;
    }
  }
}

}  // namespace

TEST(MeshHierarchy, UniformRefinementQuadruplesVerticesWithoutCracks) {
  std::vector<Polygon> polys;
  Positions p;
  grid(6, polys, p);
  const PinholeCamera cam{1000.0, 0.0, 0.0};  // 1 cm at 50 cm is 20 px
  HierarchyOptions o;
  o.levels = 3;
  o.epsilon_px = 1.0;
  const MeshHierarchy h = MeshHierarchy::build(polys, static_cast<int>(p.cols()), p, cam, o);
  ASSERT_EQ(h.num_levels(), 3);
  EXPECT_EQ(h.level(0).triangles.size(), 72u);
  EXPECT_EQ(h.level(1).triangles.size(), 4 * 72u);
  EXPECT_EQ(h.level(2).triangles.size(), 16 * 72u);
  EXPECT_EQ(h.vertices(1), 13 * 13);  // edges halve: a 12 x 12 grid of cells
  for (int l = 0; l < 3; ++l) {
    const Positions pl = h.prolong_from_coarse(p, l);
    expect_conforming(h.level(l), pl, 3.0f);
    // The linear mask keeps every level on the plane, and normals face the camera.
    EXPECT_LT((pl.row(2).array() - 50.0f).abs().maxCoeff(), 1e-5f);
    const Positions n = level_normals(h.level(l), pl);
    for (Eigen::Index i = 0; i < n.cols(); ++i) ASSERT_LT(n(2, i), -0.999f) << "level " << l << " vertex " << i;
  }
}

TEST(MeshHierarchy, ShortEdgesAreNotBisectedAndMatesKeepTheMeshConforming) {
  std::vector<Polygon> polys;
  Positions p;
  grid(6, polys, p);
  // Push the left half far away: its edges project short, the right half's long.
  for (Eigen::Index i = 0; i < p.cols(); ++i)
    if (p(0, i) < 0) p(2, i) = 400.0f;
  const PinholeCamera cam{1000.0, 0.0, 0.0};
  HierarchyOptions o;
  o.levels = 2;
  o.epsilon_px = 8.0;
  const MeshHierarchy h = MeshHierarchy::build(polys, static_cast<int>(p.cols()), p, cam, o);
  const int added = h.vertices(1) - h.vertices(0);
  EXPECT_GT(added, 0);
  EXPECT_LT(added, 13 * 13 - 7 * 7);  // not everywhere
  std::map<std::pair<int, int>, int> uses;
  for (const Triangle& t : h.level(1).triangles)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  for (const auto& [e, count] : uses) EXPECT_LE(count, 2);
}

TEST(MeshHierarchy, BuildsOnTheIctFaceWithMatchingMasks) {
  FACECAP_REQUIRE_MODEL(model);
  const std::vector<Polygon> polys(model->polygons.begin(), model->polygons.begin() + regions::kFace.num_polygons());
  HeadPose pose;
  pose.translation = Vec3d(0, 0, 60);
  const Positions p = to_camera(model->evaluate(Eigen::VectorXf(), Eigen::VectorXf(), regions::kFace), pose);
  const MeshHierarchy h =
      MeshHierarchy::build(polys, regions::kFace.num_vertices(), p, PinholeCamera::centered(1400, 1280, 720), {});
  ASSERT_GE(h.num_levels(), 2);
  EXPECT_GT(h.vertices(1), 3 * h.vertices(0));
  std::vector<bool> mask(regions::kFace.num_vertices(), false);
  for (int v = 0; v < 100; ++v) mask[v] = true;
  const std::vector<bool> fine = h.prolong_mask(mask, 1);
  EXPECT_EQ(fine.size(), size_t(h.vertices(1)));
  for (int v = 0; v < regions::kFace.num_vertices(); ++v) EXPECT_EQ(fine[v], mask[v]);
}

}  // namespace facecap
