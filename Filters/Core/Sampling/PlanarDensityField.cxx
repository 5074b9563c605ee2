#include "Sampling/PlanarDensityField.h"

#include "Common/DirectedEdges.h"
#include "Common/IdList.h"
#include "Common/SegmentCrossings.h"
#include "Sampling/Sampler.h"

#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace otparam
{
namespace
{

// Barycentric coordinates of x in the counter-clockwise triangle abc.
std::array<double, 3> barycentric(Vec2 x, Vec2 a, Vec2 b, Vec2 c)
{
  const double area = cross(b - a, c - a);
  const double la = cross(b - x, c - x) / area;
  const double lb = cross(c - x, a - x) / area;
  return { la, lb, 1.0 - la - lb };
}

bool inside(Vec2 x, Vec2 a, Vec2 b, Vec2 c, double slack)
{
  const auto l = barycentric(x, a, b, c);
  return l[0] >= -slack && l[1] >= -slack && l[2] >= -slack;
}
} // namespace

namespace
{
// What is wrong with the density values, or "".
std::string checkValues(const std::vector<double>& perPoint, const std::vector<double>& perTriangle)
{
  std::ostringstream msg;
  const std::vector<double>& values = perPoint.empty() ? perTriangle : perPoint;
  const char* where = perPoint.empty() ? "triangle" : "point";
  std::vector<size_t> bad;
  bool anyPositive = false;
  for (size_t i = 0; i < values.size(); ++i)
  {
    if (!std::isfinite(values[i]) || values[i] < 0.0)
    {
      bad.push_back(i);
    }
    anyPositive = anyPositive || values[i] > 0.0;
  }
  if (!bad.empty())
  {
    msg << "the density must be finite and non-negative, but it is " << values[bad.front()]
        << " at " << where << " id(s) " << idList(bad);
    return msg.str();
  }
  if (!anyPositive)
  {
    return "the density is zero everywhere";
  }
  return {};
}
} // namespace

std::unique_ptr<DensityField> DensityField::create(const std::vector<Vec2>& points,
  const std::vector<Triangle>& triangles, const std::vector<double>& perPoint,
  const std::vector<double>& perTriangle, std::string& error)
{
  error.clear();
  if (points.empty() || triangles.empty())
  {
    error = "the domain has no triangles";
    return nullptr;
  }
  if (perPoint.empty() == perTriangle.empty() ||
    (!perPoint.empty() && perPoint.size() != points.size()) ||
    (!perTriangle.empty() && perTriangle.size() != triangles.size()))
  {
    error = "the density needs exactly one value per point or one value per triangle";
    return nullptr;
  }
  error = checkValues(perPoint, perTriangle);
  if (!error.empty())
  {
    return nullptr;
  }
  std::unique_ptr<DensityField> field(new DensityField());
  field->Points = points;
  field->Triangles = triangles;
  field->PerPoint = relativeDensity(perPoint);
  field->PerTriangle = relativeDensity(perTriangle);
  error = field->orientAndIntegrate();
  if (error.empty())
  {
    field->keepSupport();
    error = field->checkNoOverlap();
  }
  if (error.empty() && !(field->Integral > 0.0))
  {
    error = "the density integrates to zero over the domain";
  }
  if (error.empty())
  {
    error = field->findShape();
  }
  if (!error.empty())
  {
    return nullptr;
  }
  field->buildSearchTrees();
  return field;
}

// Every triangle counter-clockwise, checked (ids, finite points, positive area); the integral
// of the density over all of them.
std::string DensityField::orientAndIntegrate()
{
  constexpr double LargestCoordinate = 1e100;
  const std::vector<Vec2>& points = this->Points;
  std::ostringstream msg;
  for (size_t t = 0; t < this->Triangles.size(); ++t)
  {
    Triangle& tri = this->Triangles[t];
    for (int v : tri)
    {
      if (v < 0 || static_cast<size_t>(v) >= points.size())
      {
        msg << "triangle " << t << " uses point id " << v << ", which does not exist";
        return msg.str();
      }
      if (!std::isfinite(points[v].x) || !std::isfinite(points[v].y))
      {
        msg << "point " << v << " has a NaN or infinite coordinate";
        return msg.str();
      }
      // The refinement squares lengths and multiplies areas: beyond this they overflow (a
      // point at 1e300 made CGAL's mesher step for minutes).
      if (std::max(std::abs(points[v].x), std::abs(points[v].y)) > LargestCoordinate)
      {
        msg << "point " << v << " has a coordinate of magnitude "
            << std::max(std::abs(points[v].x), std::abs(points[v].y)) << ", above "
            << LargestCoordinate << " (lengths are squared and would overflow): rescale the domain";
        return msg.str();
      }
    }
    double twice = cross(points[tri[1]] - points[tri[0]], points[tri[2]] - points[tri[0]]);
    if (twice < 0.0)
    {
      std::swap(tri[1], tri[2]);
      twice = -twice;
    }
    if (!(twice > 0.0))
    {
      msg << "triangle " << t << " has zero area";
      return msg.str();
    }
    const double area = 0.5 * twice;
    this->Integral += this->PerPoint.empty()
      ? area * this->PerTriangle[t]
      : area * (this->PerPoint[tri[0]] + this->PerPoint[tri[1]] + this->PerPoint[tri[2]]) / 3.0;
  }
  return {};
}

// The domain is the density's support: triangles where it vanishes identically are left out,
// so that a density that is zero on parts of the input gives a domain with holes or several
// components, sampled (boundaries included) only where there is mass.
void DensityField::keepSupport()
{
  const std::vector<Vec2>& points = this->Points;
  const std::vector<double> perPoint = this->PerPoint, perTriangle = this->PerTriangle;
  std::vector<Triangle> support;
  std::vector<double> supportValues;
  for (size_t t = 0; t < this->Triangles.size(); ++t)
  {
    const Triangle& tri = this->Triangles[t];
    const bool zero = perPoint.empty()
      ? perTriangle[t] == 0.0
      : perPoint[tri[0]] == 0.0 && perPoint[tri[1]] == 0.0 && perPoint[tri[2]] == 0.0;
    if (!zero)
    {
      support.push_back(tri);
      if (!perTriangle.empty())
      {
        supportValues.push_back(perTriangle[t]);
      }
    }
  }
  this->Triangles = std::move(support);
  if (!perTriangle.empty())
  {
    this->PerTriangle = std::move(supportValues);
  }
  for (const Triangle& tri : this->Triangles)
  {
    this->Area += 0.5 * cross(points[tri[1]] - points[tri[0]], points[tri[2]] - points[tri[0]]);
  }
}

// Once every triangle is counter-clockwise, a tiling uses each directed edge at most once: a
// repeated one means overlapping triangles (which the area check below could miss when a hole
// has the same area).
std::string DensityField::checkNoOverlap() const
{
  // Counting-sorted (Common/DirectedEdges.h): 1.09M points, 0.51 -> 0.1 s.
  const std::vector<std::pair<std::uint64_t, int>> edges = sortedDirectedEdges(this->Triangles);
  for (size_t e = 1; e < edges.size(); ++e)
  {
    if (edges[e].first == edges[e - 1].first)
    {
      const int t = edges[e].second / 3, k = edges[e].second % 3;
      std::ostringstream msg;
      msg << "triangles " << edges[e - 1].second / 3 << " and " << t
          << " overlap (both have the edge from point " << this->Triangles[t][k] << " to point "
          << this->Triangles[t][(k + 1) % 3] << " on the same side)";
      return msg.str();
    }
  }
  return {};
}

// The points the support uses.
std::vector<char> DensityField::usedPoints() const
{
  std::vector<char> used(this->Points.size(), 0);
  for (const Triangle& tri : this->Triangles)
  {
    for (int v : tri)
    {
      used[v] = 1;
    }
  }
  return used;
}

// The convex hull, whether the support tiles it (convex), its boundary loops otherwise, and
// whether it is the unit disk.
std::string DensityField::findShape()
{
  const std::vector<Vec2>& points = this->Points;
  const std::vector<char> used = this->usedPoints();
  std::string error;
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Traits =
    CGAL::Convex_hull_traits_adapter_2<K, CGAL::Pointer_property_map<K::Point_2>::type>;
  std::vector<K::Point_2> cgalPoints;
  std::vector<std::size_t> usedIds, hull;
  for (size_t i = 0; i < points.size(); ++i)
  {
    cgalPoints.emplace_back(points[i].x, points[i].y);
    if (used[i])
    {
      usedIds.push_back(i);
    }
  }
  CGAL::convex_hull_2(usedIds.begin(), usedIds.end(), std::back_inserter(hull),
    Traits(CGAL::make_property_map(cgalPoints)));
  double hullArea = 0.0;
  for (size_t k = 0; k < hull.size(); ++k)
  {
    const Vec2 a = points[hull[k]], b = points[hull[(k + 1) % hull.size()]];
    this->Hull.push_back(a);
    this->HullIds.push_back(static_cast<int>(hull[k]));
    hullArea += 0.5 * cross(a, b);
  }
  // Triangles that tile their convex hull exactly make a convex domain; anything else has holes,
  // several components or concavities, and its boundary is made of the loops of edges that
  // belong to one triangle only.
  this->Convex = std::abs(hullArea - this->Area) <= 1e-9 * hullArea;
  if (this->Convex)
  {
    this->Loops = { this->Hull };
  }
  else if (!this->traceBoundaryLoops(error))
  {
    return error;
  }
  this->UnitDisk = this->Convex;
  for (const Vec2& p : this->Hull)
  {
    // 1e-6: a disk whose points were stored in single precision (VTK's default) is still one.
    this->UnitDisk = this->UnitDisk && std::abs(norm(p) - 1.0) <= 1e-6;
  }
  return {};
}

// Box trees over the triangles and, for a density per point, over the used points.
void DensityField::buildSearchTrees()
{
  const std::vector<Vec2>& points = this->Points;
  const std::vector<char> used = this->usedPoints();
  std::vector<BoxTree::Item> triangleBoxes(this->Triangles.size());
  for (size_t t = 0; t < this->Triangles.size(); ++t)
  {
    const Triangle& tri = this->Triangles[t];
    BoxTree::Item& box = triangleBoxes[t];
    box.lo = box.hi = points[tri[0]];
    for (int v : tri)
    {
      box.lo = { std::min(box.lo.x, points[v].x), std::min(box.lo.y, points[v].y) };
      box.hi = { std::max(box.hi.x, points[v].x), std::max(box.hi.y, points[v].y) };
    }
    box.value = this->PerTriangle.empty() ? 0.0 : this->PerTriangle[t];
  }
  this->TriangleTree = BoxTree(std::move(triangleBoxes));
  this->CentroidBySlot.clear();
  if (this->PerTriangle.empty())
  {
    std::vector<BoxTree::Item> pointBoxes;
    for (size_t i = 0; i < points.size(); ++i)
    {
      if (used[i])
      {
        pointBoxes.push_back({ points[i], points[i], this->PerPoint[i] });
      }
    }
    this->PointTree = BoxTree(std::move(pointBoxes));
  }
  else
  {
    this->CentroidBySlot.resize(this->Triangles.size());
    for (size_t slot = 0; slot < this->Triangles.size(); ++slot)
    {
      const Triangle& tri = this->Triangles[this->TriangleTree.itemAt(static_cast<int>(slot))];
      this->CentroidBySlot[slot] = (1.0 / 3.0) * (points[tri[0]] + points[tri[1]] + points[tri[2]]);
    }
  }
  this->BoundaryEdges.clear();
  std::vector<BoxTree::Item> edgeBoxes;
  for (const std::vector<Vec2>& loop : this->Loops)
  {
    for (size_t k = 0; k < loop.size(); ++k)
    {
      const Vec2 a = loop[k], b = loop[(k + 1) % loop.size()];
      this->BoundaryEdges.emplace_back(a, b);
      edgeBoxes.push_back({ { std::min(a.x, b.x), std::min(a.y, b.y) },
        { std::max(a.x, b.x), std::max(a.y, b.y) }, 0.0 });
    }
  }
  this->BoundaryTree = BoxTree(std::move(edgeBoxes));
}

// Measured (2026-11-29, --repeat 3): on otparam_sampler_benchmark's even 136k-triangle mesh the
// walk saves 5% at 2e4 samples, 15% at 1e5 and 20% at 2e5; on the conformal densities of
// hand_choi_53k and bust_aphrodite_56k (106k and 112k triangles, crowded) at 5000 and 5e4
// samples it was within this machine's noise either way, while its grid and neighbours cost
// 3-6 ms to build. So the walk waits for samplings at least as numerous as the triangles.
void DensityField::prepareForQueries(long long expectedSamples) const
{
  if (!this->Walk.built() && expectedSamples >= static_cast<long long>(this->Triangles.size()))
  {
    this->Walk = TriangleWalk(this->Points, this->Triangles);
  }
}

int DensityField::locate(Vec2 x) const
{
  const int walked = this->Walk.locate(x, this->Points, this->Triangles);
  return walked >= 0 ? walked : this->search(x);
}

// The first triangle in the tree's order whose barycentric coordinates at x are all >= -1e-12,
// else -1e-9 (points on the boundary, rounded off it).
int DensityField::search(Vec2 x) const
{
  for (double slack : { 1e-12, 1e-9 })
  {
    int found = -1;
    TriangleTree.findContaining(x,
      [&](int t)
      {
        const Triangle& tri = Triangles[t];
        if (inside(x, Points[tri[0]], Points[tri[1]], Points[tri[2]], slack))
        {
          found = t;
          return true;
        }
        return false;
      });
    if (found >= 0)
    {
      return found;
    }
  }
  return -1;
}

bool DensityField::traceBoundaryLoops(std::string& error)
{
  // Directed edges of counter-clockwise triangles whose twin is absent: the outer boundaries
  // run counter-clockwise, the holes clockwise.
  std::vector<std::pair<int, int>> directed;
  for (const Triangle& tri : Triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      directed.emplace_back(tri[k], tri[(k + 1) % 3]);
    }
  }
  std::sort(directed.begin(), directed.end());
  std::unordered_map<int, int> next; // boundary vertex -> the next one along its loop
  for (const auto& [from, to] : directed)
  {
    if (std::binary_search(directed.begin(), directed.end(), std::make_pair(to, from)))
    {
      continue;
    }
    if (!next.emplace(from, to).second)
    {
      std::ostringstream msg;
      msg << "the domain's boundary touches itself at point " << from
          << " (two boundary loops or components meet in one point); separate them";
      error = msg.str();
      return false;
    }
  }
  if (!this->checkLoopsDoNotCross(next, error))
  {
    return false;
  }
  std::unordered_set<int> done;
  for (const auto& start : next)
  {
    if (done.count(start.first))
    {
      continue;
    }
    std::vector<Vec2> loop;
    int v = start.first;
    do
    {
      done.insert(v);
      loop.push_back(Points[v]);
      const auto it = next.find(v);
      if (it == next.end())
      {
        error = "the domain's boundary is not made of closed loops (inconsistent triangles)";
        return false;
      }
      v = it->second;
    } while (v != start.first && loop.size() <= next.size());
    Loops.push_back(std::move(loop));
  }
  // A fixed order (the map's is not): the loop with the lowest first point first.
  std::sort(Loops.begin(), Loops.end(),
    [](const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
      return a.front().x < b.front().x || (a.front().x == b.front().x && a.front().y < b.front().y);
    });
  return true;
}

