#include "OTParamConvert.h"

#include "vtkAbstractArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "Common/IdList.h"
#include "Transport/Discontinuities.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace otparam_vtk
{

//------------------------------------------------------------------------------
std::string ReadTriangleSoup(
  vtkPolyData* input, const char* what, otparam::TriangleSoup& soup, std::string& ignored)
{
  std::ostringstream msg;
  ignored.clear();
  const vtkIdType numberOfPoints = (input && input->GetPoints()) ? input->GetNumberOfPoints() : 0;
  if (!input || numberOfPoints == 0 || input->GetNumberOfCells() == 0)
  {
    msg << "The " << what << " is empty: it needs points and triangles.";
    return msg.str();
  }
  if (input->GetNumberOfPolys() == 0)
  {
    msg << "The " << what
        << " must be made of triangles only, but it has no triangles: " << input->GetNumberOfVerts()
        << " vertex cells, " << input->GetNumberOfLines() << " line cells and "
        << input->GetNumberOfStrips() << " triangle strips (apply vtkTriangleFilter to strips).";
    return msg.str();
  }
  if (input->GetNumberOfStrips() > 0)
  {
    msg << "The " << what << " must be made of triangles only, but it has "
        << input->GetNumberOfStrips() << " triangle strips (apply vtkTriangleFilter first).";
    return msg.str();
  }
  if (input->GetNumberOfVerts() > 0 || input->GetNumberOfLines() > 0)
  {
    std::ostringstream text;
    text << "The " << what << "'s " << input->GetNumberOfVerts() << " vertex cell(s) and "
         << input->GetNumberOfLines()
         << " line cell(s) are ignored: only its triangles are mapped (vtkCleanPolyData leaves "
            "the triangles it collapses as such cells).";
    ignored = text.str();
  }
  soup.points.resize(static_cast<std::size_t>(numberOfPoints));
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    soup.points[i] = { p[0], p[1], p[2] };
  }
  soup.triangles.clear();
  soup.triangles.reserve(static_cast<std::size_t>(input->GetNumberOfPolys()));
  std::vector<vtkIdType> notTriangles;
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
    soup.triangles.push_back({ cell->GetId(0), cell->GetId(1), cell->GetId(2) });
  }
  if (!notTriangles.empty())
  {
    msg << "The " << what << " must be made of triangles, but polygon id(s) "
        << otparam::idList(notTriangles) << " are not (apply vtkTriangleFilter first).";
  }
  return msg.str();
}

//------------------------------------------------------------------------------
std::string ReadTriangleDomain(vtkPolyData* input, const char* what, otparam::TriangleSoup& soup)
{
  std::string ignored;
  const std::string error = ReadTriangleSoup(input, what, soup, ignored);
  if (!error.empty() || ignored.empty())
  {
    return error;
  }
  std::ostringstream msg;
  msg << "The " << what << " must be made of triangles only, but it has "
      << input->GetNumberOfVerts() << " vertex cells, " << input->GetNumberOfLines()
      << " line cells and " << input->GetNumberOfStrips()
      << " triangle strips (extract the surface and apply vtkTriangleFilter first).";
  return msg.str();
}

//------------------------------------------------------------------------------
std::string ReadPlanarPoints(const std::vector<otparam::Vec3>& points,
  const std::vector<std::int64_t>& ids, const char* what, std::vector<otparam::Vec2>& planar)
{
  std::vector<std::int64_t> badCoordinates, offPlane;
  double lo[2] = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double hi[2] = { -lo[0], -lo[1] };
  planar.resize(points.size());
  for (std::size_t v = 0; v < points.size(); ++v)
  {
    const otparam::Vec3& p = points[v];
    planar[v] = { p.x, p.y };
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    {
      badCoordinates.push_back(ids[v]);
      continue;
    }
    lo[0] = std::min(lo[0], p.x);
    lo[1] = std::min(lo[1], p.y);
    hi[0] = std::max(hi[0], p.x);
    hi[1] = std::max(hi[1], p.y);
  }
  std::ostringstream msg;
  if (!badCoordinates.empty())
  {
    msg << "The " << what << " has NaN or infinite coordinates at point id(s) "
        << otparam::idList(badCoordinates) << ".";
    return msg.str();
  }
  // z = 0 up to rounding, relative to the domain's size.
  const double extent = std::max({ 1.0, hi[0] - lo[0], hi[1] - lo[1] });
  double firstZ = 0.0;
  for (std::size_t v = 0; v < points.size(); ++v)
  {
    if (std::abs(points[v].z) > 1e-12 * extent)
    {
      firstZ = offPlane.empty() ? points[v].z : firstZ;
      offPlane.push_back(ids[v]);
    }
  }
  if (!offPlane.empty())
  {
    msg << "The " << what << " is not planar: it must lie in the plane z = 0 but point id(s) "
        << otparam::idList(offPlane) << " have z != 0 (first z: " << firstZ << ").";
  }
  return msg.str();
}

