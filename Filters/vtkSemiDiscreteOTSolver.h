/**
 * @class   vtkSemiDiscreteOTSolver
 * @brief   Semi-discrete optimal transport from a planar source measure to weighted Diracs.
 *
 * Finds the heights h_i such that every cell of the power diagram of the Diracs y_i (weights
 * |y_i|^2 - 2 h_i), clipped to the source domain, carries exactly the mass of its Dirac. The
 * transport map sends each clipped cell to its Dirac; it is the gradient of the convex Brenier
 * potential u_h(x) = max_i (<x, y_i> - h_i). The solver is a damped Newton method
 * (Kitagawa-Merigot-Thibert step rule) started from the Voronoi diagram; the work is done by
 * the VTK-free OTParam core, this class converts data and validates input.
 *
 * Input port 0 (required), "Diracs": any vtkPointSet (typically the vtkPolyData output of
 * vtkAdaptiveDensitySampler). Only its points are used, projected to z = 0; it must carry a
 * numeric one-component point array `Mass` with positive values. Masses are rescaled so that
 * they sum to the source's total mass. Points must be finite and pairwise distinct. Diracs
 * outside the source domain are allowed.
 *
 * Input port 1 (optional), "SourceDomain": a vtkPolyData made of triangles that covers a convex
 * region of the plane z = 0, with an optional point array `Density` (positive, interpreted as
 * piecewise linear over the triangles; uniform density 1 when absent). When port 1 is not
 * connected or holds no points, the source is the exact unit disk with uniform density (total
 * mass pi; cells are clipped by the circle exactly).
 *
 * Outputs (all vtkPolyData in the plane z = 0 unless stated, all arrays double unless stated):
 * - Port 0, "Diracs": the Dirac points with the triangles of the weighted Delaunay
 *   triangulation (dual of the power diagram). Point arrays: the input's point arrays, with
 *   `Mass` replaced by the rescaled target masses; `Height` (h_i, rounded to double from the
 *   solver's ~128 bits: cells recomputed from it can miss their masses by ~1e-9 .. 1e-6
 *   relative where cells are tiny); `CellMass` (source measure of the clipped power cell, as the
 *   solver reached it); `Centroid` (3 components, z = 0: density-weighted barycentre of
 *   the clipped cell, i.e. where the Dirac's mass comes from). Field data: `Iterations` (int,
 *   Newton iterations done), `RelativeError` (max_i |CellMass_i - Mass_i| / Mass_i),
 *   `Converged` (int, 1 when RelativeError <= Tolerance), `GradientNormHistory` (Euclidean
 *   norm of CellMass - Mass before each Newton step) and `StepLengthHistory` (damping factor
 *   accepted at each step), one value per iteration; `SourceMass` (total mass of the source);
 *   seconds spent per stage: `SecondsTriangulation` (power diagrams), `SecondsIntegration`
 *   (cell integrals), `SecondsAssembly` (Hessian), `SecondsSolve` (linear solves),
 *   `SecondsOutput` (building these outputs) and `SecondsTotal`; `StopReason` (string).
 * - Port 1, "Power Diagram": one polygon per non-empty clipped power cell (arcs of the disk
 *   boundary sampled with at most MaximumArcAngle radians per segment). Cell arrays `DiracId`
 *   (int, index of the Dirac), `Mass` and `CellMass` of that Dirac.
 * - Port 2, "Brenier Potential": the graph of u_h over the source domain, z = u_h(x): each
 *   clipped cell fan-triangulated at height <x, y_i> - h_i. Cell array `DiracId` (int).
 * - Port 3, "Legendre Dual": the graph of the dual potential, the points (y_i, h_i) with the
 *   weighted Delaunay triangles. Point array `DiracId` (int).
 * - Port 4, "Discontinuities": the discontinuity (singularity) set of the transport map, one
 *   line per power edge (clipped to the source) between cells i, j whose Diracs are not
 *   neighbours in the target's support. The support is the union of the input's triangles
 *   (the sampler's triangulation of it); y_i and y_j are neighbours when the segment between
 *   them stays in that union (an exact straight walk through the triangles). So a jump is
 *   reported across a hole, between components, or across a concavity, never for Diracs of a
 *   convex support. Cell arrays `JumpLength` (|y_i - y_j|) and `DiracIds` (int, 2 components:
 *   i, j). Empty when the input has no triangles (the support is then unknown).
 *
 * Bad input (no points; `Mass` missing, non-numeric, NaN, zero or negative; non-finite or
 * duplicate points; a non-planar, non-triangle or non-convex source domain; a `Density` that
 * is not positive and finite; Tolerance <= 0; MaximumNumberOfIterations < 1) is reported with
 * vtkErrorMacro naming the problem and the offending point ids; RequestData then returns 0 and
 * every output is empty. The input is never modified. Reaching MaximumNumberOfIterations before
 * Tolerance gives a full output with `Converged` = 0 and a warning saying how far it got.
 * Progress is reported once per Newton iteration and AbortExecute is honoured.
 */

#ifndef vtkSemiDiscreteOTSolver_h
#define vtkSemiDiscreteOTSolver_h

#include "OTParamFiltersModule.h" // for export macro
#include "vtkOTParamAlgorithm.h"

class OTPARAMFILTERS_EXPORT vtkSemiDiscreteOTSolver : public vtkOTParamAlgorithm
{
public:
  static vtkSemiDiscreteOTSolver* New();
  vtkTypeMacro(vtkSemiDiscreteOTSolver, vtkOTParamAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Largest relative cell-mass error max_i |CellMass_i - Mass_i| / Mass_i accepted as
   * converged. Must be positive and finite. Default 1e-10.
   */
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * Largest number of Newton iterations. Must be at least 1. Default 200.
   */
  vtkSetMacro(MaximumNumberOfIterations, int);
  vtkGetMacro(MaximumNumberOfIterations, int);
  ///@}

  ///@{
  /**
   * Largest angle (radians) spanned by one segment of a sampled circular arc in the
   * "Power Diagram" and "Brenier Potential" outputs (display only: masses are computed with
   * exact arcs). Must be in (0, 1]. Default 0.05.
   */
  vtkSetMacro(MaximumArcAngle, double);
  vtkGetMacro(MaximumArcAngle, double);
  ///@}

  ///@{
  /**
   * Convenience: connect or set the optional source domain (input port 1).
   */
  void SetSourceDomainConnection(vtkAlgorithmOutput* output);
  void SetSourceDomainData(vtkDataObject* domain);
  ///@}

protected:
  vtkSemiDiscreteOTSolver();
  ~vtkSemiDiscreteOTSolver() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector) override;

  // The core's OTOptions defaults and DefaultMaximumArcAngle, set by the constructor.
  double Tolerance;
  int MaximumNumberOfIterations;
  double MaximumArcAngle;

private:
  vtkSemiDiscreteOTSolver(const vtkSemiDiscreteOTSolver&) = delete;
  void operator=(const vtkSemiDiscreteOTSolver&) = delete;
};

#endif
