// The last step of the sphere's area-preserving parameterization (sphere.md step 4): the
// conformal sphere map phi composed with the inverse of the spherical transport, T^-1 o phi.
//
// 1. Interpolation. T^-1(y_i) is the centroid of cell W_i pushed onto the sphere. A mesh vertex
//    whose conformal image x lies in the samples' spherical Delaunay triangle (a, b, c) has the
//    weights of x = l_a a + l_b b + l_c c (the gnomonic barycentric coordinates: exact for the
//    orientation of chordal triangles), and its image is l_a A + l_b B + l_c C pushed onto the
//    sphere, A, B, C the samples' images.
// 2. Untangling, as on the disk (Untangling.h), each vertex moved in the gnomonic chart at its
//    own image, where a chordal triangle's orientation seen from outside is the sign of its
//    planar area. A star that chart cannot hold (wider than a hemisphere: a coarse mesh's long
//    fan triangles) is freed with no chart, where det(p, b, c) is linear in the vertex p, if
//    CompositionOptions::untangleWideStars.
// 3. Area correction (optional, on by default), as on the disk (AreaCorrection.h) with
//    spherical triangle areas and steps in each vertex's tangent plane: the interpolation
//    between samples cannot follow the mesh-scale noise of the conformal factor (spot, brain:
//    mean |log area ratio| 0.06 at 5000 samples, 0.03 at 20000). Where the untangling leaves
//    triangles flipped and the start map has none, the correction starts from the start map
//    instead (CompositionOptions::startOverWhereTangled).
#ifndef OTPARAM_COMPOSITION_SPHERECOMPOSITION_H
#define OTPARAM_COMPOSITION_SPHERECOMPOSITION_H

#include "Common/Status.h"
#include "Composition/CompositionOptions.h"
#include "Mesh/SurfaceMesh.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace otparam
{

struct SphereCompositionResult
{
  Status status;
  std::vector<Vec3> sphere;                   // final image per mesh point
  std::vector<Vec3> interpolated;             // after step 1 only
  std::int64_t flippedAfterInterpolation = 0; // det(a, b, c) <= 0 after step 1
  std::int64_t untangledVertices = 0;
  // Triangles the untangling left flipped where the correction then started over from the start
  // map (CompositionOptions::startOverWhereTangled); 0 otherwise.
  std::int64_t flippedBeforeStartingOver = 0;
  std::int64_t flippedTriangles = 0; // after everything (0 unless untangling failed)
  int correctionSweeps = 0;
  double meanAbsLogAreaRatioInterpolated = 0.0; // after steps 1-2 (untangled, not corrected)
  double meanAbsLogAreaRatio = 0.0;
  double secondsInterpolation = 0.0;
  double secondsUntangling = 0.0;
  double secondsCorrection = 0.0;
};

// `conformal`: phi(v) per mesh point (unit vectors, triangles counter-clockwise from outside);
// `samples`, `sampleTriangles`: the Diracs and their spherical Delaunay triangulation (the
// convex hull, counter-clockwise from outside); `sampleImages`: T^-1 of each sample.
SphereCompositionResult composeOnSphere(const SurfaceMesh& surface,
  const std::vector<Vec3>& conformal, const std::vector<Vec3>& samples,
  const std::vector<Triangle>& sampleTriangles, const std::vector<Vec3>& sampleImages,
  const CompositionOptions& options = {});

// Step 2 alone on any sphere map (triangles counter-clockwise from outside where unflipped):
// the flipped triangles' vertices moved, then patches re-embedded, until none is flipped or no
// move helps. Returns the vertices moved.
std::int64_t untangleSphereMap(const SurfaceMesh& surface, std::vector<Vec3>& sphere);

// Area-weighted mean |log(spherical area fraction / surface area fraction)|, as
// param_metrics.py --sphere scores it; over the first `measured` triangles (0 = all), their
// surface fractions renormalized over them.
double sphereMeanAbsLogAreaRatio(
  const SurfaceMesh& surface, const std::vector<Vec3>& sphere, std::size_t measured = 0);

} // namespace otparam

#endif
