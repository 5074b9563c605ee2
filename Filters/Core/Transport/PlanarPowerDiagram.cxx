#include "Transport/PlanarPowerDiagram.h"

#include "Common/PowerTestKernel.h"

#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <utility>

namespace otparam
{
namespace
{
using K = PowerTestKernel;
using Vbase = CGAL::Regular_triangulation_vertex_base_2<K>;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K, Vbase>;
using Fbase = CGAL::Regular_triangulation_face_base_2<K>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int, K, Fbase>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Regular = CGAL::Regular_triangulation_2<K, Tds>;
using WeightedPoint = Regular::Weighted_point;
using BarePoint = Regular::Bare_point;
} // namespace

// The regular triangulation kept between builds, for reweightByFlips().
struct PowerDiagram::Triangulation
{
  enum class Flips
  {
    Regular,     // rt is now the regular triangulation
    HidesADirac, // hidden: a Dirac certainly has no cell under these weights
    Failed       // rt cannot be flipped (it has hidden vertices, or the flips did not end)
  };
  Flips reweightByFlips(const std::vector<Vec2>& diracs, const std::vector<Height>& heights,
    bool stopAtFirstHidden, std::vector<std::pair<int, Triangle>>& hidden);
  // The same for Diracs that moved (same count and labels): the vertices moved, then the flips
  // from every edge; Failed, with rt left unusable, where a hull vertex moved or a triangle
  // turned over.
  Flips moveByFlips(const std::vector<Vec2>& diracs, const std::vector<Height>& heights,
    bool stopAtFirstHidden, std::vector<std::pair<int, Triangle>>& hidden);
  bool moveVertices(const std::vector<Vec2>& diracs, const std::vector<Height>& heights);
  // reweightByFlips' steps: the vertices whose weight changed, the edges that can have turned
  // non-regular, and Lawson's flips from them.
  std::vector<Regular::Vertex_handle> setWeights(
    const std::vector<Vec2>& diracs, const std::vector<Height>& heights);
  std::vector<Regular::Edge> edgesToCheck(const std::vector<Regular::Vertex_handle>& changed);
  Flips flip(std::vector<Regular::Edge>& stack, bool stopAtFirstHidden,
    std::vector<std::pair<int, Triangle>>& hidden);

