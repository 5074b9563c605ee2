// Helpers shared by the vtkXxx adapters of OTParam (private to the module, not wrapped).
#ifndef OTParamAdapterUtilities_h
#define OTParamAdapterUtilities_h

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>
#include <vector>

namespace otparam_vtk
{

// "3, 17, 42" or "3, 17, ... (25 in total)": enough to find the culprits without flooding the log.
template <typename Id>
std::string FormatIds(const std::vector<Id>& ids)
{
  constexpr std::size_t shown = 10;
  std::ostringstream out;
  for (std::size_t k = 0; k < ids.size() && k < shown; ++k)
  {
    out << (k ? ", " : "") << ids[k];
  }
  if (ids.size() > shown)
  {
    out << ", ... (" << ids.size() << " in total)";
  }
  return out.str();
}

inline vtkSmartPointer<vtkDoubleArray> MakeDoubleArray(
  const char* name, const std::vector<double>& values, int components = 1)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

inline vtkSmartPointer<vtkDoubleArray> MakeScalar(const char* name, double value)
{
  return MakeDoubleArray(name, std::vector<double>{ value });
}

inline vtkSmartPointer<vtkIntArray> MakeIntScalar(const char* name, int value)
{
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name);
  array->InsertNextValue(value);
  return array;
}

inline vtkSmartPointer<vtkStringArray> MakeString(const char* name, const std::string& value)
{
  auto array = vtkSmartPointer<vtkStringArray>::New();
  array->SetName(name);
  array->InsertNextValue(value);
  return array;
}

inline double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The algorithms are global (a map of the whole surface, a transport between whole measures):
// every input port asks for all of its data, never a piece.
inline void RequestWholeInputs(vtkInformationVector** inputVector, int numberOfPorts)
{
  for (int port = 0; port < numberOfPorts; ++port)
  {
    for (int c = 0; c < inputVector[port]->GetNumberOfInformationObjects(); ++c)
    {
      vtkInformation* inInfo = inputVector[port]->GetInformationObject(c);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
  }
}

// In parallel runs piece 0 holds the whole result; other pieces stay empty so that it is not
// duplicated.
inline bool IsOtherPiece(vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  return outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) &&
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) > 0;
}

} // namespace otparam_vtk

#endif
