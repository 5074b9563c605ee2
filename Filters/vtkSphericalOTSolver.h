/**
 * @class   vtkSphericalOTSolver
 * @brief   Semi-discrete optimal transport from the uniform unit sphere to weighted Diracs on it.
 *
 * The sphere's counterpart of vtkSemiDiscreteOTSolver (sphere.md). The source is the uniform
 * measure on the unit sphere S^2 (total 4 pi), the cost c(x, y) = -log <x, y>. With heights
 * h_i > 0, cell W_i(h) is the set of directions x with <x, y_i> / h_i >= <x, y_j> / h_j for all
 * j: the radial projection onto S^2 of facet i of the polytope Q(h) = {x : <x, y_i> <= h_i},
 * bounded by great-circle arcs. Q(h) is the polar dual of the convex hull of the points
 * y_i / h_i. The filter finds the log-heights psi_i = log h_i such that every cell has the area
 * of its Dirac's mass (damped Newton method, Kitagawa-Merigot-Thibert step rule, started from
 * the spherical Voronoi diagram h_i = 1). The work is done by the VTK-free OTParam core
 * (Core/Transport/SphericalOT.h); this class converts data and reports the core's checks.
 *
 * Input port 0 (required), "Diracs": any vtkPointSet (typically vtkAdaptiveDensitySampler's
 * output on the sphere). Only its points are used; they must lie on the unit sphere (|y| = 1
 * to 1e-6; they are normalized), be pairwise distinct, at least 4 and not all in one closed
 * hemisphere (else no transport exists: Alexandrov's condition). A numeric one-component point
 * array `Mass` with positive values is required; masses are rescaled to sum to 4 pi.
 *
 * Outputs (all vtkPolyData, all arrays double unless stated):
 * - Port 0, "Diracs": the Dirac points (normalized) with the triangles of the dual convex hull
 *   (the spherical weighted Delaunay triangulation; 2 n - 4 triangles, counter-clockwise seen
 *   from outside). Point arrays: the input's point arrays, with `Mass` replaced by the
 *   rescaled target masses; `Height` (psi_i = log h_i, gauge fixed by mean 0); `CellMass`
 *   (area of the cell, as the solver reached it); `Centroid` (3 components: the centroid of
 *   the cell pushed onto the sphere, i.e. where the Dirac's mass comes from). Field data as
 *   vtkSemiDiscreteOTSolver: `Iterations` (int), `RelativeError`
 *   (max_i |CellMass_i - Mass_i| / Mass_i), `Converged` (int, 1 when RelativeError <=
 *   Tolerance), `GradientNormHistory`, `StepLengthHistory` (one value per Newton iteration),
 *   `SourceMass` (4 pi), `SecondsTriangulation`, `SecondsIntegration`, `SecondsAssembly`,
 *   `SecondsSolve`, `SecondsOutput`, `SecondsTotal`, `StopReason` (string); and
 *   `LargestTransportDegrees` (the largest angle, in degrees, between a Dirac and a point of
 *   its cell: near 90 the masses nearly fail Alexandrov's condition).
 * - Port 1, "Power Diagram": the spherical power diagram, one polygon per non-empty cell whose
 *   points lie on the sphere (great-circle arcs sampled with at most MaximumArcAngle radians
 *   per segment), counter-clockwise seen from outside. Cell arrays `DiracId` (int), `Mass` and
 *   `CellMass` of that Dirac.
 * - Port 2, "Polytope": the polytope Q(h), the vertices of its facets (one per dual triangle)
 *   and one polygon face per Dirac (counter-clockwise seen from outside). Cell array `DiracId`
 *   (int).
 * - Port 3, "Convex Hull": the convex hull of the points y_i / h_i (the polar dual of Q(h)):
 *   one point per Dirac with the dual triangles of port 0. Point array `DiracId` (int).
 *
 * Bad input (no points; `Mass` missing, non-numeric, NaN, zero or negative; non-finite points,
 * points off the unit sphere, duplicate points, fewer than 4 points, all points in one closed
 * hemisphere; Tolerance not positive and finite; MaximumNumberOfIterations < 1;
 * MaximumArcAngle outside (0, 1]) is reported with vtkErrorMacro naming the problem and the
 * offending point ids; RequestData then returns 0 and every output is empty. The input is
 * never modified. Reaching MaximumNumberOfIterations before Tolerance gives a full output with
 * `Converged` = 0 and a warning saying how far it got (and, when cells reach beyond 80 degrees,
 * that the masses nearly fail Alexandrov's condition). Progress is reported once per Newton
 * iteration and AbortExecute is honoured.
 */

#ifndef vtkSphericalOTSolver_h
#define vtkSphericalOTSolver_h

#include "OTParamFiltersModule.h" // for export macro
#include "vtkOTParamAlgorithm.h"

class OTPARAMFILTERS_EXPORT vtkSphericalOTSolver : public vtkOTParamAlgorithm
{
public:
  static vtkSphericalOTSolver* New();
  vtkTypeMacro(vtkSphericalOTSolver, vtkOTParamAlgorithm);
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
   * Largest angle (radians) spanned by one segment of a sampled great-circle arc in the
   * "Power Diagram" output (display only: areas are computed with exact arcs). Must be in
   * (0, 1]. Default 0.05.
   */
  vtkSetMacro(MaximumArcAngle, double);
  vtkGetMacro(MaximumArcAngle, double);
  ///@}

protected:
  vtkSphericalOTSolver();
  ~vtkSphericalOTSolver() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector) override;

  // The core's OTOptions defaults and DefaultMaximumArcAngle, set by the constructor.
  double Tolerance;
  int MaximumNumberOfIterations;
  double MaximumArcAngle;

private:
  vtkSphericalOTSolver(const vtkSphericalOTSolver&) = delete;
  void operator=(const vtkSphericalOTSolver&) = delete;
};

#endif
