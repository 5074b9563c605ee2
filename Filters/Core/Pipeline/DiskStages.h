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
struct AnalyzedInput;

// ---- Stage 1: surface -> unit disk, conformally.
struct ConformalStageOptions
{
  // Normalization points as ids of the soup (-1: automatic); map.centerVertex and
  // map.alignVertex are set from them.
  std::int64_t centerPointId = -1;
  std::int64_t alignPointId = -1;
  // A genus-0 surface with several boundary loops: keep the longest as the circle and close
  // the others for the computation (keepInputPart drops the fill again).
  bool fillHoles = true;
  ConformalDiskMapOptions map;

  std::string check() const; // "" or what is wrong with a value
};

struct ConformalStage
{
  Status status;
  // The soup's referenced part (ids of the stage's outputs), then any hole fill: the input's
  // points and triangles are the first inputPoints / inputTriangles (fill points have
  // original id -1).
  CompactedMesh surface;
  std::size_t inputPoints = 0, inputTriangles = 0;
  int filledHoles = 0;
  double fillAreaFraction = 0.0; // the fill's share of the surface area (and of the disk)
  std::vector<int> boundaryLoop; // in the triangles' orientation
  // The input id of a surface point, -1 for a hole-fill point (e.g. an automatic centre).
  std::int64_t inputId(int point) const
  {
    return point >= 0 && static_cast<std::size_t>(point) < this->surface.originalPointIds.size()
      ? this->surface.originalPointIds[point]
      : -1;
  }
  ConformalDiskMapResult map; // map.uv per point of `surface`
  DistortionFigures figures;  // of the conformal map
  std::vector<double> areaDensityPerTriangle, areaDensityPerPoint;
  double maximumBoundaryRadiusError = 0.0;
};

// Through a small boundary loop the disk map crowds the whole surface (spot_closed_3k with one
// triangle cut out: mean |log area ratio| 3.96 after the whole pipeline; with holes of 0.7% /
// 1.6% / 2.7% of its area: 0.064 / 0.042 / 0.017; on the sphere 0.009): a loop whose
// largestHoleFraction is at most this gets a warning that names the sphere, and Domain
// Automatic sends such a surface there. The shared disk meshes' loops span 1.8%
// (bunny_holes_35k's largest) to 97%.
constexpr double SmallHoleFraction = 0.01;

// `analyzed`: the soup's analyzeInput, when the caller has it (InputPart.h), taken over.
ConformalStage runConformalStage(const TriangleSoup& soup, const ConformalStageOptions& options,
  AnalyzedInput* analyzed = nullptr);

// Drops the hole fill from a stage's surface, map, densities and figures (which are measured
// again on the input's own triangles); `perPointMaps` are cut to the input's points as well.
void keepInputPart(ConformalStage& stage, std::vector<std::vector<Vec2>*> perPointMaps = {});

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

// The conformal stages' warning (either domain): flipped triangles in the `domain` ("disk",
// "sphere") image.
void addConformalWarnings(const DistortionFigures& figures, const char* domain, Status& status);

// What becomes of input points that no triangle uses depends on the filter: the stage filters
// leave them out of their output (`keptAsNaN` false), the whole map keeps every input point and
// gives those NaN coordinates (true).
void warnAboutUnreferencedPoints(std::int64_t count, bool keptAsNaN, Status& status);

// The warning of a transport solve (disk or sphere) that stopped before Tolerance: how far it
// got, the solver's reason, and that the outputs hold the last iterate with Converged = 0.
std::string transportNotConvergedWarning(const NewtonReport& result, const OTOptions& options);

// Diracs and masses as given (positive, finite, distinct: checked here).
TransportStage runTransportStage(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& masses, const OTOptions& options, double maximumArcAngle);

} // namespace otparam

#endif
