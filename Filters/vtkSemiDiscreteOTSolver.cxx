#include "vtkSemiDiscreteOTSolver.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "Common/IdList.h"
#include "OTParamConvert.h"
#include "Pipeline/DiskStages.h"
#include "Transport/PlanarSource.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSemiDiscreteOTSolver);

namespace
{
using namespace otparam_vtk;
constexpr int NumberOfOutputs = 5;

// Port 0: the points (z ignored) and their positive point array Mass; "" or the message.
std::string ReadPlanarDiracs(
  vtkPointSet* input, std::vector<otparam::Vec2>& diracs, std::vector<double>& masses)
{
  std::vector<otparam::Vec3> points;
  const std::string error = ReadDiracs(input, points, masses);
  if (!error.empty())
  {
    return error;
  }
  diracs.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    diracs[i] = { points[i].x, points[i].y };
  }
  // The core's check (finite, positive, pairwise distinct) names the offending ids.
  const std::string invalid = otparam::validateDiracs(diracs, masses);
  return invalid.empty() ? invalid : "Invalid Diracs input (port 0): " + invalid;
}

// Port 1: a planar triangulated convex region with an optional positive point array Density,
// or nothing for the exact unit disk; "" or the message.
std::string ReadSource(vtkPolyData* domain, std::unique_ptr<otparam::SourceMeasure>& source)
{
  if (!domain || domain->GetNumberOfPoints() == 0)
  {
    source = otparam::makeUnitDiskSource();
    return {};
  }
  const char* what = "source domain (port 1)";
  otparam::TriangleSoup soup;
  std::string error = ReadTriangleDomain(domain, what, soup);
  std::vector<otparam::Vec2> points;
  std::vector<std::int64_t> ids(soup.points.size());
  std::iota(ids.begin(), ids.end(), 0);
  if (error.empty())
  {
    error = ReadPlanarPoints(soup.points, ids, what, points);
  }
  std::vector<double> density;
  vtkAbstractArray* densityAbstract = domain->GetPointData()->GetAbstractArray("Density");
  if (error.empty() && densityAbstract)
  {
    vtkDataArray* densityArray = vtkDataArray::SafeDownCast(densityAbstract);
    if (!densityArray || densityArray->GetNumberOfComponents() != 1)
    {
      return "The point array 'Density' of the source domain must be numeric with one "
             "component.";
    }
    density.resize(points.size());
    std::vector<vtkIdType> badDensity;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      density[i] = densityArray->GetComponent(static_cast<vtkIdType>(i), 0);
      if (!(density[i] > 0.0) || !std::isfinite(density[i]))
      {
        badDensity.push_back(static_cast<vtkIdType>(i));
      }
    }
    if (!badDensity.empty())
    {
      std::ostringstream msg;
      msg << "The point array 'Density' of the source domain must be positive and finite but "
             "is not at point id(s) "
          << otparam::idList(badDensity) << " (first value: " << density[badDensity.front()]
          << ").";
      return msg.str();
    }
  }
  if (!error.empty())
  {
    return error;
  }
  std::vector<otparam::Triangle> triangles;
  for (const auto& t : soup.triangles)
  {
    triangles.push_back({ static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2]) });
  }
  source = otparam::makeTriangulatedSource(points, triangles, density, error);
  return source ? std::string() : "Invalid source domain (port 1): " + error;
}

// The input's well-formed triangles (the support of the target measure).
std::vector<otparam::Triangle> SupportTriangles(vtkPointSet* input)
{
  std::vector<otparam::Triangle> support;
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
  {
    if (input->GetCellType(c) != VTK_TRIANGLE)
    {
      continue;
    }
    input->GetCellPoints(c, ids);
    // Malformed cells (ids outside the points) cannot be part of the support.
    bool valid = ids->GetNumberOfIds() == 3;
    for (vtkIdType k = 0; valid && k < 3; ++k)
    {
      valid = ids->GetId(k) >= 0 && ids->GetId(k) < n;
    }
    if (valid)
    {
      support.push_back({ static_cast<int>(ids->GetId(0)), static_cast<int>(ids->GetId(1)),
        static_cast<int>(ids->GetId(2)) });
    }
  }
  return support;
}
} // namespace

