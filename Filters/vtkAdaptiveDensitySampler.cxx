#include "vtkAdaptiveDensitySampler.h"

#include "vtkAbstractArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "OTParamConvert.h"
#include "Pipeline/DiskStages.h"
#include "Pipeline/SphereStages.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAdaptiveDensitySampler);

using namespace otparam_vtk;

//------------------------------------------------------------------------------
vtkAdaptiveDensitySampler::vtkAdaptiveDensitySampler()
{
  const otparam::SamplerOptions defaults;
  this->NumberOfSamples = static_cast<int>(defaults.numberOfSamples);
  this->MinimumAngle = defaults.minimumAngleDegrees;
  this->MaximumNumberOfSamples = static_cast<int>(defaults.maximumNumberOfSamples);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "AreaDensity");
}

//------------------------------------------------------------------------------
vtkAdaptiveDensitySampler::~vtkAdaptiveDensitySampler() = default;

//------------------------------------------------------------------------------
int vtkAdaptiveDensitySampler::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

namespace
{
// The message for a density array that is not there, with the other association's array of
// that name if there is one.
std::string MissingDensity(
  vtkPolyData* input, const std::string& arrayName, const std::string& quotedName, int requested)
{
  const char* kind = requested == vtkDataObject::FIELD_ASSOCIATION_POINTS ? "point array"
    : requested == vtkDataObject::FIELD_ASSOCIATION_CELLS                 ? "cell array"
                                                                          : "point or cell array";
  std::string hint;
  if (!arrayName.empty() && requested == vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    input->GetCellData()->GetAbstractArray(arrayName.c_str()))
  {
    hint = " (there is a cell array of that name: select it with FIELD_ASSOCIATION_CELLS for a "
           "density per triangle)";
  }
  else if (!arrayName.empty() && requested == vtkDataObject::FIELD_ASSOCIATION_CELLS &&
    input->GetPointData()->GetAbstractArray(arrayName.c_str()))
  {
    hint = " (there is a point array of that name: select it with FIELD_ASSOCIATION_POINTS)";
  }
  return "The density array is missing: the input domain has no " + std::string(kind) + " " +
    quotedName + hint +
    "; choose the density with SetInputArrayToProcess (default: the point array "
    "'AreaDensity').";
}

// The density array `densityAbstract` (found with `association`), per point of `domain` (the input
// points used by triangles) or per triangle; "" or the message.
std::string ReadDensity(vtkInformation* arrayInfo, vtkAbstractArray* densityAbstract,
  int association, vtkPolyData* input, const otparam::CompactedMesh& domain,
  std::vector<double>& perPoint, std::vector<double>& perTriangle)
{
  const std::string arrayName = (arrayInfo && arrayInfo->Has(vtkDataObject::FIELD_NAME()))
    ? arrayInfo->Get(vtkDataObject::FIELD_NAME())
    : std::string();
  const int requested = (arrayInfo && arrayInfo->Has(vtkDataObject::FIELD_ASSOCIATION()))
    ? arrayInfo->Get(vtkDataObject::FIELD_ASSOCIATION())
    : vtkDataObject::FIELD_ASSOCIATION_POINTS;
  std::ostringstream msg;
  if (requested != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    requested != vtkDataObject::FIELD_ASSOCIATION_CELLS &&
    requested != vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS)
  {
    msg << "The density array must be a point or a cell array (field association "
        << vtkDataObject::FIELD_ASSOCIATION_POINTS << " or "
        << vtkDataObject::FIELD_ASSOCIATION_CELLS << "); the selected association is " << requested
        << ".";
    return msg.str();
  }
  const std::string quotedName =
    "'" + (arrayName.empty() ? std::string("(unnamed)") : arrayName) + "'";
  if (!densityAbstract)
  {
    return MissingDensity(input, arrayName, quotedName, requested);
  }
  const bool perPointArray = association == vtkDataObject::FIELD_ASSOCIATION_POINTS;
  const std::string description =
    std::string("The density ") + (perPointArray ? "point array " : "cell array ") + quotedName;
  vtkDataArray* densityArray = vtkDataArray::SafeDownCast(densityAbstract);
  if (!densityArray)
  {
    msg << description << " is not numeric (it is a " << densityAbstract->GetClassName()
        << "); it must hold one number per " << (perPointArray ? "point" : "triangle") << ".";
    return msg.str();
  }
  if (densityArray->GetNumberOfComponents() != 1)
  {
    msg << description << " has " << densityArray->GetNumberOfComponents()
        << " components; it must have exactly 1.";
    return msg.str();
  }
  // Per point: the points used by triangles; per cell: every triangle (cell id = polygon id,
  // since the input has no other cells).
  std::vector<std::int64_t> ids;
  if (perPointArray)
  {
    ids = domain.originalPointIds;
  }
  else
  {
    ids.resize(domain.mesh.triangles.size());
    std::iota(ids.begin(), ids.end(), 0);
  }
  std::vector<double>& values = perPointArray ? perPoint : perTriangle;
  values.resize(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    values[k] = densityArray->GetComponent(static_cast<vtkIdType>(ids[k]), 0);
  }
  const std::string error =
    otparam::checkDensityValues(values, perPointArray ? "point" : "cell", &ids);
  return error.empty() ? error : description + " " + error + ".";
}

// A sphere domain: every point on the unit sphere (to 1e-6; the core then asks 1e-9 and names
// the point) and not all in the plane z = 0, so that no planar domain (z = 0 up to 1e-12 of its
// size) is ever taken for one, even with all its points on the unit circle.
bool IsSphereDomain(const std::vector<otparam::Vec3>& points)
{
  const bool offPlane = std::any_of(
    points.begin(), points.end(), [](const otparam::Vec3& p) { return std::abs(p.z) > 1e-6; });
  return offPlane && otparam::pointsOnUnitSphere(points, 1e-6);
}

// For a domain that is neither planar nor on the unit sphere: the point farthest from the unit
// sphere (input id), to say why it is not a sphere domain either.
std::string NotOnSphereHint(const otparam::CompactedMesh& domain)
{
  std::size_t worst = 0;
  double worstError = -1.0;
  for (std::size_t v = 0; v < domain.mesh.points.size(); ++v)
  {
    const double error = std::abs(otparam::norm(domain.mesh.points[v]) - 1.0);
    if (!(error <= worstError))
    {
      worst = v;
      worstError = error;
    }
  }
  std::ostringstream msg;
  msg << " It is no sphere domain either (every point on the unit sphere): point "
      << domain.originalPointIds[worst] << " is at distance "
      << otparam::norm(domain.mesh.points[worst]) << " from the origin.";
  return msg.str();
}

// The per-triangle density of a sphere domain: the cell array as read, or a point array
// averaged over each triangle's three corners.
std::vector<double> TriangleDensity(const otparam::CompactedMesh& domain,
  const std::vector<double>& perPoint, const std::vector<double>& perTriangle)
{
  if (perPoint.empty())
  {
    return perTriangle;
  }
  std::vector<double> density(domain.mesh.triangles.size());
  for (std::size_t t = 0; t < density.size(); ++t)
  {
    const otparam::Triangle& tri = domain.mesh.triangles[t];
    density[t] = (perPoint[tri[0]] + perPoint[tri[1]] + perPoint[tri[2]]) / 3.0;
  }
  return density;
}

// Output and field data every mode and domain shares (samples in the plane or on the sphere).
template <class Point>
void WriteSamples(const std::vector<Point>& samples,
  const std::vector<otparam::Triangle>& triangles, const otparam::SamplerResultBase& result,
  vtkPolyData* output)
{
  output->SetPoints(MakePoints(samples));
  output->SetPolys(MakeTriangles(triangles));
  output->GetPointData()->AddArray(MakeDoubleArray("Mass", result.mass));
  AddIntScalar(output, "NumberOfSamples", static_cast<long long>(samples.size()));
  AddScalar(output, "MassCoefficientOfVariation", result.massCoefficientOfVariation);
  AddScalar(output, "MinimumAngle", result.minimumAngleDegrees);
  AddScalar(output, "Epsilon", result.epsilon);
  AddScalar(output, "SourceMass", result.sourceMass);
  AddIntScalar(output, "RefinementRuns", result.refinementRuns);
  AddIntScalar(output, "Capped", result.capped ? 1 : 0);
  // 1 when the relaxed samples were kept, 0 when the unrelaxed ones were (more even masses, or
  // a density varying faster than the samples follow: then adaptive sampling does not relax).
  AddIntScalar(output, "Relaxed", result.relaxed ? 1 : 0);
  AddScalar(output, "SecondsRefinement", result.secondsRefinement);
  AddScalar(output, "SecondsMasses", result.secondsMasses);
}

// Messages about the input's unreferenced points, for either domain's stage status.
void AddUnreferencedNote(const otparam::CompactedMesh& domain, otparam::Status& status)
{
  if (domain.unreferencedPoints == 0)
  {
    return;
  }
  if (!status.error.empty())
  {
    status.error += status.error.back() == '.' ? "" : ".";
    status.error += " Point ids here count only the input points used by triangles.";
  }
  std::ostringstream msg;
  msg << domain.unreferencedPoints << " input point(s) belong to no triangle and are ignored.";
  status.warnings.insert(status.warnings.begin(), msg.str());
}
} // namespace

