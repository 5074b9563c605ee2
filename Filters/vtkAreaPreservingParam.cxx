#include "vtkAreaPreservingParam.h"

#include "vtkCellData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "Mesh/Checkerboard.h"
#include "OTParamConvert.h"
#include "Pipeline/AreaPreservingPipeline.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAreaPreservingParam);

using namespace otparam_vtk;

namespace
{
otparam::AreaPreservingOptions MakeOptions(vtkAreaPreservingParam* self)
{
  otparam::AreaPreservingOptions options;
  options.sampling.numberOfSamples = self->GetNumberOfSamples();
  options.sampling.mode = static_cast<otparam::SamplingMode>(self->GetSamplingMode());
  options.transport.tolerance = self->GetTolerance();
  options.transport.maximumNumberOfIterations = self->GetMaximumNumberOfIterations();
  options.conformal.centerPointId = self->GetCenterPointId();
  options.conformal.alignPointId = self->GetAlignPointId();
  options.conformal.fillHoles = self->GetFillHoles();
  options.composition.correctAreas =
    self->GetAreaCorrection() && self->GetMaximumCorrectionSweeps() > 0;
  options.composition.maximumCorrectionSweeps = self->GetMaximumCorrectionSweeps();
  if (self->GetThoroughAreaCorrection())
  {
    otparam::makeCorrectionThorough(options.composition);
  }
  options.progress = [self](const char* stage, double fraction)
  {
    self->SetProgressText(stage);
    self->UpdateProgress(fraction);
    return !self->GetAbortExecute();
  };
  return options;
}

// Squares across the disk's diameter; longitude sectors around the sphere (and half as many
// bands): coarse enough to read on a 5k-triangle surface.
constexpr int CheckerboardSquares = 8;
constexpr int CheckerboardSectors = 12;

// The map made visible without a texture: ParaView (and VTK's mappers) colour by the active
// scalars, so the checkerboard becomes the active cell scalars; active point scalars the
// input brings keep precedence (ParaView and VTK take point scalars first).
void AddCheckerboard(vtkCellData* cells, const std::vector<int>& parity)
{
  vtkNew<vtkIntArray> checkerboard;
  checkerboard->SetName("Checkerboard");
  checkerboard->SetNumberOfValues(static_cast<vtkIdType>(parity.size()));
  for (std::size_t t = 0; t < parity.size(); ++t)
  {
    checkerboard->SetValue(static_cast<vtkIdType>(t), parity[t]);
  }
  cells->AddArray(checkerboard);
  cells->SetActiveScalars("Checkerboard");
}

std::vector<int> Checkerboard(const otparam::AreaPreservingResult& run)
{
  return otparam::diskCheckerboard(
    run.conformal.surface.mesh.triangles, run.composition.uv, CheckerboardSquares);
}

std::vector<int> Checkerboard(const otparam::SphereParameterizationResult& run)
{
  return otparam::sphereCheckerboard(
    run.conformal.surface.mesh.triangles, run.composition.sphere, CheckerboardSectors);
}

// Port 1: the flattened disk mesh, with the input's arrays.
void WriteDomainMesh(
  const otparam::AreaPreservingResult& run, vtkPolyData* input, vtkPolyData* disk)
{
  const otparam::CompactedMesh& surface = run.conformal.surface;
  disk->SetPoints(MakePoints(run.composition.uv));
  disk->SetPolys(MakeTriangles(surface.mesh.triangles));
  CopyInputArrays(input, surface.originalPointIds, disk);
  vtkPointData* pd = disk->GetPointData();
  pd->AddArray(MakeVec3Array("Coordinates3D", surface.mesh.points));
  pd->AddArray(MakeVec2Array("ConformalCoordinates", run.conformal.map.uv));
  pd->AddArray(MakeOriginalPointIds(surface.originalPointIds));
  pd->SetTCoords(MakeVec2Array("AreaPreservingCoordinates", run.composition.uv));
  AddDistortionArrays(disk->GetCellData(), run.figures);
}

// Port 0: the input surface with the coordinates (NaN on points used by no triangle) and the
// per-triangle figures (the input's triangles are the conformal image's, in the same order).
void WriteSurface(const otparam::AreaPreservingResult& run, vtkPolyData* input, vtkPolyData* output)
{
  CopyTrianglesOf(input, output);
  const auto nan = otparam::Vec2{ std::numeric_limits<double>::quiet_NaN(),
    std::numeric_limits<double>::quiet_NaN() };
  std::vector<otparam::Vec2> areaPreserving(input->GetNumberOfPoints(), nan);
  std::vector<otparam::Vec2> conformal(areaPreserving);
  const std::vector<std::int64_t>& ids = run.conformal.surface.originalPointIds;
  for (std::size_t v = 0; v < ids.size(); ++v)
  {
    areaPreserving[ids[v]] = run.composition.uv[v];
    conformal[ids[v]] = run.conformal.map.uv[v];
  }
  auto coordinates = MakeVec2Array("AreaPreservingCoordinates", areaPreserving);
  output->GetPointData()->AddArray(coordinates);
  output->GetPointData()->SetTCoords(coordinates);
  output->GetPointData()->AddArray(MakeVec2Array("ConformalCoordinates", conformal));
  AddDistortionArrays(output->GetCellData(), run.figures);
}

// The figures both domains report under the same names.
template <class Run>
void WriteCommonFigures(const Run& run, int domain, vtkDataObject* figures)
{
  const auto& transport = run.transport.result;
  AddIntScalar(figures, "Domain", domain);
  AddIntScalar(figures, "Iterations", transport.iterations);
  AddScalar(figures, "RelativeError", transport.relativeError);
  AddIntScalar(figures, "Converged", transport.converged ? 1 : 0);
  AddIntScalar(figures, "NumberOfSamples", static_cast<long long>(run.diracs.size()));
  AddIntScalar(figures, "DroppedSamples", run.droppedSamples);
  AddScalar(figures, "MassCoefficientOfVariation", run.sampling.result.massCoefficientOfVariation);
  AddDistortionFigures(figures, run.figures);
  AddDistortionFigures(figures, run.conformal.figures, "Conformal");
  const auto& composition = run.composition;
  AddScalar(
    figures, "InterpolatedMeanAbsLogAreaRatio", composition.meanAbsLogAreaRatioInterpolated);
  AddIntScalar(figures, "InterpolatedFlippedTriangles", composition.flippedAfterInterpolation);
  AddIntScalar(figures, "UntangledVertices", composition.untangledVertices);
  AddScalar(figures, "SecondsConformalMap", run.secondsConformal);
  AddScalar(figures, "SecondsSampling", run.secondsSampling);
  AddScalar(figures, "SecondsTransport", run.secondsTransport);
  AddScalar(figures, "SecondsComposition", run.secondsComposition);
  AddScalar(figures, "SecondsTotal", run.secondsTotal);
}

void WriteFigures(const otparam::AreaPreservingResult& run, vtkDataObject* figures)
{
  WriteCommonFigures(run, vtkAreaPreservingParam::DISK, figures);
  AddIntScalar(figures, "FilledHoles", run.conformal.filledHoles);
  AddScalar(figures, "FillAreaFraction", run.conformal.fillAreaFraction);
  AddIntScalar(figures, "SampleScaleSweeps", run.composition.sampleScaleSweeps);
  AddScalar(
    figures, "SampleScaleMeanAbsLogAreaRatio", run.composition.meanAbsLogAreaRatioSampleScale);
  AddIntScalar(figures, "CorrectionSweeps", run.composition.correctionSweeps);
  AddIntScalar(figures, "TransportStages", run.transportStages);
}

void WriteFigures(const otparam::SphereParameterizationResult& run, vtkDataObject* figures)
{
  WriteCommonFigures(run, vtkAreaPreservingParam::SPHERE, figures);
  AddIntScalar(figures, "FilledHoles", run.conformal.filledHoles);
  AddScalar(figures, "FillAreaFraction", run.conformal.fillAreaFraction);
  AddIntScalar(figures, "CorrectionSweeps", run.composition.correctionSweeps);
  AddIntScalar(figures, "TransportStages", run.transportStages);
}

// Longitude and latitude of points on the sphere, scaled to [0, 1] (texture coordinates).
std::vector<otparam::Vec2> LongitudeLatitude(const std::vector<otparam::Vec3>& sphere)
{
  std::vector<otparam::Vec2> tcoords(sphere.size());
  for (std::size_t v = 0; v < sphere.size(); ++v)
  {
    const otparam::Vec3 p = sphere[v];
    tcoords[v] = { 0.5 + std::atan2(p.y, p.x) / (2.0 * M_PI),
      0.5 + std::asin(std::max(-1.0, std::min(1.0, p.z))) / M_PI };
  }
  return tcoords;
}

// Port 1 for the sphere: the area-preserving sphere mesh, with the input's arrays.
void WriteDomainMesh(
  const otparam::SphereParameterizationResult& run, vtkPolyData* input, vtkPolyData* sphere)
{
  const otparam::CompactedMesh& surface = run.conformal.surface;
  sphere->SetPoints(MakePoints(run.composition.sphere));
  sphere->SetPolys(MakeTriangles(surface.mesh.triangles));
  CopyInputArrays(input, surface.originalPointIds, sphere);
  vtkPointData* pd = sphere->GetPointData();
  pd->AddArray(MakeVec3Array("Coordinates3D", surface.mesh.points));
  pd->AddArray(MakeVec3Array("AreaPreservingCoordinates", run.composition.sphere));
  pd->AddArray(MakeVec3Array("ConformalCoordinates", run.conformal.map.sphere));
  pd->AddArray(MakeOriginalPointIds(surface.originalPointIds));
  pd->SetTCoords(
    MakeVec2Array("SphericalTextureCoordinates", LongitudeLatitude(run.composition.sphere)));
  AddDistortionArrays(sphere->GetCellData(), run.figures);
}

// Port 0 for the sphere: the input surface with the sphere coordinates (NaN on points used by
// no triangle) and the per-triangle figures.
void WriteSurface(
  const otparam::SphereParameterizationResult& run, vtkPolyData* input, vtkPolyData* output)
{
  CopyTrianglesOf(input, output);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<otparam::Vec3> areaPreserving(input->GetNumberOfPoints(), { nan, nan, nan });
  std::vector<otparam::Vec3> conformal(areaPreserving);
  std::vector<otparam::Vec2> tcoords(areaPreserving.size(), { nan, nan });
  const std::vector<otparam::Vec2> lonLat = LongitudeLatitude(run.composition.sphere);
  const std::vector<std::int64_t>& ids = run.conformal.surface.originalPointIds;
  for (std::size_t v = 0; v < ids.size(); ++v)
  {
    areaPreserving[ids[v]] = run.composition.sphere[v];
    conformal[ids[v]] = run.conformal.map.sphere[v];
    tcoords[ids[v]] = lonLat[v];
  }
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(MakeVec3Array("AreaPreservingCoordinates", areaPreserving));
  pd->AddArray(MakeVec3Array("ConformalCoordinates", conformal));
  pd->SetTCoords(MakeVec2Array("SphericalTextureCoordinates", tcoords));
  AddDistortionArrays(output->GetCellData(), run.figures);
}

template <class Run>
void WriteHistogramsOf(const Run& run, int bins, vtkTable* histograms)
{
  const otparam::DistortionFigures& conformal = run.conformal.figures;
  AddHistogram(histograms, "ConformalAngleDistortion", conformal.angleDistortion, bins);
  AddHistogram(histograms, "AreaPreservingAngleDistortion", run.figures.angleDistortion, bins);
  AddHistogram(histograms, "ConformalLogAreaRatio", conformal.logAreaRatio, bins);
  AddHistogram(histograms, "AreaPreservingLogAreaRatio", run.figures.logAreaRatio, bins);
}

// Writes a finished run (either domain) to the three ports, the figures on both meshes.
template <class Run>
void WriteRun(const Run& run, int bins, vtkPolyData* input, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* domainMesh = vtkPolyData::GetData(outputVector, 1);
  WriteDomainMesh(run, input, domainMesh);
  WriteSurface(run, input, output);
  WriteHistogramsOf(run, bins, vtkTable::GetData(outputVector, 2));
  const std::vector<int> checkerboard = Checkerboard(run);
  AddCheckerboard(domainMesh->GetCellData(), checkerboard);
  AddCheckerboard(output->GetCellData(), checkerboard);
  vtkNew<vtkPolyData> figures;
  WriteFigures(run, figures);
  for (int a = 0; a < figures->GetFieldData()->GetNumberOfArrays(); ++a)
  {
    output->GetFieldData()->AddArray(figures->GetFieldData()->GetAbstractArray(a));
    domainMesh->GetFieldData()->AddArray(figures->GetFieldData()->GetAbstractArray(a));
  }
}
} // namespace

