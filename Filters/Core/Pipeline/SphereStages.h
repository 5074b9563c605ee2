// The stages of the sphere pipeline (sphere.md), as DiskStages.h is the disk's: each takes plain
// data as a reader or an adapter hands it over, checks it, runs the stage and its figures, and
// ends with a Status whose messages speak of the user's data and parameters.
#ifndef OTPARAM_PIPELINE_SPHERESTAGES_H
#define OTPARAM_PIPELINE_SPHERESTAGES_H

#include "Common/Status.h"
#include "Conformal/ConformalSphereMap.h"
#include "Mesh/DistortionMetrics.h"
#include "Mesh/SurfaceMesh.h"
#include "Sampling/SphericalSampler.h"
#include "Transport/SphericalOT.h"

#include <vector>

namespace otparam
{

// ---- Stage 1: closed genus-0 surface -> unit sphere, conformally.
struct SphereConformalStage
{
  Status status;
  CompactedMesh surface;        // the soup's referenced part (ids of the stage's outputs)
  ConformalSphereMapResult map; // map.sphere per point of `surface`
  DistortionFigures figures;    // of the conformal map
  std::vector<double> areaDensityPerTriangle, areaDensityPerPoint; // surface over sphere area
};

SphereConformalStage runSphereConformalStage(
  const TriangleSoup& soup, const ConformalSphereMapOptions& options);

// ---- Stage 2: samples of equal mass of a per-triangle density on the sphere.
struct SphereSamplingStage
{
  Status status;
  SphericalSamplerResult result;
};

SphereSamplingStage runSphereSamplingStage(const std::vector<Vec3>& spherePoints,
  const std::vector<Triangle>& triangles, const std::vector<double>& perTriangle,
  const SamplerOptions& options);

// ---- Stage 3: transport from the uniform sphere to Diracs on it.
struct SphereTransportStage
{
  Status status;
  SphericalOTResult result;
  SphericalPowerDiagramGeometry geometry; // arcs sampled at maximumArcAngle
  std::vector<Vec3> diracs;               // as solved (normalized)
};

SphereTransportStage runSphereTransportStage(const std::vector<Vec3>& diracs,
  const std::vector<double>& masses, const OTOptions& options, double maximumArcAngle);

// True when the points of a mesh lie on the unit sphere (to `tolerance`), so that it can be a
// sphere domain (the sampler's input).
bool pointsOnUnitSphere(const std::vector<Vec3>& points, double tolerance = 1e-6);

} // namespace otparam

#endif
