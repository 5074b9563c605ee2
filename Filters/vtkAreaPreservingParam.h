/**
 * @class   vtkAreaPreservingParam
 * @brief   Area-preserving parameterization of a surface onto the unit disk or the unit sphere.
 *
 * The whole method of OTParam as one filter: vtkConformalDiskMap -> vtkAdaptiveDensitySampler
 * (on the conformal image's exact per-triangle `AreaDensity`) -> vtkSemiDiscreteOTSolver (the
 * unit disk with uniform density as source) -> composition T^-1 o phi. The stages are chained
 * once, in the core (Filters/Core/Pipeline/AreaPreservingPipeline.h, which the command line
 * and the benchmarks call too); each is the one its own filter runs. The composition
 * (Filters/Core/Composition/DiskComposition.h) maps every sample to the centroid of its power cell,
 * every mesh vertex by piecewise-linear interpolation over the samples' regular triangulation
 * under the transport's weights, the dual of its power diagram (boundary vertices exactly on
 * the circle), untangles any flipped triangle, and then, with
 * AreaCorrection on (the default), moves vertices so that each triangle gets its surface area
 * fraction, which removes what the interpolation between a finite number of samples leaves. Both
 * figures, before and after the correction, are in the field data.
 *
 * Input: a triangle surface of genus 0: disk-like (one boundary loop, or several with
 * FillHoles) for the disk, closed (or with small holes and FillHoles) for the sphere (Domain).
 *
 * Domain Sphere (the default Automatic picks it for a closed surface): the same chain on the
 * unit sphere (../shared/docs/sphere.md): vtkConformalSphereMap (Moebius-balanced) ->
 * vtkAdaptiveDensitySampler on the sphere -> vtkSphericalOTSolver (uniform sphere as source)
 * -> composition (each sample to its cell's centroid on the sphere, mesh points by
 * interpolation over the samples' spherical Delaunay triangulation, untangling; no area
 * correction). `AreaPreservingCoordinates` and `ConformalCoordinates` then have 3 components
 * (points on the unit sphere), the texture coordinates `SphericalTextureCoordinates` are
 * longitude / latitude scaled to [0, 1], output port 1 is the sphere mesh, and the field data
 * names are those of the disk (`Domain` tells which: 1 disk, 2 sphere).
 *
 * Output port 0: the input surface (3D points and arrays unchanged) with texture coordinates =
 * the area-preserving disk coordinates, also as point array `AreaPreservingCoordinates`
 * (2 components), point array `ConformalCoordinates` (2 components), cell arrays
 * `LogAreaRatio` (log of disk area / surface area, both normalized to pi), `AngleDistortion`
 * (mean |log corner-angle ratio| per triangle) and `QuasiConformalDilatation`. Points used by
 * no triangle get NaN coordinates. Field data: `Iterations`, `RelativeError`, `Converged` (of
 * the transport), `NumberOfSamples`, `MassCoefficientOfVariation`, `FlippedTriangles`,
 * `MeanAbsLogAreaRatio`, `MaximumAbsLogAreaRatio`, `MeanAngleDistortion`,
 * `MaximumAngleDistortion` (degrees), `MeanQuasiConformalDilatation`, the same figures of the
 * conformal map prefixed `Conformal` (e.g. `ConformalMeanAbsLogAreaRatio`), `DroppedSamples`
 * (samples whose cell integrated to 0, left out of the transport), the composition's
 * `InterpolatedMeanAbsLogAreaRatio`, `InterpolatedFlippedTriangles`, `UntangledVertices`,
 * `CorrectionSweeps`, `FilledHoles` and `FillAreaFraction` (see FillHoles: the holes closed
 * for the computation and the fill's share of the surface area, hence of the disk; the other
 * figures are those of the input's own triangles), and `SecondsConformalMap`, `SecondsSampling`,
 * `SecondsTransport`, `SecondsComposition`, `SecondsTotal`.
 *
 * Output port 1: the flattened area-preserving disk mesh: points (u, v, 0), the same triangles
 * and cell arrays, the input's point and cell arrays (normals left out: they would shade the
 * disk as the surface), point arrays `Coordinates3D`, `ConformalCoordinates`,
 * `vtkOriginalPointIds`.
 *
 * Output port 2: a vtkTable of histograms, NumberOfHistogramBins rows, for ParaView's bar
 * chart view: for each of `ConformalAngleDistortion`, `AreaPreservingAngleDistortion`,
 * `ConformalLogAreaRatio`, `AreaPreservingLogAreaRatio` a column `<name>` (number of
 * triangles in the bin) and a column `<name>BinCenter`.
 *
 * Bad input is rejected by the stage that finds it, with that stage's message prefixed by its
 * name ("conformal map: ...", "sampling: ...", "transport: ..."); own parameters are checked
 * first. RequestData then returns 0 and the outputs are empty; the input is never modified.
 * Progress covers the four stages (the progress text names the running one); AbortExecute
 * stops the running stage.
 */
#ifndef vtkAreaPreservingParam_h
#define vtkAreaPreservingParam_h

#include "OTParamFiltersModule.h" // for export macro
#include "vtkOTParamAlgorithm.h"

