// The walking point location (Common/TriangleWalk.h): where it answers, its triangle is the only
// one holding the point within the box-tree search's slack (barycentric >= -1e-12), so the
// density field's queries give what the search alone gave; and it answers most queries.
#include "Common/TriangleWalk.h"

#include "RingDisk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace otparam
{
namespace
{
constexpr double Slack = 1e-12;

bool withinSlack(Vec2 x, Vec2 a, Vec2 b, Vec2 c)
{
  const double area = cross(b - a, c - a);
  const double la = cross(b - x, c - x) / area, lb = cross(c - x, a - x) / area;
  return la >= -Slack && lb >= -Slack && 1.0 - la - lb >= -Slack;
}

struct Mesh
{
  std::vector<Vec2> points;
  std::vector<Triangle> triangles;

  int firstHolding(Vec2 x) const
  {
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      const Triangle& tri = triangles[t];
      if (withinSlack(x, points[tri[0]], points[tri[1]], points[tri[2]]))
      {
        return static_cast<int>(t);
      }
    }
    return -1;
  }
  int countHolding(Vec2 x) const
  {
    int count = 0;
    for (const Triangle& tri : triangles)
    {
      count += withinSlack(x, points[tri[0]], points[tri[1]], points[tri[2]]);
    }
    return count;
  }
};

// The ring disk, even or crowded towards its centre (triangles from 1e-5 to 1e-1 across).
Mesh ringMesh(bool crowded)
{
  const testing::PlanarMesh disk = testing::makePlanarDisk(40, crowded ? 12.0 : 0.0);
  return { disk.points, disk.triangles };
}

// Query points: random ones and the centroids (`ordinary`), then the vertices, points on the
// edges and a hair's breadth to either side of them, and points outside the disk.
std::vector<Vec2> queries(const Mesh& mesh, size_t& ordinary)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.05, 1.05), share(0.0, 1.0);
  std::vector<Vec2> x, edgeCases;
  for (int k = 0; k < 4000; ++k)
  {
    x.push_back({ unit(random), unit(random) });
  }
  for (size_t t = 0; t < mesh.triangles.size(); t += 3)
  {
    const Triangle& tri = mesh.triangles[t];
    const Vec2 a = mesh.points[tri[0]], b = mesh.points[tri[1]], c = mesh.points[tri[2]];
    const Vec2 onEdge = a + share(random) * (b - a), normal = { a.y - b.y, b.x - a.x };
    x.push_back((1.0 / 3.0) * (a + b + c));
    edgeCases.insert(edgeCases.end(),
      { a, onEdge, onEdge + 1e-13 * normal, onEdge - 1e-13 * normal, onEdge + 1e-10 * normal });
  }
  ordinary = x.size();
  x.insert(x.end(), edgeCases.begin(), edgeCases.end());
  return x;
}

// Every answer checked against a scan of all triangles; at least `leastShareAnswered` of the
// ordinary queries inside the mesh answered.
void checkWalk(const Mesh& mesh, double leastShareAnswered)
{
  const TriangleWalk walk(mesh.points, mesh.triangles);
  size_t ordinary = 0;
  const std::vector<Vec2> x = queries(mesh, ordinary);
  int answered = 0, inside = 0;
  for (size_t q = 0; q < x.size(); ++q)
  {
    const int t = walk.locate(x[q], mesh.points, mesh.triangles);
    const int holding = mesh.countHolding(x[q]);
    if (t >= 0)
    {
      ASSERT_EQ(holding, 1) << "at (" << x[q].x << ", " << x[q].y << ")";
      ASSERT_EQ(t, mesh.firstHolding(x[q])) << "at (" << x[q].x << ", " << x[q].y << ")";
    }
    if (q < ordinary && holding > 0)
    {
      ++inside;
      answered += t >= 0;
    }
  }
  EXPECT_GE(answered, leastShareAnswered * inside) << answered << " of " << inside;
}

TEST(TriangleWalk, AnswersOnlyWhereOneTriangleHoldsThePoint)
{
  checkWalk(ringMesh(false), 0.95); // 99.6% answered
}

TEST(TriangleWalk, AnswersOnlyWhereOneTriangleHoldsThePointInACrowdedMesh)
{
  // The walks from the coarse seeds to the crowded centre give up (MaximumSteps) and leave
  // those queries to the search.
  checkWalk(ringMesh(true), 0.6); // 80%
}

TEST(TriangleWalk, AnswersOnlyWhereOneTriangleHoldsThePointAroundAHole)
{
  // The even disk less its triangles within 0.4 of the centre: walks that reach the hole's
  // rim stop there, and points in the hole are left to the search.
  Mesh mesh = ringMesh(false);
  std::vector<Triangle> kept;
  for (const Triangle& t : mesh.triangles)
  {
    if (norm((1.0 / 3.0) * (mesh.points[t[0]] + mesh.points[t[1]] + mesh.points[t[2]])) > 0.4)
    {
      kept.push_back(t);
    }
  }
  mesh.triangles = kept;
  checkWalk(mesh, 0.95);
}

TEST(TriangleWalk, EmptyMeshAnswersNothing)
{
  const TriangleWalk walk({}, {});
  EXPECT_EQ(walk.locate({ 0.0, 0.0 }, {}, {}), -1);
}

} // namespace
} // namespace otparam
