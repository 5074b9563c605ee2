/**
 * @class   vtkAdaptiveDensitySampler
 * @brief   Samples of a density on a planar domain or the unit sphere whose masses are nearly
 *          equal.
 *
 * Turns a density on a planar triangulated domain (for the paper: the area distortion
 * `AreaDensity` of vtkConformalDiskMap's disk image) into Dirac samples for
 * vtkSemiDiscreteOTSolver. Three modes:
 * - Adaptive (default): the paper's self-adaptive sampling (Algorithm 2), a Delaunay refinement
 *   graded by the density: every triangle gets its circumcentre inserted until no triangle has
 *   an angle below MinimumAngle or a circumradius whose length measured by the density is
 *   above a threshold eps. eps follows from NumberOfSamples (the count reached is within 10%
 *   of it). The samples then carry nearly equal masses.
 * - Uniform: the same refinement with a constant grading, i.e. the conventional uniform
 *   samples (their masses follow the density).
 * - MeshVertices: the input mesh's own points and triangles.
 * The work is done by the VTK-free OTParam core (Filters/Core/Sampling/PlanarSampler.h); this class
 * converts data and validates input.
 *
 * Input: a vtkPolyData made of triangles only, in the plane z = 0, without overlapping
 * triangles, carrying the density as a numeric
 * one-component array chosen with SetInputArrayToProcess(0, 0, 0, association, name); the
 * default is the point array `AreaDensity`. A point array (FIELD_ASSOCIATION_POINTS) is
 * interpolated linearly over each triangle; a cell array (FIELD_ASSOCIATION_CELLS) is one
 * constant value per triangle. The density must be finite and non-negative, not all zero. When
 * the domain's boundary lies on the unit circle, the domain is the exact unit disk (boundary
 * samples on the circle, total mass pi). Points used by no triangle are ignored (a warning
 * says so). The domain is the density's support: triangles where the density is identically
 * zero are left out. It may be non-convex, have holes and several components (target supports
 * of discontinuous transport maps); every boundary loop is then sampled by nu-length like the
 * disk's boundary, and the refinement runs on CGAL's constrained Delaunay mesher (boundary
 * samples on a curved boundary given as a polygon are put back on it afterwards, which can
 * cost a few degrees of MinimumAngle). Boundary loops must not touch each other.
 *
 * Output: the samples as points (x, y, 0) with the triangles of their Delaunay triangulation
 * (the input triangles in MeshVertices mode), no vertex cells. Point array `Mass` (double):
 * the density integrated over each sample's Voronoi cell clipped to the domain, normalized to
 * sum to the domain's source mass (pi for the unit disk, else its area), so that the output
 * connects directly to vtkSemiDiscreteOTSolver's port 0. Field data: `NumberOfSamples` (int),
 * `MassCoefficientOfVariation` (std / mean of Mass), `MinimumAngle` (degrees, smallest angle
 * of the output triangles), `Epsilon` (the length threshold eps used), `SourceMass`,
 * `RefinementRuns` (int, refinements run to reach NumberOfSamples), `Capped` (int, 1 when
 * the refinement stopped at MaximumNumberOfSamples, with a warning), `SecondsRefinement`,
 * `SecondsMasses`, `SecondsTotal`.
 *
 * Sphere domain: when every point used by a triangle lies on the unit sphere (to 1e-6) and not
 * all of them in the plane z = 0, e.g. vtkConformalSphereMap's output, the domain is the whole
 * unit sphere (sphere.md step 2; core: Filters/Core/Sampling/SphericalSampler.h). The mesh
 * must then be closed, counter-clockwise seen from outside and cover the sphere once, with
 * its points on the sphere to 1e-9. The density is one positive value per triangle: a cell
 * array as it is (select vtkConformalSphereMap's exact cell array with
 * SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "AreaDensity")), a
 * point array (the default `AreaDensity`) averaged over each triangle's three corners. The
 * same three modes refine the spherical Delaunay triangulation (the samples' convex hull,
 * circumcentres projected onto the sphere, sizes measured with the density along the sphere);
 * MeshVertices keeps the mesh's points and triangles. Output: the samples on the unit sphere
 * with the triangles of their spherical Delaunay triangulation, counter-clockwise seen from
 * outside; `Mass` is the density integrated exactly over each sample's spherical Voronoi cell,
 * normalized to sum to 4 pi (`SourceMass`), so that the output connects directly to
 * vtkSphericalOTSolver. The field data are those of the plane, plus `DensityIntegral` (the
 * integral of the density over the sphere before normalization) and `MassSumRelativeError`
 * (how far the cells' integrals summed from it). A planar domain is never taken for a sphere
 * domain: its behaviour is as described above.
 *
 * Bad input (an empty domain; the density array missing, non-numeric, with several components,
 * NaN, infinite, negative or all zero; a domain that is neither planar nor on the unit sphere,
 * not made of triangles, with overlapping triangles or boundary loops that touch; a sphere
 * domain that is not closed, not counter-clockwise seen from outside or has a triangle of
 * density 0; NumberOfSamples < 3 or above
 * MaximumNumberOfSamples; MinimumAngle outside (0, 30]; SamplingMode or SizeRule out of range)
 * is reported with vtkErrorMacro naming the problem and the offending ids; RequestData then
 * returns 0 and the output is empty. The input is never modified. Progress is reported and
 * AbortExecute honoured (an aborted run leaves the output empty, with a warning).
 */