//------------------------------------------------------------------------------
vtkAreaPreservingParam::vtkAreaPreservingParam()
{
  this->SetNumberOfOutputPorts(3);
  const otparam::AreaPreservingOptions defaults;
  this->NumberOfSamples = static_cast<int>(defaults.sampling.numberOfSamples);
  this->Tolerance = defaults.transport.tolerance;
  this->MaximumNumberOfIterations = defaults.transport.maximumNumberOfIterations;
  this->AreaCorrection = defaults.composition.correctAreas;
  this->MaximumCorrectionSweeps = defaults.composition.maximumCorrectionSweeps;
}

//------------------------------------------------------------------------------
vtkAreaPreservingParam::~vtkAreaPreservingParam() = default;

//------------------------------------------------------------------------------
int vtkAreaPreservingParam::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkAreaPreservingParam::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 2 ? "vtkTable" : "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkAreaPreservingParam::Execute(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  // Own parameters first: a bad one should not cost a conformal map.
  const otparam::AreaPreservingOptions options = MakeOptions(this);
  std::string error = options.check();
  if (error.empty() && (this->Domain < AUTOMATIC || this->Domain > SPHERE))
  {
    std::ostringstream msg;
    msg << "Domain must be 0 (Automatic), 1 (Disk) or 2 (Sphere); got " << this->Domain << ".";
    error = msg.str();
  }
  if (error.empty() && (this->NumberOfHistogramBins < 1 || this->NumberOfHistogramBins > 100000))
  {
    std::ostringstream msg;
    msg << "NumberOfHistogramBins must be in [1, 100000]; got " << this->NumberOfHistogramBins
        << ".";
    error = msg.str();
  }
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  otparam::TriangleSoup soup;
  if (!this->ReadInputSurface(input, soup, "conformal map: "))
  {
    return 0;
  }

  // Automatic's checks of the mesh serve the pipeline it chooses (0.4 s at 1e6 points).
  otparam::AnalyzedInput analysis;
  otparam::AnalyzedInput* analyzed = this->Domain == AUTOMATIC ? &analysis : nullptr;
  const bool sphere = this->Domain == SPHERE ||
    (analyzed && otparam::chooseDomain(soup, this->FillHoles, analyzed) == otparam::Domain::Sphere);
  if (sphere)
  {
    const otparam::SphereParameterizationResult run =
      otparam::parameterizeSphere(soup, options, analyzed);
    this->SetProgressText(nullptr);
    if (!this->ReportStatus(run.status))
    {
      return 0;
    }
    WriteRun(run, this->NumberOfHistogramBins, input, outputVector);
    return 1;
  }
  const otparam::AreaPreservingResult run = otparam::parameterizeDisk(soup, options, analyzed);
  this->SetProgressText(nullptr);
  if (!this->ReportStatus(run.status))
  {
    return 0;
  }
  WriteRun(run, this->NumberOfHistogramBins, input, outputVector);
  return 1;
}

//------------------------------------------------------------------------------
void vtkAreaPreservingParam::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSamples: " << this->NumberOfSamples << "\n";
  os << indent << "SamplingMode: " << this->SamplingMode << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaximumNumberOfIterations: " << this->MaximumNumberOfIterations << "\n";
  os << indent << "CenterPointId: " << this->CenterPointId << "\n";
  os << indent << "AlignPointId: " << this->AlignPointId << "\n";
  os << indent << "Domain: " << this->Domain << "\n";
  os << indent << "FillHoles: " << this->FillHoles << "\n";
  os << indent << "AreaCorrection: " << this->AreaCorrection << "\n";
  os << indent << "MaximumCorrectionSweeps: " << this->MaximumCorrectionSweeps << "\n";
  os << indent << "ThoroughAreaCorrection: " << this->ThoroughAreaCorrection << "\n";
  os << indent << "NumberOfHistogramBins: " << this->NumberOfHistogramBins << "\n";
}
