// Helpers shared by the vtkXxx adapters of OTParam (private to the module, not wrapped).
#ifndef OTParamAdapterUtilities_h
#define OTParamAdapterUtilities_h

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkSmartPointer.h"
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

} // namespace otparam_vtk

#endif