// The boundary loops become the mesher's constraints, which must not cross: CGAL's mesher
// crashed on a domain whose far-apart triangles overlapped, though every triangle and every
// edge was sound (the unfolded part of a crowded finger's map).
bool DensityField::checkLoopsDoNotCross(
  const std::unordered_map<int, int>& next, std::string& error) const
{
  std::vector<std::pair<int, int>> edges(next.begin(), next.end());
  std::sort(edges.begin(), edges.end()); // a fixed order: the map's is not
  const std::vector<std::pair<int, int>> crossings = crossingSegments(this->Points, edges);
  if (crossings.empty())
  {
    return true;
  }
  const auto [first, second] = crossings.front();
  std::ostringstream msg;
  msg << "the domain's boundary crosses itself: its edge from point " << edges[first].first
      << " to point " << edges[first].second << " meets its edge from point " << edges[second].first
      << " to point " << edges[second].second << " (triangles overlap there)";
  error = msg.str();
  return false;
}

// A search over the boundary's edges, not a scan: points outside the domain are common in the
// sampler's refinement near the circle, and a scan of every edge took ~0.15 s of the sampling at
// 273k points. The same point as the scan in the loops' order (the lowest edge among equals).
Vec2 DensityField::nearestBoundaryPoint(Vec2 x) const
{
  const int edge = this->BoundaryTree.nearest(x,
    [&](int e)
    {
      const auto& [a, b] = this->BoundaryEdges[e];
      return norm(closestOnSegment(x, a, b) - x);
    });
  if (edge < 0)
  {
    return Hull.front();
  }
  const auto& [a, b] = this->BoundaryEdges[edge];
  return closestOnSegment(x, a, b);
}