  Regular rt;
  // Settled: every edge is regular under the vertices' weights, except perhaps those listed
  // (where the last flips stopped at a hidden Dirac). A build that changes a few weights then
  // checks only the edges around them.
  bool settled = true;
  std::vector<std::pair<Regular::Vertex_handle, Regular::Vertex_handle>> unsettled;
};

PowerDiagram::PowerDiagram() = default;
PowerDiagram::~PowerDiagram() = default;
PowerDiagram::PowerDiagram(PowerDiagram&&) noexcept = default;
PowerDiagram& PowerDiagram::operator=(PowerDiagram&&) noexcept = default;

namespace
{
double weight(Vec2 y, const Height& h)
{
  return static_cast<double>(dot(y, y) - 2.0L * h.value());
}

// True when rt holds exactly these Diracs, each vertex labelled with its index.
bool triangulates(const Regular& rt, const std::vector<Vec2>& diracs)
{
  if (rt.number_of_vertices() + rt.number_of_hidden_vertices() != diracs.size())
  {
    return false;
  }
  auto same = [&](Regular::Vertex_handle v)
  {
    const BarePoint& p = v->point().point();
    const Vec2 y = diracs[v->info()];
    return p.x() == y.x && p.y() == y.y;
  };
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
  {
    if (!same(v))
    {
      return false;
    }
  }
  for (auto v = rt.hidden_vertices_begin(); v != rt.hidden_vertices_end(); ++v)
  {
    if (!same(v))
    {
      return false;
    }
  }
  return true;
}

} // namespace

// Turns a triangulation of all the points (the regular one under other weights, or one where
// earlier flips stopped) into the regular triangulation under these weights by Lawson flips:
// every edge whose opposite vertex conflicts with the power circle of its face is flipped, and
// the edges around it are checked again. A triangulation of all the points that is locally
// regular everywhere is the regular triangulation (Edelsbrunner & Shah), so when the flips end
// the result is exact. Flips cannot hide a vertex; they stop at a non-regular edge whose
// quadrilateral is not convex. Its reflex vertex then lies in the triangle of the other three,
// with its lifted point above theirs (the two triangles along the edge are above the third
// one's plane), so it is off the lower hull: it goes to hidden with that triangle, and the
// flips go on elsewhere (or stop, with stopAtFirstHidden). CGAL offers no update of weights; a
// Newton step moves few edges, so this costs a fraction of a new insertion.
// Only the edges whose quadrilaterals hold a vertex of changed weight can turn non-regular: when
// few weights change (the inflation of small cells before Newton), only those are checked.
// rt must triangulate these Diracs.
PowerDiagram::Triangulation::Flips PowerDiagram::Triangulation::reweightByFlips(
  const std::vector<Vec2>& diracs, const std::vector<Height>& heights, bool stopAtFirstHidden,
  std::vector<std::pair<int, Triangle>>& hidden)
{
  hidden.clear();
  if (rt.dimension() != 2 || rt.number_of_hidden_vertices() != 0)
  {
    return Flips::Failed;
  }
  std::vector<Regular::Edge> stack = this->edgesToCheck(this->setWeights(diracs, heights));
  return this->flip(stack, stopAtFirstHidden, hidden);
}

std::vector<Regular::Vertex_handle> PowerDiagram::Triangulation::setWeights(
  const std::vector<Vec2>& diracs, const std::vector<Height>& heights)
{
  std::vector<Regular::Vertex_handle> changed;
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
  {
    const int i = v->info();
    const double w = weight(diracs[i], heights[i]);
    if (v->point().weight() != w)
    {
      v->set_point(WeightedPoint(v->point().point(), w));
      changed.push_back(v);
    }
  }
  return changed;
}

// The hull's vertices must stay: Lawson's flips never change the hull, and with the hull fixed
// and every triangle still counter-clockwise the moved triangulation still tiles the hull (a
// local homeomorphism fixed on the boundary), so the flips end at the regular triangulation.
bool PowerDiagram::Triangulation::moveVertices(
  const std::vector<Vec2>& diracs, const std::vector<Height>& heights)
{
  if (rt.dimension() != 2 || rt.number_of_hidden_vertices() != 0 ||
    rt.number_of_vertices() != diracs.size())
  {
    return false;
  }
  const auto at = [&](Regular::Vertex_handle v)
  {
    const int i = v->info();
    return i >= 0 && i < static_cast<int>(diracs.size()) ? &diracs[i] : nullptr;
  };
  auto hull = rt.incident_vertices(rt.infinite_vertex()), end = hull;
  do
  {
    const Vec2* y = at(hull);
    const BarePoint& p = hull->point().point();
    if (!y || p.x() != y->x || p.y() != y->y)
    {
      return false;
    }
  } while (++hull != end);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
  {
    const Vec2* y = at(v);
    if (!y)
    {
      return false;
    }
    const int i = v->info();
    v->set_point(WeightedPoint(BarePoint(y->x, y->y), weight(*y, heights[i])));
  }
  const auto orientation = rt.geom_traits().orientation_2_object();
  for (auto f = rt.finite_faces_begin(); f != rt.finite_faces_end(); ++f)
  {
    if (orientation(f->vertex(0)->point().point(), f->vertex(1)->point().point(),
          f->vertex(2)->point().point()) != CGAL::LEFT_TURN)
    {
      return false;
    }
  }
  settled = false; // every edge is checked
  return true;
}

PowerDiagram::Triangulation::Flips PowerDiagram::Triangulation::moveByFlips(
  const std::vector<Vec2>& diracs, const std::vector<Height>& heights, bool stopAtFirstHidden,
  std::vector<std::pair<int, Triangle>>& hidden)
{
  hidden.clear();
  if (!this->moveVertices(diracs, heights))
  {
    return Flips::Failed;
  }
  std::vector<Regular::Edge> stack = this->edgesToCheck({});
  return this->flip(stack, stopAtFirstHidden, hidden);
}

std::vector<Regular::Edge> PowerDiagram::Triangulation::edgesToCheck(
  const std::vector<Regular::Vertex_handle>& changed)
{
  std::vector<Regular::Edge> stack;
  if (settled && changed.size() < rt.number_of_vertices() / 8)
  {
    for (const auto v : changed)
    {
      // An edge is regular when its opposite vertex is outside the power circle of its face:
      // a changed weight at any of the quadrilateral's four vertices can break it.
      auto face = rt.incident_faces(v), end = face;
      do
      {
        for (int k = 0; k < 3; ++k)
        {
          stack.emplace_back(face, k);
        }
      } while (++face != end);
    }
    for (const auto& [a, b] : unsettled)
    {
      Regular::Face_handle f;
      int i;
      if (rt.is_edge(a, b, f, i))
      {
        stack.emplace_back(f, i);
      }
    }
  }
  else
  {
    // Every finite edge once, from the face that comes first in the triangulation's own order.
    // Not rt.finite_edges_begin(): its edge iterator reports an edge from the face at the lower
    // address (Face_handle::operator< compares pointers), so the flips, hence which face object
    // ends up holding which triangle and how its vertices are rotated, depended on where malloc
    // had put the face blocks; the power vertices and cell integrals then rounded differently
    // from process to process (and after other work in the same process).
    int serial = 0;
    for (auto f = rt.all_faces_begin(); f != rt.all_faces_end(); ++f)
    {
      f->info() = serial++; // renumbered by build() once the flips are done
    }
    for (auto f = rt.all_faces_begin(); f != rt.all_faces_end(); ++f)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (f->info() < f->neighbor(k)->info() && !rt.is_infinite(f, k))
        {
          stack.emplace_back(f, k);
        }
      }
    }
  }
  return stack;
}

