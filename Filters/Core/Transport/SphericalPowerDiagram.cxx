#include "Transport/SphericalPowerDiagram.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/spatial_sort.h>

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
  for (int i = 0; i < n; ++i)
  {
    const double s = static_cast<double>(std::exp(-psi[i].value()));
    points[i] = { Kernel::Point_3(s * diracs[i].x, s * diracs[i].y, s * diracs[i].z), i };
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
  this->Offsets.assign(n + 1, 0);
  this->HiddenCount = n;
  if (t.dimension() < 3)
  {
    return false;
  }
  // Number the hull facets (the infinite cells) and count each Dirac's facets.
  std::vector<Triangulation::Cell_handle> hull;
  t.incident_cells(t.infinite_vertex(), std::back_inserter(hull));
  this->Triangles.resize(hull.size());
  for (size_t f = 0; f < hull.size(); ++f)
  {
    const auto c = hull[f];
    c->info() = static_cast<int>(f);
    const int k = c->index(t.infinite_vertex());
    // vertex_triple_index orders a facet's vertices counter-clockwise seen from the opposite
    // vertex, here the infinite one: from outside the hull.
    for (int j = 0; j < 3; ++j)
    {
      const int id = c->vertex(Triangulation::vertex_triple_index(k, j))->info();
      this->Triangles[f][j] = id;
      ++this->Offsets[id + 1];
    }
  }
  for (int i = 0; i < n; ++i)
  {
    this->HiddenCount -= this->Offsets[i + 1] > 0;
    this->Offsets[i + 1] += this->Offsets[i];
  }
  // Facet neighbours: across the edge opposite corner j of facet f.
  const int facets = static_cast<int>(hull.size());
  std::vector<std::array<int, 3>> across(facets);
  for (int f = 0; f < facets; ++f)
  {
    const auto c = hull[f];
    const int k = c->index(t.infinite_vertex());
    for (int j = 0; j < 3; ++j)
    {
      across[f][j] = c->neighbor(Triangulation::vertex_triple_index(k, j))->info();
    }
  }
  this->Vertices.resize(facets);
  bool originInside = true;
  for (int f = 0; f < facets; ++f)
  {
    const Triangle& tri = this->Triangles[f];
    const Vec3 normal = facetNormal(
      diracs[tri[0]], diracs[tri[1]], diracs[tri[2]], psi[tri[0]], psi[tri[1]], psi[tri[2]]);
    this->Vertices[f] = normalized(normal);
    // The origin is strictly inside when it is strictly behind every facet's plane.
    originInside = originInside && dot(normal, diracs[tri[0]]) > 0.0;
  }
  // Rings: around Dirac a of facet (a, b, c) the next facet counter-clockwise is the one across
  // the edge (a, c), which is opposite b; the arc between the two facets' vertices is shared
  // with c.
  this->Ring.assign(this->Offsets[n], -1);
  this->Neighbors.assign(this->Offsets[n], -1);
  std::vector<char> done(n, 0);
  for (int f0 = 0; f0 < facets; ++f0)
  {
    for (int j0 = 0; j0 < 3; ++j0)
    {
      const int a = this->Triangles[f0][j0];
      if (done[a])
      {
        continue;
      }
      done[a] = 1;
      int f = f0, j = j0;
      for (int k = this->Offsets[a]; k < this->Offsets[a + 1]; ++k)
      {
        this->Ring[k] = f;
        this->Neighbors[k] = this->Triangles[f][(j + 2) % 3];
        const int next = across[f][(j + 1) % 3];
        const Triangle& nt = this->Triangles[next];
        j = nt[0] == a ? 0 : (nt[1] == a ? 1 : 2);
        f = next;
      }
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
  for (const int* f = this->ringBegin(i); f != this->ringEnd(i); ++f)
  {
    polygon.push_back(this->Vertices[*f]);
  }
  return polygon;
}

} // namespace otparam