bool DensityField::contains(Vec2 x) const
{
  return locate(x) >= 0;
}

double DensityField::value(Vec2 x) const
{
  return this->valueAt(x, this->locate(x));
}

double DensityField::valueAt(Vec2 x, int t) const
{
  if (t < 0)
  {
    // Outside (e.g. between the inscribed polygon and the circle): use the nearest boundary
    // point of the domain.
    x = nearestBoundaryPoint(x);
    t = locate(x);
    if (t < 0)
    {
      return 0.0; // unreachable for a tiling; keeps the caller well-defined
    }
  }
  return valueIn(static_cast<std::size_t>(t), x);
}

double DensityField::valueIn(std::size_t t, Vec2 x) const
{
  if (!PerTriangle.empty())
  {
    return PerTriangle[t];
  }
  const Triangle& tri = Triangles[t];
  const auto l = barycentric(x, Points[tri[0]], Points[tri[1]], Points[tri[2]]);
  return std::max(0.0, l[0] * PerPoint[tri[0]] + l[1] * PerPoint[tri[1]] + l[2] * PerPoint[tri[2]]);
}

double DensityField::valueAtCentroid(std::size_t t) const
{
  const Triangle& tri = Triangles[t];
  return valueIn(t, (1.0 / 3.0) * (Points[tri[0]] + Points[tri[1]] + Points[tri[2]]));
}

