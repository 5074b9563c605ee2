#include "Pipeline/AreaPreservingPipeline.h"

#include "Common/Memory.h"
#include "Transport/PlanarSource.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
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
  for (std::size_t i = 0; i < samples.samples.size(); ++i)
  {
    if (samples.mass[i] > 0.0)
    {
      run.diracs.push_back(samples.samples[i]);
      run.masses.push_back(samples.mass[i]);
    }
  }
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
    run.composition = composeWithInverseTransport(conformal.surface.mesh, run.startUv,
      conformal.boundaryLoop, run.diracs, run.sampleImages, compositionOptions);
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

constexpr double CrowdedDensityRange = 1e12;

// Crowding: along a long protrusion (a finger, a limb, a tail) the conformal area density grows
// like exp(2 L / r); the transport converges while the density spans up to ~3e12 and stops at
// its start beyond (Testing/Python/TestCrowding.py). Above CrowdedDensityRange the transport
// runs in stages: each samples the current map's density clamped to StageDensityRange times
// its smallest value, transports, and composes without the area correction (the targets are
// those of the clamped density); the clamped part then gets up to StageDensityRange times its
// share of the disk, so each stage divides the range by about that, and the last transport,
// the usual one, starts from a map whose density it resolves.
constexpr double StageDensityRange = 1e10;
constexpr int MaximumTransportStages = 30; // 1e300 / 1e10^30: every range double holds

double rangeOf(const std::vector<double>& density)
{
  const auto range = std::minmax_element(density.begin(), density.end());
  return range.first == density.end() ? 1.0 : *range.second / *range.first;
}

// One stage: the map startUv moved by the transport of its clamped density. "" or the error.
std::string transportStage(const AreaPreservingOptions& options, AreaPreservingResult& run,
  const std::function<bool(double)>& keepGoing)
{
  const SurfaceMesh& mesh = run.conformal.surface.mesh;
  const double lowest = *std::min_element(run.startDensity.begin(), run.startDensity.end());
  std::vector<double> clamped = run.startDensity;
  for (double& g : clamped)
  {
    g = std::min(g, lowest * StageDensityRange);
  }
  SamplerOptions samplerOptions = options.sampling;
  samplerOptions.progress = keepGoing;
  const SamplingStage sampling =
    runSamplingStage(run.startUv, mesh.triangles, {}, clamped, samplerOptions);
  if (!sampling.status.ok())
  {
    run.status.aborted = sampling.status.aborted;
    return "sampling: " + sampling.status.error;
  }
  std::vector<Vec2> diracs;
  std::vector<double> masses;
  for (std::size_t i = 0; i < sampling.result.samples.size(); ++i)
  {
    if (sampling.result.mass[i] > 0.0)
    {
      diracs.push_back(sampling.result.samples[i]);
      masses.push_back(sampling.result.mass[i]);
    }
  }
  OTOptions transportOptions = options.transport;
  transportOptions.progress = [&keepGoing](int, double) { return keepGoing(0.0); };
  const std::unique_ptr<SourceMeasure> disk = makeUnitDiskSource();
  const TransportStage transport =
    runTransportStage(*disk, diracs, masses, transportOptions, options.maximumArcAngle);
  if (transport.status.aborted)
  {
    run.status.aborted = true;
    return "transport aborted";
  }
  if (!transport.status.error.empty() || !transport.result.converged)
  {
    std::ostringstream msg;
    msg << "transport: "
        << (transport.status.error.empty() ? "not converged (relative error " +
                std::to_string(transport.result.relativeError) + ")"
                                           : transport.status.error);
    return msg.str();
  }
  CompositionOptions compositionOptions = options.composition;
  compositionOptions.correctAreas = false;
  compositionOptions.progress = keepGoing;
  const CompositionResult composed = composeWithInverseTransport(mesh, run.startUv,
    run.conformal.boundaryLoop, diracs, inverseTransportOfDiracs(diracs, transport),
    compositionOptions);
  if (!composed.status.ok() || composed.flippedTriangles > 0)
  {
    run.status.aborted = composed.status.aborted;
    return "composition: " +
      (composed.status.error.empty() ? std::to_string(composed.flippedTriangles) +
            " triangle(s) stay flipped"
                                     : composed.status.error);
  }
  run.startUv = composed.uv;
  std::vector<double> perPoint;
  computeAreaDensity(mesh, run.startUv, run.startDensity, perPoint);
  return {};
}

