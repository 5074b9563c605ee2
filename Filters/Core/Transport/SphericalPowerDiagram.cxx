#include "Transport/SphericalPowerDiagram.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace otparam
{

namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<int, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
// A plain (not Delaunay) triangulation: its infinite cells are the convex hull. Inserted in
// spatial order it builds the hull of 1e6 points in ~1.5 s where CGAL's quickhull
// (convex_hull_3) took 12.6 s: every point of a transport is on (or near) the hull.
using Triangulation = CGAL::Triangulation_3<Kernel, Tds>;
using IndexedPoint = std::pair<Kernel::Point_3, int>;

long double heightDifference(const Height& a, const Height& b)
{
  return a - b;
}

// A vector in long double: the facet normals are computed in it (see facetNormal).
struct LongVec3
{
  long double x, y, z;
};

// In long double: expm1 of a height difference of order 1 rounded to double would move the
// cell boundary by 1e-16 / |y_a - y_b| radians, a relative error of ~1e-9 in the smallest
// cells of 1e5 Diracs of contrast 1e4.
LongVec3 longScaledDifference(
  const Vec3& ya, const Vec3& yb, const Height& psiA, const Height& psiB)
{
  const long double e = std::expm1(heightDifference(psiB, psiA));
  auto component = [e](double a, double b) { return static_cast<long double>(a - b) + e * a; };
  return { component(ya.x, yb.x), component(ya.y, yb.y), component(ya.z, yb.z) };
}
// The corner of triangle t that is neither a nor b.
int oppositeCorner(const Triangle& t, int a, int b)
{
  return t[0] != a && t[0] != b ? 0 : (t[1] != a && t[1] != b ? 1 : 2);
}

// The lifted point p = y e^-psi of a Dirac, whose hull the diagram is.
Kernel::Point_3 liftedPoint(const Vec3& y, const Height& psi)
{
  const double s = static_cast<double>(std::exp(-psi.value()));
  return Kernel::Point_3(s * y.x, s * y.y, s * y.z);
}

// False when a lifted point over- or underflowed (a Newton trial far from the solution): the
// exact predicates cannot take infinite or NaN coordinates (CGAL asserts; found by the fuzzer,
// transport-sphere seed 2 case 3294), and points collapsed to the origin have no hull.
bool finiteAndNonZero(const Kernel::Point_3& p)
{
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()) &&
    (p.x() != 0.0 || p.y() != 0.0 || p.z() != 0.0);
}

// The two hull triangles at the edge opposite corner j of triangle f: f = (c, a, b) and
// g = (d, b, a), d at corner k of g.
struct EdgeQuad
{
  int a, b, c, d, g, k;
};

EdgeQuad edgeQuad(const std::vector<Triangle>& triangles,
  const std::vector<std::array<int, 3>>& across, int f, int j)
{
  EdgeQuad q;
  q.c = triangles[f][j];
  q.a = triangles[f][(j + 1) % 3];
  q.b = triangles[f][(j + 2) % 3];
  q.g = across[f][j];
  q.k = oppositeCorner(triangles[q.g], q.a, q.b);
  q.d = triangles[q.g][q.k];
  return q;
}

