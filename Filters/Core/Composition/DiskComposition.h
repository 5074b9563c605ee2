// The last step of the area-preserving parameterization: compose the conformal disk map phi
// with the inverse of the semi-discrete transport, T^-1 o phi (method.md, "Compose").
//
// 1. Interpolation (the paper's composition). T^-1(y_i) is the centroid of the power cell W_i
//    (for a sample on the unit circle: the centroid's direction on the circle, since T maps the
//    boundary onto the boundary). Every mesh vertex of the conformal image is mapped by
//    piecewise-linear interpolation over the samples' regular triangulation under the
//    transport's weights, the dual of its power diagram (Delaunay when no heights are given);
//    a vertex in a circular segment outside that triangulation (between two boundary samples)
//    is mapped by the same interpolation along the chord and a radial blend to the circle, so
//    mesh boundary vertices end exactly on the circle.
// 2. Untangling. The centroids are not always in the order of their samples: a triangle of the
//    samples' triangulation may map flipped (hand_choi_53k: 270 of 9492 Delaunay ones), and every
//    mesh triangle inside it would inherit the flip (the face subdivided to 1.09M points: 4329
//    flipped mesh triangles, 1265 left after untangling them). So the sample images are
//    untangled first, on the samples' triangulation (its hull, on the circle, stays there);
//    then the few mesh triangles that still map flipped (those spanning several sample
//    triangles where the map bends) are repaired the same way on the mesh. Both use
//    Freitag-Plassmann moves of a small, growing neighbourhood (Untangling.h).
// 3. Area correction (optional, on by default). The transport is area-preserving in the limit
//    of many samples; at a finite count, what remains is the interpolation error: at the
//    samples' scale (the cell centroids are not exactly T^-1 of the samples), inside each
//    sample triangle (mesh triangles that span several sample triangles where the transport
//    bends, and the mesh-scale noise of the discrete conformal factor). (a) A few sweeps move
//    one sample image at a time with every mesh point of its star (SampleScaleCorrection.h);
//    then (b) Gauss-Seidel sweeps of per-vertex Gauss-Newton steps on
//    sum_t A*_t log(A_t / A*_t)^2 move each vertex so its triangles get their surface area
//    fraction A*_t; a step is kept only if it lowers the star's sum A*_t (r + 1/r - 2),
//    r = A_t / A*_t, which is infinite at zero area, so the correction never creates a flip;
//    boundary vertices keep the transport's boundary map (only ear corners, and stars still
//    off by 5% at the end, slide along the circle). Both the interpolated and the corrected
//    figures are reported.
#ifndef OTPARAM_COMPOSITION_DISKCOMPOSITION_H
#define OTPARAM_COMPOSITION_DISKCOMPOSITION_H

#include "Common/Status.h"
#include "Composition/CompositionOptions.h"
#include "Mesh/SurfaceMesh.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace otparam
{

struct CompositionResult
{
  Status status;                              // error (empty on success) or aborted
  std::vector<Vec2> uv;                       // final disk coordinates per mesh point
  std::vector<Vec2> interpolatedUv;           // after step 1 only
  std::int64_t outsideSampleHull = 0;         // mesh points mapped through a circular segment
  std::int64_t flippedSampleTriangles = 0;    // of the samples' triangulation under T^-1 ...
  std::int64_t flippedSampleTrianglesAfterUntangling = 0; // ... and after untangling them
  std::int64_t flippedAfterInterpolation = 0; // triangles with signed area <= 0 after step 1
  std::int64_t untangledVertices = 0;         // vertices moved by step 2
  std::int64_t flippedTriangles = 0;          // after everything (0 unless untangling failed)
  int sampleScaleSweeps = 0;                  // step 3a's
  int correctionSweeps = 0;                   // step 3b's
  double meanAbsLogAreaRatioInterpolated = 0.0; // after steps 1-2
  double meanAbsLogAreaRatioSampleScale = 0.0;  // after step 3a (the interpolated one without)
  double meanAbsLogAreaRatio = 0.0;             // final
  double secondsInterpolation = 0.0;
  double secondsUntangling = 0.0;
  double secondsCorrection = 0.0;
  double secondsSampleScale = 0.0; // step 3a's part of secondsCorrection
};

// The middle of the longest run of a clipped power cell's boundary (closed polygon, arcs of
// the unit circle sampled) lying on the unit circle; {NaN, NaN} when none does. For a sample
// on the circle this is a better T^-1 than its cell's centroid: T maps that arc onto the
// sample, and the arc's middle is off the exact preimage by O(h^2), where the centroid's
// direction is off by O(h) when the cell leans to one side.
Vec2 boundaryArcMidpoint(const std::vector<Vec2>& cell);

// `conformalUv`: the conformal disk image of `surface` (boundary on the unit circle,
// triangles positively oriented); `boundaryLoop` its boundary vertices in order.
// `samples`: the Dirac positions y_i in the conformal disk; `sampleImages`: their T^-1, the
// centroids of their power cells from the converged transport (for samples on the circle,
// better boundaryArcMidpoint; images of those are put on the circle in any case).
// `sampleHeights`: the transport's heights h_i (OTResult::heights), whose power diagram's dual,
// the samples' regular triangulation, is then the interpolant's; empty: their Delaunay
// triangulation.
CompositionResult composeWithInverseTransport(const SurfaceMesh& surface,
  const std::vector<Vec2>& conformalUv, const std::vector<int>& boundaryLoop,
  const std::vector<Vec2>& samples, const std::vector<Vec2>& sampleImages,
  const CompositionOptions& options = {}, const std::vector<double>& sampleHeights = {});

} // namespace otparam

#endif
