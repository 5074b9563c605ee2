#include "vtkSphericalOTSolver.h"

#include "vtkCellData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "OTParamConvert.h"
#include "Pipeline/SphereStages.h"

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSphericalOTSolver);

namespace
{
using namespace otparam_vtk;
constexpr int NumberOfOutputs = 4;

// Port 2: the polytope Q(h), one polygon per facet (Dirac), cell array DiracId.
void WritePolytope(const otparam::SphericalPowerDiagramGeometry& geometry, vtkPolyData* output)
{
  vtkNew<vtkCellArray> faces;
  std::vector<vtkIdType> ids;
  for (const std::vector<int>& face : geometry.polytopeFaces)
  {
    ids.assign(face.begin(), face.end());
    faces->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  vtkNew<vtkIntArray> diracId;
  diracId->SetName("DiracId");
  for (int dirac : geometry.polytopeFaceDirac)
  {
    diracId->InsertNextValue(dirac);
  }
  output->SetPoints(MakePoints(geometry.polytopeVertices));
  output->SetPolys(faces);
  output->GetCellData()->AddArray(diracId);
}
} // namespace

//------------------------------------------------------------------------------
vtkSphericalOTSolver::vtkSphericalOTSolver()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(NumberOfOutputs);
  const otparam::OTOptions defaults;
  this->Tolerance = defaults.tolerance;
  this->MaximumNumberOfIterations = defaults.maximumNumberOfIterations;
  this->MaximumArcAngle = otparam::DefaultMaximumArcAngle;
}

//------------------------------------------------------------------------------
vtkSphericalOTSolver::~vtkSphericalOTSolver() = default;

//------------------------------------------------------------------------------
int vtkSphericalOTSolver::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkSphericalOTSolver::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();
  otparam::OTOptions options;
  options.tolerance = this->Tolerance;
  options.maximumNumberOfIterations = this->MaximumNumberOfIterations;
  // The points and their Mass; the stage checks the parameters, then the masses and positions.
  std::vector<otparam::Vec3> points;
  std::vector<double> masses;
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0], 0);
  const std::string error = ReadDiracs(input, points, masses);
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  options.progress = this->NewtonProgressCallback(options);
  const otparam::SphereTransportStage stage =
    otparam::runSphereTransportStage(points, masses, options, this->MaximumArcAngle);
  this->SetProgressText(nullptr);
  if (!this->ReportStatus(stage.status))
  {
    return 0;
  }

  const auto startOutput = std::chrono::steady_clock::now();
  const otparam::SphericalOTResult& result = stage.result;
  const otparam::SphericalPowerDiagramGeometry& geometry = stage.geometry;
  vtkPolyData* diracsOutput = vtkPolyData::GetData(outputVector, 0);
  diracsOutput->SetPoints(MakePoints(stage.diracs));
  diracsOutput->SetPolys(MakeTriangles(geometry.triangles));
  vtkPointData* pd = diracsOutput->GetPointData();
  pd->PassData(input->GetPointData());
  pd->AddArray(MakeDoubleArray("Mass", result.mass));
  pd->AddArray(MakeDoubleArray("Height", result.heights));
  pd->AddArray(MakeDoubleArray("CellMass", result.cellMass));
  pd->AddArray(MakeVec3Array("Centroid", result.centroids));
  WriteCells(geometry.cells, geometry.cellDirac, result.mass, result.cellMass,
    vtkPolyData::GetData(outputVector, 1));
  WritePolytope(geometry, vtkPolyData::GetData(outputVector, 2));
  WriteDiracSurface(
    geometry.hullPoints, diracsOutput->GetPolys(), vtkPolyData::GetData(outputVector, 3));

  AddNewtonReport(diracsOutput, result);
  AddScalar(diracsOutput, "SourceMass", 4.0 * M_PI);
  AddScalar(diracsOutput, "LargestTransportDegrees", result.largestTransportDegrees);
  AddScalar(diracsOutput, "SecondsOutput", Seconds(startOutput));
  AddScalar(diracsOutput, "SecondsTotal", Seconds(startTotal));
  return 1;
}

//------------------------------------------------------------------------------
void vtkSphericalOTSolver::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaximumNumberOfIterations: " << this->MaximumNumberOfIterations << "\n";
  os << indent << "MaximumArcAngle: " << this->MaximumArcAngle << "\n";
}
