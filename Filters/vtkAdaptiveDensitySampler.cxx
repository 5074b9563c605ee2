#include "vtkAdaptiveDensitySampler.h"

#include "vtkAbstractArray.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "Sampling/PlanarSampler.h"
#include "Sampling/PlanarDensityField.h"
#include "OTParamAdapterUtilities.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAdaptiveDensitySampler);

using namespace otparam_vtk;

//------------------------------------------------------------------------------
vtkAdaptiveDensitySampler::vtkAdaptiveDensitySampler()
{
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

//------------------------------------------------------------------------------
int vtkAdaptiveDensitySampler::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The refinement is global: it needs the whole domain, not a piece of it.
  RequestWholeInputs(inputVector, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkAdaptiveDensitySampler::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  if (IsOtherPiece(outputVector))
  {
    return 1; // piece 0 holds the whole result
  }

  // ---- Properties: reported, never clamped.
  if (this->SamplingMode < ADAPTIVE || this->SamplingMode > MESH_VERTICES)
  {
    vtkErrorMacro("SamplingMode must be 0 (Adaptive), 1 (Uniform) or 2 (MeshVertices); got "
      << this->SamplingMode << ".");
    return 0;
  }
  if (this->SizeRule < SQRT_DENSITY || this->SizeRule > DENSITY)
  {
    vtkErrorMacro(
      "SizeRule must be 0 (R * sqrt(density)) or 1 (R * density); got " << this->SizeRule << ".");
    return 0;
  }
  if (this->NumberOfSamples < 3)
  {
    vtkErrorMacro("NumberOfSamples must be at least 3; got " << this->NumberOfSamples << ".");
    return 0;
  }
  if (this->NumberOfSamples > this->MaximumNumberOfSamples)
  {
    vtkErrorMacro("NumberOfSamples = "
      << this->NumberOfSamples << " is above MaximumNumberOfSamples = "
      << this->MaximumNumberOfSamples << "; raise MaximumNumberOfSamples or ask for fewer.");
    return 0;
  }
  if (!(this->MinimumAngle > 0.0) || !(this->MinimumAngle <= 35.0))
  {
    vtkErrorMacro("MinimumAngle must be in (0, 35] degrees (Delaunay refinement does not "
                  "terminate for larger bounds); got "
      << this->MinimumAngle << ".");
    return 0;
  }

  // ---- The domain: triangles in the plane z = 0.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  const vtkIdType numberOfPoints = (input && input->GetPoints()) ? input->GetNumberOfPoints() : 0;
  // Any cell counts here: vertices, lines and strips get the "triangles only" message below.
  if (!input || numberOfPoints == 0 || input->GetNumberOfCells() == 0)
  {
    vtkErrorMacro("The input domain is empty: it needs points and triangles.");
    return 0;
  }
  if (input->GetNumberOfVerts() > 0 || input->GetNumberOfLines() > 0 ||
    input->GetNumberOfStrips() > 0)
  {
    vtkErrorMacro("The input domain must be made of triangles only, but it has "
      << input->GetNumberOfVerts() << " vertex cells, " << input->GetNumberOfLines()
      << " line cells and " << input->GetNumberOfStrips()
      << " triangle strips (apply vtkTriangleFilter first).");
    return 0;
  }

  std::vector<otparam::Triangle> triangles;
  triangles.reserve(static_cast<std::size_t>(input->GetNumberOfPolys()));
  {
    std::vector<vtkIdType> notTriangles, badIds;
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
      otparam::Triangle t;
      for (int k = 0; k < 3; ++k)
      {
        const vtkIdType id = cell->GetId(k);
        if (id < 0 || id >= numberOfPoints)
        {
          badIds.push_back(c);
          break;
        }
        t[k] = static_cast<int>(id);
      }
      triangles.push_back(t);
    }
    if (!notTriangles.empty())
    {
      vtkErrorMacro("The input domain must be made of triangles, but polygon id(s) "
        << FormatIds(notTriangles) << " are not (apply vtkTriangleFilter first).");
      return 0;
    }
    if (!badIds.empty())
    {
      vtkErrorMacro("Triangle id(s) " << FormatIds(badIds) << " use point ids outside the input's "
                                      << numberOfPoints << " points.");
      return 0;
    }
  }

  // Points used by no triangle are left out (the core sees only the domain's own points);
  // meshId maps input point ids to the core's, originalId the other way.
  std::vector<int> meshId(static_cast<std::size_t>(numberOfPoints), -1);
  std::vector<vtkIdType> originalId;
  for (const otparam::Triangle& t : triangles)
  {
    for (int v : t)
    {
      if (meshId[v] < 0)
      {
        meshId[v] = 0;
      }
    }
  }
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    if (meshId[i] >= 0)
    {
      meshId[i] = static_cast<int>(originalId.size());
      originalId.push_back(i);
    }
  }
  const auto used = static_cast<vtkIdType>(originalId.size());
  const bool compacted = used < numberOfPoints;
  for (otparam::Triangle& t : triangles)
  {
    for (int& v : t)
    {
      v = meshId[v];
    }
  }

  std::vector<otparam::Vec2> points(static_cast<std::size_t>(used));
  {
    std::vector<vtkIdType> badCoordinates, offPlane;
    std::vector<double> z(static_cast<std::size_t>(used));
    double lo[2] = { 0.0, 0.0 }, hi[2] = { 0.0, 0.0 };
    bool first = true;
    for (vtkIdType v = 0; v < used; ++v)
    {
      double p[3];
      input->GetPoint(originalId[v], p);
      points[v] = { p[0], p[1] };
      z[v] = p[2];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      {
        badCoordinates.push_back(originalId[v]);
        continue;
      }
      for (int k = 0; k < 2; ++k)
      {
        lo[k] = first ? p[k] : std::min(lo[k], p[k]);
        hi[k] = first ? p[k] : std::max(hi[k], p[k]);
      }
      first = false;
    }
    if (!badCoordinates.empty())
    {
      vtkErrorMacro("The input domain has NaN or infinite coordinates at point id(s) "
        << FormatIds(badCoordinates) << ".");
      return 0;
    }
    // z = 0 up to rounding, relative to the domain's size (as vtkSemiDiscreteOTSolver).
    const double extent = std::max({ 1.0, hi[0] - lo[0], hi[1] - lo[1] });
    for (vtkIdType v = 0; v < used; ++v)
    {
      if (std::abs(z[v]) > 1e-12 * extent)
      {
        offPlane.push_back(originalId[v]);
      }
    }
    if (!offPlane.empty())
    {
      vtkErrorMacro("The input domain is not planar: it must lie in the plane z = 0 but point "
                    "id(s) "
        << FormatIds(offPlane) << " have z != 0 (first z: " << z[meshId[offPlane.front()]] << ").");
      return 0;
    }
  }

  // ---- The density array.
  vtkInformation* arrayInfo = this->GetInputArrayInformation(0);
  const std::string arrayName = (arrayInfo && arrayInfo->Has(vtkDataObject::FIELD_NAME()))
    ? arrayInfo->Get(vtkDataObject::FIELD_NAME())
    : std::string();
  int requested = (arrayInfo && arrayInfo->Has(vtkDataObject::FIELD_ASSOCIATION()))
    ? arrayInfo->Get(vtkDataObject::FIELD_ASSOCIATION())
    : vtkDataObject::FIELD_ASSOCIATION_POINTS;
  if (requested != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    requested != vtkDataObject::FIELD_ASSOCIATION_CELLS &&
    requested != vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS)
  {
    vtkErrorMacro("The density array must be a point or a cell array (field association "
      << vtkDataObject::FIELD_ASSOCIATION_POINTS << " or " << vtkDataObject::FIELD_ASSOCIATION_CELLS
      << "); the selected association is " << requested << ".");
    return 0;
  }
  int association = requested;
  vtkAbstractArray* densityAbstract = this->GetInputAbstractArrayToProcess(0, input, association);
  const std::string quotedName =
    "'" + (arrayName.empty() ? std::string("(unnamed)") : arrayName) + "'";
  if (!densityAbstract)
  {
    const char* kind = requested == vtkDataObject::FIELD_ASSOCIATION_POINTS ? "point array"
      : requested == vtkDataObject::FIELD_ASSOCIATION_CELLS                 ? "cell array"
                                                                            : "point or cell array";
    std::string hint;
    if (!arrayName.empty())
    {
      if (requested == vtkDataObject::FIELD_ASSOCIATION_POINTS &&
        input->GetCellData()->GetAbstractArray(arrayName.c_str()))
      {
        hint = " (there is a cell array of that name: select it with "
               "FIELD_ASSOCIATION_CELLS for a density per triangle)";
      }
      else if (requested == vtkDataObject::FIELD_ASSOCIATION_CELLS &&
        input->GetPointData()->GetAbstractArray(arrayName.c_str()))
      {
        hint = " (there is a point array of that name: select it with "
               "FIELD_ASSOCIATION_POINTS)";
      }
    }
    vtkErrorMacro("The density array is missing: the input domain has no "
      << kind << " " << quotedName << hint
      << "; choose the density with SetInputArrayToProcess (default: the point array "
         "'AreaDensity').");
    return 0;
  }
  const bool perPoint = association == vtkDataObject::FIELD_ASSOCIATION_POINTS;
  const char* kind = perPoint ? "point array" : "cell array";
  vtkDataArray* densityArray = vtkDataArray::SafeDownCast(densityAbstract);
  if (!densityArray)
  {
    vtkErrorMacro("The density " << kind << " " << quotedName << " is not numeric (it is a "
                                 << densityAbstract->GetClassName()
                                 << "); it must hold one number per "
                                 << (perPoint ? "point" : "triangle") << ".");
    return 0;
  }
  if (densityArray->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("The density " << kind << " " << quotedName << " has "
                                 << densityArray->GetNumberOfComponents()
                                 << " components; it must have exactly 1.");
    return 0;
  }

  std::vector<double> densityPerPoint, densityPerTriangle;
  {
    // Per point: the points used by triangles; per cell: every triangle (cell id = polygon
    // id, since the input has no other cells).
    const vtkIdType count = perPoint ? used : static_cast<vtkIdType>(triangles.size());
    std::vector<double>& values = perPoint ? densityPerPoint : densityPerTriangle;
    values.resize(static_cast<std::size_t>(count));
    std::vector<vtkIdType> nan, infinite, negative;
    double firstNegative = 0.0;
    bool positive = false;
    for (vtkIdType k = 0; k < count; ++k)
    {
      const vtkIdType id = perPoint ? originalId[k] : k;
      const double value = densityArray->GetComponent(id, 0);
      values[k] = value;
      if (std::isnan(value))
      {
        nan.push_back(id);
      }
      else if (std::isinf(value))
      {
        infinite.push_back(id);
      }
      else if (value < 0.0)
      {
        if (negative.empty())
        {
          firstNegative = value;
        }
        negative.push_back(id);
      }
      else if (value > 0.0)
      {
        positive = true;
      }
    }
    const char* idWord = perPoint ? "point id(s)" : "cell id(s)";
    if (!nan.empty())
    {
      vtkErrorMacro("The density " << kind << " " << quotedName
                                   << " must be finite and >= 0, but it is NaN at " << idWord << " "
                                   << FormatIds(nan) << ".");
      return 0;
    }
    if (!infinite.empty())
    {
      vtkErrorMacro("The density " << kind << " " << quotedName
                                   << " must be finite and >= 0, but it is infinite at " << idWord
                                   << " " << FormatIds(infinite) << ".");
      return 0;
    }
    if (!negative.empty())
    {
      vtkErrorMacro("The density "
        << kind << " " << quotedName << " must be finite and >= 0, but it is negative at " << idWord
        << " " << FormatIds(negative) << " (first value: " << firstNegative << ").");
      return 0;
    }
    if (!positive)
    {
      vtkErrorMacro("The density " << kind << " " << quotedName << " is zero everywhere (all "
                                   << count << (perPoint ? " points" : " triangles")
                                   << " of the domain); it must be positive somewhere.");
      return 0;
    }
  }

  std::string error;
  std::unique_ptr<otparam::DensityField> density;
  try
  {
    density =
      otparam::DensityField::create(points, triangles, densityPerPoint, densityPerTriangle, error);
  }
  catch (const std::exception& e)
  {
    density.reset();
    error = e.what();
  }
  if (!density)
  {
    vtkErrorMacro("The domain is not supported: "
      << error
      << (compacted ? " (point ids here count only the input points used by triangles)" : "")
      << ".");
    return 0;
  }

  // ---- Sample.
  otparam::SamplerOptions options;
  options.mode = static_cast<otparam::SamplingMode>(this->SamplingMode);
  options.sizeRule = static_cast<otparam::SizeRule>(this->SizeRule);
  options.numberOfSamples = static_cast<long long>(this->NumberOfSamples);
  options.maximumNumberOfSamples = static_cast<long long>(this->MaximumNumberOfSamples);
  options.minimumAngleDegrees = this->MinimumAngle;
  options.progress = [this](double fraction)
  {
    this->UpdateProgress(0.95 * std::min(1.0, std::max(0.0, fraction)));
    return !this->GetAbortExecute();
  };

  otparam::SamplerResult result;
  try
  {
    result = otparam::sampleDensity(*density, options);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("The sampling failed: " << e.what());
    return 0;
  }
  if (result.aborted || this->GetAbortExecute())
  {
    vtkWarningMacro("Aborted; the output is left empty.");
    return 1;
  }
  if (!result.error.empty())
  {
    vtkErrorMacro("The sampling failed: " << result.error);
    return 0;
  }
  const auto n = static_cast<vtkIdType>(result.samples.size());
  if (n == 0 || result.mass.size() != result.samples.size())
  {
    vtkErrorMacro("The sampling returned " << n << " samples and " << result.mass.size()
                                           << " masses; expected one mass per sample.");
    return 0;
  }

  // ---- Output: the samples with their triangulation.
  vtkNew<vtkPoints> samplePoints;
  samplePoints->SetDataTypeToDouble();
  samplePoints->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    samplePoints->SetPoint(i, result.samples[i].x, result.samples[i].y, 0.0);
  }
  output->SetPoints(samplePoints);
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(
    static_cast<vtkIdType>(result.triangles.size()), 3 * result.triangles.size());
  for (const otparam::Triangle& t : result.triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    polys->InsertNextCell(3, ids);
  }
  output->SetPolys(polys);
  output->GetPointData()->AddArray(MakeDoubleArray("Mass", result.mass));

  vtkFieldData* fd = output->GetFieldData();
  fd->AddArray(MakeIntScalar("NumberOfSamples", static_cast<int>(n)));
  fd->AddArray(MakeScalar("MassCoefficientOfVariation", result.massCoefficientOfVariation));
  fd->AddArray(MakeScalar("MinimumAngle", result.minimumAngleDegrees));
  fd->AddArray(MakeScalar("Epsilon", result.epsilon));
  fd->AddArray(MakeScalar("SourceMass", result.sourceMass));
  fd->AddArray(MakeIntScalar("RefinementRuns", result.refinementRuns));
  fd->AddArray(MakeIntScalar("Capped", result.capped ? 1 : 0));
  fd->AddArray(MakeScalar("SecondsRefinement", result.secondsRefinement));
  fd->AddArray(MakeScalar("SecondsMasses", result.secondsMasses));
  fd->AddArray(MakeScalar("SecondsTotal", Seconds(startTotal)));

  // Only now: a run that fails must not warn about an output it does not make.
  if (compacted)
  {
    vtkWarningMacro(<< (numberOfPoints - used)
                    << " input point(s) belong to no triangle and are ignored.");
  }
  const auto zeroMass =
    std::count_if(result.mass.begin(), result.mass.end(), [](double m) { return !(m > 0.0); });
  if (zeroMass > 0)
  {
    vtkWarningMacro(<< zeroMass << " of the " << n
                    << " samples have Mass 0 (the density vanishes on their cells); "
                       "vtkSemiDiscreteOTSolver needs positive masses.");
  }
  if (result.capped)
  {
    vtkWarningMacro("The refinement hit the cap MaximumNumberOfSamples = "
      << this->MaximumNumberOfSamples << " and stopped there with " << n
      << " samples: the triangles are not all refined to the size threshold (raise "
         "MaximumNumberOfSamples or lower NumberOfSamples).");
  }
  if (!result.warning.empty())
  {
    vtkWarningMacro(
      "NumberOfSamples = " << this->NumberOfSamples << " not met: " << result.warning << ".");
  }
  this->UpdateProgress(1.0);
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
