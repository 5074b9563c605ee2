// Conversions between VTK data and the core's plain types, written once for every adapter
// (private to the module, not wrapped). Readers return "" or a message that names the problem
// and where, for vtkErrorMacro; writers build VTK objects from core results.
#ifndef OTParamConvert_h
#define OTParamConvert_h

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"

#include "Common/Geometry.h"
#include "Pipeline/DiskStages.h"

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

class vtkCellData;
class vtkDataObject;
class vtkIdTypeArray;
class vtkPointSet;
class vtkPolyData;
class vtkTable;

namespace otparam_vtk
{

// ---- Reading.
// A surface's triangles: `what` names it in messages ("input surface", "input domain"). Vertex
// and line cells are left out, as VTK's surface filters leave them (vtkCleanPolyData turns
// triangles it collapses into such cells): `ignored` then says so, for a warning. Strips and
// other polygons are errors. Point ids are not checked here (compactMesh does, naming the
// triangles).
std::string ReadTriangleSoup(
  vtkPolyData* input, const char* what, otparam::TriangleSoup& soup, std::string& ignored);

// ReadTriangleSoup for inputs that are domains, not surfaces (the sampler's, the transport's
// source): their cell arrays are per triangle, so vertex and line cells are an error, which the
// message names.
std::string ReadTriangleDomain(vtkPolyData* input, const char* what, otparam::TriangleSoup& soup);

// The points `ids` of a surface, which must lie in the plane z = 0 (up to 1e-12 of the
// domain's size) and be finite; messages name the input's point ids.
std::string ReadPlanarPoints(const std::vector<otparam::Vec3>& points,
  const std::vector<std::int64_t>& ids, const char* what, std::vector<otparam::Vec2>& planar);

// The Diracs of the solvers' port 0: the points of `input` (finite) and its numeric
// one-component point array Mass. The values of Mass and the points' positions are left to the
// core's validation (validateDiracs, validateSphericalDiracs), which names the offending ids.
std::string ReadDiracs(
  vtkPointSet* input, std::vector<otparam::Vec3>& points, std::vector<double>& masses);

// ---- Writing.
vtkSmartPointer<vtkPoints> MakePoints(const std::vector<otparam::Vec2>& points);
vtkSmartPointer<vtkPoints> MakePoints(const std::vector<otparam::Vec3>& points);
vtkSmartPointer<vtkCellArray> MakeTriangles(const std::vector<otparam::Triangle>& triangles);

vtkSmartPointer<vtkDoubleArray> MakeDoubleArray(
  const char* name, const std::vector<double>& values, int components = 1);
// (x, y) per point: 2 components, or 3 with z = 0.
vtkSmartPointer<vtkDoubleArray> MakeVec2Array(
  const char* name, const std::vector<otparam::Vec2>& values, int components = 2);
vtkSmartPointer<vtkDoubleArray> MakeVec3Array(
  const char* name, const std::vector<otparam::Vec3>& values);

// One-value field data arrays.
void AddScalar(vtkDataObject* data, const char* name, double value);
void AddIntScalar(vtkDataObject* data, const char* name, long long value);
void AddIdScalar(vtkDataObject* data, const char* name, long long value);
void AddString(vtkDataObject* data, const char* name, const std::string& value);

// The input's cell arrays for its triangles only (those ReadTriangleSoup reads).
void CopyTriangleCellData(vtkPolyData* input, vtkCellData* cells);

// The input, less the vertex and line cells ReadTriangleSoup leaves out (shallow).
void CopyTrianglesOf(vtkPolyData* input, vtkPolyData* output);

// vtkOriginalPointIds: the input point id of each output point.
vtkSmartPointer<vtkIdTypeArray> MakeOriginalPointIds(const std::vector<std::int64_t>& ids);
// The input's point arrays on the points kept (output point v is input point
// originalPointIds[v]) and its cell arrays (the same triangles in the same order), for the
// maps' outputs in the disk or on the sphere. Normals are left out: they are the surface's and
// would shade the disk or the sphere as if it were the surface.
void CopyInputArrays(
  vtkPolyData* input, const std::vector<std::int64_t>& originalPointIds, vtkPolyData* output);

// Per triangle: AngleDistortion, QuasiConformalDilatation, LogAreaRatio.
void AddDistortionArrays(vtkCellData* cellData, const otparam::DistortionFigures& figures);
// Field data: FlippedTriangles, MeanAbsLogAreaRatio, MaximumAbsLogAreaRatio,
// MeanAngleDistortion, MaximumAngleDistortion (degrees), MeanQuasiConformalDilatation,
// MaximumQuasiConformalDilatation, each name prefixed by `prefix`.
void AddDistortionFigures(
  vtkDataObject* data, const otparam::DistortionFigures& figures, const std::string& prefix = "");

double Seconds(std::chrono::steady_clock::time_point start);

// Field data of a Newton solve: Iterations, RelativeError, Converged, GradientNormHistory,
// StepLengthHistory, SecondsTriangulation, SecondsIntegration, SecondsAssembly, SecondsSolve
// and StopReason.
void AddNewtonReport(vtkDataObject* data, const otparam::NewtonReport& report);

// Equal-width histogram of the finite `values` over their range: columns `<name>BinCenter`
// and `<name>` (number of values in the bin).
void AddHistogram(
  vtkTable* table, const std::string& name, const std::vector<double>& values, int bins);

// One polygon per cell (cells with fewer than 3 points are skipped), cell arrays DiracId (int,
// `cellDirac`), and Mass and CellMass of that Dirac.
void WriteCells(const std::vector<std::vector<otparam::Vec3>>& cells,
  const std::vector<int>& cellDirac, const std::vector<double>& mass,
  const std::vector<double>& cellMass, vtkPolyData* output);
// One point per Dirac with the given triangles (shared, not copied) and point array DiracId.
void WriteDiracSurface(
  const std::vector<otparam::Vec3>& points, vtkCellArray* triangles, vtkPolyData* output);

// The solver's outputs beyond the Diracs, from the transport stage: the clipped power cells
// (port 1), the Brenier potential over them (port 2), the Legendre dual (port 3) and the
// discontinuity set of the map for a target supported on `support` (port 4).
void WritePowerCells(const otparam::TransportStage& transport, vtkPolyData* output);
void WriteBrenierPotential(const otparam::TransportStage& transport,
  const std::vector<otparam::Vec2>& diracs, vtkPolyData* output);
void WriteLegendreDual(const otparam::TransportStage& transport,
  const std::vector<otparam::Vec2>& diracs, vtkCellArray* triangles, vtkPolyData* output);
void WriteDiscontinuities(const otparam::TransportStage& transport,
  const std::vector<otparam::Vec2>& diracs, const std::vector<otparam::Triangle>& support,
  vtkPolyData* output);

} // namespace otparam_vtk

#endif