// Lawson's flips from the edges on `stack`; a flip that would hide a Dirac is not done (see
// reweightByFlips).
PowerDiagram::Triangulation::Flips PowerDiagram::Triangulation::flip(
  std::vector<Regular::Edge>& stack, bool stopAtFirstHidden,
  std::vector<std::pair<int, Triangle>>& hidden)
{
  settled = false;
  unsettled.clear();
  const auto orientation = rt.geom_traits().orientation_2_object();
  // Lawson's flips end after finitely many steps; the budget only guards against a bug.
  size_t budget = 20 * stack.size() + 1000;
  while (!stack.empty())
  {
    if (budget-- == 0)
    {
      return Flips::Failed;
    }
    const auto [f, i] = stack.back();
    stack.pop_back();
    const Regular::Face_handle g = f->neighbor(i);
    if (rt.is_infinite(f) || rt.is_infinite(g))
    {
      continue; // the hull does not change: the points are the same
    }
    const int j = rt.mirror_index(f, i);
    if (rt.power_test(f, g->vertex(j)->point()) != CGAL::ON_POSITIVE_SIDE)
    {
      continue;
    }
    const BarePoint& p = f->vertex(i)->point().point();
    const BarePoint& q = f->vertex(Regular::ccw(i))->point().point();
    const BarePoint& r = f->vertex(Regular::cw(i))->point().point();
    const BarePoint& t = g->vertex(j)->point().point();
    // p, q, r counter-clockwise in f; t across the edge qr. A collinear triple counts as
    // reflex: its middle point then lies on a segment whose lifted ends are below its own.
    const bool qReflex = orientation(p, q, t) != CGAL::LEFT_TURN;
    if (qReflex || orientation(p, t, r) != CGAL::LEFT_TURN)
    {
      const int a = f->vertex(i)->info(), b = f->vertex(Regular::ccw(i))->info(),
                c = f->vertex(Regular::cw(i))->info(), d = g->vertex(j)->info();
      hidden.emplace_back(qReflex ? b : c, qReflex ? Triangle{ a, d, c } : Triangle{ a, b, d });
      if (stopAtFirstHidden)
      {
        return Flips::HidesADirac;
      }
      unsettled.emplace_back(f->vertex(Regular::ccw(i)), f->vertex(Regular::cw(i)));
      continue;
    }
    rt.tds().flip(f, i);
    for (int k = 0; k < 3; ++k)
    {
      stack.emplace_back(f, k);
      stack.emplace_back(g, k);
    }
  }
  settled = true;
  return hidden.empty() ? Flips::Regular : Flips::HidesADirac;
}

