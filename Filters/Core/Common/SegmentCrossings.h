// Where segments of a planar polygon soup meet: a sampler's boundary loops must not (CGAL's
// mesher takes them as constraints, and crossing ones crashed it), and a folded map's unfolded
// part is peeled until its loops do not.
#ifndef OTPARAM_COMMON_SEGMENTCROSSINGS_H
#define OTPARAM_COMMON_SEGMENTCROSSINGS_H

#include "Common/Geometry.h"

#include <utility>
#include <vector>

namespace otparam
{

// The pairs (i, j), i < j, of `segments` (point ids a -> b) that meet anywhere but at a point id
// they share, in increasing order. Candidate pairs come from CGAL's box intersection, and are
// tested with exact predicates.
std::vector<std::pair<int, int>> crossingSegments(
  const std::vector<Vec2>& points, const std::vector<std::pair<int, int>>& segments);

} // namespace otparam

#endif