// Above this ratio of abc's area to that of the triangle holding its centre, maximizeNearby
// leaves the maximum to the box tree: on hand_choi_53k's crowded conformal density a search
// of the triangles around gave up at its 48 triangles for most refinement triangles, and the
// sampler took 0.32 s instead of 0.17.
constexpr double NearbyAreaRatio = 6.0;

// maxInsideTriangle's maximum over the points or triangle centroids inside abc, found by the
// triangles around `seed` (which holds abc's centre) when few of them meet abc: the largest of
// the same values the box tree's search takes (a maximum, whatever the order), without the
// search. False, `largest` untouched, when there are more or abc leaves the triangles.
bool DensityField::maximizeNearby(int seed, Vec2 a, Vec2 b, Vec2 c, double& largest) const
{
  if (!this->Walk.built())
  {
    return false;
  }
  const Triangle& held = this->Triangles[seed];
  if (std::abs(cross(b - a, c - a)) > NearbyAreaRatio *
      std::abs(cross(this->Points[held[1]] - this->Points[held[0]],
        this->Points[held[2]] - this->Points[held[0]])))
  {
    return false; // many triangles to visit: the tree's pruning does better
  }
  double found = largest;
  const bool all = this->Walk.visitMeeting(seed, a, b, c, this->Points, this->Triangles,
    [&](int t)
    {
      const Triangle& tri = this->Triangles[t];
      if (!this->PerTriangle.empty())
      {
        const Vec2 centroid =
          (1.0 / 3.0) * (this->Points[tri[0]] + this->Points[tri[1]] + this->Points[tri[2]]);
        if (inside(centroid, a, b, c, 0.0))
        {
          found = std::max(found, this->PerTriangle[t]);
        }
        return;
      }
      for (int v : tri)
      {
        if (inside(this->Points[v], a, b, c, 0.0))
        {
          found = std::max(found, this->PerPoint[v]);
        }
      }
    });
  if (all)
  {
    largest = found;
  }
  return all;
}