//------------------------------------------------------------------------------
vtkSemiDiscreteOTSolver::vtkSemiDiscreteOTSolver()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(NumberOfOutputs);
  const otparam::OTOptions defaults;
  this->Tolerance = defaults.tolerance;
  this->MaximumNumberOfIterations = defaults.maximumNumberOfIterations;
  this->MaximumArcAngle = otparam::DefaultMaximumArcAngle;
}

//------------------------------------------------------------------------------
vtkSemiDiscreteOTSolver::~vtkSemiDiscreteOTSolver() = default;

//------------------------------------------------------------------------------
void vtkSemiDiscreteOTSolver::SetSourceDomainConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
void vtkSemiDiscreteOTSolver::SetSourceDomainData(vtkDataObject* domain)
{
  this->SetInputData(1, domain);
}

//------------------------------------------------------------------------------
int vtkSemiDiscreteOTSolver::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkSemiDiscreteOTSolver::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();
  otparam::OTOptions options;
  options.tolerance = this->Tolerance;
  options.maximumNumberOfIterations = this->MaximumNumberOfIterations;
  // Parameters first, then the Diracs (port 0), then the source (port 1).
  std::string error = otparam::checkTransportOptions(options, this->MaximumArcAngle);
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0], 0);
  std::vector<otparam::Vec2> diracs;
  std::vector<double> masses;
  std::unique_ptr<otparam::SourceMeasure> source;
  if (error.empty())
  {
    error = ReadPlanarDiracs(input, diracs, masses);
  }
  if (error.empty())
  {
    error = ReadSource(vtkPolyData::GetData(inputVector[1], 0), source);
  }
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }

  options.progress = this->NewtonProgressCallback(options);
  const otparam::TransportStage stage =
    otparam::runTransportStage(*source, diracs, masses, options, this->MaximumArcAngle);
  this->SetProgressText(nullptr);
  if (!this->ReportStatus(stage.status))
  {
    return 0;
  }

  const auto startOutput = std::chrono::steady_clock::now();
  const otparam::OTResult& result = stage.result;
  vtkPolyData* diracsOutput = vtkPolyData::GetData(outputVector, 0);
  diracsOutput->SetPoints(MakePoints(diracs));
  diracsOutput->SetPolys(MakeTriangles(stage.geometry.triangles));
  vtkPointData* pd = diracsOutput->GetPointData();
  pd->PassData(input->GetPointData());
  pd->AddArray(MakeDoubleArray("Mass", result.mass));
  pd->AddArray(MakeDoubleArray("Height", result.heights));
  pd->AddArray(MakeDoubleArray("CellMass", result.cellMass));
  pd->AddArray(MakeVec2Array("Centroid", result.centroids, 3));
  WritePowerCells(stage, vtkPolyData::GetData(outputVector, 1));
  WriteBrenierPotential(stage, diracs, vtkPolyData::GetData(outputVector, 2));
  WriteLegendreDual(stage, diracs, diracsOutput->GetPolys(), vtkPolyData::GetData(outputVector, 3));
  // The target's support is the union of the input's triangles (the sampler's triangulation
  // of it); without triangles it is not known and no discontinuity is reported.
  WriteDiscontinuities(
    stage, diracs, SupportTriangles(input), vtkPolyData::GetData(outputVector, 4));

  AddNewtonReport(diracsOutput, result);
  AddScalar(diracsOutput, "SourceMass", source->totalMass());
  AddScalar(diracsOutput, "SecondsOutput", Seconds(startOutput));
  AddScalar(diracsOutput, "SecondsTotal", Seconds(startTotal));
  return 1;
}

//------------------------------------------------------------------------------
void vtkSemiDiscreteOTSolver::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaximumNumberOfIterations: " << this->MaximumNumberOfIterations << "\n";
  os << indent << "MaximumArcAngle: " << this->MaximumArcAngle << "\n";
}