// Lawson's flips carried to the hull: starting from the hull of the same Diracs at earlier
// heights (a triangulated sphere around the origin), flips every reflex edge whose flip keeps
// the triangles around the origin, until every edge is convex. A closed surface that is convex at
// every edge and wraps the origin once is the hull boundary (as a locally regular triangulation is
// regular), so the result is the hull. Each flip moves the surface outward, so the flips end;
// they get stuck only where a Dirac has sunk inside the hull (hidden) or behind a fold of the
// old surface, and then return false. Written by hand: CGAL's triangulations move a point only by
// removing and inserting it. A Newton step changes few edges: at 1e5 Diracs this takes ~10 ms
// where a new hull takes ~250 ms.
bool flipToHull(const std::vector<Kernel::Point_3>& p, std::vector<Triangle>& triangles,
  std::vector<std::array<int, 3>>& across)
{
  const Kernel::Point_3 origin(0.0, 0.0, 0.0);
  const auto orientation = Kernel().orientation_3_object();
  // d above the plane of (a, b, c), seen from outside: the edge (a, b) folds inward.
  auto reflex = [&](const EdgeQuad& q)
  { return orientation(p[q.a], p[q.b], p[q.c], p[q.d]) == CGAL::POSITIVE; };
  // Most edges of the old hull stay convex: they are checked in parallel, and only the reflex
  // ones start the (sequential) flips.
  const int facets = static_cast<int>(triangles.size());
  std::vector<std::pair<int, int>> stack;
#pragma omp parallel
  {
    std::vector<std::pair<int, int>> reflexEdges;
#pragma omp for schedule(static) nowait
    for (int f = 0; f < facets; ++f)
    {
      for (int j = 0; j < 3; ++j)
      {
        if (f < across[f][j] && reflex(edgeQuad(triangles, across, f, j)))
        {
          reflexEdges.emplace_back(f, j);
        }
      }
    }
#pragma omp critical
    stack.insert(stack.end(), reflexEdges.begin(), reflexEdges.end());
  }
  // In one order whatever the threads did, so that the flips (and the run) are reproducible.
  std::sort(stack.begin(), stack.end());
  size_t flipsLeft = 20 * static_cast<size_t>(facets) + 1000;
  std::vector<std::pair<int, int>> reflexKept;
  size_t flipsSinceKept = 0;
  for (;;)
  {
    if (stack.empty())
    {
      // Edges kept reflex for a fold may be flippable after later flips.
      if (reflexKept.empty() || flipsSinceKept == 0)
      {
        break;
      }
      stack.swap(reflexKept);
      flipsSinceKept = 0;
    }
    const auto [f, j] = stack.back();
    stack.pop_back();
    const EdgeQuad q = edgeQuad(triangles, across, f, j);
    if (!reflex(q))
    {
      continue; // convex (or flat) edge
    }
    const int a = q.a, b = q.b, c = q.c, d = q.d, g = q.g, k = q.k;
    if (orientation(p[c], p[a], p[d], origin) != CGAL::NEGATIVE ||
      orientation(p[d], p[b], p[c], origin) != CGAL::NEGATIVE)
    {
      reflexKept.emplace_back(f, j);
      continue;
    }
    if (flipsLeft-- == 0)
    {
      return false;
    }
    ++flipsSinceKept;
    // f = (c, a, b) and g = (d, b, a) become f = (c, a, d) and g = (d, b, c).
    const int nfA = across[f][(j + 1) % 3], nfB = across[f][(j + 2) % 3];
    const int ngB = across[g][(k + 1) % 3], ngA = across[g][(k + 2) % 3];
    triangles[f] = { c, a, d };
    across[f] = { ngB, g, nfB };
    triangles[g] = { d, b, c };
    across[g] = { nfA, f, ngA };
    for (int m = 0; m < 3; ++m)
    {
      if (across[ngB][m] == g)
      {
        across[ngB][m] = f;
      }
      if (across[nfA][m] == f)
      {
        across[nfA][m] = g;
      }
    }
    stack.emplace_back(f, 0);
    stack.emplace_back(f, 2);
    stack.emplace_back(g, 0);
    stack.emplace_back(g, 2);
  }
  // Recheck the edges kept: every one must have become convex.
  return std::none_of(reflexKept.begin(), reflexKept.end(),
    [&](const std::pair<int, int>& edge)
    { return reflex(edgeQuad(triangles, across, edge.first, edge.second)); });
}
} // namespace

Vec3 scaledDifference(const Vec3& ya, const Vec3& yb, const Height& psiA, const Height& psiB)
{
  const LongVec3 d = longScaledDifference(ya, yb, psiA, psiB);
  return { static_cast<double>(d.x), static_cast<double>(d.y), static_cast<double>(d.z) };
}

