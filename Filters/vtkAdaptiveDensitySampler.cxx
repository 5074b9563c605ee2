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
    const char* kind = requested == vtkDataObject::FIELD_ASSOCIATION_POINTS ? "point array"
      : requested == vtkDataObject::FIELD_ASSOCIATION_CELLS                 ? "cell array"
                                                                            : "point or cell array";
    std::string hint;
    if (!arrayName.empty() && requested == vtkDataObject::FIELD_ASSOCIATION_POINTS &&
      input->GetCellData()->GetAbstractArray(arrayName.c_str()))
    {
      hint = " (there is a cell array of that name: select it with FIELD_ASSOCIATION_CELLS for "
             "a density per triangle)";
    }
    else if (!arrayName.empty() && requested == vtkDataObject::FIELD_ASSOCIATION_CELLS &&
      input->GetPointData()->GetAbstractArray(arrayName.c_str()))
    {
      hint = " (there is a point array of that name: select it with FIELD_ASSOCIATION_POINTS)";
    }
    msg << "The density array is missing: the input domain has no " << kind << " " << quotedName
        << hint
        << "; choose the density with SetInputArrayToProcess (default: the point array "
           "'AreaDensity').";
    return msg.str();
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
} // namespace

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
  // Parameters first, then the domain (triangles in the plane z = 0; points used by no
  // triangle are left out), then the density.
  std::string error = otparam::checkSamplerOptions(options);
  otparam::TriangleSoup soup;
  otparam::CompactedMesh domain;
  std::vector<otparam::Vec2> points;
  std::vector<double> perPoint, perTriangle;
  if (error.empty())
  {
    error = ReadTriangleSoup(input, "input domain", soup);
  }
  if (error.empty())
  {
    error = otparam::compactMesh(soup.points, soup.triangles, domain);
    error = error.empty() ? error : "The input domain is not a triangulation: " + error + ".";
  }
  if (error.empty())
  {
    error = ReadPlanarPoints(domain.mesh.points, domain.originalPointIds, "input domain", points);
  }
  if (error.empty())
  {
    // The array chosen with SetInputArrayToProcess (the lookup is vtkAlgorithm's, protected).
    int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
    vtkAbstractArray* density = this->GetInputAbstractArrayToProcess(0, input, association);
    error = ReadDensity(this->GetInputArrayInformation(0), density, association, input, domain,
      perPoint, perTriangle);
  }
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }

  otparam::SamplingStage stage =
    otparam::runSamplingStage(points, domain.mesh.triangles, perPoint, perTriangle, options);
  if (!stage.status.error.empty() && domain.unreferencedPoints > 0)
  {
    stage.status.error += " Point ids here count only the input points used by triangles.";
  }
  if (domain.unreferencedPoints > 0)
  {
    std::ostringstream msg;
    msg << domain.unreferencedPoints << " input point(s) belong to no triangle and are ignored.";
    stage.status.warnings.insert(stage.status.warnings.begin(), msg.str());
  }
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
  output->SetPoints(MakePoints(result.samples));
  output->SetPolys(MakeTriangles(result.triangles));
  output->GetPointData()->AddArray(MakeDoubleArray("Mass", result.mass));
  AddIntScalar(output, "NumberOfSamples", static_cast<long long>(result.samples.size()));
  AddScalar(output, "MassCoefficientOfVariation", result.massCoefficientOfVariation);
  AddScalar(output, "MinimumAngle", result.minimumAngleDegrees);
  AddScalar(output, "Epsilon", result.epsilon);
  AddScalar(output, "SourceMass", result.sourceMass);
  AddIntScalar(output, "RefinementRuns", result.refinementRuns);
  AddIntScalar(output, "Capped", result.capped ? 1 : 0);
  AddScalar(output, "SecondsRefinement", result.secondsRefinement);
  AddScalar(output, "SecondsMasses", result.secondsMasses);
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
