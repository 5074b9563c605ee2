// Folds of a map, for the staged transport of a surface crowded beyond double precision
// (Pipeline/AreaPreservingPipeline.cxx): a long finger's tip collapses and folds in the
// conformal image, and a stage's sampler, which takes only a valid triangulation of its domain,
// samples around the fold while the next stage untangles it.
#ifndef OTPARAM_MESH_FOLDS_H
#define OTPARAM_MESH_FOLDS_H

#include "Common/Geometry.h"

#include <vector>

namespace otparam
{

// A triangle of positive area in a planar map, or on the sphere (its spherical area, which the
// sphere's sampler checks).
bool positive(const std::vector<Vec2>& uv, const Triangle& t);
bool positive(const std::vector<Vec3>& x, const Triangle& t);

// Whether any triangle of the map is not positive.
bool anyFolded(const std::vector<Vec2>& uv, const std::vector<Triangle>& triangles);
bool anyFolded(const std::vector<Vec3>& x, const std::vector<Triangle>& triangles);

// The triangles of positive area in a planar map, less those at a vertex where two fans of them
// would meet (a pinch a sampler's domain cannot have): the unfolded part a disk stage samples.
// With `peel`, also, round by round, those whose boundary edges cross others (positive
// triangles overlapping across the fold; a sampler refuses a boundary that crosses itself). An
// unfolded map is kept whole.
std::vector<bool> unfoldedPart(
  const std::vector<Vec2>& uv, const std::vector<Triangle>& triangles, bool peel = false);

// A sphere's sampler takes a closed mesh of positive triangles only: the patch around folded or
// degenerate triangles is replaced by a fan from its rim's centre (a point appended to
// `points`, density the patch's largest), the patch grown ring by ring (up to 8) until its rim
// is one loop around which the fan is positive, or, failing a fan, whose loop CGAL's hole
// filling triangulates with positive triangles. All the folds are one patch first; when no
// ring gives it a rim, each fold (folded triangles sharing vertices) is healed apart. A fold
// that cannot be healed is left as it is (the sampler then names it).
void healSphereFolds(
  std::vector<Vec3>& points, std::vector<Triangle>& triangles, std::vector<double>& density);

} // namespace otparam

#endif
