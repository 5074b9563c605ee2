// The area-preserving parameterization, chained once: conformal map -> adaptive sampling of its
// area density -> semi-discrete transport from the uniform unit disk -> composition T^-1 o phi.
// vtkAreaPreservingParam, the command line and the benchmarks all call parameterizeDisk, so
// they produce and measure the same map.
#ifndef OTPARAM_PIPELINE_AREAPRESERVINGPIPELINE_H
#define OTPARAM_PIPELINE_AREAPRESERVINGPIPELINE_H

#include "Composition/DiskComposition.h"
#include "Composition/SphereComposition.h"
#include "Pipeline/DiskStages.h"
#include "Pipeline/InputPart.h"
#include "Pipeline/SphereStages.h"

#include <cstdint>
#include <functional>

namespace otparam
{

struct AreaPreservingOptions
{
  AreaPreservingOptions();

  ConformalStageOptions conformal;
  ConformalSphereMapOptions sphereMap; // the sphere's conformal stage
  // numberOfSamples 0 (the default): automaticSampleCount of the surface's point count.
  SamplerOptions sampling;
  OTOptions transport;
  // Arcs of the circle in the cells whose middles the boundary samples go to.
  double maximumArcAngle = DefaultMaximumArcAngle;
  CompositionOptions composition;
  // Called with (stage name, fraction of the whole run done); returning false aborts.
  std::function<bool(const char*, double)> progress;
  // Bytes the run may use; 0: what the machine has available. A surface whose map would need
  // more (estimatedMemoryBytes) is refused with a message instead of swapping.
  std::int64_t memoryLimitBytes = 0;

  std::string check() const; // "" or what is wrong with a value (named as the property)
};

struct AreaPreservingResult
{
  // status.error is prefixed by the stage that failed ("conformal map: ", "sampling: ",
  // "transport: ", "composition: "); status.warnings likewise.
  Status status;
  ConformalStage conformal;
  SamplingStage sampling;
  // The samples given to the transport: those of positive mass (a sample whose Voronoi cell
  // integrates to 0 carries no mass; the transport is the same without it).
  std::vector<Vec2> diracs;
  std::vector<double> masses;
  int droppedSamples = 0;
  // The map the (last) transport starts from, with its area density per triangle: the conformal
  // map, or for a crowded surface the map after `transportStages` staged transports.
  std::vector<Vec2> startUv;
  std::vector<double> startDensity;
  int transportStages = 0;
  TransportStage transport;
  std::vector<Vec2> sampleImages; // T^-1 of each Dirac
  CompositionResult composition;
  DistortionFigures figures; // of the area-preserving map, per triangle of conformal.surface
  double secondsConformal = 0, secondsSampling = 0, secondsTransport = 0, secondsComposition = 0,
         secondsTotal = 0;
};

// The sample count that follows the surface: 5000, or one sample per 50 points above 250k
// points. On the face subdivided to 1.09M points, 5000 samples left a mean |log area ratio| of
// 0.009 (mean angle distortion 31 degrees) after the correction, 20000 samples 0.0037 (24
// degrees) in the same time (the correction has less to do); on the shared meshes (up to 56k
// points) more samples than 5000 change little: their remaining error is at the mesh's scale.
std::int64_t automaticSampleCount(std::int64_t points);

// The peak memory of a whole map, from the input's vertex count and the sample count (measured on
// the shared meshes and their Loop subdivisions up to 1.09M vertices: 1.8-2.7 KiB per vertex,
// docs/robustness.md).
std::int64_t estimatedMemoryBytes(std::int64_t vertices, std::int64_t samples);

// `analyzed`: chooseDomain's analysis of `surface`, taken over (the mesh is not checked again).
AreaPreservingResult parameterizeDisk(const TriangleSoup& surface,
  const AreaPreservingOptions& options = AreaPreservingOptions(),
  AnalyzedInput* analyzed = nullptr);

// Where a surface is mapped: the disk (one boundary loop, or several with FillHoles) or the
// sphere (closed, genus 0).
enum class Domain
{
  Automatic = 0,
  Disk = 1,
  Sphere = 2
};

// The domain Automatic stands for: Sphere for a closed surface (no boundary edge), or with
// fillHoles for a connected genus-0 surface whose holes are all small (the largest would cover
// at most 1% of the surface: a closed scan with gaps); else Disk (also for a mesh that fails
// the checks, whose disk pipeline names the problem). `analysis`, when given, keeps the checks'
// results for the pipeline chosen.
Domain chooseDomain(
  const TriangleSoup& surface, bool fillHoles = true, AnalyzedInput* analysis = nullptr);

// The sphere's chain (sphere.md): conformal sphere map -> adaptive sampling of its area density
// on the sphere -> transport from the uniform sphere -> composition T^-1 o phi.
struct SphereParameterizationResult
{
  // status.error is prefixed by the stage that failed, as for the disk.
  Status status;
  SphereConformalStage conformal;
  SphereSamplingStage sampling;
  std::vector<Vec3> diracs; // the samples of positive mass
  std::vector<double> masses;
  int droppedSamples = 0;
  // As on the disk: the map the (last) transport starts from, after `transportStages` staged
  // transports of a crowded surface.
  std::vector<Vec3> startSphere;
  std::vector<double> startDensity;
  int transportStages = 0;
  std::int64_t startUntangledVertices = 0; // a folded conformal start, not crowded, untangled
  // Where the sphere's staged transports all failed: the start lifted from the disk maps of the
  // surface less a patch of its body and of that patch (Pipeline/LiftedDiskStart.h).
  bool startLiftedFromDisk = false;
  SphereTransportStage transport;
  std::vector<Vec3> sampleImages; // T^-1 of each Dirac: its cell's centroid on the sphere
  SphereCompositionResult composition;
  DistortionFigures figures; // of the area-preserving map, per triangle of conformal.surface
  double secondsConformal = 0, secondsSampling = 0, secondsTransport = 0, secondsComposition = 0,
         secondsTotal = 0;
};

SphereParameterizationResult parameterizeSphere(const TriangleSoup& surface,
  const AreaPreservingOptions& options = AreaPreservingOptions(),
  AnalyzedInput* analyzed = nullptr);

// Where each Dirac goes under T^-1: the centroid of its power cell, or for a Dirac on the unit
// circle the middle of its cell's arc of the circle (boundaryArcMidpoint).
std::vector<Vec2> inverseTransportOfDiracs(
  const std::vector<Vec2>& diracs, const TransportStage& transport);

} // namespace otparam

#endif
