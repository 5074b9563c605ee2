/**
 * @class   vtkConformalSphereMap
 * @brief   Conformal map of a closed genus-0 triangle surface onto the unit sphere.
 *
 * Maps a closed triangle surface of genus 0 conformally onto the unit sphere, Moebius-balanced
 * so that the surface area pushed to the sphere has its centre of mass at the origin (which
 * fixes the map up to a rotation; sphere.md step 1). The map is two linear (cotangent)
 * stereographic passes, north then south around a puncture triangle, followed by a Newton
 * balancing of the Moebius freedom (see Filters/Core/Conformal/ConformalSphereMap.cxx for the
 * method and why). The work is done by the VTK-free OTParam core; this class converts data.
 *
 * Input: a vtkPolyData made of triangles only (apply vtkTriangleFilter to polygons or strips;
 * vertices and lines are rejected), closed (or with small holes, see FillHoles), connected, of
 * genus 0. Points used by no triangle are left out of the output.
 *
 * Output: the same triangles, in the same order, with points on the unit sphere, every
 * triangle counter-clockwise seen from outside (an inward-oriented input is mapped to the
 * mirror image, which is still conformal; field data `Mirrored` says so). Output point i is
 * input point `vtkOriginalPointIds`[i] (the identity unless the input had unreferenced points).
 * Point arrays: the input's point arrays but normals; `Coordinates3D` (the input points);
 * `AreaDensity`
 * (surface area element over sphere area element after scaling the surface to total area
 * 4 pi, per point: area of the surface triangles around the point over that of their spherical
 * images); `vtkOriginalPointIds`. Cell arrays: the input's cell arrays but normals;
 * `AreaDensity` (the exact
 * ratio per triangle, surface area over spherical triangle area: its integral over the sphere
 * is 4 pi; select it in vtkAdaptiveDensitySampler for the exact density); `AngleDistortion`,
 * `QuasiConformalDilatation`, `LogAreaRatio` (as vtkConformalDiskMap's, against the chordal
 * triangles and spherical areas). Field data: `MeanAngleDistortion`, `MaximumAngleDistortion`
 * (degrees, over all corners, chordal image angles, as param_metrics.py --sphere scores them),
 * `MeanQuasiConformalDilatation`, `MaximumQuasiConformalDilatation`, `FlippedTriangles`,
 * `MeanAbsLogAreaRatio`, `MaximumAbsLogAreaRatio`, `MaximumRadiusError` (largest ||p| - 1|),
 * `BalanceResidual` (|centre of mass of the pushed area| / total area), `BalanceIterations`,
 * `PunctureTriangleId` (the triangle actually used), `FixedPoints`, `Mirrored`, `FilledHoles`,
 * `FillAreaFraction`,
 * `FlippedWithMeshLaplacian` and `IntrinsicLaplacian` (int: when the mesh's own cotangent
 * Laplacian flips triangles, the map is computed again with the intrinsic Delaunay Laplacian
 * and kept if it flips fewer), `SecondsFactorization`, `SecondsSolve`, `SecondsBalance`,
 * `SecondsTotal`.
 *
 * Bad input (no triangles, non-triangle cells, NaN coordinates, zero-area triangles,
 * non-manifold edges or vertices, inconsistent orientation, several components, a boundary
 * (with FillHoles: holes larger than 10%),
 * genus > 0, PunctureTriangleId out of range, absurd BalanceTolerance or
 * MaximumBalanceIterations) is reported with vtkErrorMacro naming the problem and where; the
 * output is then empty and the input untouched. Progress is reported and AbortExecute honoured.
 */
#ifndef vtkConformalSphereMap_h
#define vtkConformalSphereMap_h

#include "OTParamFiltersModule.h" // for export macro
#include "vtkOTParamAlgorithm.h"

class OTPARAMFILTERS_EXPORT vtkConformalSphereMap : public vtkOTParamAlgorithm
{
public:
  static vtkConformalSphereMap* New();
  vtkTypeMacro(vtkConformalSphereMap, vtkOTParamAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Input triangle (cell id) cut out for the first stereographic pass; -1 (default): the most
   * nearly equilateral triangle. The balanced map does not depend on it beyond rounding and a
   * rotation.
   */
  vtkSetMacro(PunctureTriangleId, vtkIdType);
  vtkGetMacro(PunctureTriangleId, vtkIdType);
  ///@}

  ///@{
  /**
   * The Moebius balancing stops when |centre of mass of the pushed area| / total area is at
   * most this. Must be positive. Default 1e-10.
   */
  vtkSetMacro(BalanceTolerance, double);
  vtkGetMacro(BalanceTolerance, double);
  ///@}

  ///@{
  /**
   * Largest number of Newton steps of the Moebius balancing (0: no balancing). Default 100.
   */
  vtkSetMacro(MaximumBalanceIterations, int);
  vtkGetMacro(MaximumBalanceIterations, int);
  ///@}

  ///@{
  /**
   * A closed scan with holes (a connected genus-0 surface with boundary loops, the largest
   * covering at most 10% of it as a round disk of its length): on (default), every hole is
   * closed for the computation with CGAL's hole filling (triangulate, refine, fair) and the
   * fill is dropped from the output, which has exactly the input's referenced points and
   * triangles (field data `FilledHoles`, `FillAreaFraction`: the fill's share of the surface
   * area, hence of the sphere). Off: such a surface is refused.
   */
  vtkSetMacro(FillHoles, bool);
  vtkGetMacro(FillHoles, bool);
  vtkBooleanMacro(FillHoles, bool);
  ///@}

protected:
  vtkConformalSphereMap();
  ~vtkConformalSphereMap() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector) override;

  vtkIdType PunctureTriangleId = -1;
  // The core's ConformalSphereMapOptions defaults, set by the constructor.
  double BalanceTolerance;
  int MaximumBalanceIterations;
  bool FillHoles = true;

private:
  vtkConformalSphereMap(const vtkConformalSphereMap&) = delete;
  void operator=(const vtkConformalSphereMap&) = delete;
};

#endif
