// The stages of the disk pipeline as every caller runs them: the VTK filters (one stage each),
// the composite filter and the command line (all of them, through AreaPreservingPipeline.h),
// and the benchmarks. Each takes plain data as a reader or an adapter hands it over, checks it,
// runs the stage's algorithm and its figures, and ends with a Status whose messages speak of
// the user's data and parameters (property names as in the filters and the XML).
#ifndef OTPARAM_PIPELINE_DISKSTAGES_H
#define OTPARAM_PIPELINE_DISKSTAGES_H

#include "Common/Geometry.h"
#include "Common/Status.h"
#include "Conformal/ConformalDiskMap.h"
#include "Mesh/DistortionMetrics.h"
#include "Mesh/SurfaceMesh.h"
#include "Sampling/PlanarSampler.h"
#include "Transport/SemiDiscreteOT.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace otparam
{

// ---- Stage 1: surface -> unit disk, conformally.
struct ConformalStageOptions
{
  // Normalization points as ids of the soup (-1: automatic); map.centerVertex and
  // map.alignVertex are set from them.
  std::int64_t centerPointId = -1;
  std::int64_t alignPointId = -1;
  ConformalDiskMapOptions map;

  std::string check() const; // "" or what is wrong with a value
};

struct ConformalStage
{
  Status status;
  CompactedMesh surface;         // the soup's referenced part (ids of the stage's outputs)
  std::vector<int> boundaryLoop; // in the triangles' orientation
  ConformalDiskMapResult map;    // map.uv per point of `surface`
  DistortionFigures figures;     // of the conformal map
  std::vector<double> areaDensityPerTriangle, areaDensityPerPoint;
  double maximumBoundaryRadiusError = 0.0;
};

ConformalStage runConformalStage(const TriangleSoup& soup, const ConformalStageOptions& options);

// ---- Stage 2: samples of equal mass of a density on a planar triangulated domain.

// What is wrong with density values, or "": "must be finite and >= 0, but it is NaN at point
// id(s) 3, 7" / "is zero everywhere (all 25 points of the domain); ...". `what` names one value
// ("point" or "cell"); `reportedIds` (optional) maps value indices to the ids to name.
std::string checkDensityValues(const std::vector<double>& values, const char* what,
  const std::vector<std::int64_t>* reportedIds = nullptr);

struct SamplingStage
{
  Status status;
  SamplerResult result;
  std::int64_t zeroMassSamples = 0; // samples whose cell integrates to 0 (density vanishes)
};

// `perPoint` or `perTriangle` (exactly one non-empty) holds checked density values.
SamplingStage runSamplingStage(const std::vector<Vec2>& points,
  const std::vector<Triangle>& triangles, const std::vector<double>& perPoint,
  const std::vector<double>& perTriangle, const SamplerOptions& options);

// ---- Stage 3: semi-discrete transport from a planar source to Diracs.

struct TransportStage
{
  Status status;
  OTResult result;
  PowerDiagramGeometry geometry; // cells with arcs sampled at maximumArcAngle
};

// Progress of a Newton solve as a fraction. Newton converges fast near the solution, so
// iterations / maximum says little: the fraction is the larger of that and the share of the
// orders of magnitude between the first error and the tolerance already gained (at most 0.95).
class NewtonProgress
{
public:
  explicit NewtonProgress(const OTOptions& options);
  double operator()(int iteration, double relativeError);

private:
  double Tolerance;
  int MaximumNumberOfIterations;
  double FirstError = -1.0;
  double Fraction = 0.0;
};

// Diracs and masses as given (positive, finite, distinct: checked here).
TransportStage runTransportStage(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& masses, const OTOptions& options, double maximumArcAngle);

} // namespace otparam

#endif
