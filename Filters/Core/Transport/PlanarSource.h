// Source measures of the semi-discrete OT problem: the exact uniform unit disk, and a convex
// triangulated planar domain with a piecewise-linear density. Each knows how to integrate its
// density exactly over a convex power cell (mass, first moment, and the density integrated
// along the cell's edges, which is what the Newton Hessian needs).
#ifndef OTPARAM_TRANSPORT_PLANARSOURCE_H
#define OTPARAM_TRANSPORT_PLANARSOURCE_H

#include "Common/Geometry.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace otparam
{

// A convex polygon, counter-clockwise. Edge k runs from vertices[k] to vertices[k+1 mod n]
// and lies on the bisector shared with Dirac neighbor[k] (-1: an edge of the outer box).
// vertices[k] + correction[k] is the vertex to long double precision (correction empty: exact
// as it is). The rounding to double (~1e-16) is ~1e-9 of the mass of the thin cells that hug the
// circle at high contrast; the disk source integrates the corrected vertices.
struct PowerCell
{
  std::vector<Vec2> vertices;
  std::vector<int> neighbor;
  std::vector<Vec2> correction;
};

struct CellIntegrals
{
  bool wantEdgeMass = true; // input: false when only mass and moment are needed (faster)
  double mass = 0.0;
  Vec2 moment;                                  // integral of x * density over the clipped cell
  std::vector<std::pair<int, double>> edgeMass; // (neighbour, integral of density along the edge)
};

class SourceMeasure
{
public:
  virtual ~SourceMeasure() = default;

  virtual double totalMass() const = 0;
  // True for the exact unit disk (makeUnitDiskSource), whose geometry some starts rely on.
  virtual bool isUnitDisk() const { return false; }
  // Axis-aligned box that contains the domain.
  virtual void bounds(Vec2& lo, Vec2& hi) const = 0;
  // A disk inside the domain: where a starting configuration is placed when Diracs lie outside.
  virtual void innerDisk(Vec2& center, double& radius) const = 0;
  // Exact integrals of the density over cell ∩ domain. Thread-safe.
  virtual void integrate(const PowerCell& cell, CellIntegrals& out) const = 0;
  // Boundary of cell ∩ domain as a closed polygon (no repeated first point), counter-clockwise;
  // circular arcs are sampled so that no piece spans more than maxArcAngle radians. Display only.
  virtual std::vector<Vec2> clippedBoundary(const PowerCell& cell, double maxArcAngle) const = 0;
};

// The unit disk with density 1 (total mass pi). Cells are clipped by the circle exactly:
// straight edges plus circular segments in closed form.
std::unique_ptr<SourceMeasure> makeUnitDiskSource();

// A planar triangulated convex domain. density: one value per point (piecewise linear), or empty
// for density 1. Returns nullptr and sets error when the domain is empty, not convex, has
// degenerate or inverted... triangles, or a density that is not finite and positive (or, with
// allowZeroDensity, negative: the sampler integrates densities that vanish on parts of the
// domain; an OT source must not). With allowNonConvex, any tiling is accepted (the sampler
// integrates over supports with holes; only cell integrals are then meaningful, not the
// clipped boundaries or the inner disk). hullCandidates, when given, holds every corner of the
// used points' convex hull (a caller that knows its domain's hull): the hull is taken of them
// instead of every point.
std::unique_ptr<SourceMeasure> makeTriangulatedSource(const std::vector<Vec2>& points,
  const std::vector<Triangle>& triangles, const std::vector<double>& density, std::string& error,
  bool allowZeroDensity = false, bool allowNonConvex = false,
  const std::vector<Vec2>* hullCandidates = nullptr);

// A source of makeTriangulatedSource with each per-point density value d replaced by map(d),
// sharing its domain (triangles, hull, search tree): a second density over one large
// triangulation costs a pass over its points, not a build. nullptr and error set when
// `triangulated` is not such a source or a mapped value is not finite and positive (or zero,
// with allowZeroDensity).
std::unique_ptr<SourceMeasure> withMappedDensity(const SourceMeasure& triangulated,
  const std::function<double(double)>& map, std::string& error, bool allowZeroDensity = false);

} // namespace otparam

#endif
