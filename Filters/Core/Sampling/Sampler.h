// What every sampler shares (the plane's now, the sphere's next): the modes, the options and
// the result of sampling a density with samples of equal mass.
#ifndef OTPARAM_SAMPLING_SAMPLER_H
#define OTPARAM_SAMPLING_SAMPLER_H

#include "Common/Geometry.h"
#include "Common/Status.h"

#include <chrono>
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
  // Plane only: the sample nearest the origin is moved onto it before the masses are integrated
  // (a staged transport of a protrusion whose tip the map put at the origin keeps it there).
  bool sampleAtOrigin = false;
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
  bool stalled = false;             // ... or stepped without inserting (capped is set too)
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
  // Integrations over the density the relaxation ran: all its steps, or 1 when the first showed
  // the unrelaxed masses too uneven for it to help (adaptive sampling then keeps them as they are).
  int relaxationSteps = 0;
  std::vector<Vec2> samples;
  std::vector<Triangle> triangles; // Delaunay triangulation of the samples (mesh triangles in
                                   // MeshVertices mode)
};

// What is wrong with a value of the options (named as the filters' properties), or "".
std::string checkSamplerOptions(const SamplerOptions& options);

// The density scaled to a largest value in [1/4, 1) by an even power of two (positive values
// stay at least the smallest normal double): only ratios of the density matter to a sampler (the
// threshold is calibrated to the target count, the masses are normalized to the source's), and its
// relaxation integrates g^2 or g^4, which overflows for values above 1e77 and made NaN samples (a
// contrast of 1e300, found by the fuzzer). Zero stays zero, so the support is unchanged.
std::vector<double> relativeDensity(const std::vector<double>& values);

// Standard deviation over mean of the masses (0 for no masses).
double massCoefficientOfVariation(const std::vector<double>& mass);

// The warning when the sample count missed the target by more than 10% (uncapped), or "".
std::string sampleCountWarning(long long reached, long long target, bool capped);

// The most samples one refinement run may place: MaximumNumberOfSamples, and for a run aiming at
// `runTarget` samples (for an angles-only repair, its input count) at most 10 x its target +
// 2e4. Grading alone needs far fewer (a density range of 1e300 adds a few thousand); a run
// past it does not end in reasonable time: a disk with a spike 1e6 times its radius needs
// millions of samples to mesh at 30 degrees, and CGAL's insertions into its long thin
// triangles cost O(n) each (1e5 samples in 42 s).
long long refinementLimit(const SamplerOptions& options, double runTarget);

// The error for a run that was capped (`reached` samples) when it stalled or its cap was
// refinementLimit below MaximumNumberOfSamples (a runaway), naming what to check; "" when the
// cap was the user's MaximumNumberOfSamples.
std::string runawayRefinementError(
  const SamplerOptions& options, double runTarget, long long reached, bool stalled);

// The target-count loop of the graded refinement: the count scales like 1 / eps^2 where eps
// sets the sizes, so the first eps is sqrt(gradedArea / target) (from 5e4 samples a pilot run
// at a quarter of the target); later runs correct it by the power of count / target that the
// last two runs measured (2 after the first run).
// `refine(epsilon)` refines from scratch and returns the count it reached, or a negative number
// when aborted or failed (with result.status.error set); it sets result.capped when it hit the
// cap. Stops when a run lands within `tolerance` (relative) of the target, after 5 runs, or
// when capped. Sets result.epsilon (of the last run) and result.refinementRuns. Returns false
// when aborted (result.status.aborted is then set) or when the refinement ran away (the last
// run stopped at refinementLimit below MaximumNumberOfSamples, or any run stalled;
// result.status.error says so).
bool refineToTargetCount(const SamplerOptions& options, double gradedArea, double tolerance,
  const std::function<double(double epsilon)>& refine, SamplerResultBase& result);

// Progress over the refinement runs of refineToTargetCount: each run gets its rough share of the
// first 90% of the sampler's work. Most densities need one or two runs: each gets half the
// share, the runs after the second none.
class RefinementProgress
{
public:
  explicit RefinementProgress(const SamplerOptions& options)
    : Options(options)
  {
  }

  // The callback of the next run, which aims at NumberOfSamples: false to abort.
  std::function<bool(long long count)> ofRun();

private:
  const SamplerOptions& Options;
  double Done = 0.0;
};

// A refinement step's abort check: asks `keepGoing(count)` once 0.1 s has passed since it last
// did. A step costs from a microsecond (a small density mesh) to milliseconds (bounding the
// density over a large triangle of a 1e6-triangle mesh), so no fixed step count suits both.
class RefinementAbortCheck
{
public:
  explicit RefinementAbortCheck(const std::function<bool(long long)>& keepGoing);
  bool stepDone(long long count);

private:
  const std::function<bool(long long)>& KeepGoing;
  std::chrono::steady_clock::time_point Last;
};

} // namespace otparam

#endif
