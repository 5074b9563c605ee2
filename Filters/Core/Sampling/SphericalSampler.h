// Samples of a density on the unit sphere whose masses are as equal as possible (sphere.md,
// step 2): the paper's Algorithm 2 on S^2 (Delaunay refinement of the sphere graded by the
// density), and the baselines (uniform samples, the density mesh's own points).
#ifndef OTPARAM_SAMPLING_SPHERICALSAMPLER_H
#define OTPARAM_SAMPLING_SPHERICALSAMPLER_H

#include "Common/Geometry.h"
#include "Sampling/Sampler.h"

#include <vector>

namespace otparam
{

struct SphericalSamplerResult : SamplerResultBase
{
  SphericalSamplerResult() { this->sourceMass = 4.0 * 3.14159265358979323846; }
  std::vector<Vec3> samples;       // on the unit sphere (|y| = 1 to rounding)
  std::vector<Triangle> triangles; // spherical Delaunay triangulation = convex hull of the
                                   // samples, counter-clockwise seen from outside (the density
                                   // mesh's triangles in MeshVertices mode)
  // mass: the exact integral of g over each sample's spherical Voronoi cell, normalized to sum
  // to sourceMass = 4 pi.
  double densityIntegral = 0.0;      // integral of g over the sphere (before normalization)
  double massSumRelativeError = 0.0; // |sum of the cells' integrals - densityIntegral| / it
};

// spherePoints: the density mesh's points on the unit sphere; triangles: counter-clockwise
// seen from outside, covering the sphere once; triangleDensity: g > 0 per triangle (surface
// area over spherical area). Bad input gives status.error, never a crash.
SphericalSamplerResult sampleSphere(const std::vector<Vec3>& spherePoints,
  const std::vector<Triangle>& triangles, const std::vector<double>& triangleDensity,
  const SamplerOptions& options);

} // namespace otparam

#endif
