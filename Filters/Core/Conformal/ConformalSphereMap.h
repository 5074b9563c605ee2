// The conformal map of a closed genus-0 triangle surface onto the unit sphere, Moebius-balanced
// so that the pushed-forward surface area has its centre of mass at the origin (sphere.md
// step 1).
#ifndef OTPARAM_CONFORMAL_CONFORMALSPHEREMAP_H
#define OTPARAM_CONFORMAL_CONFORMALSPHEREMAP_H

#include "Common/Status.h"
#include "Mesh/SurfaceMesh.h"

#include <cstdint>
#include <functional>

namespace otparam
{

struct ConformalSphereMapOptions
{
  // Triangle cut out for the first (north) pass; -1: the most nearly equilateral triangle.
  int punctureTriangle = -1;
  // Fraction of the points, those farthest from the puncture, whose first-pass positions are
  // kept as boundary values of the second (south) pass; the rest is solved again.
  double fixedFraction = 0.05;
  // Stop the Moebius balancing when |centre of mass| / total mass is at most this.
  double balanceTolerance = 1e-10;
  int maximumBalanceIterations = 100;
  // Use the intrinsic Delaunay Laplacian from the start (by default it is only the fallback
  // when the mesh's own Laplacian flips triangles).
  bool intrinsicLaplacian = false;
  // Called with the fraction done; returning false aborts.
  std::function<bool(double)> progress;
};

struct ConformalSphereMapResult
{
  Status status;            // error (empty on success) or aborted; a warning if unbalanced
  std::vector<Vec3> sphere; // per mesh point, unit vectors; det(a, b, c) > 0 per triangle
  int punctureTriangle = -1;
  int fixedPoints = 0; // points held fixed in the second pass
  // The triangles face inward (negative enclosed volume). The map always makes the triangles
  // as given counter-clockwise seen from outside the sphere, so it is then the mirror image of
  // the surface (still conformal: angles and areas are unsigned).
  bool mirrored = false;
  std::int64_t flippedTriangles = 0;       // det(a, b, c) <= 0, as param_metrics.py --sphere counts
  double meanAngleDistortionDegrees = 0.0; // over corners, chordal image angles
  double maximumAngleDistortionDegrees = 0.0;
  // Triangles the mesh's own cotangent Laplacian flipped; when > 0 the map was computed again
  // with the intrinsic Delaunay Laplacian, kept if it flips fewer (intrinsicLaplacian = true).
  std::int64_t flippedWithMeshLaplacian = 0;
  bool intrinsicLaplacian = false;
  // Both cotangent Laplacians flipped triangles, and the mesh's with every weight floored at a
  // small positive value flipped fewer: that map was kept (no longer exactly conformal at the
  // floored edges: a coarse sharp corner's).
  bool flooredWeights = false;
  // ... and the floored weights too: the map is the surface less its puncture mapped to the
  // disk (ConformalDiskMap, which cannot fold it), lifted by inverse stereographic projection.
  bool liftedFromTheDisk = false;
  int intrinsicFlips = 0;
  int balanceIterations = 0;    // Newton steps of the final Moebius balancing
  double balanceResidual = 0.0; // |centre of mass| / total mass after balancing
  double secondsFactorization = 0.0;
  double secondsSolve = 0.0;
  double secondsBalance = 0.0;
};

// The mesh must pass checkSphereTopology (closed, connected, genus 0, consistently oriented).
ConformalSphereMapResult computeConformalSphereMap(
  const SurfaceMesh& mesh, const ConformalSphereMapOptions& options = {});

// The centre of mass of the surface area pushed to the sphere (each triangle's surface area
// spread uniformly over its spherical image triangle), over the total surface area: the
// quantity the balancing sends to 0. `sphere` holds unit vectors.
Vec3 pushedAreaCentre(const SurfaceMesh& mesh, const std::vector<Vec3>& sphere);

// Moebius maps (hyperbolic translations) applied to `sphere` until the measure that gives each
// triangle `weight[t]` (summing to 1) spread over its image has its centre of mass within
// `tolerance` of the origin, or no step lowers it. Returns that distance.
double balanceMeasure(const std::vector<Triangle>& triangles, const std::vector<double>& weight,
  std::vector<Vec3>& sphere, double tolerance, int maximumIterations);

} // namespace otparam

#endif
