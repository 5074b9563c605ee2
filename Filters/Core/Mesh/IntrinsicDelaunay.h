// The intrinsic Delaunay triangulation of a triangle mesh's metric (Bobenko and Springborn,
// "A discrete Laplace-Beltrami operator for simplicial surfaces", 2007): interior edges are
// flipped on the edge lengths alone (the surface does not move) until every one is locally
// Delaunay. Its cotangent Laplacian has no negative weight, so harmonic maps obey the maximum
// principle: every interior vertex is a convex combination of its neighbours, which is what
// keeps a disk map of a mesh with obtuse triangles from folding. The mesh's own cotangent
// weights can be negative there (a lifted height field with steep bumps: hundreds of flipped
// triangles). No library offers intrinsic flips on a plain triangle list (CGAL's are extrinsic,
// geometry-central is not packaged for Debian), hence this file.
#ifndef OTPARAM_MESH_INTRINSICDELAUNAY_H
#define OTPARAM_MESH_INTRINSICDELAUNAY_H

#include "Common/Geometry.h"

#include <array>
#include <vector>

namespace otparam
{

struct IntrinsicTriangulation
{
  std::vector<Triangle> triangles;            // counter-clockwise, same vertex ids
  std::vector<std::array<double, 3>> lengths; // lengths[t][k]: edge opposite corner k
  int flips = 0;
};

// `triangles` must form an oriented manifold surface with boundary (each interior edge shared
// by two triangles in opposite directions); lengths[t][k] is the length of the edge opposite
// corner k of triangle t. Boundary edges are never flipped.
IntrinsicTriangulation intrinsicDelaunay(
  const std::vector<Triangle>& triangles, const std::vector<std::array<double, 3>>& lengths);

// The extrinsic edge lengths of a mesh's triangles, as intrinsicDelaunay takes them.
std::vector<std::array<double, 3>> edgeLengthsOf(
  const std::vector<Vec3>& points, const std::vector<Triangle>& triangles);

// Half the cotangent of the angle at corner k of a triangle with these edge lengths.
double halfCotangent(const std::array<double, 3>& lengths, int k);

} // namespace otparam

#endif