// The map the last transport starts from (run.startUv, run.startDensity): the conformal map,
// moved by staged transports while its density spans more than CrowdedDensityRange. Sets
// run.sampling.status when a stage fails.
void transportInStages(const AreaPreservingOptions& options, AreaPreservingResult& run)
{
  run.startUv = run.conformal.map.uv;
  run.startDensity = run.conformal.areaDensityPerTriangle;
  const auto keepGoing = [&options](double)
  { return !options.progress || options.progress("sampling", SamplingRange.start); };
  while (rangeOf(run.startDensity) > CrowdedDensityRange && run.status.ok())
  {
    if (run.transportStages == MaximumTransportStages ||
      checkDensityValues(run.startDensity, "cell") != "")
    {
      break; // the last transport says what it can
    }
    const double range = rangeOf(run.startDensity);
    const std::string error = transportStage(options, run, keepGoing);
    if (run.status.aborted)
    {
      run.sampling.status.aborted = true;
      return;
    }
    if (!error.empty())
    {
      std::ostringstream msg;
      msg << "The conformal map crowds part of the surface (its area density spans " << range
          << ": a long protrusion such as a finger, a limb or a tail), and stage "
          << run.transportStages + 1
          << " of the staged transport that widens it failed in its " << error
          << ". Cut the surface open closer to the protrusion, or map its parts separately.";
      run.sampling.status.error = msg.str();
      return;
    }
    ++run.transportStages;
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
    run.status.warnings.push_back(msg.str());
    msg.str("");
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
  const TriangleSoup& surface, const AreaPreservingOptions& requested)
{
  const AreaPreservingOptions options = withSampleCount(requested, surface);
  AreaPreservingResult run;
  chainStages(
    options, surface, run, "in the disk",
    [&]
    {
      ConformalStageOptions conformalOptions = options.conformal;
      conformalOptions.map.progress = stageProgress(options, ConformalRange);
      run.conformal = runConformalStage(surface, conformalOptions);
    },
    [&]
    {
      transportInStages(options, run);
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
Domain chooseDomain(const TriangleSoup& surface)
{
  CompactedMesh compacted;
  SurfaceTopology topology;
  if (compactMesh(surface.points, surface.triangles, compacted).empty() &&
    analyzeSurface(compacted.mesh, topology).empty() && topology.boundaryLoops.empty())
  {
    return Domain::Sphere;
  }
  return Domain::Disk;
}

namespace
{
void composeOnTheSphere(const AreaPreservingOptions& options, SphereParameterizationResult& run)
{
  const SphereConformalStage& conformal = run.conformal;
  run.sampleImages = run.transport.result.centroids;
  // The interpolation needs the Diracs' own spherical Delaunay triangulation: the sampler's
  // (all its samples kept) or, after samples were dropped, the Voronoi diagram's dual.
  const std::vector<Triangle> triangles = run.droppedSamples == 0
    ? run.sampling.result.triangles
    : computeSphericalPowerDiagramGeometry(
        run.transport.diracs, std::vector<double>(run.diracs.size(), 0.0))
        .triangles;
  try
  {
    CompositionOptions compositionOptions = options.composition;
    compositionOptions.progress = stageProgress(options, CompositionRange);
    run.composition = composeOnSphere(conformal.surface.mesh, conformal.map.sphere,
      run.transport.diracs, triangles, run.sampleImages, compositionOptions);
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
    run.figures = measureSphereDistortion(conformal.surface.mesh, run.composition.sphere);
  }
  catch (const std::exception& e)
  {
    run.status.error = std::string("composition: ") + e.what();
  }
}
} // namespace

//------------------------------------------------------------------------------
SphereParameterizationResult parameterizeSphere(
  const TriangleSoup& surface, const AreaPreservingOptions& requested)
{
  const AreaPreservingOptions options = withSampleCount(requested, surface);
  SphereParameterizationResult run;
  chainStages(
    options, surface, run, "on the sphere",
    [&]
    {
      ConformalSphereMapOptions conformalOptions = options.sphereMap;
      conformalOptions.progress = stageProgress(options, ConformalRange);
      run.conformal = runSphereConformalStage(surface, conformalOptions);
    },
    [&]
    {
      sample(options, run, run.conformal.areaDensityPerTriangle,
        [&](const SamplerOptions& samplerOptions)
        {
          return runSphereSamplingStage(run.conformal.map.sphere,
            run.conformal.surface.mesh.triangles, run.conformal.areaDensityPerTriangle,
            samplerOptions);
        });
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
