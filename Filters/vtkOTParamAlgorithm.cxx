#include "vtkOTParamAlgorithm.h"

#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "Common/Status.h"
#include "Mesh/SurfaceMesh.h"
#include "OTParamConvert.h"
#include "Pipeline/DiskStages.h"

#include <exception>
#include <memory>
#include <new>
#include <sstream>

//------------------------------------------------------------------------------
vtkOTParamAlgorithm::vtkOTParamAlgorithm() = default;

//------------------------------------------------------------------------------
vtkOTParamAlgorithm::~vtkOTParamAlgorithm() = default;

//------------------------------------------------------------------------------
int vtkOTParamAlgorithm::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  for (int port = 0; port < this->GetNumberOfInputPorts(); ++port)
  {
    for (int c = 0; c < inputVector[port]->GetNumberOfInformationObjects(); ++c)
    {
      vtkInformation* inInfo = inputVector[port]->GetInformationObject(c);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkOTParamAlgorithm::ClearOutputs(vtkInformationVector* outputVector)
{
  for (int port = 0; port < outputVector->GetNumberOfInformationObjects(); ++port)
  {
    if (vtkDataObject* output = vtkDataObject::GetData(outputVector, port))
    {
      output->Initialize();
    }
  }
}

//------------------------------------------------------------------------------
int vtkOTParamAlgorithm::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->ClearOutputs(outputVector);
  this->Aborted = false;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) &&
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) > 0)
  {
    return 1; // piece 0 holds the whole result
  }
  int done = 0;
  try
  {
    done = this->Execute(inputVector, outputVector);
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("Out of memory: the input is too large for this machine's memory.");
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("The computation failed: " << e.what());
  }
  if (this->Aborted || this->GetAbortExecute())
  {
    this->ClearOutputs(outputVector);
    vtkWarningMacro("Aborted; the output is left empty.");
    return 1;
  }
  if (!done)
  {
    this->ClearOutputs(outputVector);
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkOTParamAlgorithm::ReportStatus(const otparam::Status& status, const char* prefix)
{
  if (status.aborted)
  {
    this->Aborted = true;
    return false;
  }
  if (!status.error.empty())
  {
    vtkErrorMacro(<< prefix << status.error);
    return false;
  }
  for (const std::string& warning : status.warnings)
  {
    vtkWarningMacro(<< prefix << warning);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkOTParamAlgorithm::ReadInputSurface(
  vtkPolyData* input, otparam::TriangleSoup& soup, const char* prefix)
{
  std::string ignored;
  const std::string error = otparam_vtk::ReadTriangleSoup(input, "input surface", soup, ignored);
  if (!error.empty())
  {
    vtkErrorMacro(<< prefix << error);
    return false;
  }
  if (!ignored.empty())
  {
    vtkWarningMacro(<< ignored);
  }
  return true;
}

//------------------------------------------------------------------------------
std::function<bool(double)> vtkOTParamAlgorithm::ProgressCallback(double start, double end)
{
  return [this, start, end](double fraction)
  {
    this->UpdateProgress(start + (end - start) * std::min(1.0, std::max(0.0, fraction)));
    return !this->GetAbortExecute();
  };
}

//------------------------------------------------------------------------------
std::function<bool(int, double)> vtkOTParamAlgorithm::NewtonProgressCallback(
  const otparam::OTOptions& options)
{
  // Shared: the core may copy the callback, and the fraction must only grow.
  auto fraction = std::make_shared<otparam::NewtonProgress>(options);
  return [this, fraction](int iteration, double relativeError)
  {
    std::ostringstream text;
    text << "Newton iteration " << iteration << ", relative error " << relativeError;
    this->SetProgressText(text.str().c_str());
    this->UpdateProgress((*fraction)(iteration, relativeError));
    return !this->GetAbortExecute();
  };
}

//------------------------------------------------------------------------------
void vtkOTParamAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
