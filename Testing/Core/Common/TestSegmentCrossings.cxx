// Where segments meet: the sampler refuses boundary loops that cross, and a folded map's
// unfolded part is peeled until its loops do not.
#include "Common/SegmentCrossings.h"

#include <gtest/gtest.h>

using namespace otparam;

TEST(SegmentCrossings, FindsWhatMeetsBesidesSharedEnds)
{
  const std::vector<Vec2> points = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 }, { 0.5, 0 },
    { 2, 0 }, { 0.5, -1 }, { 0.5, 0.5 } };
  // The square's loop: neighbours share their ends, opposite sides are apart.
  const std::vector<std::pair<int, int>> square = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 } };
  EXPECT_TRUE(crossingSegments(points, square).empty());
  // Its diagonals cross each other; segments through a corner or touching a side meet them
  // there; segments sharing an end meet only if they leave it in the same direction.
  std::vector<std::pair<int, int>> segments = square;
  segments.push_back({ 0, 2 }); // 4: shares an end with 0, 1, 2, 3, meets none of them else
  segments.push_back({ 1, 3 }); // 5: crosses 4
  segments.push_back({ 4, 6 }); // 6: touches 0 at its middle
  segments.push_back({ 4, 5 }); // 7: along 0 from its middle (overlap), through corner 1 (1, 5)
  segments.push_back({ 7, 3 }); // 8: from the centre (on 4) to corner 3, along 5 (shared end)
  const std::vector<std::pair<int, int>> expected = { { 0, 6 }, { 0, 7 }, { 1, 7 }, { 4, 5 },
    { 4, 8 }, { 5, 7 }, { 5, 8 } };
  EXPECT_EQ(crossingSegments(points, segments), expected);
}