//------------------------------------------------------------------------------
struct vtkAdaptiveDensitySampler::Input
{
  otparam::CompactedMesh domain;     // points used by no triangle left out
  bool sphere = false;               // on the unit sphere, else in the plane z = 0
  std::vector<otparam::Vec2> points; // the planar domain's points
  std::vector<double> perPoint, perTriangle;
};

//------------------------------------------------------------------------------
// The domain (triangles in the plane z = 0, or on the unit sphere), then the density.
std::string vtkAdaptiveDensitySampler::ReadInput(vtkPolyData* input, Input& read)
{
  otparam::TriangleSoup soup;
  std::string error = ReadTriangleDomain(input, "input domain", soup);
  if (error.empty())
  {
    error = otparam::compactMesh(soup.points, soup.triangles, read.domain);
    error = error.empty() ? error : "The input domain is not a triangulation: " + error + ".";
  }
  read.sphere = error.empty() && IsSphereDomain(read.domain.mesh.points);
  if (error.empty() && !read.sphere)
  {
    error = ReadPlanarPoints(
      read.domain.mesh.points, read.domain.originalPointIds, "input domain", read.points);
    error = error.empty() ? error : error + NotOnSphereHint(read.domain);
  }
  if (error.empty())
  {
    // The array chosen with SetInputArrayToProcess (the lookup is vtkAlgorithm's, protected).
    int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
    vtkAbstractArray* density = this->GetInputAbstractArrayToProcess(0, input, association);
    error = ReadDensity(this->GetInputArrayInformation(0), density, association, input, read.domain,
      read.perPoint, read.perTriangle);
  }
  return error;
}