#ifndef vtkAdaptiveDensitySampler_h
#define vtkAdaptiveDensitySampler_h

#include "OTParamFiltersModule.h" // for export macro
#include "vtkOTParamAlgorithm.h"

#include <string> // for ReadInput

class OTPARAMFILTERS_EXPORT vtkAdaptiveDensitySampler : public vtkOTParamAlgorithm
{
public:
  static vtkAdaptiveDensitySampler* New();
  vtkTypeMacro(vtkAdaptiveDensitySampler, vtkOTParamAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SizeRules
  {
    SQRT_DENSITY = 0,
    DENSITY = 1
  };

  ///@{
  /**
   * Approximate number of samples (Adaptive and Uniform modes): the threshold eps is chosen so
   * that the refinement reaches this count within 10%. Must be at least 3 and at most
   * MaximumNumberOfSamples (checked in every mode). Default 1000.
   */
  vtkSetMacro(NumberOfSamples, int);
  vtkGetMacro(NumberOfSamples, int);
  ///@}

  ///@{
  /**
   * 0 (ADAPTIVE, default): Delaunay refinement graded by the density (the paper's
   * Algorithm 2); 1 (UNIFORM): the same with a constant grading; 2 (MESH_VERTICES): the input
   * mesh's own points.
   */
  vtkSetMacro(SamplingMode, int);
  vtkGetMacro(SamplingMode, int);
  void SetSamplingModeToAdaptive() { this->SetSamplingMode(ADAPTIVE); }
  void SetSamplingModeToUniform() { this->SetSamplingMode(UNIFORM); }
  void SetSamplingModeToMeshVertices() { this->SetSamplingMode(MESH_VERTICES); }
  ///@}

  ///@{
  /**
   * Smallest angle (degrees) the refinement aims at: triangles with a smaller angle get their
   * circumcentre inserted. Must be in (0, 30]. Default 30. The angle actually reached is
   * reported as the field data `MinimumAngle`.
   */
  vtkSetMacro(MinimumAngle, double);
  vtkGetMacro(MinimumAngle, double);
  ///@}

  ///@{
  /**
   * Hard cap on the number of samples of one refinement; when it is hit, the refinement stops
   * there, the output says `Capped` = 1 and a warning is issued. Default 10000000.
   */
  vtkSetMacro(MaximumNumberOfSamples, int);
  vtkGetMacro(MaximumNumberOfSamples, int);
  ///@}

  ///@{
  /**
   * How the density g measures a length R (the circumradius of a triangle): 0 (SQRT_DENSITY,
   * default) R * sqrt(g), which gives every triangle a mass of about eps^2 since g is an area
   * density; 1 (DENSITY) the paper's literal R * g.
   */
  vtkSetMacro(SizeRule, int);
  vtkGetMacro(SizeRule, int);
  void SetSizeRuleToSqrtDensity() { this->SetSizeRule(SQRT_DENSITY); }
  void SetSizeRuleToDensity() { this->SetSizeRule(DENSITY); }
  ///@}

protected:
  vtkAdaptiveDensitySampler();
  ~vtkAdaptiveDensitySampler() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector) override;

  // NumberOfSamples, MinimumAngle and MaximumNumberOfSamples: the core's SamplerOptions
  // defaults, set by the constructor.
  int NumberOfSamples;
  int SamplingMode = ADAPTIVE;
  double MinimumAngle;
  int MaximumNumberOfSamples;
  int SizeRule = SQRT_DENSITY;

private:
  // The domain and density read and checked from the input (defined in the .cxx).
  struct Input;
  std::string ReadInput(vtkPolyData* input, Input& read);

  vtkAdaptiveDensitySampler(const vtkAdaptiveDensitySampler&) = delete;
  void operator=(const vtkAdaptiveDensitySampler&) = delete;
};

#endif
