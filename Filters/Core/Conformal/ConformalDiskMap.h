// The conformal (Riemann) map of a disk-like triangle surface onto the unit disk, with the
// boundary exactly on the unit circle (method.md step 1).
#ifndef OTPARAM_CONFORMAL_CONFORMALDISKMAP_H
#define OTPARAM_CONFORMAL_CONFORMALDISKMAP_H

#include "Common/Status.h"
#include "Mesh/SurfaceMesh.h"

#include <functional>

namespace otparam
{

struct ConformalDiskMapOptions
{
  // Interior vertex sent to the origin; -1: the interior vertex nearest to the centre of mass of
  // the surface area once that centre of mass is moved to the origin by a Moebius map.
  int centerVertex = -1;
  int alignVertex = -1; // boundary vertex sent to (1, 0); -1: the boundary vertex of lowest id
  // Stop when no boundary angle moves by more than this (radians) in one iteration.
  double tolerance = 1e-6;
  int maximumNumberOfIterations = 100;
  // Called with the fraction done; returning false aborts.
  std::function<bool(double)> progress;
};

struct ConformalDiskMapResult
{
  Status status;        // error (empty on success) or aborted
  std::vector<Vec2> uv; // per mesh point; boundary points on the unit circle
  int centerVertex = -1;
  int alignVertex = -1;
  int iterations = 0;           // boundary-angle iterations after the first flattening
  double lastAngleUpdate = 0.0; // radians
  double conformalEnergy = 0.0; // Dirichlet energy minus image area (0 = conformal)
  int clippedEars = 0;
  // Triangles the mesh's own cotangent Laplacian folded; when > 0 the map was computed again
  // with the intrinsic Delaunay Laplacian, kept if it folds fewer (intrinsicLaplacian = true).
  std::int64_t foldedWithMeshLaplacian = 0;
  bool intrinsicLaplacian = false;
  // Both cotangent Laplacians folded triangles, and the mesh's with every weight floored at a
  // small positive value (CotangentLaplacian.h) folded none: that map was kept.
  bool flooredWeights = false;
  int intrinsicFlips = 0; // edge flips to the intrinsic Delaunay triangulation
  double secondsFactorization = 0.0;
  double secondsIterations = 0.0;
};

// `boundaryLoop` is the mesh's single boundary loop in the triangles' orientation, as
// checkDiskTopology returns it (the mesh must pass that check).
ConformalDiskMapResult computeConformalDiskMap(const SurfaceMesh& mesh,
  const std::vector<int>& boundaryLoop, const ConformalDiskMapOptions& options = {});

} // namespace otparam

#endif
