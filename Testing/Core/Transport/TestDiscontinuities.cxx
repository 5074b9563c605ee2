// The support test behind the singularity set (Discontinuities.cxx): which segments between
// Diracs stay in the union of their triangles, in the cases the straight walk must get right.
#include "Transport/Discontinuities.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace otparam;

namespace
{
// A 3 x 3 grid of unit squares (points id = 4 row + column), two triangles per kept square.
std::vector<Triangle> gridSquares(const std::vector<std::pair<int, int>>& squares)
{
  std::vector<Triangle> triangles;
  for (const auto& [row, column] : squares)
  {
    const int a = 4 * row + column;
    triangles.push_back({ a, a + 1, a + 5 });
    triangles.push_back({ a, a + 5, a + 4 });
  }
  return triangles;
}

std::vector<Vec2> gridPoints()
{
  std::vector<Vec2> points;
  for (int row = 0; row < 4; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      points.push_back({ static_cast<double>(column), static_cast<double>(row) });
    }
  }
  return points;
}
} // namespace

TEST(Discontinuities, SegmentsInAnLShape)
{
  // The L: the bottom row and the left column of the 3 x 3 squares.
  const SupportTriangulation l(
    gridPoints(), gridSquares({ { 0, 0 }, { 0, 1 }, { 0, 2 }, { 1, 0 }, { 2, 0 } }));
  EXPECT_TRUE(l.segmentInside(0, 3));   // along the bottom edge, through points 1 and 2
  EXPECT_FALSE(l.segmentInside(3, 12)); // (3, 0) to (0, 3): through (1.5, 1.5), outside
  EXPECT_TRUE(l.segmentInside(2, 8));   // (2, 0) to (0, 2): through the corner point (1, 1)
  EXPECT_TRUE(l.segmentInside(0, 5));   // an edge
  EXPECT_TRUE(l.segmentInside(4, 7));   // along the inner side of the bottom row
  EXPECT_FALSE(l.segmentInside(7, 13)); // (3, 1) to (1, 3): through (2, 2), outside
  EXPECT_TRUE(l.segmentInside(7, 5));   // (3, 1) to (1, 1): along the inner side to the corner
  EXPECT_TRUE(l.segmentInside(5, 13));  // (1, 1) to (1, 3): up the inner side of the column
  EXPECT_FALSE(l.segmentInside(7, 14)); // (3, 1) to (2, 3): across the missing squares
  EXPECT_FALSE(l.segmentInside(3, 15)); // (3, 0) to (3, 3): up the right side, out at (3, 1)
  EXPECT_FALSE(l.segmentInside(6, 9));  // (2, 1) to (1, 2): the diagonal cutting the corner
}

TEST(Discontinuities, SegmentsBetweenComponentsAndAroundAHole)
{
  // Two components: the left column and the right column.
  const SupportTriangulation columns(
    gridPoints(), gridSquares({ { 0, 0 }, { 1, 0 }, { 2, 0 }, { 0, 2 }, { 1, 2 }, { 2, 2 } }));
  EXPECT_TRUE(columns.segmentInside(0, 13));
  EXPECT_FALSE(columns.segmentInside(1, 2));  // (1, 0) to (2, 0): across the gap
  EXPECT_FALSE(columns.segmentInside(5, 10)); // (1, 1) to (2, 2)
  // A ring of eight squares around a hole (the middle one).
  const SupportTriangulation ring(gridPoints(),
    gridSquares(
      { { 0, 0 }, { 0, 1 }, { 0, 2 }, { 1, 0 }, { 1, 2 }, { 2, 0 }, { 2, 1 }, { 2, 2 } }));
  EXPECT_TRUE(ring.segmentInside(0, 3));
  EXPECT_TRUE(ring.segmentInside(5, 6));   // a side of the hole
  EXPECT_FALSE(ring.segmentInside(5, 10)); // the hole's diagonal
  EXPECT_TRUE(ring.segmentInside(4, 7));   // along the hole's lower side: on the boundary
  EXPECT_FALSE(ring.segmentInside(8, 7));  // (0, 2) to (3, 1): through the hole
  EXPECT_FALSE(ring.segmentInside(0, 15)); // the whole diagonal crosses the hole
}

TEST(Discontinuities, EdgesOfAConvexSupportNeverJump)
{
  // The whole 3 x 3 grid: convex, so every segment between its points stays inside.
  std::vector<std::pair<int, int>> all;
  for (int row = 0; row < 3; ++row)
  {
    for (int column = 0; column < 3; ++column)
    {
      all.emplace_back(row, column);
    }
  }
  const SupportTriangulation full(gridPoints(), gridSquares(all));
  for (int i = 0; i < 16; ++i)
  {
    for (int j = 0; j < 16; ++j)
    {
      if (i != j)
      {
        EXPECT_TRUE(full.segmentInside(i, j)) << i << " -> " << j;
      }
    }
  }
}
