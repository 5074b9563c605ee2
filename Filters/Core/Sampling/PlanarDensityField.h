// A density on a planar triangulated domain: piecewise linear (one value per point) or
// piecewise constant (one value per triangle), with point queries, the largest value over a
// triangle, and the domain's shape (the unit disk, or a convex polygon).
#ifndef OTPARAM_SAMPLING_PLANARDENSITYFIELD_H
#define OTPARAM_SAMPLING_PLANARDENSITYFIELD_H

#include "Common/BoxTree.h"
#include "Common/Geometry.h"
#include "Common/TriangleWalk.h"
#include "Transport/PlanarSource.h"

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace otparam
{

class DensityField
{
public:
  // perPoint: one value per point (piecewise linear), or perTriangle: one per triangle
  // (piecewise constant); exactly one of the two is non-empty. Values must be finite and >= 0,
  // not all zero. The domain is the support: the triangles where the density is not identically
  // zero. They must not overlap; the domain may be non-convex, have holes and several
  // components, as long as its boundary loops do not touch. Returns nullptr and sets error
  // otherwise (the message names the offending ids).
  static std::unique_ptr<DensityField> create(const std::vector<Vec2>& points,
    const std::vector<Triangle>& triangles, const std::vector<double>& perPoint,
    const std::vector<double>& perTriangle, std::string& error);

  // Readies the queries for a sampling of `expectedSamples` samples: from as many samples as
  // triangles, they first walk from a seed triangle (Common/TriangleWalk.h), with the same
  // answers. Not thread-safe: call before any query.
  void prepareForQueries(long long expectedSamples) const;
  // Density at x (x outside the domain: the value at the nearest point of the domain).
  double value(Vec2 x) const;
  // value() at the centroid of triangle t, without the search (the centroid lies in t).
  double valueAtCentroid(std::size_t t) const;
  // Largest density over the triangle abc at its centroid and every input point inside it (a
  // piecewise-linear density peaks at input points, which a coarse triangle's corners and
  // centre would miss), and never below `atLeast`: the caller passes its corners' largest
  // value there (it usually knows them already), which prunes the search sooner.
  double maxInsideTriangle(Vec2 a, Vec2 b, Vec2 c, double atLeast = 0.0) const;
  double integral() const { return Integral; }
  double area() const { return Area; }

  // The corners of the domain's convex hull, counter-clockwise.
  const std::vector<Vec2>& boundary() const { return Hull; }
  // True when the domain is its convex hull (one convex component).
  bool isConvex() const { return Convex; }
  // The domain's boundary loops (the hull alone for a convex domain): outer boundaries
  // counter-clockwise, holes clockwise, so the domain is always on the left.
  const std::vector<std::vector<Vec2>>& boundaryLoops() const { return Loops; }
  // True when x lies in one of the domain's triangles (up to rounding).
  bool contains(Vec2 x) const;
  // The point of the domain's boundary loops nearest to x.
  Vec2 nearestBoundaryPoint(Vec2 x) const;
  // True when every boundary point of the input lies on the unit circle (to 1e-6): the domain
  // is then treated as the unit disk (boundary samples on the circle, source mass pi).
  bool isUnitDisk() const { return UnitDisk; }

  const std::vector<Vec2>& points() const { return Points; }
  const std::vector<Triangle>& triangles() const { return Triangles; }

  // The density as a source measure (exact integrals over cells clipped to the domain; a power
  // of the density interpolated the same way is withMappedDensity of it). For the unit disk
  // the domain is the inscribed polygon plus a cap triangle on every boundary edge (tangents'
  // intersection as apex), so that a sample on the circle always has a cell of positive
  // measure, with the density of its edge's ends.
  std::unique_ptr<SourceMeasure> makeSource(std::string& error) const;

private:
  DensityField() = default;
  int locate(Vec2 x) const; // triangle containing x, or -1
  int search(Vec2 x) const; // the same, by TriangleTree alone
  double valueIn(std::size_t t, Vec2 x) const; // the density of triangle t at x
  double valueAt(Vec2 x, int t) const;         // value(x) where locate(x) gave t
  bool maximizeNearby(int seed, Vec2 a, Vec2 b, Vec2 c, double& largest) const;
  bool traceBoundaryLoops(std::string& error);
  bool checkLoopsDoNotCross(const std::unordered_map<int, int>& next, std::string& error) const;
  // The steps of create(), each "" or its message.
  std::string orientAndIntegrate();
  void keepSupport();
  std::string checkNoOverlap() const;
  std::vector<char> usedPoints() const;
  std::string findShape();
  void buildSearchTrees();

  std::vector<Vec2> Points;
  std::vector<Triangle> Triangles; // counter-clockwise
  std::vector<double> PerPoint, PerTriangle;
  std::vector<Vec2> Hull;
  std::vector<int> HullIds; // input point id of each hull corner
  std::vector<std::vector<Vec2>> Loops;
  bool Convex = true;
  bool UnitDisk = false;
  double Integral = 0.0, Area = 0.0;
  BoxTree TriangleTree;          // item = triangle, value = PerTriangle (0 if per point)
  mutable TriangleWalk Walk;     // prepareForQueries: answers most queries before TriangleTree
  BoxTree PointTree;             // per-point densities only: item = used point
  // Per-triangle densities: each triangle's centroid in TriangleTree's slot order, so that a
  // maximum query reads them leaf by leaf rather than gathering corners across the mesh (the
  // refinement's largest cost at 1.09M points).
  std::vector<Vec2> CentroidBySlot;
  // The boundary loops' edges, in the loops' order (item = edge, for nearestBoundaryPoint).
  BoxTree BoundaryTree;
  std::vector<std::pair<Vec2, Vec2>> BoundaryEdges;
};

} // namespace otparam

#endif
