#include "vtkAreaPreservingParam.h"

#include "vtkAdaptiveDensitySampler.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkConformalDiskMap.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSemiDiscreteOTSolver.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"

#include "Composition/DiskComposition.h"
#include "OTParamAdapterUtilities.h"
#include "Mesh/DistortionMetrics.h"
#include "Mesh/SurfaceMesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAreaPreservingParam);

using namespace otparam_vtk;

namespace
{
// Forwards a stage's progress (mapped to a sub-range of the owner's), passes the owner's abort
// on, and collects the stage's errors and warnings, prefixed with the stage's name.
class StageObserver : public vtkCommand
{
public:
  static StageObserver* New() { return new StageObserver; }

  vtkAreaPreservingParam* Owner = nullptr;
  vtkAlgorithm* Stage = nullptr;
  std::string* Error = nullptr;
  std::vector<std::string>* Warnings = nullptr;
  const char* Name = "";
  double Start = 0.0, End = 1.0;

  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    if (event == vtkCommand::ProgressEvent)
    {
      const double fraction = *static_cast<double*>(callData);
      this->Owner->SetProgressText(this->Name);
      this->Owner->UpdateProgress(this->Start + (this->End - this->Start) * fraction);
      if (this->Owner->GetAbortExecute())
      {
        this->Stage->SetAbortExecute(1);
      }
      return;
    }
    // The message comes as "<class> (<address>): <text>": keep the text.
    std::string text = callData ? static_cast<const char*>(callData) : "";
    const size_t cut = text.find("): ");
    if (cut != std::string::npos)
    {
      text = text.substr(cut + 3);
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
    {
      text.pop_back();
    }
    if (event == vtkCommand::ErrorEvent)
    {
      if (this->Error->empty())
      {
        *this->Error = std::string(this->Name) + ": " + text;
      }
    }
    else if (event == vtkCommand::WarningEvent)
    {
      this->Warnings->push_back(std::string(this->Name) + ": " + text);
    }
  }
};

// Equal-width histogram of `values` over their range.
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

std::vector<double> ArrayValues(vtkDataArray* array)
{
  std::vector<double> values(array ? static_cast<size_t>(array->GetNumberOfTuples()) : 0);
  for (size_t i = 0; i < values.size(); ++i)
  {
    values[i] = array->GetComponent(static_cast<vtkIdType>(i), 0);
  }
  return values;
}

double FieldScalar(vtkDataObject* data, const char* name)
{
  vtkDataArray* array = data->GetFieldData()->GetArray(name);
  return array && array->GetNumberOfTuples() > 0 ? array->GetComponent(0, 0)
                                                 : std::numeric_limits<double>::quiet_NaN();
}
} // namespace

//------------------------------------------------------------------------------
vtkAreaPreservingParam::vtkAreaPreservingParam()
{
  this->SetNumberOfOutputPorts(3);
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
int vtkAreaPreservingParam::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  RequestWholeInputs(inputVector, 1);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkAreaPreservingParam::RunStage(
  vtkAlgorithm* stage, const char* name, double start, double end)
{
  vtkNew<StageObserver> observer;
  observer->Owner = this;
  observer->Stage = stage;
  observer->Error = &this->StageError;
  observer->Warnings = &this->StageWarnings;
  observer->Name = name;
  observer->Start = start;
  observer->End = end;
  for (unsigned long event :
    { vtkCommand::ProgressEvent, vtkCommand::ErrorEvent, vtkCommand::WarningEvent })
  {
    stage->AddObserver(event, observer);
  }
  // The stage's executive reports "returned failure" as an error of its own: the stage's
  // message, prefixed, is the one that counts, and ours reaches the user.
  vtkNew<vtkCallbackCommand> silence;
  stage->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, silence);
  stage->Update();
  stage->RemoveAllObservers();
  stage->GetExecutive()->RemoveAllObservers();
  for (const std::string& warning : this->StageWarnings)
  {
    // The composition drops zero-mass samples itself (DroppedSamples in the field data).
    if (warning.find("have Mass 0") == std::string::npos)
    {
      vtkWarningMacro(<< warning);
    }
  }
  this->StageWarnings.clear();
  return this->StageError.empty() && !this->GetAbortExecute() && !stage->GetAbortExecute();
}