//------------------------------------------------------------------------------
std::string ReadDiracs(
  vtkPointSet* input, std::vector<otparam::Vec3>& points, std::vector<double>& masses)
{
  const vtkIdType n = (input && input->GetPoints()) ? input->GetNumberOfPoints() : 0;
  if (n == 0)
  {
    return "The Diracs input (port 0) has no points; the target measure needs points with a "
           "positive Mass.";
  }
  vtkAbstractArray* massAbstract = input->GetPointData()->GetAbstractArray("Mass");
  if (!massAbstract)
  {
    return "The Diracs input (port 0) has no point array 'Mass'; each point needs a positive "
           "Mass.";
  }
  std::ostringstream msg;
  vtkDataArray* massArray = vtkDataArray::SafeDownCast(massAbstract);
  if (!massArray)
  {
    msg << "The point array 'Mass' of the Diracs input is not numeric (it is a "
        << massAbstract->GetClassName() << "); it must hold one positive number per point.";
    return msg.str();
  }
  if (massArray->GetNumberOfComponents() != 1)
  {
    msg << "The point array 'Mass' of the Diracs input has " << massArray->GetNumberOfComponents()
        << " components; it must have exactly 1.";
    return msg.str();
  }
  points.resize(static_cast<std::size_t>(n));
  masses.resize(static_cast<std::size_t>(n));
  std::vector<vtkIdType> badCoordinates;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      badCoordinates.push_back(i);
    }
    points[i] = { p[0], p[1], p[2] };
    masses[i] = massArray->GetComponent(i, 0);
  }
  if (!badCoordinates.empty())
  {
    msg << "The Diracs input has NaN or infinite coordinates at point id(s) "
        << otparam::idList(badCoordinates) << ".";
  }
  return msg.str();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPoints> MakePoints(const std::vector<otparam::Vec2>& points)
{
  auto result = vtkSmartPointer<vtkPoints>::New();
  result->SetDataTypeToDouble();
  result->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    result->SetPoint(static_cast<vtkIdType>(i), points[i].x, points[i].y, 0.0);
  }
  return result;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPoints> MakePoints(const std::vector<otparam::Vec3>& points)
{
  auto result = vtkSmartPointer<vtkPoints>::New();
  result->SetDataTypeToDouble();
  result->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    result->SetPoint(static_cast<vtkIdType>(i), points[i].x, points[i].y, points[i].z);
  }
  return result;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkCellArray> MakeTriangles(const std::vector<otparam::Triangle>& triangles)
{
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  const auto count = static_cast<vtkIdType>(triangles.size());
  cells->AllocateExact(count, 3 * count);
  for (const otparam::Triangle& t : triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    cells->InsertNextCell(3, ids);
  }
  return cells;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDoubleArray> MakeDoubleArray(
  const char* name, const std::vector<double>& values, int components)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDoubleArray> MakeVec2Array(
  const char* name, const std::vector<otparam::Vec2>& values, int components)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const double tuple[3] = { values[i].x, values[i].y, 0.0 };
    array->SetTuple(static_cast<vtkIdType>(i), tuple);
  }
  return array;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDoubleArray> MakeVec3Array(
  const char* name, const std::vector<otparam::Vec3>& values)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetTuple3(static_cast<vtkIdType>(i), values[i].x, values[i].y, values[i].z);
  }
  return array;
}

//------------------------------------------------------------------------------
void AddScalar(vtkDataObject* data, const char* name, double value)
{
  data->GetFieldData()->AddArray(MakeDoubleArray(name, std::vector<double>{ value }));
}

