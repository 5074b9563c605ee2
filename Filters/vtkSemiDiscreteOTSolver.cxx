#include "vtkSemiDiscreteOTSolver.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "Transport/Discontinuities.h"
#include "OTParamAdapterUtilities.h"
#include "Transport/SemiDiscreteOT.h"
#include "Transport/PlanarSource.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSemiDiscreteOTSolver);

namespace
{
using namespace otparam_vtk;
constexpr int NumberOfOutputs = 5;

} // namespace

//------------------------------------------------------------------------------
vtkSemiDiscreteOTSolver::vtkSemiDiscreteOTSolver()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(NumberOfOutputs);
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
int vtkSemiDiscreteOTSolver::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Transport couples every Dirac with every other one: the solve needs all of the data, not a
  // piece of it (in parallel ParaView, piece 0 does the work, see RequestData).
  RequestWholeInputs(inputVector, 2);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSemiDiscreteOTSolver::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();

  vtkPolyData* outputs[NumberOfOutputs];
  for (int port = 0; port < NumberOfOutputs; ++port)
  {
    outputs[port] = vtkPolyData::GetData(outputVector, port);
    if (!outputs[port])
    {
      vtkErrorMacro("Output port " << port << " holds no vtkPolyData.");
      return 0;
    }
    outputs[port]->Initialize();
  }

  // Other pieces stay empty so that parallel runs do not duplicate the (replicated) result.
  if (IsOtherPiece(outputVector))
  {
    return 1;
  }

  // Properties are validated here rather than clamped by the setters so that an absurd value is
  // reported instead of silently replaced.
  if (!(this->Tolerance > 0.0) || !std::isfinite(this->Tolerance))
  {
    vtkErrorMacro("Tolerance must be positive and finite; got " << this->Tolerance << ".");
    return 0;
  }
  if (this->MaximumNumberOfIterations < 1)
  {
    vtkErrorMacro("MaximumNumberOfIterations must be at least 1; got "
      << this->MaximumNumberOfIterations << ".");
    return 0;
  }
  if (!(this->MaximumArcAngle > 0.0) || !(this->MaximumArcAngle <= 1.0))
  {
    vtkErrorMacro(
      "MaximumArcAngle must be in (0, 1] radians; got " << this->MaximumArcAngle << ".");
    return 0;
  }

  // ---- Input port 0: the Diracs.
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0], 0);
  const vtkIdType n = (input && input->GetPoints()) ? input->GetNumberOfPoints() : 0;
  if (n == 0)
  {
    vtkErrorMacro("The Diracs input (port 0) has no points; the target measure needs at least "
                  "one point with a positive Mass.");
    return 0;
  }
  vtkAbstractArray* massAbstract = input->GetPointData()->GetAbstractArray("Mass");
  if (!massAbstract)
  {
    vtkErrorMacro("The Diracs input (port 0) has no point array 'Mass'; each point needs a "
                  "positive Mass.");
    return 0;
  }
  vtkDataArray* massArray = vtkDataArray::SafeDownCast(massAbstract);
  if (!massArray)
  {
    vtkErrorMacro("The point array 'Mass' of the Diracs input is not numeric (it is a "
      << massAbstract->GetClassName() << "); it must hold one positive number per point.");
    return 0;
  }
  if (massArray->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("The point array 'Mass' of the Diracs input has "
      << massArray->GetNumberOfComponents() << " components; it must have exactly 1.");
    return 0;
  }

  std::vector<otparam::Vec2> diracs(static_cast<std::size_t>(n));
  std::vector<double> masses(static_cast<std::size_t>(n));
  {
    std::vector<vtkIdType> badCoordinates, badMass;
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      input->GetPoint(i, p);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      {
        badCoordinates.push_back(i);
      }
      diracs[i] = { p[0], p[1] };
      masses[i] = massArray->GetComponent(i, 0);
      if (!(masses[i] > 0.0) || !std::isfinite(masses[i]))
      {
        badMass.push_back(i);
      }
    }
    if (!badCoordinates.empty())
    {
      vtkErrorMacro("The Diracs input has NaN or infinite coordinates at point id(s) "
        << FormatIds(badCoordinates) << ".");
      return 0;
    }
    if (!badMass.empty())
    {
      vtkErrorMacro("The point array 'Mass' must be positive and finite (not zero, negative, "
                    "NaN or infinite) but is not at point id(s) "
        << FormatIds(badMass) << " (first value: " << masses[badMass.front()] << ").");
      return 0;
    }
  }
  // The core's own check (finite, positive, pairwise distinct) covers duplicate points.
  const std::string diracError = otparam::validateDiracs(diracs, masses);
  if (!diracError.empty())
  {
    vtkErrorMacro("Invalid Diracs input (port 0): " << diracError);
    return 0;
  }

  // ---- Input port 1: the source measure.
  std::unique_ptr<otparam::SourceMeasure> source;
  vtkPolyData* domain = vtkPolyData::GetData(inputVector[1], 0);
  if (!domain || domain->GetNumberOfPoints() == 0)
  {
    source = otparam::makeUnitDiskSource();
  }
  else
  {
    const vtkIdType np = domain->GetNumberOfPoints();
    double bounds[6];
    domain->GetBounds(bounds);
    const double extent = std::max({ 1.0, bounds[1] - bounds[0], bounds[3] - bounds[2] });
    std::vector<otparam::Vec2> points(static_cast<std::size_t>(np));
    std::vector<vtkIdType> badCoordinates, offPlane;
    for (vtkIdType i = 0; i < np; ++i)
    {
      double p[3];
      domain->GetPoint(i, p);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      {
        badCoordinates.push_back(i);
      }
      else if (std::abs(p[2]) > 1e-12 * extent)
      {
        offPlane.push_back(i);
      }
      points[i] = { p[0], p[1] };
    }
    if (!badCoordinates.empty())
    {
      vtkErrorMacro("The source domain (port 1) has NaN or infinite coordinates at point id(s) "
        << FormatIds(badCoordinates) << ".");
      return 0;
    }
    if (!offPlane.empty())
    {
      vtkErrorMacro("The source domain (port 1) is not planar: it must lie in the plane z = 0 "
                    "but point id(s) "
        << FormatIds(offPlane) << " have z != 0.");
      return 0;
    }
    if (domain->GetNumberOfStrips() > 0)
    {
      vtkErrorMacro("The source domain (port 1) has triangle strips; it must be made of "
                    "triangles (apply vtkTriangleFilter first).");
      return 0;
    }

    std::vector<otparam::Triangle> triangles;
    triangles.reserve(static_cast<std::size_t>(domain->GetNumberOfPolys()));
    std::vector<vtkIdType> notTriangles;
    vtkNew<vtkIdList> cellPoints;
    vtkCellArray* polys = domain->GetPolys();
    for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
    {
      polys->GetCellAtId(c, cellPoints);
      if (cellPoints->GetNumberOfIds() != 3)
      {
        notTriangles.push_back(c);
        continue;
      }
      triangles.push_back({ static_cast<int>(cellPoints->GetId(0)),
        static_cast<int>(cellPoints->GetId(1)), static_cast<int>(cellPoints->GetId(2)) });
    }
    if (!notTriangles.empty())
    {
      vtkErrorMacro("The source domain (port 1) must be triangulated, but polygon ids "
        << FormatIds(notTriangles) << " are not triangles (apply vtkTriangleFilter first).");
      return 0;
    }
    if (triangles.empty())
    {
      vtkErrorMacro("The source domain (port 1) has points but no triangles.");
      return 0;
    }

    std::vector<double> density;
    if (vtkAbstractArray* densityAbstract = domain->GetPointData()->GetAbstractArray("Density"))
    {
      vtkDataArray* densityArray = vtkDataArray::SafeDownCast(densityAbstract);
      if (!densityArray || densityArray->GetNumberOfComponents() != 1)
      {
        vtkErrorMacro("The point array 'Density' of the source domain must be numeric with one "
                      "component.");
        return 0;
      }
      density.resize(static_cast<std::size_t>(np));
      std::vector<vtkIdType> badDensity;
      for (vtkIdType i = 0; i < np; ++i)
      {
        density[i] = densityArray->GetComponent(i, 0);
        if (!(density[i] > 0.0) || !std::isfinite(density[i]))
        {
          badDensity.push_back(i);
        }
      }
      if (!badDensity.empty())
      {
        vtkErrorMacro("The point array 'Density' of the source domain must be positive and "
                      "finite but is not at point id(s) "
          << FormatIds(badDensity) << " (first value: " << density[badDensity.front()] << ").");
        return 0;
      }
    }

    std::string domainError;
    source = otparam::makeTriangulatedSource(points, triangles, density, domainError);
    if (!source)
    {
      vtkErrorMacro("Invalid source domain (port 1): " << domainError);
      return 0;
    }
  }

  // ---- Solve.
  otparam::OTOptions options;
  options.tolerance = this->Tolerance;
  options.maximumNumberOfIterations = this->MaximumNumberOfIterations;
  // Newton converges fast near the solution, so iterations/maximum says little: report the
  // larger of that and the fraction of orders of magnitude of the error already gained.
  double firstError = -1.0;
  double progress = 0.0;
  options.progress = [this, &firstError, &progress](int iteration, double error)
  {
    if (firstError < 0.0)
    {
      firstError = error;
    }
    double fraction = static_cast<double>(iteration) / this->MaximumNumberOfIterations;
    if (firstError > this->Tolerance && error > 0.0)
    {
      fraction =
        std::max(fraction, std::log(firstError / error) / std::log(firstError / this->Tolerance));
    }
    progress = std::max(progress, std::min(0.95, fraction));
    std::ostringstream text;
    text << "Newton iteration " << iteration << ", relative error " << error;
    this->SetProgressText(text.str().c_str());
    this->UpdateProgress(progress);
    return !this->GetAbortExecute();
  };

  otparam::OTResult result;
  otparam::PowerDiagramGeometry geometry;
  double secondsOutput = 0.0;
  try
  {
    result = otparam::solveSemiDiscreteOT(*source, diracs, masses, options);
    if (result.aborted || this->GetAbortExecute())
    {
      vtkWarningMacro("Aborted after " << result.iterations
                                       << " Newton iterations; the outputs "
                                          "are left empty.");
      return 1;
    }
    const auto startOutput = std::chrono::steady_clock::now();
    geometry =
      otparam::computePowerDiagramGeometry(*source, diracs, result.heights, this->MaximumArcAngle);
    secondsOutput = Seconds(startOutput);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("The semi-discrete OT solve failed: " << e.what());
    return 0;
  }
  if (result.heights.size() != diracs.size() || result.mass.size() != diracs.size() ||
    result.cellMass.size() != diracs.size() || result.centroids.size() != diracs.size())
  {
    vtkErrorMacro("The semi-discrete OT solve returned no solution: " << result.message);
    return 0;
  }
  if (!result.converged)
  {
    vtkWarningMacro("Not converged after "
      << result.iterations
      << " Newton iterations (MaximumNumberOfIterations = " << this->MaximumNumberOfIterations
      << "): relative error " << result.relativeError << " > Tolerance " << this->Tolerance << ". "
      << result.message << " The outputs hold this last iterate, with Converged = 0.");
  }

  const auto startOutput = std::chrono::steady_clock::now();
  const vtkIdType numberOfTriangles = static_cast<vtkIdType>(geometry.triangles.size());

  // ---- Port 0: Diracs + weighted Delaunay triangles.
  {
    vtkPolyData* out = outputs[0];
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      points->SetPoint(i, diracs[i].x, diracs[i].y, 0.0);
    }
    out->SetPoints(points);
    vtkNew<vtkCellArray> triangles;
    triangles->AllocateExact(numberOfTriangles, 3 * numberOfTriangles);
    for (const otparam::Triangle& t : geometry.triangles)
    {
      const vtkIdType ids[3] = { t[0], t[1], t[2] };
      triangles->InsertNextCell(3, ids);
    }
    out->SetPolys(triangles);

    out->GetPointData()->PassData(input->GetPointData());
    out->GetPointData()->AddArray(MakeDoubleArray("Mass", result.mass));
    out->GetPointData()->AddArray(MakeDoubleArray("Height", result.heights));
    out->GetPointData()->AddArray(MakeDoubleArray("CellMass", result.cellMass));
    vtkNew<vtkDoubleArray> centroids;
    centroids->SetName("Centroid");
    centroids->SetNumberOfComponents(3);
    centroids->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      centroids->SetTuple3(i, result.centroids[i].x, result.centroids[i].y, 0.0);
    }
    out->GetPointData()->AddArray(centroids);
  }

  // ---- Port 1: power diagram, one polygon per non-empty clipped cell.
  {
    vtkPolyData* out = outputs[1];
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> polygons;
    vtkNew<vtkIntArray> diracId;
    diracId->SetName("DiracId");
    vtkNew<vtkDoubleArray> mass, cellMass;
    mass->SetName("Mass");
    cellMass->SetName("CellMass");
    std::vector<vtkIdType> ids;
    for (std::size_t c = 0; c < geometry.cells.size(); ++c)
    {
      const std::vector<otparam::Vec2>& cell = geometry.cells[c];
      if (cell.size() < 3)
      {
        continue;
      }
      ids.clear();
      for (const otparam::Vec2& p : cell)
      {
        ids.push_back(points->InsertNextPoint(p.x, p.y, 0.0));
      }
      polygons->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
      const int dirac = geometry.cellDirac[c];
      diracId->InsertNextValue(dirac);
      mass->InsertNextValue(result.mass[dirac]);
      cellMass->InsertNextValue(result.cellMass[dirac]);
    }
    out->SetPoints(points);
    out->SetPolys(polygons);
    out->GetCellData()->AddArray(diracId);
    out->GetCellData()->AddArray(mass);
    out->GetCellData()->AddArray(cellMass);
  }

  // ---- Port 2: Brenier potential u_h(x) = max_i <x, y_i> - h_i, affine on each cell.
  {
    vtkPolyData* out = outputs[2];
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
      const double h = result.heights[dirac];
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
    out->SetPoints(points);
    out->SetPolys(triangles);
    out->GetCellData()->AddArray(diracId);
  }

  // ---- Port 3: Legendre dual, the points (y_i, h_i) over the weighted Delaunay triangles.
  {
    vtkPolyData* out = outputs[3];
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(n);
    vtkNew<vtkIntArray> diracId;
    diracId->SetName("DiracId");
    diracId->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      points->SetPoint(i, diracs[i].x, diracs[i].y, result.heights[i]);
      diracId->SetValue(i, static_cast<int>(i));
    }
    out->SetPoints(points);
    out->SetPolys(outputs[0]->GetPolys());
    out->GetPointData()->AddArray(diracId);
  }

  // ---- Port 4: discontinuity set. The target's support is the union of the input's triangles
  // (the sampler's triangulation of it); without triangles it is not known and nothing is
  // reported.
  {
    std::vector<otparam::Triangle> support;
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
    {
      if (input->GetCellType(c) == VTK_TRIANGLE)
      {
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
    }
    const auto jumps = support.empty() ? std::vector<otparam::PowerDiagramGeometry::Edge>()
                                       : otparam::discontinuityEdges(geometry, diracs, support);
    vtkPolyData* out = outputs[4];
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
    out->SetPoints(points);
    out->SetLines(lines);
    out->GetCellData()->AddArray(jump);
    out->GetCellData()->AddArray(pair);
  }

  secondsOutput += Seconds(startOutput);

  // ---- Figures of the run, as field data of port 0.
  vtkFieldData* fd = outputs[0]->GetFieldData();
  fd->AddArray(MakeIntScalar("Iterations", result.iterations));
  fd->AddArray(MakeScalar("RelativeError", result.relativeError));
  fd->AddArray(MakeIntScalar("Converged", result.converged ? 1 : 0));
  fd->AddArray(MakeDoubleArray("GradientNormHistory", result.gradientNormHistory));
  fd->AddArray(MakeDoubleArray("StepLengthHistory", result.stepLengthHistory));
  fd->AddArray(MakeScalar("SourceMass", source->totalMass()));
  fd->AddArray(MakeScalar("SecondsTriangulation", result.secondsTriangulation));
  fd->AddArray(MakeScalar("SecondsIntegration", result.secondsIntegration));
  fd->AddArray(MakeScalar("SecondsAssembly", result.secondsAssembly));
  fd->AddArray(MakeScalar("SecondsSolve", result.secondsSolve));
  fd->AddArray(MakeScalar("SecondsOutput", secondsOutput));
  fd->AddArray(MakeScalar("SecondsTotal", Seconds(startTotal)));
  vtkNew<vtkStringArray> reason;
  reason->SetName("StopReason");
  reason->InsertNextValue(result.message);
  fd->AddArray(reason);

  this->UpdateProgress(1.0);
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
