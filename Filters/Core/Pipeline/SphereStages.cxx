#include "Pipeline/SphereStages.h"

#include "Mesh/HoleFilling.h"
#include "Pipeline/DiskStages.h"
#include "Pipeline/InputPart.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace otparam
{

namespace
{
// Beyond this (largestHoleFraction) a fill is no hole of a closed surface but half of it: a
// flat disk closed by its fill mapped with a mean |log area ratio| of 0.76.
constexpr double LargestSphereHole = 0.1;

// "" or, when a boundary loop is a slit (an unmerged seam), what merges it: checked before the
// holes' size (and without FillHoles, where sphereTopologyError would say to use the Disk domain).
std::string slitMessage(const SurfaceTopology& topology, const SphereConformalStage& stage)
{
  const std::size_t loops = topology.boundaryLoops.size();
  if (loops == 0 || topology.components != 1)
  {
    return {};
  }
  const std::string slit = slitAmongHoles(
    stage.surface.mesh, topology.boundaryLoops, loops, &stage.surface.originalPointIds);
  return slit.empty() ? slit
                      : "the surface has " + std::to_string(loops) + " boundary loop" +
      (loops > 1 ? "s" : "") + ", and " + slit;
}

// A connected genus-0 surface, analyzed into `topology`, with boundary loops closed by filling
// every hole; "" or what stops it. A closed surface is left as it is.
std::string closeHoles(const SurfaceTopology& topology, SphereConformalStage& stage)
{
  CompactedMesh& surface = stage.surface;
  const auto loops = static_cast<long long>(topology.boundaryLoops.size());
  if (loops == 0 || topology.components != 1)
  {
    return {}; // sphereTopologyError names the rest
  }
  std::ostringstream msg;
  msg << "the surface has " << loops << " boundary loop" << (loops > 1 ? "s" : "");
  const long long genus = (2 - topology.eulerCharacteristic - loops) / 2;
  if (genus != 0)
  {
    msg << " and genus " << genus << " (Euler characteristic " << topology.eulerCharacteristic
        << "); FillHoles closes holes, but the sphere needs genus 0";
    return msg.str();
  }
  const std::string slit = slitMessage(topology, stage);
  if (!slit.empty())
  {
    return slit;
  }
  const double largest = largestHoleFraction(surface.mesh, topology.boundaryLoops);
  if (largest > LargestSphereHole)
  {
    msg << ", the largest of which would cover " << percentOf(largest)
        << " of the surface (a round disk of its length): the sphere takes closed surfaces, "
           "and closed scans whose holes cover at most "
        << percentOf(LargestSphereHole) << " (use the Disk domain)";
    return msg.str();
  }
  FilledSurface filled;
  const std::string fillError = fillHoles(surface.mesh, topology.boundaryLoops,
    topology.boundaryLoops.size(), filled, &surface.originalPointIds);
  if (!fillError.empty())
  {
    return msg.str() + ", and " + fillError;
  }
  adoptHoleFill(stage, std::move(filled));
  return {};
}
} // namespace

SphereConformalStage runSphereConformalStage(const TriangleSoup& soup,
  const ConformalSphereMapOptions& options, bool fillHoles, AnalyzedInput* analyzed)
{
  SphereConformalStage stage;
  Status& status = stage.status;
  SurfaceTopology topology;
  status.error = takeOrAnalyzeInput(soup, analyzed, stage.surface, topology);
  stage.inputPoints = stage.surface.mesh.points.size();
  stage.inputTriangles = stage.surface.mesh.triangles.size();
  if (!status.error.empty())
  {
    return stage;
  }
  std::string error = fillHoles ? closeHoles(topology, stage) : slitMessage(topology, stage);
  if (error.empty())
  {
    // A filled surface is checked anew (its fill too must be a valid mesh).
    error = stage.filledHoles > 0
      ? checkSphereTopology(stage.surface.mesh, &stage.surface.originalPointIds)
      : sphereTopologyError(topology);
  }
  if (!error.empty())
  {
    status.error = "The input is not a closed genus-0 triangle surface: " + error + ".";
    return stage;
  }
  // The mesh checks take about 2 s at 1e6 points: an abort is honoured before the map.
  if (options.progress && !options.progress(0.0))
  {
    status.aborted = true;
    return stage;
  }
  const SurfaceMesh& mesh = stage.surface.mesh;
  try
  {
    stage.map = computeConformalSphereMap(mesh, options);
    if (stage.map.status.aborted)
    {
      status.aborted = true;
      return stage;
    }
    if (!stage.map.status.error.empty())
    {
      status.error = "The conformal sphere map failed: " + stage.map.status.error + ".";
      return stage;
    }
    stage.figures = measureSphereDistortion(mesh, stage.map.sphere);
    computeSphereAreaDensity(
      mesh, stage.map.sphere, stage.areaDensityPerTriangle, stage.areaDensityPerPoint);
  }
  catch (const std::exception& e)
  {
    status.error = std::string("The conformal sphere map failed: ") + e.what();
    return stage;
  }
  status.warnings = stage.map.status.warnings;
  if (stage.map.flippedTriangles == 0) // else the map's own warning says it
  {
    addConformalWarnings(stage.figures, "sphere", status);
  }
  return stage;
}

void keepInputPart(SphereConformalStage& stage, std::vector<std::vector<Vec3>*> perPointMaps)
{
  dropHoleFill(stage, stage.map.sphere, std::move(perPointMaps),
    [&stage]
    {
      const SurfaceMesh& mesh = stage.surface.mesh;
      stage.figures = measureSphereDistortion(mesh, stage.map.sphere);
      computeSphereAreaDensity(
        mesh, stage.map.sphere, stage.areaDensityPerTriangle, stage.areaDensityPerPoint);
    });
}

SphereSamplingStage runSphereSamplingStage(const std::vector<Vec3>& spherePoints,
  const std::vector<Triangle>& triangles, const std::vector<double>& perTriangle,
  const SamplerOptions& options)
{
  SphereSamplingStage stage;
  Status& status = stage.status;
  status.error = checkSamplerOptions(options);
  if (!status.error.empty())
  {
    return stage;
  }
  try
  {
    stage.result = sampleSphere(spherePoints, triangles, perTriangle, options);
  }
  catch (const std::exception& e)
  {
    status.error = std::string("The sampling failed: ") + e.what();
    return stage;
  }
  const SphericalSamplerResult& result = stage.result;
  if (result.status.aborted)
  {
    status.aborted = true;
    return stage;
  }
  if (!result.status.error.empty())
  {
    status.error = "The sampling failed: " + result.status.error;
    return stage;
  }
  if (result.capped)
  {
    std::ostringstream msg;
    msg << "The refinement hit the cap MaximumNumberOfSamples = " << options.maximumNumberOfSamples
        << " and stopped there with " << result.samples.size()
        << " samples (raise MaximumNumberOfSamples or lower NumberOfSamples).";
    status.warnings.push_back(msg.str());
  }
  status.warnings.insert(
    status.warnings.end(), result.status.warnings.begin(), result.status.warnings.end());
  return stage;
}

SphereTransportStage runSphereTransportStage(const std::vector<Vec3>& diracs,
  const std::vector<double>& masses, const OTOptions& options, double maximumArcAngle)
{
  SphereTransportStage stage;
  Status& status = stage.status;
  status.error = checkTransportOptions(options, maximumArcAngle);
  if (!status.error.empty())
  {
    return stage;
  }
  stage.diracs = diracs;
  const std::string diracError = validateSphericalDiracs(stage.diracs, masses);
  if (!diracError.empty())
  {
    status.error = "Invalid Diracs input (port 0): " + diracError + ".";
    return stage;
  }
  SphericalOTResult& result = stage.result;
  try
  {
    result = solveSphericalOT(stage.diracs, masses, options);
    if (result.aborted)
    {
      status.aborted = true;
      return stage;
    }
    stage.geometry =
      computeSphericalPowerDiagramGeometry(stage.diracs, result.heights, maximumArcAngle);
  }
  catch (const std::exception& e)
  {
    status.error = std::string("The spherical OT solve failed: ") + e.what();
    return stage;
  }
  if (result.heights.size() != diracs.size())
  {
    status.error = "The spherical OT solve returned no solution: " + result.message + ".";
    return stage;
  }
  if (!result.converged)
  {
    status.warnings.push_back(transportNotConvergedWarning(result, options));
  }
  return stage;
}

bool pointsOnUnitSphere(const std::vector<Vec3>& points, double tolerance)
{
  for (const Vec3& p : points)
  {
    if (!(std::abs(norm(p) - 1.0) <= tolerance))
    {
      return false;
    }
  }
  return !points.empty();
}

} // namespace otparam
