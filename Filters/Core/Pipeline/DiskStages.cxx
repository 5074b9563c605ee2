#include "Pipeline/DiskStages.h"

#include "Common/IdList.h"
#include "Mesh/HoleFilling.h"
#include "Pipeline/InputPart.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>

namespace otparam
{

namespace
{
// Soup ids of the normalization points -> ids of the compacted surface, checked against the
// boundary loop; "" or the message.
std::string normalizationVertices(const TriangleSoup& soup, const ConformalStageOptions& options,
  const CompactedMesh& surface, const std::vector<int>& loop, ConformalDiskMapOptions& map)
{
  const auto numberOfPoints = static_cast<std::int64_t>(soup.points.size());
  std::vector<int> meshId(soup.points.size(), -1);
  for (std::size_t v = 0; v < surface.originalPointIds.size(); ++v)
  {
    if (surface.originalPointIds[v] >= 0) // not a hole-fill point
    {
      meshId[surface.originalPointIds[v]] = static_cast<int>(v);
    }
  }
  std::ostringstream msg;
  auto toMeshId = [&](std::int64_t id, const char* property, int& out)
  {
    out = -1;
    if (id == -1)
    {
      return true;
    }
    if (id < 0 || id >= numberOfPoints)
    {
      msg << property << " = " << id << " is not a point id of the input (it has " << numberOfPoints
          << " points; -1 chooses automatically).";
      return false;
    }
    if (meshId[id] < 0)
    {
      msg << property << " = " << id << " names a point that belongs to no triangle.";
      return false;
    }
    out = meshId[id];
    return true;
  };
  if (!toMeshId(options.centerPointId, "CenterPointId", map.centerVertex) ||
    !toMeshId(options.alignPointId, "AlignPointId", map.alignVertex))
  {
    return msg.str();
  }
  std::vector<char> onBoundary(surface.mesh.points.size(), 0);
  for (int v : loop)
  {
    onBoundary[v] = 1;
  }
  if (map.centerVertex >= 0 && onBoundary[map.centerVertex])
  {
    msg << "CenterPointId = " << options.centerPointId
        << " is a boundary point; the point sent to the disk's centre must be an interior "
           "point.";
  }
  else if (map.alignVertex >= 0 && !onBoundary[map.alignVertex])
  {
    msg << "AlignPointId = " << options.alignPointId
        << " is not a boundary point; the point sent to (1, 0) must be on the boundary loop.";
  }
  return msg.str();
}

// The stage's surface, analyzed into `topology`, made a disk: checked, and with FillHoles its
// extra boundary loops closed; "" or what is wrong with its topology.
std::string makeDisk(
  const ConformalStageOptions& options, SurfaceTopology& topology, ConformalStage& stage)
{
  CompactedMesh& surface = stage.surface;
  std::string error;
  const long long loops = static_cast<long long>(topology.boundaryLoops.size());
  const long long genus = (2 - topology.eulerCharacteristic - loops) / 2;
  if (loops > 1 && topology.components == 1)
  {
    std::ostringstream msg;
    msg << "the surface has " << loops << " boundary loops";
    if (!options.fillHoles)
    {
      const std::string slit = slitAmongHoles(surface.mesh, topology.boundaryLoops,
        longestLoop(surface.mesh, topology.boundaryLoops), &surface.originalPointIds);
      return msg.str() +
        (slit.empty() ? "; a disk-like surface needs exactly 1 (turn FillHoles on to close all "
                        "but the longest)"
                      : ", and " + slit);
    }
    if (genus != 0)
    {
      msg << " and genus " << genus << " (Euler characteristic " << topology.eulerCharacteristic
          << "); FillHoles closes holes, but the surface must have genus 0 to become a disk";
      return msg.str();
    }
    FilledSurface filled;
    error =
      fillHolesButLongest(surface.mesh, topology.boundaryLoops, filled, &surface.originalPointIds);
    if (!error.empty())
    {
      return msg.str() + ", and " + error;
    }
    adoptHoleFill(stage, std::move(filled));
    error = checkDiskTopology(surface.mesh, stage.boundaryLoop, &surface.originalPointIds);
    return error.empty() ? error : "closing its holes gave a surface that is not a disk: " + error;
  }
  return diskTopologyError(topology, stage.boundaryLoop);
}
} // namespace

//------------------------------------------------------------------------------
std::string ConformalStageOptions::check() const
{
  std::string error = checkPositiveFinite("Tolerance", this->map.tolerance);
  if (error.empty())
  {
    error = checkAtLeast("MaximumNumberOfIterations", this->map.maximumNumberOfIterations, 0);
  }
  return error;
}

//------------------------------------------------------------------------------
ConformalStage runConformalStage(
  const TriangleSoup& soup, const ConformalStageOptions& options, AnalyzedInput* analyzed)
{
  ConformalStage stage;
  Status& status = stage.status;
  status.error = options.check();
  if (!status.error.empty())
  {
    return stage;
  }
  SurfaceTopology topology;
  status.error = takeOrAnalyzeInput(soup, analyzed, stage.surface, topology);
  stage.inputPoints = stage.surface.mesh.points.size();
  stage.inputTriangles = stage.surface.mesh.triangles.size();
  if (!status.error.empty())
  {
    return stage;
  }
  const std::string error = makeDisk(options, topology, stage);
  if (!error.empty())
  {
    status.error = "The input is not a disk-like triangle surface: " + error + ".";
    return stage;
  }
  ConformalDiskMapOptions mapOptions = options.map;
  status.error =
    normalizationVertices(soup, options, stage.surface, stage.boundaryLoop, mapOptions);
  if (!status.error.empty())
  {
    return stage;
  }
  // The mesh checks take about 2 s at 1e6 points: an abort is honoured before the map.
  if (options.map.progress && !options.map.progress(0.0))
  {
    status.aborted = true;
    return stage;
  }
  const SurfaceMesh& mesh = stage.surface.mesh;
  try
  {
    stage.map = computeConformalDiskMap(mesh, stage.boundaryLoop, mapOptions);
    if (stage.map.status.aborted)
    {
      status.aborted = true;
      return stage;
    }
    if (!stage.map.status.error.empty())
    {
      status.error = "The conformal map failed: " + stage.map.status.error + ".";
      return stage;
    }
    stage.figures = measureDistortion(mesh, stage.map.uv);
    computeAreaDensity(mesh, stage.map.uv, stage.areaDensityPerTriangle, stage.areaDensityPerPoint);
  }
  catch (const std::exception& e)
  {
    status.error = std::string("The conformal map failed: ") + e.what();
    return stage;
  }
  status.warnings = stage.map.status.warnings;
  for (int v : stage.boundaryLoop)
  {
    stage.maximumBoundaryRadiusError = std::max(stage.maximumBoundaryRadiusError,
      std::abs(std::hypot(stage.map.uv[v].x, stage.map.uv[v].y) - 1.0));
  }
  addConformalWarnings(stage.figures, "disk", status);
  const double hole = largestHoleFraction(mesh, { stage.boundaryLoop });
  if (hole <= SmallHoleFraction)
  {
    status.warnings.push_back("The boundary loop is small (a round disk of its length would "
                              "cover " +
      percentOf(hole) +
      " of the surface): the disk map squeezes the whole surface through it. A map onto the "
      "sphere with the hole closed fits such a surface better (vtkConformalSphereMap, or Domain "
      "Sphere of the area-preserving parameterization; FillHoles closes the hole).");
  }
  return stage;
}

//------------------------------------------------------------------------------
void keepInputPart(ConformalStage& stage, std::vector<std::vector<Vec2>*> perPointMaps)
{
  dropHoleFill(stage, stage.map.uv, std::move(perPointMaps),
    [&stage]
    {
      const SurfaceMesh& mesh = stage.surface.mesh;
      stage.figures = measureDistortion(mesh, stage.map.uv);
      computeAreaDensity(
        mesh, stage.map.uv, stage.areaDensityPerTriangle, stage.areaDensityPerPoint);
    });
}

//------------------------------------------------------------------------------
std::string checkDensityValues(
  const std::vector<double>& values, const char* what, const std::vector<std::int64_t>* reportedIds)
{
  std::vector<std::int64_t> nan, infinite, negative;
  double firstNegative = 0.0;
  bool positive = false;
  for (std::size_t k = 0; k < values.size(); ++k)
  {
    const std::int64_t id = reportedIds ? (*reportedIds)[k] : static_cast<std::int64_t>(k);
    const double value = values[k];
    if (std::isnan(value))
    {
      nan.push_back(id);
    }
    else if (std::isinf(value))
    {
      infinite.push_back(id);
    }
    else if (value < 0.0)
    {
      firstNegative = negative.empty() ? value : firstNegative;
      negative.push_back(id);
    }
    else if (value > 0.0)
    {
      positive = true;
    }
  }
  std::ostringstream msg;
  const std::string ids = std::string(" at ") + what + " id(s) ";
  if (!nan.empty())
  {
    msg << "must be finite and >= 0, but it is NaN" << ids << idList(nan);
  }
  else if (!infinite.empty())
  {
    msg << "must be finite and >= 0, but it is infinite" << ids << idList(infinite);
  }
  else if (!negative.empty())
  {
    msg << "must be finite and >= 0, but it is negative" << ids << idList(negative)
        << " (first value: " << firstNegative << ")";
  }
  else if (!positive)
  {
    msg << "is zero everywhere (all " << values.size()
        << (std::string(what) == "point" ? " points" : " triangles")
        << " of the domain); it must be positive somewhere";
  }
  return msg.str();
}

//------------------------------------------------------------------------------
SamplingStage runSamplingStage(const std::vector<Vec2>& points,
  const std::vector<Triangle>& triangles, const std::vector<double>& perPoint,
  const std::vector<double>& perTriangle, const SamplerOptions& options)
{
  SamplingStage stage;
  Status& status = stage.status;
  status.error = checkSamplerOptions(options);
  if (!status.error.empty())
  {
    return stage;
  }
  std::string error;
  std::unique_ptr<DensityField> density;
  try
  {
    density = DensityField::create(points, triangles, perPoint, perTriangle, error);
  }
  catch (const std::exception& e)
  {
    density.reset();
    error = e.what();
  }
  if (!density)
  {
    status.error = "The domain is not supported: " + error + ".";
    return stage;
  }
  if (options.progress && !options.progress(0.0)) // the density's search trees took a while
  {
    status.aborted = true;
    return stage;
  }
  SamplerResult& result = stage.result;
  try
  {
    result = sampleDensity(*density, options);
  }
  catch (const std::exception& e)
  {
    status.error = std::string("The sampling failed: ") + e.what();
    return stage;
  }
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
  if (result.samples.empty() || result.mass.size() != result.samples.size())
  {
    std::ostringstream msg;
    msg << "The sampling returned " << result.samples.size() << " samples and "
        << result.mass.size() << " masses; expected one mass per sample.";
    status.error = msg.str();
    return stage;
  }
  stage.zeroMassSamples =
    std::count_if(result.mass.begin(), result.mass.end(), [](double m) { return !(m > 0.0); });
  std::ostringstream msg;
  if (result.capped)
  {
    msg << "The refinement hit the cap MaximumNumberOfSamples = " << options.maximumNumberOfSamples
        << " and stopped there with " << result.samples.size()
        << " samples: the triangles are not all refined to the size threshold (raise "
           "MaximumNumberOfSamples or lower NumberOfSamples).";
    status.warnings.push_back(msg.str());
    msg.str("");
  }
  status.warnings.insert(
    status.warnings.end(), result.status.warnings.begin(), result.status.warnings.end());
  return stage;
}

//------------------------------------------------------------------------------
NewtonProgress::NewtonProgress(const OTOptions& options)
  : Tolerance(options.tolerance)
  , MaximumNumberOfIterations(std::max(1, options.maximumNumberOfIterations))
{
}

//------------------------------------------------------------------------------
double NewtonProgress::operator()(int iteration, double relativeError)
{
  if (this->FirstError < 0.0)
  {
    this->FirstError = relativeError;
  }
  double fraction = static_cast<double>(iteration) / this->MaximumNumberOfIterations;
  if (this->FirstError > this->Tolerance && relativeError > 0.0)
  {
    fraction = std::max(fraction,
      std::log(this->FirstError / relativeError) / std::log(this->FirstError / this->Tolerance));
  }
  this->Fraction = std::max(this->Fraction, std::min(0.95, fraction));
  return this->Fraction;
}

//------------------------------------------------------------------------------
void addConformalWarnings(const DistortionFigures& figures, const char* domain, Status& status)
{
  if (figures.flippedTriangles > 0)
  {
    std::ostringstream msg;
    msg << figures.flippedTriangles << " triangle(s) are flipped in the " << domain << " image.";
    status.warnings.push_back(msg.str());
  }
}

//------------------------------------------------------------------------------
void warnAboutUnreferencedPoints(std::int64_t count, bool keptAsNaN, Status& status)
{
  if (count == 0)
  {
    return;
  }
  std::ostringstream msg;
  msg << count << " input point(s) belong to no triangle and "
      << (keptAsNaN ? "keep NaN map coordinates in the output."
                    : "are left out of the output; the point array vtkOriginalPointIds gives "
                      "each output point's input id.");
  status.warnings.push_back(msg.str());
}

//------------------------------------------------------------------------------
std::string transportNotConvergedWarning(const NewtonReport& result, const OTOptions& options)
{
  std::ostringstream msg;
  msg << "Not converged after " << result.iterations
      << " Newton iterations (MaximumNumberOfIterations = " << options.maximumNumberOfIterations
      << "): relative error " << result.relativeError << " > Tolerance " << options.tolerance
      << ". ";
  // Out of iterations, the solver's own message says no more than this one.
  if (result.iterations >= options.maximumNumberOfIterations)
  {
    msg << "Raise MaximumNumberOfIterations.";
  }
  else if (!result.message.empty())
  {
    msg << result.message << (result.message.back() == '.' ? "" : ".");
  }
  msg << " The outputs hold this last iterate, with Converged = 0.";
  return msg.str();
}

//------------------------------------------------------------------------------
TransportStage runTransportStage(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& masses, const OTOptions& options, double maximumArcAngle)
{
  TransportStage stage;
  Status& status = stage.status;
  status.error = checkTransportOptions(options, maximumArcAngle);
  if (!status.error.empty())
  {
    return stage;
  }
  const std::string diracError = validateDiracs(diracs, masses);
  if (!diracError.empty())
  {
    status.error = "Invalid Diracs input (port 0): " + diracError;
    return stage;
  }
  OTResult& result = stage.result;
  try
  {
    result = solveSemiDiscreteOT(source, diracs, masses, options);
    if (result.aborted)
    {
      status.aborted = true;
      return stage;
    }
    stage.geometry = computePowerDiagramGeometry(source, diracs, result.heights, maximumArcAngle);
  }
  catch (const std::exception& e)
  {
    status.error = std::string("The semi-discrete OT solve failed: ") + e.what();
    return stage;
  }
  const std::size_t n = diracs.size();
  if (result.heights.size() != n || result.mass.size() != n || result.cellMass.size() != n ||
    result.centroids.size() != n)
  {
    status.error = "The semi-discrete OT solve returned no solution: " + result.message;
    return stage;
  }
  if (!result.converged)
  {
    status.warnings.push_back(transportNotConvergedWarning(result, options));
  }
  return stage;
}

} // namespace otparam
