#include "vtkConformalDiskMap.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "Conformal/ConformalDiskMap.h"
#include "OTParamAdapterUtilities.h"
#include "Mesh/DistortionMetrics.h"
#include "Mesh/SurfaceMesh.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkConformalDiskMap);

using namespace otparam_vtk;

//------------------------------------------------------------------------------
vtkConformalDiskMap::vtkConformalDiskMap() = default;

//------------------------------------------------------------------------------
vtkConformalDiskMap::~vtkConformalDiskMap() = default;

//------------------------------------------------------------------------------
int vtkConformalDiskMap::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkConformalDiskMap::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The map is global: it needs the whole surface, not a piece of it.
  RequestWholeInputs(inputVector, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkConformalDiskMap::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  if (IsOtherPiece(outputVector))
  {
    return 1; // piece 0 holds the whole result
  }

  if (!(this->Tolerance > 0.0) || !std::isfinite(this->Tolerance))
  {
    vtkErrorMacro("Tolerance must be positive and finite; got " << this->Tolerance << ".");
    return 0;
  }
  if (this->MaximumNumberOfIterations < 0)
  {
    vtkErrorMacro("MaximumNumberOfIterations must be at least 0; got "
      << this->MaximumNumberOfIterations << ".");
    return 0;
  }

  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  const vtkIdType numberOfPoints = (input && input->GetPoints()) ? input->GetNumberOfPoints() : 0;
  // Any cell counts here: vertices, lines and strips get the "triangles only" message below.
  if (!input || numberOfPoints == 0 || input->GetNumberOfCells() == 0)
  {
    vtkErrorMacro("The input surface is empty: it needs points and triangles.");
    return 0;
  }
  if (input->GetNumberOfVerts() > 0 || input->GetNumberOfLines() > 0 ||
    input->GetNumberOfStrips() > 0)
  {
    vtkErrorMacro("The input must be made of triangles only, but it has "
      << input->GetNumberOfVerts() << " vertex cells, " << input->GetNumberOfLines()
      << " line cells and " << input->GetNumberOfStrips()
      << " triangle strips (extract the surface and apply vtkTriangleFilter first).");
    return 0;
  }

  std::vector<otparam::Vec3> points(static_cast<size_t>(numberOfPoints));
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    points[i] = { p[0], p[1], p[2] };
  }
  std::vector<std::array<std::int64_t, 3>> triangles;
  triangles.reserve(static_cast<size_t>(input->GetNumberOfPolys()));
  std::vector<vtkIdType> notTriangles;
  {
    vtkNew<vtkIdList> cell;
    vtkCellArray* polys = input->GetPolys();
    for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
    {
      polys->GetCellAtId(c, cell);
      if (cell->GetNumberOfIds() != 3)
      {
        notTriangles.push_back(c);
        continue;
      }
      triangles.push_back({ cell->GetId(0), cell->GetId(1), cell->GetId(2) });
    }
  }
  if (!notTriangles.empty())
  {
    vtkErrorMacro("The input must be made of triangles, but polygon id(s) "
      << FormatIds(notTriangles) << " are not (apply vtkTriangleFilter first).");
    return 0;
  }

  otparam::CompactedMesh compacted;
  std::string error = otparam::compactMesh(points, triangles, compacted);
  std::vector<int> loop;
  if (error.empty())
  {
    error = otparam::checkDiskTopology(compacted.mesh, loop, &compacted.originalPointIds);
  }
  if (!error.empty())
  {
    vtkErrorMacro("The input is not a disk-like triangle surface: " << error << ".");
    return 0;
  }

  // Input point ids -> mesh ids for the two properties.
  std::vector<int> meshId(static_cast<size_t>(numberOfPoints), -1);
  for (size_t v = 0; v < compacted.originalPointIds.size(); ++v)
  {
    meshId[compacted.originalPointIds[v]] = static_cast<int>(v);
  }
  otparam::ConformalDiskMapOptions options;
  auto toMeshId = [&](vtkIdType id, const char* property, int& out)
  {
    if (id == -1)
    {
      out = -1;
      return true;
    }
    if (id < 0 || id >= numberOfPoints)
    {
      vtkErrorMacro(<< property << " = " << id << " is not a point id of the input (it has "
                    << numberOfPoints << " points; -1 chooses automatically).");
      return false;
    }
    if (meshId[id] < 0)
    {
      vtkErrorMacro(<< property << " = " << id << " names a point that belongs to no triangle.");
      return false;
    }
    out = meshId[id];
    return true;
  };
  std::vector<char> onBoundary(compacted.mesh.points.size(), 0);
  for (int v : loop)
  {
    onBoundary[v] = 1;
  }
  if (!toMeshId(this->CenterPointId, "CenterPointId", options.centerVertex) ||
    !toMeshId(this->AlignPointId, "AlignPointId", options.alignVertex))
  {
    return 0;
  }
  if (options.centerVertex >= 0 && onBoundary[options.centerVertex])
  {
    vtkErrorMacro("CenterPointId = " << this->CenterPointId
                                     << " is a boundary point; the point sent to the disk's "
                                        "centre must be an interior point.");
    return 0;
  }
  if (options.alignVertex >= 0 && !onBoundary[options.alignVertex])
  {
    vtkErrorMacro("AlignPointId = " << this->AlignPointId
                                    << " is not a boundary point; the point sent to (1, 0) "
                                       "must be on the boundary loop.");
    return 0;
  }
  options.tolerance = this->Tolerance;
  options.maximumNumberOfIterations = this->MaximumNumberOfIterations;
  options.progress = [this](double fraction)
  {
    this->UpdateProgress(0.95 * fraction);
    return !this->GetAbortExecute();
  };

  otparam::ConformalDiskMapResult map;
  otparam::DistortionFigures figures;
  std::vector<double> densityPerTriangle, densityPerPoint;
  try
  {
    map = otparam::computeConformalDiskMap(compacted.mesh, loop, options);
    if (map.aborted || this->GetAbortExecute())
    {
      vtkWarningMacro("Aborted; the output is left empty.");
      return 1;
    }
    if (!map.error.empty())
    {
      vtkErrorMacro("The conformal map failed: " << map.error << ".");
      return 0;
    }
    figures = otparam::measureDistortion(compacted.mesh, map.uv);
    otparam::computeAreaDensity(compacted.mesh, map.uv, densityPerTriangle, densityPerPoint);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("The conformal map failed: " << e.what());
    return 0;
  }

  // ---- Output: the disk image.
  const auto n = static_cast<vtkIdType>(compacted.mesh.points.size());
  vtkNew<vtkPoints> diskPoints;
  diskPoints->SetDataTypeToDouble();
  diskPoints->SetNumberOfPoints(n);
  std::vector<double> coordinates3D(3 * n), uv(2 * n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    diskPoints->SetPoint(v, map.uv[v].x, map.uv[v].y, 0.0);
    const auto& p = compacted.mesh.points[v];
    coordinates3D[3 * v] = p.x;
    coordinates3D[3 * v + 1] = p.y;
    coordinates3D[3 * v + 2] = p.z;
    uv[2 * v] = map.uv[v].x;
    uv[2 * v + 1] = map.uv[v].y;
  }
  output->SetPoints(diskPoints);
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(triangles.size()), 3 * triangles.size());
  for (const auto& t : compacted.mesh.triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    polys->InsertNextCell(3, ids);
  }
  output->SetPolys(polys);

  vtkPointData* outPD = output->GetPointData();
  outPD->CopyAllocate(input->GetPointData(), n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    outPD->CopyData(input->GetPointData(), compacted.originalPointIds[v], v);
  }
  outPD->AddArray(MakeDoubleArray("Coordinates3D", coordinates3D, 3));
  outPD->AddArray(MakeDoubleArray("AreaDensity", densityPerPoint));
  outPD->SetTCoords(MakeDoubleArray("ConformalCoordinates", uv, 2));
  vtkNew<vtkIdTypeArray> originalIds;
  originalIds->SetName("vtkOriginalPointIds");
  originalIds->SetNumberOfTuples(n);
  std::copy(compacted.originalPointIds.begin(), compacted.originalPointIds.end(),
    originalIds->GetPointer(0));
  outPD->AddArray(originalIds);

  vtkCellData* outCD = output->GetCellData();
  outCD->ShallowCopy(input->GetCellData()); // same triangles in the same order
  outCD->AddArray(MakeDoubleArray("AreaDensity", densityPerTriangle));
  outCD->AddArray(MakeDoubleArray("AngleDistortion", figures.angleDistortion));
  outCD->AddArray(MakeDoubleArray("QuasiConformalDilatation", figures.dilatation));
  outCD->AddArray(MakeDoubleArray("LogAreaRatio", figures.logAreaRatio));

  double radiusError = 0.0;
  for (int v : loop)
  {
    radiusError = std::max(radiusError, std::abs(std::hypot(map.uv[v].x, map.uv[v].y) - 1.0));
  }
  vtkFieldData* fd = output->GetFieldData();
  fd->AddArray(MakeScalar("MeanAngleDistortion", figures.meanAngleDistortionDegrees));
  fd->AddArray(MakeScalar("MaximumAngleDistortion", figures.maximumAngleDistortionDegrees));
  fd->AddArray(MakeScalar("MeanQuasiConformalDilatation", figures.meanDilatation));
  fd->AddArray(MakeScalar("MaximumQuasiConformalDilatation", figures.maximumDilatation));
  fd->AddArray(MakeIntScalar("FlippedTriangles", static_cast<int>(figures.flippedTriangles)));
  fd->AddArray(MakeScalar("MeanAbsLogAreaRatio", figures.meanAbsLogAreaRatio));
  fd->AddArray(MakeScalar("MaximumAbsLogAreaRatio", figures.maximumAbsLogAreaRatio));
  fd->AddArray(MakeScalar("MaximumBoundaryRadiusError", radiusError));
  fd->AddArray(MakeIntScalar("Iterations", map.iterations));
  fd->AddArray(MakeScalar("ConformalEnergy", map.conformalEnergy));
  fd->AddArray(MakeIntScalar("ClippedEars", map.clippedEars));
  fd->AddArray(
    MakeIntScalar("FoldedWithMeshLaplacian", static_cast<int>(map.foldedWithMeshLaplacian)));
  fd->AddArray(MakeIntScalar("IntrinsicLaplacian", map.intrinsicLaplacian ? 1 : 0));
  auto idScalar = [](const char* name, vtkIdType value)
  {
    vtkNew<vtkIdTypeArray> array;
    array->SetName(name);
    array->InsertNextValue(value);
    return array;
  };
  fd->AddArray(idScalar("CenterPointId", compacted.originalPointIds[map.centerVertex]));
  fd->AddArray(idScalar("AlignPointId", compacted.originalPointIds[map.alignVertex]));
  fd->AddArray(MakeScalar("SecondsFactorization", map.secondsFactorization));
  fd->AddArray(MakeScalar("SecondsIterations", map.secondsIterations));
  fd->AddArray(MakeScalar("SecondsTotal", Seconds(startTotal)));
  // Only now: a run that fails must not warn about an output it does not make.
  if (compacted.unreferencedPoints > 0)
  {
    vtkWarningMacro(<< compacted.unreferencedPoints
                    << " input point(s) belong to no triangle and are left out of the output; "
                       "the point array vtkOriginalPointIds gives each output point's input id.");
  }
  if (figures.flippedTriangles > 0)
  {
    vtkWarningMacro(<< figures.flippedTriangles << " triangle(s) are flipped in the disk image.");
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkConformalDiskMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CenterPointId: " << this->CenterPointId << "\n";
  os << indent << "AlignPointId: " << this->AlignPointId << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaximumNumberOfIterations: " << this->MaximumNumberOfIterations << "\n";
}