double DensityField::maxInsideTriangle(Vec2 a, Vec2 b, Vec2 c, double atLeast) const
{
  if (cross(b - a, c - a) < 0.0)
  {
    std::swap(b, c);
  }
  const Vec2 centre = (1.0 / 3.0) * (a + b + c);
  const int seed = this->locate(centre);
  double largest = std::max(atLeast, this->valueAt(centre, seed));
  if (seed >= 0 && this->maximizeNearby(seed, a, b, c, largest))
  {
    return largest;
  }
  const Vec2 lo = { std::min({ a.x, b.x, c.x }), std::min({ a.y, b.y, c.y }) };
  const Vec2 hi = { std::max({ a.x, b.x, c.x }), std::max({ a.y, b.y, c.y }) };
  // A box lies outside the (counter-clockwise) triangle when even its corner furthest to the
  // left of some edge is on the edge's right, by more than rounding.
  const auto mayMeet = [&](Vec2 boxLo, Vec2 boxHi)
  {
    for (const auto& [p, q] : { std::pair{ a, b }, std::pair{ b, c }, std::pair{ c, a } })
    {
      const Vec2 d = q - p;
      const Vec2 corner = { d.y > 0.0 ? boxLo.x : boxHi.x, d.x > 0.0 ? boxHi.y : boxLo.y };
      if (rightOfBeyondRounding(p, q, corner))
      {
        return false;
      }
    }
    return true;
  };
  if (PerTriangle.empty())
  {
    PointTree.maximize(
      lo, hi, largest,
      [&](int slot, double& best)
      {
        const BoxTree::Item& point = PointTree.box(slot); // a box of one point
        if (inside(point.lo, a, b, c, 0.0))
        {
          best = point.value;
        }
      },
      mayMeet);
  }
  else
  {
    TriangleTree.maximize(
      lo, hi, largest,
      [&](int slot, double& best)
      {
        if (inside(CentroidBySlot[slot], a, b, c, 0.0))
        {
          best = TriangleTree.box(slot).value;
        }
      },
      mayMeet);
  }
  return largest;
}