void PowerDiagram::clearCells(int n)
{
  Triangles.clear();
  PowerVertices.clear();
  PowerVertexCorrections.clear();
  RingFace.clear();
  Offsets.assign(n + 1, 0);
  Adjacency.clear();
  Dimension = 0;
}

void PowerDiagram::releaseCellGeometry()
{
  std::vector<Triangle>().swap(Triangles);
  std::vector<Vec2>().swap(PowerVertices);
  std::vector<Vec2>().swap(PowerVertexCorrections);
  std::vector<int>().swap(RingFace);
  std::vector<Vec2>().swap(Sites);
  std::vector<Height>().swap(Heights);
  std::vector<Triangle>().swap(HiddenFace);
}

void PowerDiagram::takeTriangulationFrom(PowerDiagram& other)
{
  if (&other != this && other.Kept)
  {
    Kept = std::move(other.Kept);
  }
}

void PowerDiagram::build(
  const std::vector<Vec2>& diracs, const std::vector<Height>& heights, WhenHidden whenHidden)
{
  const int n = static_cast<int>(diracs.size());
  Sites = diracs;
  Heights = heights;
  std::unique_ptr<Triangulation> fresh;
  Triangulation* triangulation = this->triangulate(diracs, heights, whenHidden, fresh);
  if (!triangulation)
  {
    return;
  }
  this->findHidden(*triangulation, n);
  clearCells(n);
  if (whenHidden != WhenHidden::FindAll && HiddenCount > 0)
  {
    return;
  }
  Dimension = triangulation->rt.dimension();
  if (Dimension == 2)
  {
    this->buildPlanarCells(*triangulation, n);
  }
  else
  {
    this->buildLowDimensionalAdjacency(*triangulation, n);
  }
}

PowerDiagram::Triangulation* PowerDiagram::triangulate(const std::vector<Vec2>& diracs,
  const std::vector<Height>& heights, WhenHidden whenHidden, std::unique_ptr<Triangulation>& fresh)
{
  const int n = static_cast<int>(diracs.size());
  const bool sameDiracs = Kept && triangulates(Kept->rt, diracs);
  std::vector<std::pair<int, Triangle>> certainlyHidden;
  using Flips = Triangulation::Flips;
  const bool stopAtFirst = whenHidden == WhenHidden::StopAtFirst;
  Flips flips = Flips::Failed;
  if (sameDiracs)
  {
    flips = Kept->reweightByFlips(diracs, heights, stopAtFirst, certainlyHidden);
  }
  else if (Kept)
  {
    flips = Kept->moveByFlips(diracs, heights, stopAtFirst, certainlyHidden);
  }
  if (flips == Flips::HidesADirac && whenHidden != WhenHidden::FindAll)
  {
    // The kept triangulation, where the flips stopped, is still one of all the points.
    clearCells(n);
    Hidden.assign(n, 0);
    HiddenFace.assign(n, Triangle{ -1, -1, -1 });
    for (const auto& [i, face] : certainlyHidden)
    {
      Hidden[i] = 1;
      HiddenFace[i] = face;
    }
    HiddenCount = static_cast<int>(std::count(Hidden.begin(), Hidden.end(), 1));
    return nullptr;
  }
  if (flips != Flips::Regular)
  {
    std::vector<std::pair<WeightedPoint, int>> input;
    input.reserve(n);
    for (int i = 0; i < n; ++i)
    {
      input.emplace_back(
        WeightedPoint(BarePoint(diracs[i].x, diracs[i].y), weight(diracs[i], heights[i])), i);
    }
    fresh = std::make_unique<Triangulation>();
    fresh->rt.insert(input.begin(), input.end()); // spatially sorted insertion
    // A triangulation with hidden Diracs cannot be flipped into the next one; the last one,
    // where the flips stopped, still can (a Newton trial that hides Diracs is followed by a
    // shorter one from the same heights).
    if (!sameDiracs || fresh->rt.number_of_hidden_vertices() == 0)
    {
      Kept = std::move(fresh);
    }
  }
  return fresh ? fresh.get() : Kept.get();
}