//------------------------------------------------------------------------------
int vtkAdaptiveDensitySampler::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);

  otparam::SamplerOptions options;
  options.mode = static_cast<otparam::SamplingMode>(this->SamplingMode);
  options.sizeRule = static_cast<otparam::SizeRule>(this->SizeRule);
  options.numberOfSamples = this->NumberOfSamples;
  options.maximumNumberOfSamples = this->MaximumNumberOfSamples;
  options.minimumAngleDegrees = this->MinimumAngle;
  options.progress = this->ProgressCallback();
  // Parameters first, then the input.
  std::string error = otparam::checkSamplerOptions(options);
  Input read;
  if (error.empty())
  {
    error = this->ReadInput(input, read);
  }
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const otparam::CompactedMesh& domain = read.domain;
  const std::vector<double>&perPoint = read.perPoint, &perTriangle = read.perTriangle;

  if (read.sphere)
  {
    otparam::SphereSamplingStage stage = otparam::runSphereSamplingStage(domain.mesh.points,
      domain.mesh.triangles, TriangleDensity(domain, perPoint, perTriangle), options);
    AddUnreferencedNote(domain, stage.status);
    if (!this->ReportStatus(stage.status))
    {
      return 0;
    }
    const otparam::SphericalSamplerResult& result = stage.result;
    WriteSamples(result.samples, result.triangles, result, output);
    AddScalar(output, "DensityIntegral", result.densityIntegral);
    AddScalar(output, "MassSumRelativeError", result.massSumRelativeError);
    AddScalar(output, "SecondsTotal", Seconds(startTotal));
    return 1;
  }

  otparam::SamplingStage stage =
    otparam::runSamplingStage(read.points, domain.mesh.triangles, perPoint, perTriangle, options);
  AddUnreferencedNote(domain, stage.status);
  if (stage.zeroMassSamples > 0)
  {
    std::ostringstream msg;
    msg << stage.zeroMassSamples << " of the " << stage.result.samples.size()
        << " samples have Mass 0 (the density vanishes on their cells); "
           "vtkSemiDiscreteOTSolver needs positive masses.";
    stage.status.warnings.push_back(msg.str());
  }
  if (!this->ReportStatus(stage.status))
  {
    return 0;
  }
  const otparam::SamplerResult& result = stage.result;
  WriteSamples(result.samples, result.triangles, result, output);
  AddScalar(output, "SecondsTotal", Seconds(startTotal));
  return 1;
}

//------------------------------------------------------------------------------
void vtkAdaptiveDensitySampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSamples: " << this->NumberOfSamples << "\n";
  os << indent << "SamplingMode: " << this->SamplingMode << "\n";
  os << indent << "MinimumAngle: " << this->MinimumAngle << "\n";
  os << indent << "MaximumNumberOfSamples: " << this->MaximumNumberOfSamples << "\n";
  os << indent << "SizeRule: " << this->SizeRule << "\n";
}
