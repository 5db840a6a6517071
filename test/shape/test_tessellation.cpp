// Tessellation: exact vertex counts, vertices on the surface, closed outward meshes, OBJ and
// FCL BVH export.

#include <fcl/math/bv/OBBRSS.h>

#include <map>
#include <sstream>

#include "fcl_superellipsoid/tessellation.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

template <typename S>
class TessellationTest : public ::testing::Test {};
TYPED_TEST_SUITE(TessellationTest, test::Scalars);

TYPED_TEST(TessellationTest, MeshesHaveTheRequestedCountAreOnTheSurfaceClosedAndOutward) {
  using S = TypeParam;
  for (double e1 : test::exponentGrid()) {
    for (double e2 : {0.02, 0.3, 1.0, 1.7, 1.98}) {
      for (const auto& a : {std::array<double, 3>{1, 1, 1}, std::array<double, 3>{3.5, 3.0, 2.0},
                            std::array<double, 3>{1000, 1, 1}}) {
        const Superellipsoid<S> shape{S(a[0]), S(a[1]), S(a[2]), S(e1), S(e2)};
        for (int count : {5, 6, 72, 272, 1001}) {
          SCOPED_TRACE(test::describe(shape) + " with " + std::to_string(count) + " vertices");
          const TriangleMesh<S> mesh = tessellate(shape, count);
          ASSERT_EQ(mesh.vertices.size(), size_t(count));
          // Closed, 2-manifold surface of genus 0: V − E + F = 2, every edge in two triangles.
          EXPECT_EQ(mesh.triangles.size(), size_t(2 * count - 4));
          std::map<std::pair<int, int>, int> directed;
          for (const auto& t : mesh.triangles) {
            for (int e = 0; e < 3; ++e) ++directed[{int(t[e]), int(t[(e + 1) % 3])}];
          }
          for (const auto& [edge, n] : directed) {
            EXPECT_EQ(n, 1) << "edge used twice in one direction";
            EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "boundary edge";
          }
          // On the surface, by the independent long-double gauge.
          for (const auto& v : mesh.vertices) {
            EXPECT_NEAR(double(test::referenceGauge(shape, v)), 1.0, 4 * test::evalTolerance<S>());
          }
          // Outward: seen from the centre, every triangle winds counter-clockwise (its signed
          // tetrahedron volume with the origin is positive).
          double volume = 0;
          for (const auto& t : mesh.triangles) {
            const Eigen::Vector3d v0 = mesh.vertices[t[0]].template cast<double>();
            const Eigen::Vector3d v1 = mesh.vertices[t[1]].template cast<double>();
            const Eigen::Vector3d v2 = mesh.vertices[t[2]].template cast<double>();
            const double tet = v0.dot(v1.cross(v2)) / 6;
            EXPECT_GE(tet, -1e-6 * a[0] * a[1] * a[2]);
            volume += tet;
          }
          EXPECT_GT(volume, 0);
          EXPECT_LT(volume, shape.computeVolume() * (1 + 1e-5));  // inscribed in a convex body
        }
      }
    }
  }
}

TYPED_TEST(TessellationTest, FineMeshesConvergeToTheVolume) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(1), S(2), S(1.5), S(0.65), S(1.35)};
  const TriangleMesh<S> mesh = tessellate(shape, 20000);
  double volume = 0;
  for (const auto& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].template cast<double>().dot(
                  mesh.vertices[t[1]].template cast<double>().cross(
                      mesh.vertices[t[2]].template cast<double>())) /
              6;
  }
  EXPECT_NEAR(volume / shape.computeVolume(), 1.0, 2e-3);
}

TYPED_TEST(TessellationTest, ThePapersMeshIsReproducible) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(1), S(1), S(1), S(0.3), S(0.3)};
  const TriangleMesh<S> a = tessellate(shape, 272), b = tessellate(shape, 272);
  ASSERT_EQ(a.vertices.size(), 272u);
  EXPECT_EQ(a.triangles.size(), 540u);
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]);
}

TYPED_TEST(TessellationTest, RejectsTooFewVertices) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(1), S(1), S(1), S(1), S(1)};
  try {
    tessellate(shape, 4);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("got 4"), std::string::npos) << e.what();
  }
}

TYPED_TEST(TessellationTest, ObjExportRoundTrips) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(2), S(1), S(1), S(0.5), S(0.5)};
  const TriangleMesh<S> mesh = tessellate(shape, 72);
  std::stringstream obj;
  writeObj(mesh, obj);
  std::vector<Vector3<S>> vertices;
  std::vector<std::array<int, 3>> faces;
  std::string tag;
  while (obj >> tag) {
    if (tag == "v") {
      double x, y, z;
      obj >> x >> y >> z;
      vertices.emplace_back(S(x), S(y), S(z));
    } else if (tag == "f") {
      std::array<int, 3> f;
      obj >> f[0] >> f[1] >> f[2];
      faces.push_back(f);
    }
  }
  ASSERT_EQ(vertices.size(), mesh.vertices.size());
  ASSERT_EQ(faces.size(), mesh.triangles.size());
  for (size_t i = 0; i < vertices.size(); ++i)
    EXPECT_EQ(vertices[i], mesh.vertices[i]);  // max_digits10
  for (size_t i = 0; i < faces.size(); ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(faces[i][k], int(mesh.triangles[i][k]) + 1);  // 1-based
  }
  EXPECT_THROW(writeObj(mesh, std::string("/nonexistent-dir/x.obj")), std::runtime_error);
}

TYPED_TEST(TessellationTest, BuildsFclBvhModels) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(1), S(1), S(1), S(1), S(1)};
  TriangleMesh<S> mesh = tessellate(shape, 272);
  const auto model = makeBVHModel<fcl::OBBRSS<S>>(mesh);
  EXPECT_EQ(model->num_vertices, 272);
  EXPECT_EQ(model->num_tris, 540);
  EXPECT_EQ(model->getModelType(), fcl::BVH_MODEL_TRIANGLES);
  mesh.triangles.clear();
  const auto cloud = makeBVHModel<fcl::OBBRSS<S>>(mesh);
  EXPECT_EQ(cloud->num_vertices, 272);
  EXPECT_EQ(cloud->getModelType(), fcl::BVH_MODEL_POINTCLOUD);
}

}  // namespace
}  // namespace fcl_superellipsoid