void PowerDiagram::findHidden(const Triangulation& triangulation, int n)
{
  const Regular& rt = triangulation.rt;
  Hidden.assign(n, 1);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
  {
    Hidden[v->info()] = 0;
  }
  HiddenCount = static_cast<int>(std::count(Hidden.begin(), Hidden.end(), 1));
  HiddenFace.assign(n, Triangle{ -1, -1, -1 });
  for (auto v = rt.hidden_vertices_begin(); rt.dimension() == 2 && v != rt.hidden_vertices_end();
       ++v)
  {
    const auto f = v->face();
    if (f != Regular::Face_handle() && !rt.is_infinite(f))
    {
      HiddenFace[v->info()] = { f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() };
    }
  }
}

// Each power vertex is computed once and shared by its three cells, so that the clipped cells
// tile the domain exactly: with per-cell clipping, every cell rounds its own copy of a vertex
// and the overlaps and gaps (~1e-16 x edge length each) add up over 1e5 cells to more than
// 1e-10 of a cell's mass. Faces are numbered serially; their power vertices and the rings
// around the Diracs are then filled in parallel (serially they cost nearly as much as the
// insertion).
void PowerDiagram::buildPlanarCells(Triangulation& triangulation, int n)
{
  Regular& rt = triangulation.rt;
  const int faceCount = static_cast<int>(rt.number_of_faces());
  Triangles.resize(faceCount);
  int face = 0;
  for (auto f = rt.finite_faces_begin(); f != rt.finite_faces_end(); ++f)
  {
    f->info() = face;
    Triangles[face++] = { f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() };
  }
  auto infinite = rt.incident_faces(rt.infinite_vertex()), infiniteEnd = infinite;
  do
  {
    infinite->info() = -1;
  } while (++infinite != infiniteEnd);
  PowerVertices.resize(faceCount);
  PowerVertexCorrections.resize(faceCount);
#pragma omp parallel for schedule(static)
  for (int f = 0; f < faceCount; ++f)
  {
    const Triangle& t = Triangles[f];
    powerVertex(t[0], t[1], t[2], PowerVertices[f], PowerVertexCorrections[f]);
  }
  // Faces around each Dirac, counter-clockwise, and the neighbour across the edge that follows
  // each face (-1: the edge to the infinite vertex), in rows by Dirac id; visited in the
  // triangulation's own (spatially sorted) order, which keeps the circulators' memory accesses
  // local.
  std::vector<Regular::Vertex_handle> vertices;
  vertices.reserve(rt.number_of_vertices());
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v)
  {
    vertices.push_back(v);
  }
  const int vertexCount = static_cast<int>(vertices.size());
#pragma omp parallel for schedule(static)
  for (int k = 0; k < vertexCount; ++k)
  {
    Offsets[vertices[k]->info() + 1] = static_cast<int>(rt.degree(vertices[k]));
  }
  for (int i = 0; i < n; ++i)
  {
    Offsets[i + 1] += Offsets[i];
  }
  RingFace.resize(Offsets[n]);
  Adjacency.resize(Offsets[n]);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < vertexCount; ++k)
  {
    const auto v = vertices[k];
    int slot = Offsets[v->info()];
    auto fc = rt.incident_faces(v), done = fc;
    do
    {
      const auto next = fc->vertex(Regular::cw(fc->index(v)));
      RingFace[slot] = fc->info();
      Adjacency[slot] = rt.is_infinite(next) ? -1 : next->info();
      ++slot;
    } while (++fc != done);
  }
}

// Dimension 0 or 1 (one Dirac, or all on a line): adjacency from the finite edges; cells are
// cut out of a box by half-planes.
void PowerDiagram::buildLowDimensionalAdjacency(const Triangulation& triangulation, int n)
{
  const Regular& rt = triangulation.rt;
  std::vector<std::pair<int, int>> edges;
  for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e)
  {
    const int a = e->first->vertex(Regular::cw(e->second))->info();
    const int b = e->first->vertex(Regular::ccw(e->second))->info();
    edges.emplace_back(a, b);
  }
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
}

