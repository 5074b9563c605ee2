// What every sampler shares (the plane's now, the sphere's next): the modes, the options and
// the result of sampling a density with samples of equal mass.
#ifndef OTPARAM_SAMPLING_SAMPLER_H
#define OTPARAM_SAMPLING_SAMPLER_H

#include "Common/Geometry.h"
#include "Common/Status.h"

#include <functional>
#include <string>
#include <vector>

namespace otparam
{

enum class SamplingMode
{
  Adaptive = 0,    // Delaunay refinement with the density as grading (Algorithm 2)
  Uniform = 1,     // the same refinement with a constant grading: samples uniform over the domain
  MeshVertices = 2 // the input mesh's own points
};

enum class SizeRule
{
  SqrtDensity = 0, // nu-length of a length R is R * sqrt(g) (g is an area density)
  Density = 1      // the paper's literal R * g
};

struct SamplerOptions
{
  SamplingMode mode = SamplingMode::Adaptive;
  SizeRule sizeRule = SizeRule::SqrtDensity;
  long long numberOfSamples = 1000;            // target; the threshold eps follows from it
  long long maximumNumberOfSamples = 10000000; // hard cap on the refinement
  double minimumAngleDegrees = 30.0;
  // Called with the fraction done; returning false aborts.
  std::function<bool(double)> progress;
};

// The fields every sampler's result has, whatever its domain (plane or sphere).
struct SamplerResultBase
{
  // error (empty on success), warnings (e.g. the sample count could not come within 10% of
  // the target), or aborted.
  Status status;
  bool capped = false;              // the refinement stopped at maximumNumberOfSamples
  std::vector<double> mass;         // density integrated over each sample's Voronoi cell clipped
                                    // to the domain, normalized to sum to sourceMass
  double sourceMass = 0.0;          // pi for the unit disk, 4 pi for the sphere, else the area
  double epsilon = 0.0;             // the nu-length threshold used (Adaptive/Uniform)
  int refinementRuns = 0;           // runs needed to reach the target count within 10%
  bool relaxed = false;             // Lloyd relaxation kept (it made the masses more even)
  double minimumAngleDegrees = 0.0; // smallest angle of the triangles
  double massCoefficientOfVariation = 0.0;
  double secondsRefinement = 0.0;
  double secondsMasses = 0.0;
};

struct SamplerResult : SamplerResultBase
{
  std::vector<Vec2> samples;
  std::vector<Triangle> triangles; // Delaunay triangulation of the samples (mesh triangles in
                                   // MeshVertices mode)
};

// What is wrong with a value of the options (named as the filters' properties), or "".
std::string checkSamplerOptions(const SamplerOptions& options);

// Standard deviation over mean of the masses (0 for no masses).
double massCoefficientOfVariation(const std::vector<double>& mass);

// The warning when the sample count missed the target by more than 10% (uncapped), or "".
std::string sampleCountWarning(long long reached, long long target, bool capped);

// The target-count loop of the graded refinement: the count scales like 1 / eps^2, so the first
// eps is sqrt(gradedArea / target) and each later one is corrected by sqrt(count / target);
// targets of 4000 and more first run at a quarter of the target (cheap), which calibrates the
// constant. `refine(epsilon, runTarget)` refines from scratch and returns the count it
// reached, or a negative number when aborted; it sets result.capped when it hit the cap. Stops
// when a full-target run lands within `tolerance` (relative) of the target, after 5 runs, or
// when capped. Sets result.epsilon (of the last run) and result.refinementRuns. Returns false
// when aborted (result.status.aborted is then set).
bool refineToTargetCount(const SamplerOptions& options, double gradedArea, double tolerance,
  const std::function<double(double epsilon, double runTarget)>& refine, SamplerResultBase& result);

} // namespace otparam

#endif
