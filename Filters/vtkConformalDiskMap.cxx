#include "vtkConformalDiskMap.h"

#include "vtkCellData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "OTParamConvert.h"
#include "Pipeline/DiskStages.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkConformalDiskMap);

using namespace otparam_vtk;

//------------------------------------------------------------------------------
vtkConformalDiskMap::vtkConformalDiskMap()
{
  const otparam::ConformalDiskMapOptions defaults;
  this->Tolerance = defaults.tolerance;
  this->MaximumNumberOfIterations = defaults.maximumNumberOfIterations;
}

//------------------------------------------------------------------------------
vtkConformalDiskMap::~vtkConformalDiskMap() = default;

//------------------------------------------------------------------------------
int vtkConformalDiskMap::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkConformalDiskMap::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);

  otparam::ConformalStageOptions options;
  options.centerPointId = this->CenterPointId;
  options.alignPointId = this->AlignPointId;
  options.fillHoles = this->FillHoles;
  options.map.tolerance = this->Tolerance;
  options.map.maximumNumberOfIterations = this->MaximumNumberOfIterations;
  options.map.progress = this->ProgressCallback();
  // Parameters first: a bad one is reported whatever the input.
  const std::string error = options.check();
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  otparam::TriangleSoup soup;
  if (!this->ReadInputSurface(input, soup))
  {
    return 0;
  }
  otparam::ConformalStage stage = otparam::runConformalStage(soup, options);
  otparam::warnAboutUnreferencedPoints(stage.surface.unreferencedPoints, false, stage.status);
  if (!this->ReportStatus(stage.status))
  {
    return 0;
  }
  // The automatic centre may be a point of a hole fill: its id is then -1.
  const std::int64_t centerPointId = stage.inputId(stage.map.centerVertex);
  otparam::keepInputPart(stage);

  const otparam::CompactedMesh& surface = stage.surface;
  const auto n = static_cast<vtkIdType>(surface.mesh.points.size());
  output->SetPoints(MakePoints(stage.map.uv));
  output->SetPolys(MakeTriangles(surface.mesh.triangles));
  CopyInputArrays(input, surface.originalPointIds, output);
  vtkPointData* outPD = output->GetPointData();
  outPD->AddArray(MakeVec3Array("Coordinates3D", surface.mesh.points));
  outPD->AddArray(MakeDoubleArray("AreaDensity", stage.areaDensityPerPoint));
  outPD->SetTCoords(MakeVec2Array("ConformalCoordinates", stage.map.uv));
  outPD->AddArray(MakeOriginalPointIds(surface.originalPointIds));
  vtkCellData* outCD = output->GetCellData();
  outCD->AddArray(MakeDoubleArray("AreaDensity", stage.areaDensityPerTriangle));
  AddDistortionArrays(outCD, stage.figures);

  AddDistortionFigures(output, stage.figures);
  const otparam::ConformalDiskMapResult& map = stage.map;
  AddScalar(output, "MaximumBoundaryRadiusError", stage.maximumBoundaryRadiusError);
  AddIntScalar(output, "Iterations", map.iterations);
  AddScalar(output, "ConformalEnergy", map.conformalEnergy);
  AddIntScalar(output, "ClippedEars", map.clippedEars);
  AddIntScalar(output, "FoldedWithMeshLaplacian", map.foldedWithMeshLaplacian);
  AddIntScalar(output, "IntrinsicLaplacian", map.intrinsicLaplacian ? 1 : 0);
  AddIntScalar(output, "FlooredWeights", map.flooredWeights ? 1 : 0);
  AddIdScalar(output, "CenterPointId", centerPointId);
  AddIdScalar(output, "AlignPointId", stage.inputId(map.alignVertex));
  AddIntScalar(output, "FilledHoles", stage.filledHoles);
  AddScalar(output, "FillAreaFraction", stage.fillAreaFraction);
  AddScalar(output, "SecondsFactorization", map.secondsFactorization);
  AddScalar(output, "SecondsIterations", map.secondsIterations);
  AddScalar(output, "SecondsTotal", Seconds(startTotal));
  return 1;
}

//------------------------------------------------------------------------------
void vtkConformalDiskMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CenterPointId: " << this->CenterPointId << "\n";
  os << indent << "AlignPointId: " << this->AlignPointId << "\n";
  os << indent << "FillHoles: " << this->FillHoles << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaximumNumberOfIterations: " << this->MaximumNumberOfIterations << "\n";
}