namespace
{
// Below this squared sine of the angle between two bisectors, their crossing is found in quad
// precision (powerVertex).
constexpr long double IllConditionedSine2 = 1e-3L;

// <x, y_a - y_b> = h_a - h_b and <x, y_a - y_c> = h_a - h_c with x = y_a + z (Cramer's rule),
// in the precision of T; the result rounded to double and what the rounding left out.
template <typename T>
void solveVertex(Vec2 ya, Vec2 yb, Vec2 yc, T hab, T hac, Vec2& rounded, Vec2& correction)
{
  const T ax = ya.x, ay = ya.y;
  const T ux = ax - T(yb.x), uy = ay - T(yb.y);
  const T vx = ax - T(yc.x), vy = ay - T(yc.y);
  const T r1 = hab - (ax * ux + ay * uy), r2 = hac - (ax * vx + ay * vy);
  const T det = ux * vy - uy * vx;
  const T x = ax + (r1 * vy - r2 * uy) / det, y = ay + (ux * r2 - vx * r1) / det;
  rounded = { static_cast<double>(x), static_cast<double>(y) };
  correction = { static_cast<double>(x - T(rounded.x)), static_cast<double>(y - T(rounded.y)) };
}
} // namespace

void PowerDiagram::powerVertex(int a, int b, int c, Vec2& rounded, Vec2& correction) const
{
  // In long double: the right-hand sides are differences of nearly equal heights. The base a is
  // the corner opposite the longest side, whose two bisectors cross at the widest angle.
  const Vec2 sab = Sites[a] - Sites[b], sbc = Sites[b] - Sites[c], sca = Sites[c] - Sites[a];
  const double ab = dot(sab, sab), bc = dot(sbc, sbc), ca = dot(sca, sca);
  if (ab >= bc && ab >= ca)
  {
    std::swap(a, c); // c is opposite ab
  }
  else if (ca >= bc && ca >= ab)
  {
    std::swap(a, b);
  }
  using LD = long double;
  const LD ux = LD(Sites[a].x) - Sites[b].x, uy = LD(Sites[a].y) - Sites[b].y;
  const LD vx = LD(Sites[a].x) - Sites[c].x, vy = LD(Sites[a].y) - Sites[c].y;
  const LD det = ux * vy - uy * vx;
  if (det * det >= IllConditionedSine2 * (ux * ux + uy * uy) * (vx * vx + vy * vy))
  {
    solveVertex<LD>(Sites[a], Sites[b], Sites[c], Heights[a] - Heights[b], Heights[a] - Heights[c],
      rounded, correction);
    return;
  }
  // Nearly parallel bisectors: the long double rounding of the right-hand sides, over the sine
  // of their angle, moves the vertex. At high contrast the tiny cells hugging the circle have
  // such vertices; from an arbitrary corner they moved by up to ~3e-15 and a cell's mass by up
  // to 3e-10 of itself (1e6 Diracs of contrast 1e6 stalled at 2e-10). Quad precision (GCC's
  // software __float128) for these few: ~0.2% of the vertices at 1e5 Diracs of contrast 1e4.
  solveVertex<Quad>(Sites[a], Sites[b], Sites[c], Heights[a].preciseDifference(Heights[b]),
    Heights[a].preciseDifference(Heights[c]), rounded, correction);
}