Vec3 facetNormal(const Vec3& ya, const Vec3& yb, const Vec3& yc, const Height& psiA,
  const Height& psiB, const Height& psiC)
{
  // (p_b - p_a) x (p_c - p_a), both differences scaled by e^psi_a (the direction is all that
  // is needed), normalized. In long double: for a thin hull triangle the cross product of two
  // nearly parallel edges loses digits in proportion (random Diracs have angles of 1e-3), and
  // in double that left relative errors of ~1e-9 in the smallest cells at 1e5 Diracs.
  const LongVec3 u = longScaledDifference(yb, ya, psiB, psiA);
  const LongVec3 v = longScaledDifference(yc, ya, psiC, psiA);
  const long double x = u.y * v.z - u.z * v.y, y = u.z * v.x - u.x * v.z, z = u.x * v.y - u.y * v.x;
  const long double length = std::sqrt(x * x + y * y + z * z);
  if (!(length > 0.0L))
  {
    return {};
  }
  return { static_cast<double>(x / length), static_cast<double>(y / length),
    static_cast<double>(z / length) };
}

bool SphericalPowerDiagram::build(const std::vector<Vec3>& diracs, const std::vector<Height>& psi)
{
  const int n = static_cast<int>(diracs.size());
  this->Diracs = diracs;
  this->Psi = psi;
  std::vector<IndexedPoint> points(n);
  bool representable = true;
  for (int i = 0; i < n; ++i)
  {
    points[i] = { liftedPoint(diracs[i], psi[i]), i };
    representable = representable && finiteAndNonZero(points[i].first);
  }
  if (!representable)
  {
    this->Triangles.clear();
    this->Across.clear();
    this->Offsets.assign(n + 1, 0);
    this->HiddenCount = n;
    return false;
  }
  CGAL::spatial_sort(points.begin(), points.end(),
    CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::First_of_pair_property_map<IndexedPoint>>());
  Triangulation t;
  Triangulation::Cell_handle hint;
  for (const IndexedPoint& p : points)
  {
    const auto v = t.insert(p.first, hint);
    v->info() = p.second;
    hint = v->cell();
  }
  this->Triangles.clear();
  this->Across.clear();
  this->Offsets.assign(n + 1, 0);
  this->HiddenCount = n;
  if (t.dimension() < 3)
  {
    return false;
  }
  // Number the hull facets (the infinite cells).
  std::vector<Triangulation::Cell_handle> hull;
  t.incident_cells(t.infinite_vertex(), std::back_inserter(hull));
  const int facets = static_cast<int>(hull.size());
  this->Triangles.resize(facets);
  this->Across.resize(facets);
  for (int f = 0; f < facets; ++f)
  {
    hull[f]->info() = f;
  }
  for (int f = 0; f < facets; ++f)
  {
    const auto c = hull[f];
    const int k = c->index(t.infinite_vertex());
    // vertex_triple_index orders a facet's vertices counter-clockwise seen from the opposite
    // vertex, here the infinite one: from outside the hull.
    for (int j = 0; j < 3; ++j)
    {
      this->Triangles[f][j] = c->vertex(Triangulation::vertex_triple_index(k, j))->info();
      this->Across[f][j] = c->neighbor(Triangulation::vertex_triple_index(k, j))->info();
    }
  }
  return this->finishCells();
}

bool SphericalPowerDiagram::buildFrom(const SphericalPowerDiagram& previous,
  const std::vector<Vec3>& diracs, const std::vector<Height>& psi)
{
  const int n = static_cast<int>(diracs.size());
  if (previous.size() != n || previous.HiddenCount > 0 || previous.Triangles.empty())
  {
    return this->build(diracs, psi);
  }
  std::vector<Kernel::Point_3> points(n);
  int unrepresentable = 0;
#pragma omp parallel for schedule(static) reduction(+ : unrepresentable)
  for (int i = 0; i < n; ++i)
  {
    points[i] = liftedPoint(diracs[i], psi[i]);
    unrepresentable += !finiteAndNonZero(points[i]);
  }
  this->Triangles = previous.Triangles;
  this->Across = previous.Across;
  this->Diracs = diracs;
  this->Psi = psi;
  if (unrepresentable > 0 || !flipToHull(points, this->Triangles, this->Across))
  {
    this->Triangles.clear();
    this->Across.clear();
    this->Offsets.assign(n + 1, 0);
    this->HiddenCount = 1;
    return false;
  }
  return this->finishCells();
}