class OTPARAMFILTERS_EXPORT vtkAreaPreservingParam : public vtkOTParamAlgorithm
{
public:
  static vtkAreaPreservingParam* New();
  vtkTypeMacro(vtkAreaPreservingParam, vtkOTParamAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Approximate number of Dirac samples of the conformal factor (vtkAdaptiveDensitySampler's
   * NumberOfSamples). 0 (the default): automatic, 5000 or one sample per 50 input points,
   * whichever is more (a surface of 1M points needs ~20000 for the area error of a small one);
   * the count used is the field data NumberOfSamples. More than 4 times both the point count
   * and 5000 is warned about: the map is computed at the points and gains little from more.
   */
  vtkSetMacro(NumberOfSamples, int);
  vtkGetMacro(NumberOfSamples, int);
  ///@}

  ///@{
  /**
   * 0 = Adaptive (default, the paper's Algorithm 2), 1 = Uniform, 2 = MeshVertices
   * (vtkAdaptiveDensitySampler's SamplingMode).
   */
  vtkSetMacro(SamplingMode, int);
  vtkGetMacro(SamplingMode, int);
  void SetSamplingModeToAdaptive() { this->SetSamplingMode(ADAPTIVE); }
  void SetSamplingModeToUniform() { this->SetSamplingMode(UNIFORM); }
  void SetSamplingModeToMeshVertices() { this->SetSamplingMode(MESH_VERTICES); }
  ///@}

  ///@{
  /**
   * Largest relative cell-mass error the transport accepts (vtkSemiDiscreteOTSolver's
   * Tolerance). Default 1e-10.
   */
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * Newton iterations allowed to the transport. Default 200.
   */
  vtkSetMacro(MaximumNumberOfIterations, int);
  vtkGetMacro(MaximumNumberOfIterations, int);
  ///@}

  ///@{
  /**
   * The conformal map's normalization (vtkConformalDiskMap): the interior point sent to the
   * origin and the boundary point sent to the positive u axis; -1 (default) = automatic. The
   * transport keeps the centre at the origin only approximately; the alignment ray is kept
   * for radially symmetric surfaces.
   */
  vtkSetMacro(CenterPointId, vtkIdType);
  vtkGetMacro(CenterPointId, vtkIdType);
  vtkSetMacro(AlignPointId, vtkIdType);
  vtkGetMacro(AlignPointId, vtkIdType);
  ///@}

  ///@{
  /**
   * A genus-0 surface with several boundary loops (a scan with holes): on (default), the
   * longest loop (by surface length) becomes the disk's boundary and the others are closed
   * for the computation with CGAL's hole filling (triangulate, refine, fair); the fill is
   * dropped from the outputs, which have exactly the input's referenced points and
   * triangles. On the sphere (see Domain) every loop is closed the same way. Off: such a
   * surface is refused.
   */
  vtkSetMacro(FillHoles, bool);
  vtkGetMacro(FillHoles, bool);
  vtkBooleanMacro(FillHoles, bool);
  ///@}

  ///@{
  /**
   * Where the surface is mapped: AUTOMATIC (default: the sphere for a closed surface, and with
   * FillHoles for a closed scan whose holes are all small, the largest covering at most 1% of
   * the surface as a round disk of its length; the disk otherwise), DISK (a warning when the
   * boundary loop is that small: the disk map squeezes the whole surface through it), or SPHERE
   * (a closed surface, or with FillHoles one whose holes cover at most 10%).
   */
  enum DomainType
  {
    AUTOMATIC = 0,
    DISK = 1,
    SPHERE = 2
  };
  vtkSetMacro(Domain, int);
  vtkGetMacro(Domain, int);
  void SetDomainToAutomatic() { this->SetDomain(AUTOMATIC); }
  void SetDomainToDisk() { this->SetDomain(DISK); }
  void SetDomainToSphere() { this->SetDomain(SPHERE); }
  ///@}

  ///@{
  /**
   * Move vertices after the interpolation so that every triangle gets its surface area
   * fraction (see the class description). Default on.
   */
  vtkSetMacro(AreaCorrection, bool);
  vtkGetMacro(AreaCorrection, bool);
  vtkBooleanMacro(AreaCorrection, bool);
  ///@}

  ///@{
  /**
   * Most Gauss-Seidel sweeps of the area correction. Default 200 (the correction usually stops
   * earlier, when a sweep lowers the mean |log area ratio| by less than 1%).
   */
  vtkSetMacro(MaximumCorrectionSweeps, int);
  vtkGetMacro(MaximumCorrectionSweeps, int);
  ///@}

  ///@{
  /**
   * A thorough area correction: a gentler over-relaxation and about twice the sweeps. On every
   * shared mesh the area distortion ends lower than with the default correction, and on all
   * but hand_stein_810 (38.9 -> 39.3 degrees) the angle distortion too (hand_choi_53k: mean |log
   * area ratio| 0.0132 -> 0.0110, mean angle distortion 44.80 -> 44.60 degrees), for about twice
   * the correction's time (0.22 -> 0.39 s at 53k points). Default off.
   */
  vtkSetMacro(ThoroughAreaCorrection, bool);
  vtkGetMacro(ThoroughAreaCorrection, bool);
  vtkBooleanMacro(ThoroughAreaCorrection, bool);
  ///@}

  ///@{
  /**
   * Bins of each histogram on output port 2. Default 50.
   */
  vtkSetMacro(NumberOfHistogramBins, int);
  vtkGetMacro(NumberOfHistogramBins, int);
  ///@}

protected:
  vtkAreaPreservingParam();
  ~vtkAreaPreservingParam() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector) override;

  // Defaults of the core's AreaPreservingOptions, set by the constructor.
  int NumberOfSamples;
  int SamplingMode = ADAPTIVE;
  double Tolerance;
  int MaximumNumberOfIterations;
  int Domain = AUTOMATIC;
  vtkIdType CenterPointId = -1;
  vtkIdType AlignPointId = -1;
  bool FillHoles = true;
  bool AreaCorrection;
  int MaximumCorrectionSweeps;
  bool ThoroughAreaCorrection = false;
  int NumberOfHistogramBins = 50;

private:
  vtkAreaPreservingParam(const vtkAreaPreservingParam&) = delete;
  void operator=(const vtkAreaPreservingParam&) = delete;
};

#endif
