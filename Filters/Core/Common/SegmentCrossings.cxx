#include "Common/SegmentCrossings.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>

namespace otparam
{

std::vector<std::pair<int, int>> crossingSegments(
  const std::vector<Vec2>& points, const std::vector<std::pair<int, int>>& segments)
{
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, int>;
  std::vector<Box> boxes;
  boxes.reserve(segments.size());
  for (size_t s = 0; s < segments.size(); ++s)
  {
    const Vec2 a = points[segments[s].first], b = points[segments[s].second];
    double lo[2] = { std::min(a.x, b.x), std::min(a.y, b.y) };
    double hi[2] = { std::max(a.x, b.x), std::max(a.y, b.y) };
    boxes.emplace_back(lo, hi, static_cast<int>(s));
  }
  const auto point = [&points](int v) { return K::Point_2(points[v].x, points[v].y); };
  // Segments sharing an end (neighbours along a loop) meet only there unless they leave it in
  // the same direction.
  const auto overlapFromSharedEnd = [&point](int a, int b, int c, int d)
  {
    const int shared = a == c || a == d ? a : b;
    const int first = shared == a ? b : a, second = shared == c ? d : c;
    return first == second ||
      (CGAL::collinear(point(shared), point(first), point(second)) &&
        CGAL::angle(point(first), point(shared), point(second)) == CGAL::ACUTE);
  };
  std::vector<std::pair<int, int>> crossings;
  // Sequential: Debian's CGAL is built here without TBB.
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(),
    [&](const Box& p, const Box& q)
    {
      const auto [a, b] = segments[p.info()];
      const auto [c, d] = segments[q.info()];
      const bool sharesAnEnd = a == c || a == d || b == c || b == d;
      if (sharesAnEnd ? overlapFromSharedEnd(a, b, c, d)
                      : CGAL::do_intersect(
                          K::Segment_2(point(a), point(b)), K::Segment_2(point(c), point(d))))
      {
        crossings.push_back(std::minmax(p.info(), q.info()));
      }
    });
  std::sort(crossings.begin(), crossings.end());
  return crossings;
}

} // namespace otparam
