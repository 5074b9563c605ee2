#include "vtkConformalSphereMap.h"

#include "vtkCellData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "OTParamConvert.h"
#include "Pipeline/SphereStages.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkConformalSphereMap);

using namespace otparam_vtk;

//------------------------------------------------------------------------------
vtkConformalSphereMap::vtkConformalSphereMap()
{
  const otparam::ConformalSphereMapOptions defaults;
  this->BalanceTolerance = defaults.balanceTolerance;
  this->MaximumBalanceIterations = defaults.maximumBalanceIterations;
}

//------------------------------------------------------------------------------
vtkConformalSphereMap::~vtkConformalSphereMap() = default;

//------------------------------------------------------------------------------
int vtkConformalSphereMap::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkConformalSphereMap::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);

  otparam::ConformalSphereMapOptions options;
  // Out-of-range ids stay out of range (the core names them against the triangle count).
  options.punctureTriangle = static_cast<int>(std::clamp<vtkIdType>(
    this->PunctureTriangleId, static_cast<vtkIdType>(INT_MIN), static_cast<vtkIdType>(INT_MAX)));
  options.balanceTolerance = this->BalanceTolerance;
  options.maximumBalanceIterations = this->MaximumBalanceIterations;
  options.progress = this->ProgressCallback();
  otparam::TriangleSoup soup;
  if (!this->ReadInputSurface(input, soup))
  {
    return 0;
  }
  otparam::SphereConformalStage stage =
    otparam::runSphereConformalStage(soup, options, this->FillHoles);
  otparam::warnAboutUnreferencedPoints(stage.surface.unreferencedPoints, false, stage.status);
  if (!this->ReportStatus(stage.status))
  {
    return 0;
  }
  otparam::keepInputPart(stage);

  const otparam::CompactedMesh& surface = stage.surface;
  const otparam::ConformalSphereMapResult& map = stage.map;
  const auto n = static_cast<vtkIdType>(surface.mesh.points.size());
  output->SetPoints(MakePoints(map.sphere));
  output->SetPolys(MakeTriangles(surface.mesh.triangles));
  CopyInputArrays(input, surface.originalPointIds, output);
  vtkPointData* outPD = output->GetPointData();
  outPD->AddArray(MakeVec3Array("Coordinates3D", surface.mesh.points));
  outPD->AddArray(MakeDoubleArray("AreaDensity", stage.areaDensityPerPoint));
  outPD->AddArray(MakeOriginalPointIds(surface.originalPointIds));
  vtkCellData* outCD = output->GetCellData();
  outCD->AddArray(MakeDoubleArray("AreaDensity", stage.areaDensityPerTriangle));
  AddDistortionArrays(outCD, stage.figures);

  double radiusError = 0.0;
  for (const otparam::Vec3& p : map.sphere)
  {
    radiusError = std::max(radiusError, std::abs(otparam::norm(p) - 1.0));
  }
  AddDistortionFigures(output, stage.figures);
  AddScalar(output, "MaximumRadiusError", radiusError);
  AddScalar(output, "BalanceResidual", map.balanceResidual);
  AddIntScalar(output, "BalanceIterations", map.balanceIterations);
  AddIdScalar(output, "PunctureTriangleId", map.punctureTriangle);
  AddIntScalar(output, "FixedPoints", map.fixedPoints);
  AddIntScalar(output, "Mirrored", map.mirrored ? 1 : 0);
  AddIntScalar(output, "FilledHoles", stage.filledHoles);
  AddScalar(output, "FillAreaFraction", stage.fillAreaFraction);
  AddIntScalar(output, "FlippedWithMeshLaplacian", map.flippedWithMeshLaplacian);
  AddIntScalar(output, "IntrinsicLaplacian", map.intrinsicLaplacian ? 1 : 0);
  AddIntScalar(output, "FlooredWeights", map.flooredWeights ? 1 : 0);
  AddIntScalar(output, "LiftedFromTheDisk", map.liftedFromTheDisk ? 1 : 0);
  AddScalar(output, "SecondsFactorization", map.secondsFactorization);
  AddScalar(output, "SecondsSolve", map.secondsSolve);
  AddScalar(output, "SecondsBalance", map.secondsBalance);
  AddScalar(output, "SecondsTotal", Seconds(startTotal));
  return 1;
}

//------------------------------------------------------------------------------
void vtkConformalSphereMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PunctureTriangleId: " << this->PunctureTriangleId << "\n";
  os << indent << "BalanceTolerance: " << this->BalanceTolerance << "\n";
  os << indent << "MaximumBalanceIterations: " << this->MaximumBalanceIterations << "\n";
  os << indent << "FillHoles: " << this->FillHoles << "\n";
}