//------------------------------------------------------------------------------
void AddIntScalar(vtkDataObject* data, const char* name, long long value)
{
  vtkNew<vtkIntArray> array;
  array->SetName(name);
  array->InsertNextValue(static_cast<int>(value));
  data->GetFieldData()->AddArray(array);
}

//------------------------------------------------------------------------------
void AddIdScalar(vtkDataObject* data, const char* name, long long value)
{
  vtkNew<vtkIdTypeArray> array;
  array->SetName(name);
  array->InsertNextValue(static_cast<vtkIdType>(value));
  data->GetFieldData()->AddArray(array);
}

//------------------------------------------------------------------------------
void AddString(vtkDataObject* data, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  data->GetFieldData()->AddArray(array);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkIdTypeArray> MakeOriginalPointIds(const std::vector<std::int64_t>& ids)
{
  auto array = vtkSmartPointer<vtkIdTypeArray>::New();
  array->SetName("vtkOriginalPointIds");
  array->SetNumberOfTuples(static_cast<vtkIdType>(ids.size()));
  std::copy(ids.begin(), ids.end(), array->GetPointer(0));
  return array;
}

//------------------------------------------------------------------------------
void CopyTriangleCellData(vtkPolyData* input, vtkCellData* cells)
{
  // vtkPolyData numbers its cells vertices, lines, polygons, strips: the triangles' arrays
  // start after the vertex and line cells ReadTriangleSoup left out.
  const vtkIdType first = input->GetNumberOfVerts() + input->GetNumberOfLines();
  if (first == 0)
  {
    cells->ShallowCopy(input->GetCellData());
    return;
  }
  const vtkIdType count = input->GetNumberOfPolys();
  cells->Initialize();
  cells->CopyAllocate(input->GetCellData(), count);
  for (vtkIdType c = 0; c < count; ++c)
  {
    cells->CopyData(input->GetCellData(), first + c, c);
  }
}

//------------------------------------------------------------------------------
void CopyTrianglesOf(vtkPolyData* input, vtkPolyData* output)
{
  output->ShallowCopy(input);
  if (input->GetNumberOfVerts() + input->GetNumberOfLines() > 0)
  {
    output->SetVerts(vtkNew<vtkCellArray>());
    output->SetLines(vtkNew<vtkCellArray>());
    CopyTriangleCellData(input, output->GetCellData());
  }
}

//------------------------------------------------------------------------------
void CopyInputArrays(
  vtkPolyData* input, const std::vector<std::int64_t>& originalPointIds, vtkPolyData* output)
{
  vtkPointData* points = output->GetPointData();
  points->CopyNormalsOff();
  const auto n = static_cast<vtkIdType>(originalPointIds.size());
  points->CopyAllocate(input->GetPointData(), n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    points->CopyData(input->GetPointData(), originalPointIds[v], v);
  }
  vtkCellData* cells = output->GetCellData();
  CopyTriangleCellData(input, cells);
  if (vtkDataArray* normals = cells->GetNormals())
  {
    cells->RemoveArray(normals->GetName());
  }
}

//------------------------------------------------------------------------------
void AddDistortionArrays(vtkCellData* cellData, const otparam::DistortionFigures& figures)
{
  cellData->AddArray(MakeDoubleArray("AngleDistortion", figures.angleDistortion));
  cellData->AddArray(MakeDoubleArray("QuasiConformalDilatation", figures.dilatation));
  cellData->AddArray(MakeDoubleArray("LogAreaRatio", figures.logAreaRatio));
}

//------------------------------------------------------------------------------
void AddDistortionFigures(
  vtkDataObject* data, const otparam::DistortionFigures& figures, const std::string& prefix)
{
  auto name = [&prefix](const char* figure) { return prefix + figure; };
  AddIntScalar(data, name("FlippedTriangles").c_str(), figures.flippedTriangles);
  AddScalar(data, name("MeanAbsLogAreaRatio").c_str(), figures.meanAbsLogAreaRatio);
  AddScalar(data, name("MaximumAbsLogAreaRatio").c_str(), figures.maximumAbsLogAreaRatio);
  AddScalar(data, name("MeanAngleDistortion").c_str(), figures.meanAngleDistortionDegrees);
  AddScalar(data, name("MaximumAngleDistortion").c_str(), figures.maximumAngleDistortionDegrees);
  AddScalar(data, name("MeanQuasiConformalDilatation").c_str(), figures.meanDilatation);
  AddScalar(data, name("MaximumQuasiConformalDilatation").c_str(), figures.maximumDilatation);
}

//------------------------------------------------------------------------------
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

//------------------------------------------------------------------------------
void AddNewtonReport(vtkDataObject* data, const otparam::NewtonReport& report)
{
  AddIntScalar(data, "Iterations", report.iterations);
  AddScalar(data, "RelativeError", report.relativeError);
  AddIntScalar(data, "Converged", report.converged ? 1 : 0);
  data->GetFieldData()->AddArray(
    MakeDoubleArray("GradientNormHistory", report.gradientNormHistory));
  data->GetFieldData()->AddArray(MakeDoubleArray("StepLengthHistory", report.stepLengthHistory));
  AddScalar(data, "SecondsTriangulation", report.secondsTriangulation);
  AddScalar(data, "SecondsIntegration", report.secondsIntegration);
  AddScalar(data, "SecondsAssembly", report.secondsAssembly);
  AddScalar(data, "SecondsSolve", report.secondsSolve);
  AddString(data, "StopReason", report.message);
}

//------------------------------------------------------------------------------
void AddHistogram(
  vtkTable* table, const std::string& name, const std::vector<double>& values, int bins)
{
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (double v : values)
  {
    if (std::isfinite(v))
    {
      low = std::min(low, v);
      high = std::max(high, v);
    }
  }
  if (!(low <= high))
  {
    low = 0.0;
    high = 1.0;
  }
  if (high - low <= 1e-12 * std::max(1.0, std::abs(low)))
  {
    low -= 0.5;
    high += 0.5;
  }
  const double width = (high - low) / bins;
  vtkNew<vtkDoubleArray> centers;
  centers->SetName((name + "BinCenter").c_str());
  centers->SetNumberOfTuples(bins);
  vtkNew<vtkIntArray> counts;
  counts->SetName(name.c_str());
  counts->SetNumberOfTuples(bins);
  for (int b = 0; b < bins; ++b)
  {
    centers->SetValue(b, low + (b + 0.5) * width);
    counts->SetValue(b, 0);
  }
  for (double v : values)
  {
    if (std::isfinite(v))
    {
      const int b = std::clamp(static_cast<int>((v - low) / width), 0, bins - 1);
      counts->SetValue(b, counts->GetValue(b) + 1);
    }
  }
  table->AddColumn(centers);
  table->AddColumn(counts);
}

//------------------------------------------------------------------------------
void WriteCells(const std::vector<std::vector<otparam::Vec3>>& cells,
  const std::vector<int>& cellDirac, const std::vector<double>& mass,
  const std::vector<double>& cellMass, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polygons;
  vtkNew<vtkIntArray> diracId;
  diracId->SetName("DiracId");
  vtkNew<vtkDoubleArray> cellTarget, cellReached;
  cellTarget->SetName("Mass");
  cellReached->SetName("CellMass");
  std::vector<vtkIdType> ids;
  for (std::size_t c = 0; c < cells.size(); ++c)
  {
    if (cells[c].size() < 3)
    {
      continue;
    }
    ids.clear();
    for (const otparam::Vec3& p : cells[c])
    {
      ids.push_back(points->InsertNextPoint(p.x, p.y, p.z));
    }
    polygons->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    const int dirac = cellDirac[c];
    diracId->InsertNextValue(dirac);
    cellTarget->InsertNextValue(mass[dirac]);
    cellReached->InsertNextValue(cellMass[dirac]);
  }
  output->SetPoints(points);
  output->SetPolys(polygons);
  output->GetCellData()->AddArray(diracId);
  output->GetCellData()->AddArray(cellTarget);
  output->GetCellData()->AddArray(cellReached);
}

//------------------------------------------------------------------------------
void WriteDiracSurface(
  const std::vector<otparam::Vec3>& points, vtkCellArray* triangles, vtkPolyData* output)
{
  vtkNew<vtkIntArray> diracId;
  diracId->SetName("DiracId");
  diracId->SetNumberOfTuples(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    diracId->SetValue(static_cast<vtkIdType>(i), static_cast<int>(i));
  }
  output->SetPoints(MakePoints(points));
  output->SetPolys(triangles);
  output->GetPointData()->AddArray(diracId);
}

//------------------------------------------------------------------------------
void WritePowerCells(const otparam::TransportStage& transport, vtkPolyData* output)
{
  const otparam::PowerDiagramGeometry& geometry = transport.geometry;
  std::vector<std::vector<otparam::Vec3>> cells(geometry.cells.size());
  for (std::size_t c = 0; c < cells.size(); ++c)
  {
    for (const otparam::Vec2& p : geometry.cells[c])
    {
      cells[c].push_back({ p.x, p.y, 0.0 });
    }
  }
  WriteCells(cells, geometry.cellDirac, transport.result.mass, transport.result.cellMass, output);
}

//------------------------------------------------------------------------------
void WriteBrenierPotential(const otparam::TransportStage& transport,
  const std::vector<otparam::Vec2>& diracs, vtkPolyData* output)
{
  // u_h(x) = max_i <x, y_i> - h_i, affine on each cell.
  const otparam::PowerDiagramGeometry& geometry = transport.geometry;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkIntArray> diracId;
  diracId->SetName("DiracId");
  for (std::size_t c = 0; c < geometry.cells.size(); ++c)
  {
    const std::vector<otparam::Vec2>& cell = geometry.cells[c];
    if (cell.size() < 3)
    {
      continue;
    }
    const int dirac = geometry.cellDirac[c];
    const otparam::Vec2 y = diracs[dirac];
    const double h = transport.result.heights[dirac];
    const vtkIdType first = points->GetNumberOfPoints();
    for (const otparam::Vec2& p : cell)
    {
      points->InsertNextPoint(p.x, p.y, otparam::dot(p, y) - h);
    }
    // The clipped cell is convex: a fan from its first vertex triangulates it.
    for (std::size_t k = 1; k + 1 < cell.size(); ++k)
    {
      const vtkIdType tri[3] = { first, first + static_cast<vtkIdType>(k),
        first + static_cast<vtkIdType>(k + 1) };
      triangles->InsertNextCell(3, tri);
      diracId->InsertNextValue(dirac);
    }
  }
  output->SetPoints(points);
  output->SetPolys(triangles);
  output->GetCellData()->AddArray(diracId);
}

//------------------------------------------------------------------------------
void WriteLegendreDual(const otparam::TransportStage& transport,
  const std::vector<otparam::Vec2>& diracs, vtkCellArray* triangles, vtkPolyData* output)
{
  std::vector<otparam::Vec3> points(diracs.size());
  for (std::size_t i = 0; i < diracs.size(); ++i)
  {
    points[i] = { diracs[i].x, diracs[i].y, transport.result.heights[i] };
  }
  WriteDiracSurface(points, triangles, output);
}

//------------------------------------------------------------------------------
void WriteDiscontinuities(const otparam::TransportStage& transport,
  const std::vector<otparam::Vec2>& diracs, const std::vector<otparam::Triangle>& support,
  vtkPolyData* output)
{
  const auto jumps = support.empty()
    ? std::vector<otparam::PowerDiagramGeometry::Edge>()
    : otparam::discontinuityEdges(transport.geometry, diracs, support);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkDoubleArray> jump;
  jump->SetName("JumpLength");
  vtkNew<vtkIntArray> pair;
  pair->SetName("DiracIds");
  pair->SetNumberOfComponents(2);
  for (const auto& e : jumps)
  {
    const vtkIdType line[2] = { points->InsertNextPoint(e.a.x, e.a.y, 0.0),
      points->InsertNextPoint(e.b.x, e.b.y, 0.0) };
    lines->InsertNextCell(2, line);
    jump->InsertNextValue(otparam::norm(diracs[e.i] - diracs[e.j]));
    const int dirac[2] = { e.i, e.j };
    pair->InsertNextTypedTuple(dirac);
  }
  output->SetPoints(points);
  output->SetLines(lines);
  output->GetCellData()->AddArray(jump);
  output->GetCellData()->AddArray(pair);
}

} // namespace otparam_vtk
