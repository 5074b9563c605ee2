// The box hierarchy's nearest-item search (DensityField::nearestBoundaryPoint) must find what a
// scan in id order finds, ties included, at any scale of coordinates.
#include "Common/BoxTree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace otparam;

namespace
{
// A polygon of `sides` edges on a circle of radius `scale` about `centre`, as the sampler's
// boundary loops are, and the item index of the edge nearest to x by a scan.
struct Polygon
{
  std::vector<std::pair<Vec2, Vec2>> edges;
  BoxTree tree;
  Polygon(int sides, Vec2 centre, double scale)
  {
    std::vector<BoxTree::Item> boxes;
    for (int k = 0; k < sides; ++k)
    {
      const double s = 2.0 * M_PI * k / sides, t = 2.0 * M_PI * (k + 1) / sides;
      const Vec2 a = centre + scale * Vec2{ std::cos(s), std::sin(s) };
      const Vec2 b = centre + scale * Vec2{ std::cos(t), std::sin(t) };
      edges.emplace_back(a, b);
      boxes.push_back({ { std::min(a.x, b.x), std::min(a.y, b.y) },
        { std::max(a.x, b.x), std::max(a.y, b.y) }, 0.0 });
    }
    tree = BoxTree(std::move(boxes));
  }
  double distance(Vec2 x, int e) const
  {
    return norm(closestOnSegment(x, edges[e].first, edges[e].second) - x);
  }
  int scan(Vec2 x) const
  {
    int best = -1;
    double bestDistance = HUGE_VAL;
    for (int e = 0; e < static_cast<int>(edges.size()); ++e)
    {
      if (distance(x, e) < bestDistance)
      {
        bestDistance = distance(x, e);
        best = e;
      }
    }
    return best;
  }
  int search(Vec2 x) const
  {
    return tree.nearest(x, [&](int e) { return distance(x, e); });
  }
};
} // namespace

TEST(BoxTree, NearestItemIsTheScansAtEveryScale)
{
  std::mt19937 random(7);
  for (const double scale : { 1.0, 1e-20, 1e12 })
  {
    const Vec2 centre = { 0.3 * scale, -0.2 * scale };
    const Polygon polygon(2000, centre, scale);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), radius(0.9, 1.1);
    for (int k = 0; k < 2000; ++k)
    {
      const double a = angle(random), r = radius(random);
      const Vec2 x = centre + (r * scale) * Vec2{ std::cos(a), std::sin(a) };
      ASSERT_EQ(polygon.search(x), polygon.scan(x)) << "scale " << scale << ", point " << k;
    }
    // Corners are equally near to both of their edges: the lower id wins, as in a scan.
    for (int e = 0; e < 2000; e += 97)
    {
      const Vec2 corner = polygon.edges[e].first;
      EXPECT_EQ(polygon.search(corner), polygon.scan(corner));
    }
    // Far points and the centre (every edge about equally far).
    for (const Vec2 x : { centre, centre + Vec2{ 50.0 * scale, 3.0 * scale } })
    {
      EXPECT_EQ(polygon.search(x), polygon.scan(x));
    }
  }
  EXPECT_EQ(BoxTree().nearest({ 0.0, 0.0 }, [](int) { return 0.0; }), -1);
}
