/**
 * @class   vtkOTParamAlgorithm
 * @brief   Base class of the OTParam filters: the part every adapter shares.
 *
 * In the spirit of TTK's ttkAlgorithm: the algorithms are global (a map of a whole surface, a
 * transport between whole measures), so every input port asks for all of its data and, in
 * parallel runs, piece 0 does the work while other pieces stay empty. RequestData empties
 * every output, calls Execute inside a try/catch, and empties them again when Execute fails,
 * throws or is aborted: a failed run never leaves a partial output. Subclasses implement
 * Execute (convert in, call the core, convert out) and report the core's Status with
 * ReportStatus.
 */
#ifndef vtkOTParamAlgorithm_h
#define vtkOTParamAlgorithm_h

#include "OTParamFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#ifndef __VTK_WRAP__
#include <functional> // for the progress callbacks
namespace otparam
{
struct OTOptions;
struct Status;
struct TriangleSoup;
}
class vtkPolyData;
#endif

class OTPARAMFILTERS_EXPORT vtkOTParamAlgorithm : public vtkPolyDataAlgorithm
{
public:
  vtkTypeMacro(vtkOTParamAlgorithm, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The SamplingMode values of the filters that sample (vtkAdaptiveDensitySampler,
   * vtkAreaPreservingParam), as the core's otparam::SamplingMode.
   */
  enum SamplingModes
  {
    ADAPTIVE = 0,
    UNIFORM = 1,
    MESH_VERTICES = 2
  };

protected:
  vtkOTParamAlgorithm();
  ~vtkOTParamAlgorithm() override;

  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * The filter's work, on emptied outputs: 1 on success, 0 after an error message.
   */
  virtual int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector) = 0;

#ifndef __VTK_WRAP__
  /**
   * Warnings of the core as vtkWarningMacro, its error as vtkErrorMacro (each prefixed by
   * `prefix`); true when the stage succeeded and was not aborted.
   */
  bool ReportStatus(const otparam::Status& status, const char* prefix = "");

  /**
   * The input surface's triangles (OTParamConvert's ReadTriangleSoup): what is wrong with it as
   * vtkErrorMacro (prefixed by `prefix`), the cells it leaves out as vtkWarningMacro; false
   * after an error.
   */
  bool ReadInputSurface(vtkPolyData* input, otparam::TriangleSoup& soup, const char* prefix = "");

  /**
   * A core progress callback: fraction f of the stage is reported as start + (end - start) f,
   * and the answer is whether to go on (AbortExecute not set).
   */
  std::function<bool(double)> ProgressCallback(double start = 0.0, double end = 0.95);

  /**
   * A transport solve's progress callback (OTOptions::progress): the progress text names the
   * Newton iteration and its relative error, the fraction is otparam::NewtonProgress's. Clear
   * the text with SetProgressText(nullptr) once the solve is over.
   */
  std::function<bool(int, double)> NewtonProgressCallback(const otparam::OTOptions& options);
#endif

  // Set by ReportStatus when the core stopped on AbortExecute: the outputs are then emptied and
  // a warning says so.
  bool Aborted = false;

private:
  vtkOTParamAlgorithm(const vtkOTParamAlgorithm&) = delete;
  void operator=(const vtkOTParamAlgorithm&) = delete;

  void ClearOutputs(vtkInformationVector* outputVector);
};

#endif
