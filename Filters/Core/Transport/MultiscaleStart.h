// Start heights for the semi-discrete OT solver from a coarser problem (Mérigot's multiscale
// idea), and the repair that gives every hidden Dirac a cell again.
#ifndef OTPARAM_TRANSPORT_MULTISCALESTART_H
#define OTPARAM_TRANSPORT_MULTISCALESTART_H

#include "Common/Geometry.h"
#include "Transport/PlanarPowerDiagram.h"
#include "Transport/PlanarSource.h"

#include <vector>

namespace otparam
{

// Below this many Diracs the coarse problem costs more than it saves.
constexpr int MultiscaleMinimumDiracs = 20000;
// Largest spread of the Diracs' spacing (90th / 10th percentile of Delaunay edge lengths) for
// which the coarse-to-fine start is tried.
constexpr double MaximumSpacingSpread = 8.0;

// The stencil over which a coarse solution's dual potential is averaged to give fine heights
// (plane: translates; sphere: rotations): its centre (weight 1), an inner and an outer ring at
// half and all of StencilRadiusInSpacings median coarse Delaunay edges, with these weights per
// sixth of a ring. Fine iterations were flat from 1 to 2 coarse spacings.
constexpr double StencilRadiusInSpacings = 1.3;
constexpr double StencilInnerWeight = 0.8;
constexpr double StencilOuterWeight = 0.4;
// Share of the Voronoi diagram's potential mixed in, curved everywhere.
constexpr double StencilVoronoiShare = 1e-4;

// A random sixth of 0..n-1 (fixed seed: runs are reproducible), sorted: the coarse Diracs.
std::vector<int> randomSixth(int n);

// The median of the coarse Delaunay edge lengths (the stencil's scale), or 0 when their spread
// (90th / 10th percentile) exceeds MaximumSpacingSpread.
double stencilSpacing(std::vector<double> edgeLengths);

// Heights for the Diracs y_i with masses nu (summing to the source's mass) from the solution of
// a coarse problem: a sixth of the Diracs and their hull, each carrying the masses of the
// Diracs nearest to it, solved by solveSemiDiscreteOT (itself coarse-to-fine while large
// enough). The fine heights sample a smoothed dual potential of the coarse solution, a convex
// function, so that no Dirac is hidden. Unit-disk source only. Returns false, leaving h alone,
// when the Diracs' spacing varies too much or the coarse problem could not be solved.
bool coarseToFineHeights(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& h);

// The sphere's twin: log-heights psi for unit Diracs y_i with masses nu (summing to 4 pi) from
// a coarse problem solved by solveSphericalOT; the fine heights sample a smoothed support
// function of the coarse polytope Q. Returns false, leaving psi alone, under the same conditions.
bool sphericalCoarseToFineLogHeights(
  const std::vector<Vec3>& diracs, const std::vector<double>& nu, std::vector<Height>& psi);

// Lowers every hidden Dirac just below the lower hull of the lifted points (y_j, h_j), by as
// much as gives its cell about its mass nu_i, until none is hidden (at most maxRounds rounds:
// a lowered Dirac can hide a neighbour). Leaves diagram built at the final heights and returns
// the number of Diracs still hidden.
int unhideDiracs(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& h, PowerDiagram& diagram, int maxRounds = 30);

// Lowers every Dirac whose cell misses the unit disk (cellMass 0, not hidden) to just below
// the largest value of <x, y_i> - max_j (<x, y_j> - h_j) over the disk, found among the cells of
// its two rings, so that it owns a small region there. Returns the number of Diracs changed.
int pullEmptyCellsIntoDisk(const std::vector<Vec2>& diracs, const std::vector<double>& nu,
  const std::vector<double>& cellMass, const PowerDiagram& diagram, std::vector<Height>& h);

} // namespace otparam

#endif
