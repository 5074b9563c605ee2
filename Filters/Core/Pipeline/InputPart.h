// The input's own part of a conformal stage whose surface was closed by a hole fill, for
// either domain (keepInputPart in DiskStages.h and SphereStages.h): the input's points and
// triangles come first, the fill after them.
#ifndef OTPARAM_PIPELINE_INPUTPART_H
#define OTPARAM_PIPELINE_INPUTPART_H

#include "Mesh/HoleFilling.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace otparam
{

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
