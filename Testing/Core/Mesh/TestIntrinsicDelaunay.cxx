// Intrinsic Delaunay flips on a planar mesh, where the intrinsic triangulation is the plane's
// Delaunay triangulation: lengths stay Euclidean distances, every edge ends locally Delaunay.
#include "Mesh/IntrinsicDelaunay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

using namespace otparam;

TEST(IntrinsicDelaunay, PlanarMeshBecomesDelaunay)
{
  // A jittered grid of thin cells, every cell split along its long diagonal: far from Delaunay.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const int n = 30;
  std::vector<Vec2> points;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      const bool interior = i > 0 && i < n - 1 && j > 0 && j < n - 1;
      points.push_back({ i + (interior ? jitter(random) : 0.0),
        0.3 * j + (interior ? 0.1 * jitter(random) : 0.0) });
    }
  std::vector<Triangle> triangles;
  std::vector<std::array<double, 3>> lengths;
  auto distance = [&](int a, int b) { return norm(points[a] - points[b]); };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i)
    {
      const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      for (const Triangle& t : { Triangle{ a, b, c }, Triangle{ a, c, d } })
      {
        triangles.push_back(t);
        lengths.push_back({ distance(t[1], t[2]), distance(t[2], t[0]), distance(t[0], t[1]) });
      }
    }
  const IntrinsicTriangulation result = intrinsicDelaunay(triangles, lengths);
  EXPECT_GT(result.flips, 100);
  ASSERT_EQ(result.triangles.size(), triangles.size());
  std::map<std::pair<int, int>, double> halfCotangentsOfEdge;
  for (size_t t = 0; t < result.triangles.size(); ++t)
  {
    const Triangle& tri = result.triangles[t];
    EXPECT_GT(cross(points[tri[1]] - points[tri[0]], points[tri[2]] - points[tri[0]]), 0.0);
    for (int k = 0; k < 3; ++k)
    {
      const int a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
      EXPECT_NEAR(result.lengths[t][k], distance(a, b), 1e-12);
      halfCotangentsOfEdge[{ std::min(a, b), std::max(a, b) }] +=
        halfCotangent(result.lengths[t], k);
    }
  }
  // Boundary edges have one triangle only; interior ones must have cot + cot >= 0.
  int interior = 0;
  for (const auto& [edge, weight] : halfCotangentsOfEdge)
  {
    const auto [a, b] = edge;
    const bool onBoundary = (a / n == b / n && (a / n == 0 || a / n == n - 1)) ||
      (a % n == b % n && (a % n == 0 || a % n == n - 1));
    if (!onBoundary)
    {
      ++interior;
      EXPECT_GE(weight, -1e-12) << a << "-" << b;
    }
  }
  EXPECT_GT(interior, 2000);
}
