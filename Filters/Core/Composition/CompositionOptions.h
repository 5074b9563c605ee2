// The options of the composition T^-1 o phi, the same for the disk (DiskComposition.h) and the
// sphere (SphereComposition.h).
#ifndef OTPARAM_COMPOSITION_COMPOSITIONOPTIONS_H
#define OTPARAM_COMPOSITION_COMPOSITIONOPTIONS_H

#include <cstddef>
#include <functional>
#include <vector>

namespace otparam
{

struct CompositionOptions
{
  bool correctAreas = true;
  int maximumCorrectionSweeps = 200;
  // Sweeps stop once one of them lowers the area-weighted mean |log area ratio| by less than
  // this fraction of its value (or moves no vertex); then at most 50 more sweeps move only
  // the vertices that still have a triangle off by more than 5%.
  double correctionRelativeDecrease = 0.01;
  // Each vertex's Gauss-Newton step is tried first at this multiple (then halved).
  double correctionOverrelaxation = 1.8;
  // The polishing goes on past its 50 sweeps while a triangle is still off by more than a
  // factor e (a knot the untangling left; AreaCorrection.h, KnotLogRatio).
  bool polishKnots = true;
  // On the disk, the per-vertex sweeps begin after a few sweeps at the samples' scale
  // (SampleScaleCorrection.h), which lower the final mean angle distortion.
  bool correctAtSampleScale = true;
  // The figures (mean |log area ratio| before and after the correction) speak of the surface's
  // first this many triangles, 0 = all: with holes filled, the input's own triangles come first
  // and the fill after them (the fill is corrected with the rest, but is not the user's).
  std::size_t measuredTriangles = 0;
  // The share of the domain each triangle's area is corrected towards (summing to 1); empty:
  // its share of the surface. A staged transport's stage aims at its clamped density's shares.
  std::vector<double> targetAreaShares;
  // The sphere's untangling also moves a vertex whose star no gnomonic chart at it holds (a
  // coarse mesh's long fan triangles) free of charts. Off for a staged transport's stages, whose
  // maps folded at double precision's end have such stars everywhere: moved, they broke a closed
  // finger's second stage (L / rho = 50).
  bool untangleWideStars = true;
  // On the sphere, where the untangling leaves triangles flipped and the start map (`conformal`)
  // has none, the correction starts from the start map: a map with no flip whose areas are
  // corrected, but which keeps the start's layout rather than following the transport. Measured
  // on coarse meshes whose long fan triangles the untangling cannot free (VTK's cone at
  // resolution 60: 10 triangles flipped, mean |log area ratio| 49 -> none, 0.054). Off for a
  // staged transport's stages, whose maps must follow their transports.
  bool startOverWhereTangled = true;
  // Called with the fraction done; returning false aborts.
  std::function<bool(double)> progress;
};

// The thorough correction: a gentler over-relaxation and per-vertex sweeps until they gain less
// than 0.25% of the mean. On every shared disk mesh the area distortion ends lower than with the
// defaults, and on all but hand_stein_810 (38.62 -> 39.47 degrees) and face_choi_bff_17k (24.15
// -> 24.22) the angle distortion too, for about twice the sweeps (hand_choi_53k: mean |log area
// ratio| 0.0119 -> 0.0104, mean angle distortion 44.67 -> 44.39 degrees; the sphere's brain
// 0.0024 -> 0.0019, 17.01 -> 16.75 degrees; docs/design.md, 2026-11-28).
inline void makeCorrectionThorough(CompositionOptions& options)
{
  options.correctionOverrelaxation = 1.5;
  options.correctionRelativeDecrease = 0.0025;
}

} // namespace otparam

#endif
