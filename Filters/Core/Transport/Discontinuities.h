// The discontinuity (singularity) set of a semi-discrete transport map onto a target whose
// support is not convex: the power edges between cells whose Diracs are not neighbours in the
// support (method.md, complicated supports).
#ifndef OTPARAM_TRANSPORT_DISCONTINUITIES_H
#define OTPARAM_TRANSPORT_DISCONTINUITIES_H

#include "Transport/SemiDiscreteOT.h"

#include <vector>

namespace otparam
{

// True when the segment from diracs[i] to diracs[j] lies in the union of the support triangles
// (triangles over the Dirac ids; a Dirac used by none is outside). Exact predicates.
class SupportTriangulation
{
public:
  SupportTriangulation(const std::vector<Vec2>& diracs, const std::vector<Triangle>& triangles);
  bool segmentInside(int i, int j) const;

private:
  int neighbourAcross(int t, int a, int b) const; // the triangle sharing edge ab with t, or -1
  std::vector<Vec2> Points;
  std::vector<Triangle> Triangles;        // counter-clockwise
  std::vector<std::vector<int>> Incident; // triangles around each point
};

// Power edges (inside the source) between Diracs i, j whose segment leaves the support: the map
// jumps there by |y_i - y_j|.
std::vector<PowerDiagramGeometry::Edge> discontinuityEdges(const PowerDiagramGeometry& geometry,
  const std::vector<Vec2>& diracs, const std::vector<Triangle>& support);

} // namespace otparam

#endif
