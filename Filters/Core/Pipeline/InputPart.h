// What the conformal stages of both domains do alike with their input: its checks of the mesh
// itself, and its own part once its surface was closed by a hole fill (keepInputPart in
// DiskStages.h and SphereStages.h): the input's points and triangles come first, the fill after
// them.
#ifndef OTPARAM_PIPELINE_INPUTPART_H
#define OTPARAM_PIPELINE_INPUTPART_H

#include "Mesh/HoleFilling.h"
#include "Mesh/SurfaceMesh.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace otparam
{

// The input compacted into `compacted` and analyzed into `topology` once, for either domain:
// "" or what is wrong with the mesh itself (ids, coordinates, degenerate triangles, edges),
// which no domain could take; each domain judges the topology after this.
inline std::string analyzeInput(
  const TriangleSoup& soup, CompactedMesh& compacted, SurfaceTopology& topology)
{
  std::string error = compactMesh(soup.points, soup.triangles, compacted);
  if (error.empty())
  {
    error = analyzeSurface(compacted.mesh, topology, &compacted.originalPointIds);
  }
  return error.empty() ? error : "The input is not a valid triangle surface: " + error + ".";
}

// analyzeInput's results kept to be handed on: chooseDomain's analysis serves the pipeline it
// chooses, whose conformal stage would otherwise check the mesh again (0.4 s at 1.09M points).
struct AnalyzedInput
{
  CompactedMesh compacted;
  SurfaceTopology topology;
  std::string error; // analyzeInput's
};

// analyzeInput's results: `analyzed`'s, moved out of it (it must be the same soup's), or made
// here when it is null.
inline std::string takeOrAnalyzeInput(const TriangleSoup& soup, AnalyzedInput* analyzed,
  CompactedMesh& compacted, SurfaceTopology& topology)
{
  if (!analyzed)
  {
    return analyzeInput(soup, compacted, topology);
  }
  compacted = std::move(analyzed->compacted);
  topology = std::move(analyzed->topology);
  return analyzed->error;
}

// Takes a hole fill into the stage: the filled mesh as its surface (fill points have original
// id -1), the fill's counts for the figures.
template <class Stage>
void adoptHoleFill(Stage& stage, FilledSurface&& filled)
{
  stage.filledHoles = filled.filledHoles;
  stage.fillAreaFraction = filled.fillAreaFraction;
  stage.surface.mesh = std::move(filled.mesh);
  stage.surface.originalPointIds.resize(stage.surface.mesh.points.size(), -1);
}

// Cuts the stage's surface, `map` and `perPointMaps` to the input's points and triangles, then
// `remeasure()`s the stage's figures and densities; nothing when there is no fill.
template <class Stage, class Point, class Remeasure>
void dropHoleFill(Stage& stage, std::vector<Point>& map,
  std::vector<std::vector<Point>*> perPointMaps, const Remeasure& remeasure)
{
  if (stage.surface.mesh.points.size() == stage.inputPoints &&
    stage.surface.mesh.triangles.size() == stage.inputTriangles)
  {
    return;
  }
  stage.surface.mesh.points.resize(stage.inputPoints);
  stage.surface.mesh.triangles.resize(stage.inputTriangles);
  stage.surface.originalPointIds.resize(stage.inputPoints);
  perPointMaps.push_back(&map);
  for (std::vector<Point>* perPoint : perPointMaps)
  {
    perPoint->resize(std::min(perPoint->size(), stage.inputPoints));
  }
  remeasure();
}

} // namespace otparam

#endif
