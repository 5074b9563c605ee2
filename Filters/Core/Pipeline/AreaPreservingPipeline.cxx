#include "Pipeline/AreaPreservingPipeline.h"

#include "Conformal/GreenDiskMap.h"
#include "Pipeline/LiftedDiskStart.h"

#include "Common/Memory.h"
#include "Common/SphericalGeometry.h"
#include "Mesh/DistortionMetrics.h"
#include "Mesh/Folds.h"
#include "Mesh/HoleFilling.h"
#include "Transport/PlanarSource.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <exception>
#include <numeric>
#include <sstream>

namespace otparam
{

namespace
{
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Each stage's share of the run's progress (measured on the shared meshes at the default
// sample count: the conformal map and the composition are the cheap ends).
struct StageRange
{
  const char* name;
  double start, end;
};
constexpr StageRange ConformalRange{ "conformal map", 0.0, 0.15 };
constexpr StageRange SamplingRange{ "sampling", 0.15, 0.4 };
constexpr StageRange TransportRange{ "transport", 0.4, 0.8 };
constexpr StageRange CompositionRange{ "composition", 0.8, 0.99 };

std::function<bool(double)> stageProgress(const AreaPreservingOptions& options, StageRange range)
{
  if (!options.progress)
  {
    return {};
  }
  return [&options, range](double fraction)
  { return options.progress(range.name, range.start + (range.end - range.start) * fraction); };
}

// Takes a stage's status into the run's, prefixed with the stage's name; true to go on.
bool passOn(const Status& stage, StageRange range, Status& run)
{
  for (const std::string& warning : stage.warnings)
  {
    run.warnings.push_back(std::string(range.name) + ": " + warning);
  }
  if (!stage.error.empty())
  {
    run.error = std::string(range.name) + ": " + stage.error;
  }
  run.aborted = run.aborted || stage.aborted;
  return run.ok();
}

// The samples of positive mass: the Diracs.
template <class Point>
void keepSamplesWithMass(const std::vector<Point>& samples, const std::vector<double>& mass,
  std::vector<Point>& diracs, std::vector<double>& masses)
{
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    if (mass[i] > 0.0)
    {
      diracs.push_back(samples[i]);
      masses.push_back(mass[i]);
    }
  }
}

// The sampling stage of either domain on the conformal image's exact per-triangle area ratio
// (masses are then exact surface areas); `runStage(options)` runs the domain's sampler. The
// Diracs are the samples of positive mass.
template <class Run, class RunStage>
void sample(const AreaPreservingOptions& options, Run& run, const std::vector<double>& density,
  const RunStage& runStage)
{
  const std::string densityError = checkDensityValues(density, "cell");
  if (!densityError.empty())
  {
    run.sampling.status.error = "The density cell array 'AreaDensity' " + densityError + ".";
    return;
  }
  SamplerOptions samplerOptions = options.sampling;
  samplerOptions.progress = stageProgress(options, SamplingRange);
  run.sampling = runStage(samplerOptions);
  if (!run.sampling.status.ok())
  {
    return;
  }
  const auto& samples = run.sampling.result;
  // Samples whose Voronoi cell integrates to 0 carry no mass: the transport is the same
  // without them, and the solver rejects zero masses. (A conformal factor is positive, so this
  // is a safety net: it caught cells ~1e-7 wide at a coarse hand's finger tips, density 1e10,
  // whose rounding-noise edges once made the integral 0.)
  keepSamplesWithMass(samples.samples, samples.mass, run.diracs, run.masses);
  run.droppedSamples = static_cast<int>(samples.samples.size() - run.diracs.size());
}

void compose(const AreaPreservingOptions& options, AreaPreservingResult& run)
{
  ConformalStage& conformal = run.conformal;
  run.sampleImages = inverseTransportOfDiracs(run.diracs, run.transport);
  CompositionOptions compositionOptions = options.composition;
  compositionOptions.progress = stageProgress(options, CompositionRange);
  if (conformal.filledHoles > 0)
  {
    compositionOptions.measuredTriangles = conformal.inputTriangles;
  }
  try
  {
    run.composition =
      composeWithInverseTransport(conformal.surface.mesh, run.startUv, conformal.boundaryLoop,
        run.diracs, run.sampleImages, compositionOptions, run.transport.result.heights);
    if (run.composition.status.aborted)
    {
      run.status.aborted = true;
      return;
    }
    if (!run.composition.status.error.empty())
    {
      run.status.error = "composition: " + run.composition.status.error + ".";
      return;
    }
    // A hole fill was mapped with the surface (it is part of the disk) and is dropped now:
    // the figures speak of the input's own triangles.
    CompositionResult& composition = run.composition;
    keepInputPart(conformal, { &composition.uv, &composition.interpolatedUv });
    run.figures = measureDistortion(conformal.surface.mesh, composition.uv);
  }
  catch (const std::exception& e)
  {
    run.status.error = std::string("composition: ") + e.what();
  }
}

// Domain Automatic sends a surface whose holes are all small (SmallHoleFraction, DiskStages.h)
// to the sphere, FillHoles closing them.

// Crowding: along a long protrusion (a finger, a limb, a tail) the conformal area density grows
// like exp(2 L / r); the transport converges while the density spans up to ~3e12 and stops at
// its start beyond (Testing/Python/TestCrowding.py, TestCrowdingSphere.py). Where the density
// spans more than CrowdedDensityRange over the bulk of the surface (crowdingRange), the
// transport runs in stages, on either domain: each samples the current map's density clamped to
// StageDensityRange times its value at CrowdingLowShare of the surface, transports, and composes
// with the area correction aiming at the clamped density's shares (stageAreaShares); the
// clamped part then gets up to StageDensityRange times its share of the domain, so each stage
// divides the range by about that, and the last transport, the usual one, starts from a map
// whose density it resolves.
constexpr double StageDensityRange = 1e10;
constexpr int MaximumTransportStages = 30; // 1e300 / 1e10^30: every range double holds
// SphereStaging::rebalanceOffset, tried in turn where the stages failed (TestCrowding's closed
// finger: 0.3 alone leaves 52 failing, 0.15 alone 45; together 37-53 and 55-60).
constexpr double StageBalanceOffsets[] = { 0.3, 0.15 };
// The sphere's last resort, where the rebalanced stages failed too: each stage clamped to 1e3
// instead of 1e10 (more, gentler stages). TestCrowding's closed finger: 54, 62, 65 and 68 then
// converge (9-13 stages), where a clamp of 1e5 left 62 and 70 failing; as the first choice
// it had made 36-40 fail (docs/design.md).
constexpr double NarrowStageDensityRange = 1e3;
// DiskStaging::keepOriginFixed: a Moebius map moving c to the origin multiplies areas by up to
// ((1 + |c|) / (1 - |c|))^2, 361 at 0.9; beyond, the stage keeps its map (and loses the tip's
// precision).
constexpr double MaximumRecentring = 0.9;

// The bulk's lowest density, not the smallest value, sets the clamp: a single sliver far below
// the rest (a procedural quadruped's marching-cubes mesh after its first stage: 7.5e-6 against
// 0.64 at 1% of the surface) had made every later clamp so low that 30 stages left the legs
// crowded, and the map at mean |log area ratio| 0.44 (docs/design.md).
std::vector<double> clampedForStage(const SurfaceMesh& surface, const std::vector<double>& density,
  double range, double lowShare = CrowdingLowShare)
{
  const double lowest = densitiesAtAreaShares(surface, density, { lowShare })[0];
  std::vector<double> clamped = density;
  for (double& g : clamped)
  {
    g = std::min(g, lowest * range);
  }
  return clamped;
}

// "" when a stage's transport converged, else what its error says.
template <class Transport>
std::string transportFailure(const Transport& transport)
{
  if (transport.status.error.empty() && transport.result.converged)
  {
    return {};
  }
  return "transport: " +
    (transport.status.error.empty()
        ? "not converged (relative error " + std::to_string(transport.result.relativeError) + ")"
        : transport.status.error);
}

// "" when a stage's composition ran, else why not. It may leave triangles flipped (a fold the
// conformal map made of a crowded finger): the next stage untangles them.
template <class Composition>
std::string compositionFailure(const Composition& composed)
{
  return composed.status.ok() ? std::string() : "composition: " + composed.status.error;
}

// The Diracs' spherical Delaunay triangulation for the composition: the sampler's when every
// sample became a Dirac, else the dual of their Voronoi diagram. (The dual of the transport's
// power diagram, which the disk interpolates over, was tried on 2026-11-27: brain_choi_closed_48k
// the same, spot_closed_3k's mean |log area ratio| 0.0093 -> 0.0099, TestCrowding's closed
// finger better at some lengths and worse at others; docs/design.md.)
std::vector<Triangle> diracTriangulation(
  const SphereSamplingStage& sampling, const SphereTransportStage& transport, std::size_t diracs)
{
  if (diracs == sampling.result.samples.size())
  {
    return sampling.result.triangles;
  }
  return computeSphericalPowerDiagramGeometry(transport.diracs, std::vector<double>(diracs, 0.0))
    .triangles;
}

// The shares of the domain a stage's transport gives the triangles of a start map: each its
// clamped density times its area there (a folded triangle's none). The stage's area correction aims
// at them: without it the compositions' mesh-scale errors piled up from stage to stage
// (TestCrowding's finger at L / rho = 80: the last transport started from a map with triangles
// crushed 1e8-fold between sound ones, and its map kept 3963 flipped triangles; now none).
template <class Staging, class Run>
std::vector<double> stageAreaShares(const Run& run, const std::vector<double>& clamped)
{
  const std::vector<Triangle>& triangles = run.conformal.surface.mesh.triangles;
  std::vector<double> shares(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    shares[t] = clamped[t] * std::max(0.0, Staging::area(run, triangles[t]));
  }
  const double total = std::accumulate(shares.begin(), shares.end(), 0.0);
  for (double& share : shares)
  {
    share /= total;
  }
  return shares;
}

// What a staged transport does on each domain: sample the map run.startUv / run.startSphere,
// transport from the uniform domain, compose, and adopt the composed map with its density.
// A stage may fold: a finger crowded beyond double precision folds and collapses its tip in the
// conformal image (disk, L / rho = 60: 222 triangles flipped; sphere, 36: 100), so a stage
// samples around the fold (the disk's unfolded part, the sphere with the fold healed by a fan),
// transports, and leaves the fold to the next stage's composition, which untangles it at the
// wider scale the stage gave the finger (TestCrowding: converged with no flip up to L / rho =
// 95, e^190, on the disk, 53 on the sphere, where a folded stage ended in an error from 60 and
// 33).
struct DiskStaging
{
  using Point = Vec2;
  void start(AreaPreservingResult& run) const
  {
    if (this->centredStart.empty())
    {
      run.startUv = run.conformal.map.uv;
      run.startDensity = run.conformal.areaDensityPerTriangle;
      return;
    }
    run.startUv = this->centredStart;
    std::vector<double> perPoint;
    computeAreaDensity(run.conformal.surface.mesh, run.startUv, run.startDensity, perPoint);
  }
  void prepare(AreaPreservingResult&) const {}
  static bool folded(const AreaPreservingResult& run)
  {
    return anyFolded(run.startUv, run.conformal.surface.mesh.triangles);
  }
  static double area(const AreaPreservingResult& run, const Triangle& t)
  {
    const Vec2 a = run.startUv[t[0]];
    return 0.5 * cross(run.startUv[t[1]] - a, run.startUv[t[2]] - a);
  }
  // The unfolded part, or with `peel` the same peeled of the triangles lying across the fold
  // (Mesh/Folds.h). Each alone fails somewhere in L / rho = 85-100 on TestCrowding's finger:
  // the unpeeled part at 85 and 95 (its boundary crosses itself), the peeled one at 90 (too
  // fine for the mesher); parameterizeDisk stages with the one, then the other.
  bool peel = false;
  // When not empty, the stages start from this map instead of the conformal one: the conformal
  // map centred at the tip of the protrusion, in polar form (GreenDiskMap.h), whose images keep
  // their relative precision at the origin where the usual map folds them.
  std::vector<Vec2> centredStart;
  double densityRange = StageDensityRange;
  double lowShare = CrowdingLowShare;
  SamplingStage sample(const AreaPreservingResult& run, const std::vector<double>& density,
    const SamplerOptions& options) const
  {
    const std::vector<Triangle>& all = run.conformal.surface.mesh.triangles;
    const std::vector<bool> kept = unfoldedPart(run.startUv, all, this->peel);
    std::vector<Triangle> triangles;
    std::vector<double> values;
    for (size_t t = 0; t < all.size(); ++t)
    {
      if (kept[t])
      {
        triangles.push_back(all[t]);
        values.push_back(density[t]);
      }
    }
    SamplerOptions samplerOptions = options;
    samplerOptions.sampleAtOrigin = !this->centredStart.empty();
    return runSamplingStage(run.startUv, triangles, {}, values, samplerOptions);
  }
  static TransportStage transport(const std::vector<Vec2>& diracs,
    const std::vector<double>& masses, const OTOptions& options, double maximumArcAngle)
  {
    const std::unique_ptr<SourceMeasure> disk = makeUnitDiskSource();
    return runTransportStage(*disk, diracs, masses, options, maximumArcAngle);
  }
  // Over the transport's regular triangulation where the start is unfolded (the stage corrects
  // its areas), as the last composition; a folded start's stage over the Delaunay triangulation:
  // over the regular one, TestCrowding's finger failed at L / rho = 80 and 95 (a later stage's
  // sampling), where it had converged.
  CompositionResult compose(const AreaPreservingResult& run, const SamplingStage&,
    const TransportStage& transport, const std::vector<Vec2>& diracs,
    const CompositionOptions& options) const
  {
    std::vector<Vec2> images = inverseTransportOfDiracs(diracs, transport);
    if (!this->centredStart.empty())
    {
      keepOriginFixed(diracs, images);
    }
    return composeWithInverseTransport(run.conformal.surface.mesh, run.startUv,
      run.conformal.boundaryLoop, diracs, images, options,
      options.correctAreas ? transport.result.heights : std::vector<double>());
  }
  // A centred start's stage moves the images by the Moebius map of the disk that sends the
  // image c of the Dirac at the origin back to it, so that the protrusion's tip, inside that
  // Dirac's triangles, keeps its relative precision (its images are a similarity of its start
  // positions there; SampleInterpolant). The next stage samples the map as it is, so the
  // Moebius map's area distortion (between ((1 - |c|) / (1 + |c|))^2 and its inverse; |c| was
  // 0.16-0.26 on TestCrowding's finger) costs only a little of that stage's range.
  static void keepOriginFixed(const std::vector<Vec2>& diracs, std::vector<Vec2>& images)
  {
    const auto atOrigin = std::find_if(
      diracs.begin(), diracs.end(), [](const Vec2& y) { return y.x == 0.0 && y.y == 0.0; });
    if (atOrigin == diracs.end())
    {
      return;
    }
    const std::size_t pinned = static_cast<std::size_t>(atOrigin - diracs.begin());
    const std::complex<double> c(images[pinned].x, images[pinned].y);
    if (!(std::abs(c) < MaximumRecentring))
    {
      return;
    }
    for (Vec2& image : images)
    {
      const std::complex<double> w(image.x, image.y);
      const std::complex<double> moved = (w - c) / (1.0 - std::conj(c) * w);
      image = { moved.real(), moved.imag() };
    }
    images[pinned] = { 0.0, 0.0 };
  }
  static void adopt(AreaPreservingResult& run, const CompositionResult& composed)
  {
    run.startUv = composed.uv;
    std::vector<double> perPoint;
    computeAreaDensity(run.conformal.surface.mesh, run.startUv, run.startDensity, perPoint);
  }
};

struct SphereStaging
{
  using Point = Vec3;
  static void start(SphereParameterizationResult& run)
  {
    run.startSphere = run.conformal.map.sphere;
    run.startDensity = run.conformal.areaDensityPerTriangle;
  }
  // With a `rebalanceOffset`, the first stage's start is moved by a Moebius map that brings
  // the centre of its clamped density's mass within that distance of the origin. The spherical
  // transport's cells lie within 90 degrees of their Diracs, so a cap of Diracs cannot take
  // more than about a hemisphere: a closed finger 38 times its radius long puts 59% of the first
  // stage's mass within 8 degrees of one point (the rest of the surface, squeezed by the
  // conformal map's area balancing against the finger), and that transport does not converge.
  // Balancing fully crushes the finger's tip further (its images collapse); the offsets tried
  // in turn, StageBalanceOffsets, were chosen on TestCrowding's closed finger (docs/design.md).
  double rebalanceOffset = 0.0;
  double densityRange = StageDensityRange;
  // The share of the surface below the density that sets the clamp and the crowding
  // (crowdingRange); 0, the smallest density, is the sphere's last resort (parameterizeSphere).
  double lowShare = CrowdingLowShare;
  void prepare(SphereParameterizationResult& run) const
  {
    if (!(this->rebalanceOffset > 0.0) || run.transportStages > 0)
    {
      return;
    }
    const std::vector<double> mass = stageAreaShares<SphereStaging>(run,
      clampedForStage(
        run.conformal.surface.mesh, run.startDensity, this->densityRange, this->lowShare));
    balanceMeasure(
      run.conformal.surface.mesh.triangles, mass, run.startSphere, this->rebalanceOffset, 50);
    std::vector<double> perPoint;
    computeSphereAreaDensity(
      run.conformal.surface.mesh, run.startSphere, run.startDensity, perPoint);
  }
  static bool folded(const SphereParameterizationResult& run)
  {
    return anyFolded(run.startSphere, run.conformal.surface.mesh.triangles);
  }
  static double area(const SphereParameterizationResult& run, const Triangle& t)
  {
    return sphericalTriangleArea(
      run.startSphere[t[0]], run.startSphere[t[1]], run.startSphere[t[2]]);
  }
  static SphereSamplingStage sample(const SphereParameterizationResult& run,
    const std::vector<double>& density, const SamplerOptions& options)
  {
    std::vector<Vec3> points = run.startSphere;
    std::vector<Triangle> triangles = run.conformal.surface.mesh.triangles;
    std::vector<double> values = density;
    healSphereFolds(points, triangles, values);
    return runSphereSamplingStage(points, triangles, values, options);
  }
  static SphereTransportStage transport(const std::vector<Vec3>& diracs,
    const std::vector<double>& masses, const OTOptions& options, double maximumArcAngle)
  {
    return runSphereTransportStage(diracs, masses, options, maximumArcAngle);
  }
  static SphereCompositionResult compose(const SphereParameterizationResult& run,
    const SphereSamplingStage& sampling, const SphereTransportStage& transport,
    const std::vector<Vec3>& diracs, const CompositionOptions& options)
  {
    CompositionOptions stageOptions = options;
    stageOptions.untangleWideStars = false;
    stageOptions.startOverWhereTangled = false;
    return composeOnSphere(run.conformal.surface.mesh, run.startSphere, transport.diracs,
      diracTriangulation(sampling, transport, diracs.size()), transport.result.centroids,
      stageOptions);
  }
  static void adopt(SphereParameterizationResult& run, const SphereCompositionResult& composed)
  {
    run.startSphere = composed.sphere;
    std::vector<double> perPoint;
    computeSphereAreaDensity(
      run.conformal.surface.mesh, run.startSphere, run.startDensity, perPoint);
  }
};

// One stage: the start map moved by the transport of its clamped density. "" or the error.
template <class Staging, class Run>
std::string transportStage(const AreaPreservingOptions& options, const Staging& staging, Run& run,
  const std::function<bool(double)>& keepGoing)
{
  SamplerOptions samplerOptions = options.sampling;
  samplerOptions.progress = keepGoing;
  staging.prepare(run);
  const std::vector<double> clamped = clampedForStage(
    run.conformal.surface.mesh, run.startDensity, staging.densityRange, staging.lowShare);
  // A folded start has no areas to aim at; its stage only widens the crowd, and the next one,
  // once the fold is untangled, corrects (correcting around a fold left the fold's rim too
  // long for a stage's sampler at L / rho = 80).
  const bool correct = !Staging::folded(run);
  const auto sampling = staging.sample(run, clamped, samplerOptions);
  if (!sampling.status.ok())
  {
    run.status.aborted = sampling.status.aborted;
    return "sampling: " + sampling.status.error;
  }
  std::vector<typename Staging::Point> diracs;
  std::vector<double> masses;
  keepSamplesWithMass(sampling.result.samples, sampling.result.mass, diracs, masses);
  OTOptions transportOptions = options.transport;
  transportOptions.progress = [&keepGoing](int, double) { return keepGoing(0.0); };
  // The stages keep the start and the Newton rows their chain was measured with (TestCrowding):
  // each stage's map feeds the next one's sampler, so the chain follows its transports' last
  // digits. Started from the Voronoi diagram shifted by 0.3 in height (the same cells, other
  // roundings), the finger of L / rho = 120 failed at stage 12, against 10 stages and 0.106 as
  // measured; with the square-root rows (DampedNewton.cxx), the closed finger of L / rho = 40
  // failed in its first stage.
  transportOptions.radialStart = false;
  transportOptions.squareRootGrowth = false;
  const auto transport =
    Staging::transport(diracs, masses, transportOptions, options.maximumArcAngle);
  run.status.aborted = transport.status.aborted;
  const std::string transportError = transportFailure(transport);
  if (!transportError.empty())
  {
    return transportError;
  }
  CompositionOptions compositionOptions = options.composition;
  compositionOptions.correctAreas = correct;
  // A stage's map must follow its transport and feeds the next stage's density: the stages
  // keep the per-vertex sweeps alone, polished 50 sweeps (TestCrowding's stage counts were
  // measured with them).
  compositionOptions.correctAtSampleScale = false;
  compositionOptions.polishKnots = false;
  if (correct)
  {
    compositionOptions.targetAreaShares = stageAreaShares<Staging>(run, clamped);
  }
  compositionOptions.progress = keepGoing;
  const auto composed = staging.compose(run, sampling, transport, diracs, compositionOptions);
  run.status.aborted = composed.status.aborted;
  const std::string compositionError = compositionFailure(composed);
  if (!compositionError.empty())
  {
    return compositionError;
  }
  Staging::adopt(run, composed);
  return {};
}

// The map the last transport starts from (run.startUv or run.startSphere, run.startDensity):
// the conformal map, moved by staged transports while its density spans more than
// CrowdedDensityRange. Sets run.sampling.status when a stage fails.
template <class Staging, class Run>
void transportInStages(const AreaPreservingOptions& options, const Staging& staging, Run& run)
{
  staging.start(run);
  run.transportStages = 0;
  run.sampling.status = Status();
  const auto keepGoing = [&options](double)
  { return !options.progress || options.progress("sampling", SamplingRange.start); };
  // The current map's crowding, measured once per stage (a sort of its densities when crowded).
  double range = crowdingRange(run.conformal.surface.mesh, run.startDensity, staging.lowShare);
  // A stage that left a fold is followed by another, which untangles it.
  while ((range > CrowdedDensityRange || (run.transportStages > 0 && Staging::folded(run))) &&
    run.status.ok())
  {
    if (run.transportStages == MaximumTransportStages ||
      checkDensityValues(run.startDensity, "cell") != "")
    {
      break; // the last transport says what it can
    }
    const std::string error = transportStage(options, staging, run, keepGoing);
    if (run.status.aborted)
    {
      run.sampling.status.aborted = true;
      return;
    }
    if (!error.empty())
    {
      std::ostringstream msg;
      const bool endsSentence = error.back() == '.';
      msg << "The conformal map crowds part of the surface (its area density spans " << range
          << ": a long protrusion such as a finger, a limb or a tail), and stage "
          << run.transportStages + 1 << " of the staged transport that widens it failed in its "
          << error.substr(0, error.size() - (endsSentence ? 1 : 0))
          << ". Cut the surface open closer to the protrusion, or map its parts separately.";
      run.sampling.status.error = msg.str();
      return;
    }
    ++run.transportStages;
    range = crowdingRange(run.conformal.surface.mesh, run.startDensity, staging.lowShare);
  }
}

// The disk's staged transports, tried in turn until one maps: from the conformal map, from its
// unfolded part peeled (when the conformal image folds), and from the conformal map centred at
// the protrusion's tip (GreenDiskMap.h), whose images keep their relative precision. The
// centred start maps TestCrowding's finger up to L / rho = 120 where the others fail from 100,
// and it mapped that finger better at 60-95 (mean |log area ratio| 0.046-0.087 against
// 0.074-0.174); but on coarser tubes (8 points per ring) the others did better (L = 60 cells:
// 0.080 against 0.25; with a second finger of 30 cells 0.12 against a transport that did not
// converge), so it comes last. Where every attempt fails, the user reads the error of the one
// that got furthest. Sets run.sampling.status as transportInStages.
void transportDiskInStages(const AreaPreservingOptions& options, AreaPreservingResult& run)
{
  Status furthest;
  int furthestStages = -1;
  const auto failed = [&]
  {
    const bool stopped = !run.sampling.status.ok() && !run.sampling.status.aborted;
    if (stopped && run.transportStages > furthestStages)
    {
      furthest = run.sampling.status;
      furthestStages = run.transportStages;
    }
    return stopped;
  };
  transportInStages(options, DiskStaging{}, run);
  if (failed() && run.conformal.figures.flippedTriangles > 0)
  {
    transportInStages(options, DiskStaging{ true }, run);
  }
  if (!failed())
  {
    return;
  }
  const GreenDiskMap green = computeGreenDiskMap(
    run.conformal.surface.mesh, run.conformal.boundaryLoop, -1, run.conformal.map.alignVertex);
  if (green.status.ok() && !anyFolded(green.uv, run.conformal.surface.mesh.triangles))
  {
    DiskStaging centred;
    centred.centredStart = green.uv;
    transportInStages(options, centred, run);
  }
  if (failed())
  {
    run.sampling.status = furthest;
  }
}

// What the composite adds to its stages' warnings: the two ways the map can still be off.
// `where`: "in the disk" or "on the sphere".
template <class Run>
void warnAboutTheMap(Run& run, const char* where)
{
  std::ostringstream msg;
  if (run.figures.flippedTriangles > 0)
  {
    msg << run.figures.flippedTriangles << " triangle(s) are flipped " << where
        << ": the untangling did not free them.";
    if (run.transportStages > 0)
    {
      msg << " The conformal map crowds part of the surface beyond what " << run.transportStages
          << " staged transport(s) could widen (a protrusion such as a finger, a limb or a tail "
             "too long for its width). Cut the surface open closer to the protrusion, or map its "
             "parts separately.";
    }
    else
    {
      // Measured: VTK's cube (8 points), capped cone (25) and a pyramid over a grid with a low
      // apex, whose few triangles cannot take the areas the samples give them.
      msg << " The map is far from area-preserving there (mean |log area ratio| "
          << run.figures.meanAbsLogAreaRatio << "): the mesh is too coarse for its shape ("
          << run.conformal.surface.mesh.points.size()
          << " points; sharp corners, fans of thin triangles): subdivide it, e.g. with a linear "
             "or Loop subdivision.";
    }
    run.status.warnings.push_back(msg.str());
    msg.str("");
  }
  else if (run.conformal.figures.flippedTriangles > 0)
  {
    // The conformal stage's own warning (addConformalWarnings) speaks of its image only: say
    // that the map the user gets has no such fold (a finger crowded beyond double precision).
    for (std::string& warning : run.status.warnings)
    {
      if (warning.rfind("conformal map: ", 0) == 0 &&
        warning.find(" are flipped ") != std::string::npos)
      {
        warning += std::string(warning.back() == '.' ? " " : ". ") +
          "The area-preserving map has none: its composition untangled them.";
      }
    }
  }
  if (!run.transport.result.converged)
  {
    msg << "The transport did not converge (relative error " << run.transport.result.relativeError
        << "); the map is approximate.";
    const std::vector<double>& density = run.conformal.areaDensityPerTriangle;
    const auto range = std::minmax_element(density.begin(), density.end());
    // Measured on a disk with a finger of growing length (Testing/Python/TestCrowding.py):
    // the transport converges up to a range of 3e12 and stops at its start beyond 2e13.
    if (range.first != density.end() && *range.second > CrowdedDensityRange * *range.first)
    {
      msg << " The conformal map crowds part of the surface into a tiny part of the domain: its "
             "area density spans "
          << *range.second / *range.first
          << " (a long protrusion such as a finger, a limb or a tail), more than the samples "
             "can resolve in double precision. Cut the surface open closer to the protrusion "
             "(put a boundary loop at its end), or map its parts separately.";
    }
    run.status.warnings.push_back(msg.str());
  }
}

// Beyond this mean |log area ratio| of a map with no flip, from a converged transport, the user is
// told: a triangle's area is then off by a factor 1.28 on average. The shared meshes end at
// 0.002-0.013, TestCrowding's fingers at up to 0.15; a procedural quadruped whose thin tail the
// staged transports left crushed ended at 0.32, silently until this warning (docs/design.md).
constexpr double FarFromAreaPreserving = 0.25;

// The third way the map can be off, where warnAboutTheMap's have not spoken: its areas, with
// what to try.
template <class Run>
void warnAboutTheAreas(Run& run, const AreaPreservingOptions& options)
{
  if (run.figures.flippedTriangles > 0 || !run.transport.result.converged ||
    !(run.figures.meanAbsLogAreaRatio > FarFromAreaPreserving))
  {
    return;
  }
  std::ostringstream msg;
  msg << "The map is far from area-preserving: mean |log area ratio| "
      << run.figures.meanAbsLogAreaRatio << " (cell array LogAreaRatio shows where). ";
  if (!options.composition.correctAreas)
  {
    msg << "AreaCorrection is off: turn it on.";
  }
  else if (run.transportStages > 0)
  {
    msg << "The conformal map crowds part of the surface (a long protrusion such as a finger, a "
           "limb or a tail), and "
        << run.transportStages
        << " staged transport(s) did not widen it enough. Cut the surface open closer to the "
           "protrusion, map its parts separately, or refine the mesh where the protrusion is "
           "only a few triangles wide.";
  }
  else
  {
    msg << "Raise NumberOfSamples (now " << options.sampling.numberOfSamples
        << ") or subdivide the mesh.";
  }
  run.status.warnings.push_back(msg.str());
}

// Samples far beyond the points buy little: the map is computed at the points, and the area
// correction removes what a finite count leaves (face_choi_bff_17k: mean |log area ratio|
// 0.011-0.012 at 5000 and at 20000 samples), while the sampler and the transport grow with the
// count (2e6 samples on that 17k-point face ran for 6 minutes, silently until this warning).
// The automatic count never reaches the bound.
void warnAboutTheSampleCount(std::int64_t samples, std::size_t points, Status& status)
{
  const std::int64_t useful =
    std::max(static_cast<std::int64_t>(points), automaticSampleCount(points));
  if (samples <= 4 * useful)
  {
    return;
  }
  std::ostringstream msg;
  msg << "NumberOfSamples = " << samples << " is more than 4 times the surface's " << points
      << " points: the map gains little from samples beyond the points, and sampling and "
         "transport take far longer (0 chooses "
      << automaticSampleCount(points) << " for this surface).";
  status.warnings.push_back(msg.str());
}

// The options with NumberOfSamples 0 (automatic) resolved for this surface.
AreaPreservingOptions withSampleCount(
  const AreaPreservingOptions& requested, const TriangleSoup& surface)
{
  AreaPreservingOptions options = requested;
  if (options.sampling.numberOfSamples == 0)
  {
    options.sampling.numberOfSamples =
      automaticSampleCount(static_cast<std::int64_t>(surface.points.size()));
  }
  return options;
}

// The four stages chained once, for either domain: each callable runs its stage into `run`;
// the chain checks the options, times the stages, passes their statuses on (prefixed with the
// stage's name), stops at the first that fails or aborts, and adds warnAboutTheMap's.
template <class Run, class Conformal, class Sample, class Transport, class Compose>
void chainStages(const AreaPreservingOptions& options, const TriangleSoup& surface, Run& run,
  const char* where, Conformal conformal, Sample sample, Transport transport, Compose compose)
{
  const auto startTotal = Clock::now();
  run.status.error = options.check();
  if (run.status.error.empty())
  {
    const std::int64_t vertices = static_cast<std::int64_t>(surface.points.size());
    run.status.error = checkMemory("Mapping a surface of " + std::to_string(vertices) +
        " points with " + std::to_string(options.sampling.numberOfSamples) + " samples",
      estimatedMemoryBytes(vertices, options.sampling.numberOfSamples), options.memoryLimitBytes);
  }
  if (!run.status.error.empty())
  {
    return;
  }
  warnAboutTheSampleCount(options.sampling.numberOfSamples, surface.points.size(), run.status);
  auto timed = [](double& seconds, const auto& stage)
  {
    const auto start = Clock::now();
    stage();
    seconds = secondsSince(start);
  };
  timed(run.secondsConformal, conformal);
  if (!passOn(run.conformal.status, ConformalRange, run.status))
  {
    return;
  }
  warnAboutUnreferencedPoints(run.conformal.surface.unreferencedPoints, true, run.status);
  timed(run.secondsSampling, sample);
  if (!passOn(run.sampling.status, SamplingRange, run.status))
  {
    return;
  }
  OTOptions transportOptions = options.transport;
  if (options.progress)
  {
    NewtonProgress fraction(transportOptions);
    auto progress = stageProgress(options, TransportRange);
    transportOptions.progress = [fraction, progress](int iteration, double error) mutable
    { return progress(fraction(iteration, error)); };
  }
  timed(run.secondsTransport, [&] { transport(transportOptions); });
  if (!passOn(run.transport.status, TransportRange, run.status))
  {
    return;
  }
  timed(run.secondsComposition, compose);
  if (run.status.ok())
  {
    warnAboutTheMap(run, where);
    warnAboutTheAreas(run, options);
  }
  run.secondsTotal = secondsSince(startTotal);
}
} // namespace

//------------------------------------------------------------------------------
AreaPreservingOptions::AreaPreservingOptions()
{
  this->sampling.numberOfSamples = 0; // automaticSampleCount
}

//------------------------------------------------------------------------------
std::int64_t automaticSampleCount(std::int64_t points)
{
  // 5000: a whole map then takes a few seconds at 50k points, and the area correction removes
  // what a finite count leaves (mean |log area ratio| 0.002-0.02 on the shared meshes).
  return std::max<std::int64_t>(5000, points / 50);
}

//------------------------------------------------------------------------------
std::string AreaPreservingOptions::check() const
{
  if (this->sampling.numberOfSamples < 3 && this->sampling.numberOfSamples != 0)
  {
    std::ostringstream msg;
    msg << "NumberOfSamples must be 0 (automatic) or at least 3; got "
        << this->sampling.numberOfSamples << ".";
    return msg.str();
  }
  SamplerOptions sampling = this->sampling;
  if (sampling.numberOfSamples == 0)
  {
    sampling.numberOfSamples = automaticSampleCount(0); // checked again once the surface is known
  }
  std::string error = checkSamplerOptions(sampling);
  if (error.empty())
  {
    error = checkTransportOptions(this->transport, this->maximumArcAngle);
  }
  if (error.empty() && this->composition.maximumCorrectionSweeps < 0)
  {
    std::ostringstream msg;
    msg << "MaximumCorrectionSweeps must be at least 0; got "
        << this->composition.maximumCorrectionSweeps << ".";
    error = msg.str();
  }
  if (error.empty())
  {
    error = this->conformal.check();
  }
  return error;
}

//------------------------------------------------------------------------------
std::vector<Vec2> inverseTransportOfDiracs(
  const std::vector<Vec2>& diracs, const TransportStage& transport)
{
  std::vector<Vec2> images = transport.result.centroids;
  const PowerDiagramGeometry& geometry = transport.geometry;
  for (std::size_t c = 0; c < geometry.cells.size(); ++c)
  {
    const int i = geometry.cellDirac[c];
    if (geometry.cells[c].size() < 3 || i < 0 || i >= static_cast<int>(diracs.size()) ||
      std::abs(std::hypot(diracs[i].x, diracs[i].y) - 1.0) > 1e-9)
    {
      continue;
    }
    const Vec2 middle = boundaryArcMidpoint(geometry.cells[c]);
    if (std::isfinite(middle.x))
    {
      images[i] = middle;
    }
  }
  return images;
}

//------------------------------------------------------------------------------
std::int64_t estimatedMemoryBytes(std::int64_t vertices, std::int64_t samples)
{
  // Peaks measured (whole process, default options): 182 MiB at 68k points, 567 MiB at 273k,
  // 2.3-2.75 GiB at 1.09M (face_choi_bff_17k Loop-subdivided), 438 MiB at 212k; 1e6 Diracs
  // of the transport alone 1.65 GiB.
  constexpr std::int64_t Base = 64 << 20, PerVertex = 2800, PerSample = 2000;
  return Base + PerVertex * vertices + PerSample * samples;
}

//------------------------------------------------------------------------------
AreaPreservingResult parameterizeDisk(
  const TriangleSoup& surface, const AreaPreservingOptions& requested, AnalyzedInput* analyzed)
{
  const AreaPreservingOptions options = withSampleCount(requested, surface);
  AreaPreservingResult run;
  chainStages(
    options, surface, run, "in the disk",
    [&]
    {
      ConformalStageOptions conformalOptions = options.conformal;
      conformalOptions.map.progress = stageProgress(options, ConformalRange);
      run.conformal = runConformalStage(surface, conformalOptions, analyzed);
    },
    [&]
    {
      transportDiskInStages(options, run);
      if (!run.sampling.status.ok())
      {
        return;
      }
      sample(options, run, run.startDensity,
        [&](const SamplerOptions& samplerOptions)
        {
          return runSamplingStage(run.startUv, run.conformal.surface.mesh.triangles, {},
            run.startDensity, samplerOptions);
        });
    },
    [&](const OTOptions& transportOptions)
    {
      const std::unique_ptr<SourceMeasure> disk = makeUnitDiskSource();
      run.transport =
        runTransportStage(*disk, run.diracs, run.masses, transportOptions, options.maximumArcAngle);
    },
    [&] { compose(options, run); });
  return run;
}

//------------------------------------------------------------------------------
Domain chooseDomain(const TriangleSoup& surface, bool fillHoles, AnalyzedInput* analysis)
{
  AnalyzedInput own;
  AnalyzedInput& input = analysis ? *analysis : own;
  input.error = analyzeInput(surface, input.compacted, input.topology);
  if (!input.error.empty())
  {
    return Domain::Disk; // its checks name the problem
  }
  const CompactedMesh& compacted = input.compacted;
  const SurfaceTopology& topology = input.topology;
  const bool closable = fillHoles && topology.components == 1 &&
    topology.eulerCharacteristic + static_cast<long long>(topology.boundaryLoops.size()) == 2 &&
    largestHoleFraction(compacted.mesh, topology.boundaryLoops) <= SmallHoleFraction;
  return topology.boundaryLoops.empty() || closable ? Domain::Sphere : Domain::Disk;
}

namespace
{
void composeOnTheSphere(const AreaPreservingOptions& options, SphereParameterizationResult& run)
{
  SphereConformalStage& conformal = run.conformal;
  run.sampleImages = run.transport.result.centroids;
  try
  {
    CompositionOptions compositionOptions = options.composition;
    compositionOptions.progress = stageProgress(options, CompositionRange);
    if (conformal.filledHoles > 0)
    {
      compositionOptions.measuredTriangles = conformal.inputTriangles;
    }
    run.composition = composeOnSphere(conformal.surface.mesh, run.startSphere, run.transport.diracs,
      diracTriangulation(run.sampling, run.transport, run.diracs.size()), run.sampleImages,
      compositionOptions);
    if (run.composition.status.aborted)
    {
      run.status.aborted = true;
      return;
    }
    if (!run.composition.status.error.empty())
    {
      run.status.error = "composition: " + run.composition.status.error + ".";
      if (run.startLiftedFromDisk)
      {
        run.status.error += " The map started from the surface's disk map lifted onto the "
                            "sphere, because the conformal sphere map crowds a protrusion (a "
                            "finger, a limb or a tail, too long for its width) beyond what staged "
                            "transports on the sphere widen: cut the surface open closer to the "
                            "protrusion, or map its parts separately.";
      }
      return;
    }
    // As on the disk, the fill was mapped with the surface and is dropped now.
    SphereCompositionResult& composition = run.composition;
    keepInputPart(conformal, { &composition.sphere, &composition.interpolated });
    run.figures = measureSphereDistortion(conformal.surface.mesh, composition.sphere);
    if (composition.flippedBeforeStartingOver > 0)
    {
      std::ostringstream msg;
      msg << composition.flippedBeforeStartingOver
          << " triangle(s) stayed flipped after the composition's untangling, so the map "
             "delivered is the "
          << (run.transportStages > 0 ? "staged transports' map" : "conformal map")
          << " corrected towards the surface's areas (no flip, mean |log area ratio| "
          << run.figures.meanAbsLogAreaRatio << "), not the transport's map. ";
      if (run.transportStages > 0)
      {
        msg << "The conformal map crowds part of the surface (a protrusion such as a finger, a "
               "limb or a tail, too long for its width): cut the surface open closer to the "
               "protrusion, or map its parts separately, for the transport's map.";
      }
      else
      {
        msg << "The mesh is coarse for its shape (" << conformal.surface.mesh.points.size()
            << " points; sharp corners, fans of long thin triangles): subdivide it (e.g. a "
               "linear or Loop subdivision) for the transport's map.";
      }
      run.status.warnings.push_back(msg.str());
    }
  }
  catch (const std::exception& e)
  {
    run.status.error = std::string("composition: ") + e.what();
  }
}
// A conformal sphere map can fold where the surface is not crowded: at a coarse sharp corner
// (the base corners of a pyramid, a vertex of three triangles whose cotangent weights are
// negative, and whose intrinsic Delaunay triangulation leaves it two neighbours). The sampler
// takes only positive triangles: the start is untangled as the composition untangles its map,
// which moves those corners' vertices only. (A crowded start is healed by its stages instead.)
void untangleConformalStart(SphereParameterizationResult& run)
{
  const SurfaceMesh& mesh = run.conformal.surface.mesh;
  run.startUntangledVertices = untangleSphereMap(mesh, run.startSphere);
  std::vector<double> perPoint;
  computeSphereAreaDensity(mesh, run.startSphere, run.startDensity, perPoint);
}

// Where every staged transport on the sphere failed (run.sampling.status's error): the start
// lifted from the disk (LiftedDiskStart.h), or the reason it gave added to the error.
void startFromLiftedDiskMap(const AreaPreservingOptions& options, SphereParameterizationResult& run)
{
  const SurfaceMesh& mesh = run.conformal.surface.mesh;
  LiftedDiskStart lifted = liftedDiskStart(options, mesh);
  if (lifted.aborted)
  {
    run.sampling.status.aborted = true;
    return;
  }
  if (!lifted.error.empty())
  {
    run.sampling.status.error += " (The disk map of the surface less a patch of its body, "
                                 "lifted onto the sphere, did not help either: " +
      lifted.error + ")";
    return;
  }
  run.startSphere = std::move(lifted.sphere);
  std::vector<double> perPoint;
  computeSphereAreaDensity(mesh, run.startSphere, run.startDensity, perPoint);
  run.transportStages = lifted.diskStages + 1;
  run.startLiftedFromDisk = true;
  run.sampling.status = Status();
  const std::int64_t centre = run.conformal.surface.originalPointIds[lifted.patchCentre];
  std::ostringstream msg;
  msg << "The conformal sphere map crowds part of the surface beyond what staged transports on "
         "the sphere widen (a protrusion such as a finger, a limb or a tail, too long for its "
         "width), so the map starts from the area-preserving disk map of the surface less a patch "
         "of "
      << 100.0 * lifted.patchShare << "% of its area around "
      << (centre >= 0 ? "point " + std::to_string(centre) : std::string("a point of a hole's fill"))
      << " (" << lifted.diskStages
      << " staged transport(s) in the disk) and that patch's own disk map, both lifted onto the "
         "sphere; the patch goes to the south pole, where angles are less faithful.";
  run.status.warnings.push_back(msg.str()); // the last sampling replaces run.sampling
}

} // namespace

//------------------------------------------------------------------------------
SphereParameterizationResult parameterizeSphere(
  const TriangleSoup& surface, const AreaPreservingOptions& requested, AnalyzedInput* analyzed)
{
  const AreaPreservingOptions options = withSampleCount(requested, surface);
  SphereParameterizationResult run;
  chainStages(
    options, surface, run, "on the sphere",
    [&]
    {
      ConformalSphereMapOptions conformalOptions = options.sphereMap;
      conformalOptions.progress = stageProgress(options, ConformalRange);
      run.conformal =
        runSphereConformalStage(surface, conformalOptions, options.conformal.fillHoles, analyzed);
    },
    [&]
    {
      // The stages from the conformal map; where a stage fails, again from a start rebalanced
      // for the first stage, then with the narrower clamp; then all of it with the clamp and the
      // crowding set by the smallest density instead of the bulk's (the rule before 2026-11-29,
      // whose chains mapped the closed finger at L / rho = 60 and 65 where the bulk's fail).
      std::vector<SphereStaging> attempts;
      for (const double lowShare : { CrowdingLowShare, 0.0 })
      {
        attempts.push_back(SphereStaging{ 0.0, StageDensityRange, lowShare });
        for (const double range : { StageDensityRange, NarrowStageDensityRange })
        {
          for (const double offset : StageBalanceOffsets)
          {
            attempts.push_back(SphereStaging{ offset, range, lowShare });
          }
        }
      }
      for (std::size_t k = 0; k < attempts.size(); ++k)
      {
        if (k == 0 || (!run.sampling.status.ok() && !run.sampling.status.aborted))
        {
          transportInStages(options, attempts[k], run);
        }
      }
      if (!run.sampling.status.ok() && !run.sampling.status.aborted)
      {
        startFromLiftedDiskMap(options, run);
      }
      if (!run.sampling.status.ok())
      {
        return;
      }
      const bool folded = run.transportStages == 0 && SphereStaging::folded(run);
      if (folded)
      {
        untangleConformalStart(run);
      }
      // Healed where the untangling left folds, as a stage samples.
      sample(options, run, run.startDensity,
        [&](const SamplerOptions& samplerOptions)
        { return SphereStaging::sample(run, run.startDensity, samplerOptions); });
      if (folded && !run.sampling.status.ok() && !run.sampling.status.aborted)
      {
        std::int64_t stillFolded = 0;
        for (const Triangle& t : run.conformal.surface.mesh.triangles)
        {
          stillFolded += positive(run.startSphere, t) ? 0 : 1;
        }
        std::ostringstream msg;
        msg << "the conformal sphere map folds " << run.conformal.map.flippedTriangles
            << " triangle(s), " << stillFolded
            << " after untangling, which the sampler cannot take. The mesh is too coarse around "
               "a sharp feature (a corner of three triangles, a cone's tip, a fan of thin "
               "triangles): refine it, e.g. with a linear or Loop subdivision";
        run.sampling.status.error = msg.str();
      }
    },
    [&](const OTOptions& transportOptions)
    {
      run.transport =
        runSphereTransportStage(run.diracs, run.masses, transportOptions, options.maximumArcAngle);
    },
    [&] { composeOnTheSphere(options, run); });
  return run;
}

} // namespace otparam