//------------------------------------------------------------------------------
int vtkAreaPreservingParam::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto startTotal = std::chrono::steady_clock::now();
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* disk = vtkPolyData::GetData(outputVector, 1);
  vtkTable* histograms = vtkTable::GetData(outputVector, 2);
  output->Initialize();
  disk->Initialize();
  histograms->Initialize();
  if (IsOtherPiece(outputVector))
  {
    return 1;
  }

  // Own parameters first: a bad one should not cost a conformal map.
  if (this->NumberOfSamples < 3)
  {
    vtkErrorMacro("NumberOfSamples must be at least 3; got " << this->NumberOfSamples << ".");
    return 0;
  }
  if (this->SamplingMode < ADAPTIVE || this->SamplingMode > MESH_VERTICES)
  {
    vtkErrorMacro("SamplingMode must be 0 (Adaptive), 1 (Uniform) or 2 (MeshVertices); got "
      << this->SamplingMode << ".");
    return 0;
  }
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
  if (this->MaximumCorrectionSweeps < 0)
  {
    vtkErrorMacro(
      "MaximumCorrectionSweeps must be at least 0; got " << this->MaximumCorrectionSweeps << ".");
    return 0;
  }
  if (this->NumberOfHistogramBins < 1 || this->NumberOfHistogramBins > 100000)
  {
    vtkErrorMacro(
      "NumberOfHistogramBins must be in [1, 100000]; got " << this->NumberOfHistogramBins << ".");
    return 0;
  }
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  if (!input)
  {
    vtkErrorMacro("conformal map: the input surface is empty: it needs points and triangles.");
    return 0;
  }
  this->StageError.clear();

  // ---- The internal pipeline, on a shallow copy so that nothing reaches back to the input.
  vtkNew<vtkPolyData> surfaceCopy;
  surfaceCopy->ShallowCopy(input);
  auto stamp = std::chrono::steady_clock::now();
  vtkNew<vtkConformalDiskMap> conformalMap;
  conformalMap->SetInputData(surfaceCopy);
  conformalMap->SetCenterPointId(this->CenterPointId);
  conformalMap->SetAlignPointId(this->AlignPointId);
  const bool conformalDone = this->RunStage(conformalMap, "conformal map", 0.0, 0.15);
  const double secondsConformal = Seconds(stamp);

  stamp = std::chrono::steady_clock::now();
  vtkNew<vtkAdaptiveDensitySampler> sampler;
  vtkNew<vtkSemiDiscreteOTSolver> transport;
  bool sampled = false, transported = false;
  if (conformalDone)
  {
    sampler->SetInputConnection(conformalMap->GetOutputPort());
    // The exact per-triangle area ratio: masses are then exact surface areas.
    sampler->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "AreaDensity");
    sampler->SetNumberOfSamples(this->NumberOfSamples);
    sampler->SetSamplingMode(this->SamplingMode);
    sampled = this->RunStage(sampler, "sampling", 0.15, 0.4);
  }
  const double secondsSampling = Seconds(stamp);
  stamp = std::chrono::steady_clock::now();
  // Samples whose Voronoi cell integrates to 0 carry no mass: the transport is the same
  // without them, and the solver rejects zero masses. (A conformal factor is positive, so this
  // is a safety net: it caught cells ~1e-7 wide at a coarse hand's finger tips, density 1e10,
  // whose rounding-noise edges once made the integral 0.)
  vtkNew<vtkPolyData> massiveSamples;
  int droppedSamples = 0;
  if (sampled)
  {
    vtkPolyData* samples = sampler->GetOutput();
    vtkDataArray* mass = samples->GetPointData()->GetArray("Mass");
    vtkNew<vtkPoints> kept;
    kept->SetDataTypeToDouble();
    vtkNew<vtkDoubleArray> keptMass;
    keptMass->SetName("Mass");
    for (vtkIdType i = 0; mass && i < samples->GetNumberOfPoints(); ++i)
    {
      if (mass->GetComponent(i, 0) > 0.0)
      {
        kept->InsertNextPoint(samples->GetPoint(i));
        keptMass->InsertNextValue(mass->GetComponent(i, 0));
      }
    }
    droppedSamples = static_cast<int>(samples->GetNumberOfPoints() - kept->GetNumberOfPoints());
    massiveSamples->SetPoints(kept);
    massiveSamples->GetPointData()->AddArray(keptMass);
    transport->SetInputData(massiveSamples);
    transport->SetTolerance(this->Tolerance);
    transport->SetMaximumNumberOfIterations(this->MaximumNumberOfIterations);
    transported = this->RunStage(transport, "transport", 0.4, 0.8);
  }
  const double secondsTransport = Seconds(stamp);
  if (this->GetAbortExecute())
  {
    vtkWarningMacro("Aborted; the output is left empty.");
    return 1;
  }
  if (!transported)
  {
    vtkErrorMacro(<< (this->StageError.empty() ? std::string("a stage produced no output")
                                               : this->StageError));
    return 0;
  }

  // ---- Composition on the core's plain types.
  stamp = std::chrono::steady_clock::now();
  vtkPolyData* conformal = conformalMap->GetOutput();
  vtkPolyData* diracs = transport->GetOutput();
  vtkDataArray* coordinates3D = conformal->GetPointData()->GetArray("Coordinates3D");
  vtkDataArray* originalIds = conformal->GetPointData()->GetArray("vtkOriginalPointIds");
  vtkDataArray* centroids = diracs->GetPointData()->GetArray("Centroid");
  if (!coordinates3D || !originalIds || !centroids)
  {
    vtkErrorMacro("composition: a stage's output lacks Coordinates3D, vtkOriginalPointIds or "
                  "Centroid.");
    return 0;
  }
  const vtkIdType n = conformal->GetNumberOfPoints();
  otparam::SurfaceMesh surface;
  std::vector<otparam::Vec2> conformalUv(static_cast<size_t>(n));
  surface.points.resize(static_cast<size_t>(n));
  for (vtkIdType v = 0; v < n; ++v)
  {
    double p[3];
    coordinates3D->GetTuple(v, p);
    surface.points[v] = { p[0], p[1], p[2] };
    conformal->GetPoint(v, p);
    conformalUv[v] = { p[0], p[1] };
  }
  {
    vtkNew<vtkIdList> cell;
    vtkCellArray* polys = conformal->GetPolys();
    surface.triangles.reserve(static_cast<size_t>(polys->GetNumberOfCells()));
    for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
    {
      polys->GetCellAtId(c, cell);
      surface.triangles.push_back({ static_cast<int>(cell->GetId(0)),
        static_cast<int>(cell->GetId(1)), static_cast<int>(cell->GetId(2)) });
    }
  }
  const vtkIdType numberOfSamples = diracs->GetNumberOfPoints();
  std::vector<otparam::Vec2> samples(static_cast<size_t>(numberOfSamples)),
    images(static_cast<size_t>(numberOfSamples));
  for (vtkIdType i = 0; i < numberOfSamples; ++i)
  {
    double p[3], c[3];
    diracs->GetPoint(i, p);
    centroids->GetTuple(i, c);
    samples[i] = { p[0], p[1] };
    images[i] = { c[0], c[1] };
  }
  {
    // Samples on the circle: the middle of their cell's arc of the circle (port 1 of the
    // transport: clipped cells, arcs sampled, cell array DiracId).
    vtkPolyData* cells = transport->GetOutput(1);
    vtkDataArray* diracId = cells->GetCellData()->GetArray("DiracId");
    vtkNew<vtkIdList> ids;
    std::vector<otparam::Vec2> polygon;
    for (vtkIdType c = 0; diracId && c < cells->GetNumberOfCells(); ++c)
    {
      const auto i = static_cast<vtkIdType>(diracId->GetComponent(c, 0));
      if (i < 0 || i >= numberOfSamples ||
        std::abs(std::hypot(samples[i].x, samples[i].y) - 1.0) > 1e-9)
      {
        continue;
      }
      cells->GetCellPoints(c, ids);
      polygon.clear();
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        double p[3];
        cells->GetPoint(ids->GetId(k), p);
        polygon.push_back({ p[0], p[1] });
      }
      const otparam::Vec2 middle = otparam::boundaryArcMidpoint(polygon);
      if (std::isfinite(middle.x))
      {
        images[i] = middle;
      }
    }
  }
  std::vector<int> loop;
  otparam::CompositionResult composed;
  otparam::DistortionFigures figures;
  try
  {
    const std::string topology = otparam::checkDiskTopology(surface, loop);
    if (!topology.empty())
    {
      vtkErrorMacro("composition: the conformal image is not a disk: " << topology << ".");
      return 0;
    }
    otparam::CompositionOptions options;
    options.correctAreas = this->AreaCorrection && this->MaximumCorrectionSweeps > 0;
    options.maximumCorrectionSweeps = this->MaximumCorrectionSweeps;
    options.correctionRelativeDecrease = 0.01;
    this->SetProgressText("composition");
    options.progress = [this](double fraction)
    {
      this->UpdateProgress(0.8 + 0.19 * fraction);
      return !this->GetAbortExecute();
    };
    composed =
      otparam::composeWithInverseTransport(surface, conformalUv, loop, samples, images, options);
    if (composed.aborted || this->GetAbortExecute())
    {
      vtkWarningMacro("Aborted; the output is left empty.");
      return 1;
    }
    if (!composed.error.empty())
    {
      vtkErrorMacro("composition: " << composed.error << ".");
      return 0;
    }
    figures = otparam::measureDistortion(surface, composed.uv);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("composition: " << e.what());
    return 0;
  }
  const double secondsComposition = Seconds(stamp);
  if (figures.flippedTriangles > 0)
  {
    vtkWarningMacro(<< figures.flippedTriangles
                    << " triangle(s) are flipped in the disk: the untangling did not free them.");
  }
  if (FieldScalar(diracs, "Converged") != 1.0)
  {
    vtkWarningMacro("The transport did not converge (relative error "
      << FieldScalar(diracs, "RelativeError") << "); the map is approximate.");
  }

  // ---- Port 1: the flattened disk mesh.
  vtkNew<vtkPoints> diskPoints;
  diskPoints->SetDataTypeToDouble();
  diskPoints->SetNumberOfPoints(n);
  std::vector<double> apUv(2 * n), confUv(2 * n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    diskPoints->SetPoint(v, composed.uv[v].x, composed.uv[v].y, 0.0);
    apUv[2 * v] = composed.uv[v].x;
    apUv[2 * v + 1] = composed.uv[v].y;
    confUv[2 * v] = conformalUv[v].x;
    confUv[2 * v + 1] = conformalUv[v].y;
  }
  disk->SetPoints(diskPoints);
  disk->SetPolys(conformal->GetPolys());
  auto apArray = MakeDoubleArray("AreaPreservingCoordinates", apUv, 2);
  disk->GetPointData()->AddArray(coordinates3D);
  disk->GetPointData()->AddArray(MakeDoubleArray("ConformalCoordinates", confUv, 2));
  disk->GetPointData()->AddArray(originalIds);
  disk->GetPointData()->SetTCoords(apArray);
  auto logAreaRatio = MakeDoubleArray("LogAreaRatio", figures.logAreaRatio);
  auto angleDistortion = MakeDoubleArray("AngleDistortion", figures.angleDistortion);
  auto dilatation = MakeDoubleArray("QuasiConformalDilatation", figures.dilatation);
  disk->GetCellData()->AddArray(logAreaRatio);
  disk->GetCellData()->AddArray(angleDistortion);
  disk->GetCellData()->AddArray(dilatation);

  // ---- Port 0: the input surface with the coordinates (NaN on points used by no triangle).
  output->ShallowCopy(input);
  const vtkIdType inputPoints = input->GetNumberOfPoints();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> apIn(2 * inputPoints, nan), confIn(2 * inputPoints, nan);
  for (vtkIdType v = 0; v < n; ++v)
  {
    const auto id = static_cast<vtkIdType>(originalIds->GetComponent(v, 0));
    apIn[2 * id] = apUv[2 * v];
    apIn[2 * id + 1] = apUv[2 * v + 1];
    confIn[2 * id] = confUv[2 * v];
    confIn[2 * id + 1] = confUv[2 * v + 1];
  }
  auto apInput = MakeDoubleArray("AreaPreservingCoordinates", apIn, 2);
  output->GetPointData()->AddArray(apInput);
  output->GetPointData()->SetTCoords(apInput);
  output->GetPointData()->AddArray(MakeDoubleArray("ConformalCoordinates", confIn, 2));
  // The input's triangles are the conformal image's, in the same order.
  output->GetCellData()->AddArray(logAreaRatio);
  output->GetCellData()->AddArray(angleDistortion);
  output->GetCellData()->AddArray(dilatation);

  // ---- Port 2: the histograms (the paper's Fig. 5).
  const int bins = this->NumberOfHistogramBins;
  AddHistogram(histograms, "ConformalAngleDistortion",
    ArrayValues(conformal->GetCellData()->GetArray("AngleDistortion")), bins);
  AddHistogram(histograms, "AreaPreservingAngleDistortion", figures.angleDistortion, bins);
  AddHistogram(histograms, "ConformalLogAreaRatio",
    ArrayValues(conformal->GetCellData()->GetArray("LogAreaRatio")), bins);
  AddHistogram(histograms, "AreaPreservingLogAreaRatio", figures.logAreaRatio, bins);

  // ---- Field data, the same on the two meshes.
  vtkNew<vtkFieldData> fd;
  fd->AddArray(MakeIntScalar("Iterations", static_cast<int>(FieldScalar(diracs, "Iterations"))));
  fd->AddArray(MakeScalar("RelativeError", FieldScalar(diracs, "RelativeError")));
  fd->AddArray(MakeIntScalar("Converged", FieldScalar(diracs, "Converged") == 1.0 ? 1 : 0));
  fd->AddArray(MakeIntScalar("NumberOfSamples", static_cast<int>(numberOfSamples)));
  fd->AddArray(MakeIntScalar("DroppedSamples", droppedSamples));
  fd->AddArray(MakeScalar(
    "MassCoefficientOfVariation", FieldScalar(sampler->GetOutput(), "MassCoefficientOfVariation")));
  fd->AddArray(MakeIntScalar("FlippedTriangles", static_cast<int>(figures.flippedTriangles)));
  fd->AddArray(MakeScalar("MeanAbsLogAreaRatio", figures.meanAbsLogAreaRatio));
  fd->AddArray(MakeScalar("MaximumAbsLogAreaRatio", figures.maximumAbsLogAreaRatio));
  fd->AddArray(MakeScalar("MeanAngleDistortion", figures.meanAngleDistortionDegrees));
  fd->AddArray(MakeScalar("MaximumAngleDistortion", figures.maximumAngleDistortionDegrees));
  fd->AddArray(MakeScalar("MeanQuasiConformalDilatation", figures.meanDilatation));
  for (const char* name : { "MeanAbsLogAreaRatio", "MaximumAbsLogAreaRatio", "MeanAngleDistortion",
         "MaximumAngleDistortion", "MeanQuasiConformalDilatation" })
  {
    fd->AddArray(
      MakeScalar(("Conformal" + std::string(name)).c_str(), FieldScalar(conformal, name)));
  }
  fd->AddArray(
    MakeScalar("InterpolatedMeanAbsLogAreaRatio", composed.meanAbsLogAreaRatioInterpolated));
  fd->AddArray(MakeIntScalar(
    "InterpolatedFlippedTriangles", static_cast<int>(composed.flippedAfterInterpolation)));
  fd->AddArray(MakeIntScalar("UntangledVertices", static_cast<int>(composed.untangledVertices)));
  fd->AddArray(MakeIntScalar("CorrectionSweeps", composed.correctionSweeps));
  fd->AddArray(MakeScalar("SecondsConformalMap", secondsConformal));
  fd->AddArray(MakeScalar("SecondsSampling", secondsSampling));
  fd->AddArray(MakeScalar("SecondsTransport", secondsTransport));
  fd->AddArray(MakeScalar("SecondsComposition", secondsComposition));
  fd->AddArray(MakeScalar("SecondsTotal", Seconds(startTotal)));
  for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
  {
    output->GetFieldData()->AddArray(fd->GetAbstractArray(a));
    disk->GetFieldData()->AddArray(fd->GetAbstractArray(a));
  }
  this->UpdateProgress(1.0);
  this->SetProgressText(nullptr);
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
  os << indent << "AreaCorrection: " << this->AreaCorrection << "\n";
  os << indent << "MaximumCorrectionSweeps: " << this->MaximumCorrectionSweeps << "\n";
  os << indent << "NumberOfHistogramBins: " << this->NumberOfHistogramBins << "\n";
}
