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
struct AnalyzedInput;

// ---- Stage 1: closed genus-0 surface -> unit sphere, conformally.
struct SphereConformalStage
{
  Status status;
  // The soup's referenced part (ids of the stage's outputs), then any hole fill, as on the disk
  // (ConformalStage): the input's points and triangles are the first inputPoints /
  // inputTriangles.
  CompactedMesh surface;
  std::size_t inputPoints = 0, inputTriangles = 0;
  int filledHoles = 0;
  double fillAreaFraction = 0.0; // the fill's share of the surface area (and of the sphere)
  ConformalSphereMapResult map; // map.sphere per point of `surface`
  DistortionFigures figures;    // of the conformal map
  std::vector<double> areaDensityPerTriangle, areaDensityPerPoint; // surface over sphere area
};

// fillHoles: a connected genus-0 surface with boundary loops (a closed scan with holes) is
// closed for the computation by filling every hole; keepInputPart drops the fill again.
// `analyzed`: the soup's analyzeInput, when the caller has it (InputPart.h), taken over.
SphereConformalStage runSphereConformalStage(const TriangleSoup& soup,
  const ConformalSphereMapOptions& options, bool fillHoles = false,
  AnalyzedInput* analyzed = nullptr);

// Drops the hole fill from a stage's surface, map, densities and figures (measured again on
// the input's own triangles); `perPointMaps` are cut to the input's points as well.
void keepInputPart(SphereConformalStage& stage, std::vector<std::vector<Vec3>*> perPointMaps = {});

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