bool SphericalPowerDiagram::finishCells()
{
  const int n = static_cast<int>(this->Diracs.size());
  const int facets = static_cast<int>(this->Triangles.size());
  this->Offsets.assign(n + 1, 0);
  for (const Triangle& tri : this->Triangles)
  {
    for (const int id : tri)
    {
      ++this->Offsets[id + 1];
    }
  }
  this->HiddenCount = n;
  for (int i = 0; i < n; ++i)
  {
    this->HiddenCount -= this->Offsets[i + 1] > 0;
    this->Offsets[i + 1] += this->Offsets[i];
  }
  this->Vertices.resize(facets);
  int facetsFacingOrigin = 0;
#pragma omp parallel for schedule(static) reduction(+ : facetsFacingOrigin)
  for (int f = 0; f < facets; ++f)
  {
    const Triangle& tri = this->Triangles[f];
    const Vec3 normal = facetNormal(this->Diracs[tri[0]], this->Diracs[tri[1]],
      this->Diracs[tri[2]], this->Psi[tri[0]], this->Psi[tri[1]], this->Psi[tri[2]]);
    this->Vertices[f] = normalized(normal);
    // The origin is strictly inside when it is strictly behind every facet's plane.
    facetsFacingOrigin += !(dot(normal, this->Diracs[tri[0]]) > 0.0);
  }
  const bool originInside = facetsFacingOrigin == 0;
  // Rings: around Dirac a of facet (a, b, c) the next facet counter-clockwise is the one across
  // the edge (a, c), which is opposite b; the arc between the two facets' vertices is shared
  // with c.
  this->Ring.assign(this->Offsets[n], -1);
  this->Neighbors.assign(this->Offsets[n], -1);
  // Each ring starts at the Dirac's first facet: 3 f + j, corner j of facet f.
  std::vector<int> firstCorner(n, -1);
  for (int f = facets - 1; f >= 0; --f)
  {
    for (int j = 2; j >= 0; --j)
    {
      firstCorner[this->Triangles[f][j]] = 3 * f + j;
    }
  }
#pragma omp parallel for schedule(static)
  for (int a = 0; a < n; ++a)
  {
    if (firstCorner[a] < 0)
    {
      continue;
    }
    int f = firstCorner[a] / 3, j = firstCorner[a] % 3;
    for (int k = this->Offsets[a]; k < this->Offsets[a + 1]; ++k)
    {
      this->Ring[k] = f;
      this->Neighbors[k] = this->Triangles[f][(j + 2) % 3];
      const int next = this->Across[f][(j + 1) % 3];
      const Triangle& nt = this->Triangles[next];
      j = nt[0] == a ? 0 : (nt[1] == a ? 1 : 2);
      f = next;
    }
  }
  return originInside;
}

Vec3 SphericalPowerDiagram::polytopeVertex(int triangle) const
{
  const Triangle& tri = this->Triangles[triangle];
  const Vec3& normal = this->Vertices[triangle];
  const double s = static_cast<double>(std::exp(-this->Psi[tri[0]].value()));
  return (1.0 / (s * dot(normal, this->Diracs[tri[0]]))) * normal;
}

std::vector<Vec3> SphericalPowerDiagram::cell(int i) const
{
  std::vector<Vec3> polygon;
  this->cell(i, polygon);
  return polygon;
}

void SphericalPowerDiagram::cell(int i, std::vector<Vec3>& polygon) const
{
  polygon.clear();
  for (const int* f = this->ringBegin(i); f != this->ringEnd(i); ++f)
  {
    polygon.push_back(this->Vertices[*f]);
  }
}

} // namespace otparam
