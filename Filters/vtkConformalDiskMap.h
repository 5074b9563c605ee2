/**
 * @class   vtkConformalDiskMap
 * @brief   Conformal (Riemann) map of a disk-like triangle surface onto the unit disk.
 *
 * Maps a triangle surface of genus 0 with exactly one boundary loop conformally onto the unit
 * disk, with every boundary point exactly on the unit circle. The map is the discrete harmonic
 * (cotangent) extension of boundary angles chosen to minimize the conformal energy: a
 * boundary-first-flattening start refined by Dirichlet-to-Neumann-preconditioned descent (see
 * Filters/Core/Conformal/ConformalDiskMap.cxx for the method and why). "Ears" (boundary points on a
 * single triangle) are handled without manual cleaning. The work is done by the VTK-free
 * OTParam core; this class converts data and validates input.
 *
 * Input: a vtkPolyData made of triangles only (apply vtkTriangleFilter to polygons or strips;
 * vertices and lines are rejected). Points used by no triangle are left out of the output.
 *
 * Output: the same triangles, in the same order, with points (u, v, 0) in the unit disk. Output
 * point i is input point `vtkOriginalPointIds`[i] (the identity unless the input had unreferenced
 * points). Point arrays: the input's point arrays but normals; `Coordinates3D` (the input points);
 * `AreaDensity` (surface area element over disk area element after scaling the surface to total
 * area pi, per point: area of the surface triangles around the point over that of their disk
 * images); texture coordinates `ConformalCoordinates` = (u, v); `vtkOriginalPointIds`. Cell arrays:
 * the input's cell arrays but normals; `AreaDensity` (the exact ratio per triangle, which is what
 * vtkAdaptiveDensitySampler integrates); `AngleDistortion` (mean |log corner-angle ratio|);
 * `QuasiConformalDilatation` (sigma_max / sigma_min); `LogAreaRatio` (log of disk area fraction
 * over surface area fraction). Field data: `MeanAngleDistortion`, `MaximumAngleDistortion`
 * (degrees, mean and largest |disk angle - surface angle| over all corners),
 * `MeanQuasiConformalDilatation` (area-weighted), `MaximumQuasiConformalDilatation`,
 * `FlippedTriangles`, `MeanAbsLogAreaRatio`, `MaximumAbsLogAreaRatio`,
 * `MaximumBoundaryRadiusError`, `Iterations`, `ConformalEnergy`, `ClippedEars`,
 * `FoldedWithMeshLaplacian` and `IntrinsicLaplacian` (int: when the mesh's own cotangent
 * Laplacian folds triangles, which its negative weights across obtuse triangles allow, the
 * map is computed again with the Laplacian of the intrinsic Delaunay triangulation, which
 * cannot fold, and kept if it folds fewer), `CenterPointId`, `AlignPointId` (input point ids
 * actually used; -1 when the automatic centre is a point of a hole fill), `FilledHoles`,
 * `FillAreaFraction` (see FillHoles), `SecondsFactorization`, `SecondsIterations`, `SecondsTotal`.
 *
 * Bad input (no triangles, non-triangle cells, NaN coordinates, zero-area triangles,
 * non-manifold edges or vertices, inconsistent orientation, several components, no boundary
 * loop, several with FillHoles off, genus > 0, CenterPointId / AlignPointId out of range or on the
 * wrong side of the boundary, absurd Tolerance or MaximumNumberOfIterations) is reported with
 * vtkErrorMacro naming the problem and where; the output is then empty and the input untouched.
 * Progress is reported and AbortExecute honoured.
 */
#ifndef vtkConformalDiskMap_h
#define vtkConformalDiskMap_h

#include "OTParamFiltersModule.h" // for export macro
#include "vtkOTParamAlgorithm.h"

class OTPARAMFILTERS_EXPORT vtkConformalDiskMap : public vtkOTParamAlgorithm
{
public:
  static vtkConformalDiskMap* New();
  vtkTypeMacro(vtkConformalDiskMap, vtkOTParamAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Input point id of an interior vertex sent to the disk's centre. -1 (default): the interior
   * vertex nearest to the surface's area barycentre in the disk (the Moebius normalization
   * that puts the centre of mass of the surface area at the origin), which balances the area
   * distortion (a vertex "farthest from the boundary" would be a finger tip on a hand).
   */
  vtkSetMacro(CenterPointId, vtkIdType);
  vtkGetMacro(CenterPointId, vtkIdType);
  ///@}

  ///@{
  /**
   * Input point id of a boundary vertex sent to (1, 0). -1 (default): the boundary vertex with
   * the lowest point id.
   */
  vtkSetMacro(AlignPointId, vtkIdType);
  vtkGetMacro(AlignPointId, vtkIdType);
  ///@}

  ///@{
  /**
   * A genus-0 surface with several boundary loops (a scan with holes): on (default), the
   * longest loop (by surface length) becomes the disk's boundary and the others are closed
   * for the computation with CGAL's hole filling (triangulate, refine, fair); the fill is
   * dropped from the outputs, which have exactly the input's referenced points and
   * triangles. Off: such a surface is refused.
   */
  vtkSetMacro(FillHoles, bool);
  vtkGetMacro(FillHoles, bool);
  vtkBooleanMacro(FillHoles, bool);
  ///@}

  ///@{
  /**
   * The iteration on the boundary angles stops when no angle moves by more than Tolerance
   * radians. Must be positive. Default 1e-6.
   */
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * Largest number of boundary-angle iterations (0: the boundary-first-flattening start
   * only). Default 100.
   */
  vtkSetMacro(MaximumNumberOfIterations, int);
  vtkGetMacro(MaximumNumberOfIterations, int);
  ///@}

protected:
  vtkConformalDiskMap();
  ~vtkConformalDiskMap() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector) override;

  vtkIdType CenterPointId = -1;
  vtkIdType AlignPointId = -1;
  bool FillHoles = true;
  // The core's ConformalDiskMapOptions defaults, set by the constructor.
  double Tolerance;
  int MaximumNumberOfIterations;

private:
  vtkConformalDiskMap(const vtkConformalDiskMap&) = delete;
  void operator=(const vtkConformalDiskMap&) = delete;
};

#endif
