// A checkerboard drawn through a parameterization, one value (0 or 1) per triangle, so that a
// map is visible on the surface without a texture. Every square of the board has the same
// area in the domain, so on an area-preserving map the squares have equal areas on the
// surface too.
#ifndef OTPARAM_MESH_CHECKERBOARD_H
#define OTPARAM_MESH_CHECKERBOARD_H

#include "Common/Geometry.h"

#include <vector>

namespace otparam
{

// Squares of side 2 / squaresPerDiameter over [-1, 1]^2, taken at each triangle's centroid.
std::vector<int> diskCheckerboard(
  const std::vector<Triangle>& triangles, const std::vector<Vec2>& uv, int squaresPerDiameter);

// `sectors` longitude sectors times sectors / 2 bands of equal height in z (Archimedes: equal
// heights cut equal areas), taken at each triangle's normalized centroid.
std::vector<int> sphereCheckerboard(
  const std::vector<Triangle>& triangles, const std::vector<Vec3>& sphere, int sectors);

} // namespace otparam

#endif