std::unique_ptr<SourceMeasure> DensityField::makeSource(std::string& error) const
{
  // Every triangle gets its own three points (piecewise-constant densities need that; for
  // piecewise-linear ones it costs memory only).
  std::vector<Vec2> points;
  std::vector<Triangle> triangles;
  std::vector<double> density;
  points.reserve(3 * Triangles.size());
  density.reserve(3 * Triangles.size());
  auto add = [&](Vec2 a, Vec2 b, Vec2 c, double fa, double fb, double fc)
  {
    const int first = static_cast<int>(points.size());
    points.insert(points.end(), { a, b, c });
    density.insert(density.end(), { fa, fb, fc });
    triangles.push_back({ first, first + 1, first + 2 });
  };
  std::vector<Vec2> hullCandidates = Hull; // the domain's hull: Hull, and the disk's apexes
  for (size_t t = 0; t < Triangles.size(); ++t)
  {
    const Triangle& tri = Triangles[t];
    if (PerTriangle.empty())
    {
      add(Points[tri[0]], Points[tri[1]], Points[tri[2]], PerPoint[tri[0]], PerPoint[tri[1]],
        PerPoint[tri[2]]);
    }
    else
    {
      add(Points[tri[0]], Points[tri[1]], Points[tri[2]], PerTriangle[t], PerTriangle[t],
        PerTriangle[t]);
    }
  }
  if (UnitDisk)
  {
    for (size_t k = 0; k < Hull.size(); ++k)
    {
      const size_t next = (k + 1) % Hull.size();
      const Vec2 a = Hull[k], b = Hull[next];
      const double fa = value(a), fb = value(b);
      // Where the tangents at a and b meet (p.a = |a|^2, p.b = |b|^2: exact also for points
      // stored in single precision, whose radii differ from 1 by ~1e-7).
      const double det = cross(a, b);
      const Vec2 apex = { (dot(a, a) * b.y - dot(b, b) * a.y) / det,
        (dot(b, b) * a.x - dot(a, a) * b.x) / det };
      add(a, apex, b, fa, 0.5 * (fa + fb), fb);
      hullCandidates.push_back(apex);
    }
  }
  return makeTriangulatedSource(
    points, triangles, density, error, true, !Convex, &hullCandidates);
}

} // namespace otparam