void PowerDiagram::cell(int i, Vec2 lo, Vec2 hi, PowerCell& out) const
{
  out.vertices.clear();
  out.neighbor.clear();
  out.correction.clear();
  if (Hidden[i])
  {
    return;
  }
  if (Dimension == 2)
  {
    ringCell(i, lo, hi, out);
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

void PowerDiagram::ringCell(int i, Vec2 lo, Vec2 hi, PowerCell& out) const
{
  const int begin = Offsets[i], m = Offsets[i + 1] - begin;
  const Vec2 center = 0.5 * (lo + hi);
  const double boxRadius = 0.5 * norm(hi - lo);
  // A nearly flat hull face (three boundary samples on one straight edge, collinear up to
  // rounding) has its power vertex ~1e14 away: kept, it would wreck every integral of the cell
  // to cancellation. Far outside the box, such a face is treated like an infinite one: inside
  // the box the cell is the same, bounded by the same two bisectors.
  const double farLimit = 64.0 * boxRadius + 1.0, farLimit2 = farLimit * farLimit;
  thread_local std::vector<char> far;
  far.resize(m);
  for (int k = 0; k < m; ++k)
  {
    const int f = RingFace[begin + k];
    const Vec2 d = f < 0 ? Vec2{ 0.0, 0.0 } : PowerVertices[f] - center;
    far[k] = f < 0 || d.x * d.x + d.y * d.y > farLimit2;
  }
  auto farFace = [&](int k) { return far[k] != 0; };
  // Walk from the first near face after a far or infinite one: the far and infinite faces of a
  // hull Dirac's (unbounded) cell then come last. More than one such run does not happen for a
  // regular triangulation (flat faces lie on the hull, next to its infinite faces); if it did,
  // only infinite faces are left out.
  int start = 0, runs = 0;
  for (int k = 0; k < m; ++k)
  {
    if (!farFace(k) && farFace((k + m - 1) % m))
    {
      start = runs++ == 0 ? k : start;
    }
  }
  bool useFar = runs == 1;
  bool unbounded = false;
  for (int k = 0; k < m && !useFar; ++k)
  {
    if (RingFace[begin + k] >= 0 && RingFace[begin + (k + m - 1) % m] < 0)
    {
      start = k;
      break;
    }
  }
  auto skipped = [&](int k) { return useFar ? farFace(k) : RingFace[begin + k] < 0; };
  for (int k = 0; k < m; ++k)
  {
    unbounded = unbounded || skipped(k);
  }
  for (int s = 0; s < m; ++s)
  {
    const int k = begin + (start + s) % m;
    if (!skipped((start + s) % m))
    {
      out.vertices.push_back(PowerVertices[RingFace[k]]);
      out.correction.push_back(PowerVertexCorrections[RingFace[k]]);
      out.neighbor.push_back(Adjacency[k]);
    }
  }
  if (!unbounded)
  {
    return;
  }
  // The cell leaves the last power vertex along the bisector with its last neighbour and comes
  // back to the first one along the bisector with the neighbour before the first face. Close it
  // with far points, counter-clockwise in steps below 60 degrees so that the closing edges stay
  // far outside the domain.
  auto direction = [&](int j)
  {
    const Vec2 d = Sites[i] - Sites[j];
    return (1.0 / norm(d)) * Vec2{ d.y, -d.x }; // the cell is on the left
  };
  const Vec2 last = out.vertices.back(), first = out.vertices.front();
  const Vec2 outDir = direction(out.neighbor.back());
  const int inNeighbor = Adjacency[begin + (start + m - 1) % m];
  const Vec2 inDir = direction(inNeighbor);
  // Each ray's far point depends only on its start (shared with the neighbour's cell) and the
  // box, so that both cells along it compute the same segment.
  const double farOut = 2.0 * (boxRadius + norm(last - center)) + 1.0;
  const double farIn = 2.0 * (boxRadius + norm(first - center)) + 1.0;
  const double a0 = std::atan2(outDir.y, outDir.x);
  double a1 = std::atan2(-inDir.y, -inDir.x);
  while (a1 <= a0)
  {
    a1 += 2.0 * 3.14159265358979323846;
  }
  out.vertices.push_back(last + farOut * outDir);
  out.neighbor.push_back(-1);
  // Rays that turn by more than half a turn meet (at a far face's vertex): no arc between them.
  const int steps =
    a1 - a0 > 3.14159265358979323846 ? 1 : static_cast<int>(std::ceil((a1 - a0) / 1.0));
  for (int t = 1; t < steps; ++t)
  {
    const double a = a0 + (a1 - a0) * t / steps;
    out.vertices.push_back(center + (2.0 * (farOut + farIn)) * Vec2{ std::cos(a), std::sin(a) });
    out.neighbor.push_back(-1);
  }
  out.vertices.push_back(first - farIn * inDir);
  out.neighbor.push_back(inNeighbor);
  out.correction.resize(out.vertices.size()); // the far points are exact as they are
}

} // namespace otparam
