#include "PowerDiagram.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <utility>

namespace otparam
{
namespace
{
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vbase = CGAL::Regular_triangulation_vertex_base_2<K>;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K, Vbase>;
using Fb = CGAL::Regular_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Regular = CGAL::Regular_triangulation_2<K, Tds>;
using WeightedPoint = Regular::Weighted_point;
using BarePoint = Regular::Bare_point;
} // namespace

void PowerDiagram::build(const std::vector<Vec2>& diracs, const std::vector<Height>& heights)
{
  const int n = static_cast<int>(diracs.size());
  Sites = diracs;
  Heights = heights;
  std::vector<std::pair<WeightedPoint, int>> input;
  input.reserve(n);
  for (int i = 0; i < n; ++i)
  {
    const Vec2 y = diracs[i];
    input.emplace_back(WeightedPoint(BarePoint(y.x, y.y), static_cast<double>(dot(y, y) - 2.0L * heights[i])), i);
  }
  Regular rt;
  rt.insert(input.begin(), input.end()); // spatially sorted insertion

  Hidden.assign(n, 1);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
  {
    Hidden[v->info()] = 0;
  }
  HiddenCount = static_cast<int>(std::count(Hidden.begin(), Hidden.end(), 1));

  // Adjacency in compressed rows, from the finite edges (also right in dimension 1).
  std::vector<std::pair<int, int>> edges;
  edges.reserve(6 * static_cast<size_t>(n));
  for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e)
  {
    const int a = e->first->vertex(Regular::cw(e->second))->info();
    const int b = e->first->vertex(Regular::ccw(e->second))->info();
    edges.emplace_back(a, b);
  }
  Offsets.assign(n + 1, 0);
  for (const auto& e : edges)
  {
    ++Offsets[e.first + 1];
    ++Offsets[e.second + 1];
  }
  for (int i = 0; i < n; ++i)
  {
    Offsets[i + 1] += Offsets[i];
  }
  Adjacency.assign(Offsets[n], 0);
  std::vector<int> fill(Offsets.begin(), Offsets.end() - 1);
  for (const auto& e : edges)
  {
    Adjacency[fill[e.first]++] = e.second;
    Adjacency[fill[e.second]++] = e.first;
  }

  Triangles.clear();
  if (rt.dimension() == 2)
  {
    Triangles.reserve(rt.number_of_faces());
    for (auto f = rt.finite_faces_begin(); f != rt.finite_faces_end(); ++f)
    {
      Triangles.push_back({ f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() });
    }
  }
}

void PowerDiagram::cell(int i, Vec2 lo, Vec2 hi, PowerCell& out) const
{
  out.vertices.clear();
  out.neighbor.clear();
  if (Hidden[i])
  {
    return;
  }
  // Start from the box; clip by the half-plane of every neighbour, keeping edge labels
  // (Sutherland–Hodgman: the polygon stays convex, degrees are ~6).
  out.vertices = { lo, { hi.x, lo.y }, hi, { lo.x, hi.y } };
  out.neighbor = { -1, -1, -1, -1 };
  thread_local std::vector<Vec2> verts;
  thread_local std::vector<int> labels;
  thread_local std::vector<double> side;
  const Vec2 yi = Sites[i];
  for (const int* it = neighborsBegin(i); it != neighborsEnd(i); ++it)
  {
    const int j = *it;
    const Vec2 d = yi - Sites[j];
    const double c = static_cast<double>(Heights[i] - Heights[j]);
    // Keep <x, y_i - y_j> >= h_i - h_j.
    const size_t m = out.vertices.size();
    side.resize(m);
    bool anyOut = false, anyIn = false;
    for (size_t k = 0; k < m; ++k)
    {
      side[k] = dot(out.vertices[k], d) - c;
      anyOut |= side[k] < 0.0;
      anyIn |= side[k] >= 0.0;
    }
    if (!anyOut)
    {
      continue;
    }
    if (!anyIn)
    {
      out.vertices.clear();
      out.neighbor.clear();
      return;
    }
    verts.clear();
    labels.clear();
    for (size_t k = 0; k < m; ++k)
    {
      const size_t k1 = (k + 1) % m;
      const Vec2 p = out.vertices[k], q = out.vertices[k1];
      const bool pin = side[k] >= 0.0, qin = side[k1] >= 0.0;
      if (pin)
      {
        verts.push_back(p);
        labels.push_back(out.neighbor[k]);
      }
      if (pin != qin)
      {
        const double t = side[k] / (side[k] - side[k1]);
        verts.push_back(p + t * (q - p));
        labels.push_back(pin ? j : out.neighbor[k]);
      }
    }
    out.vertices.swap(verts);
    out.neighbor.swap(labels);
    if (out.vertices.size() < 3)
    {
      out.vertices.clear();
      out.neighbor.clear();
      return;
    }
  }
}

} // namespace otparam
