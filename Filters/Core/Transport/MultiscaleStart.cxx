#include "Transport/MultiscaleStart.h"

#include "Common/PowerTestKernel.h"
#include "Transport/SemiDiscreteOT.h"

#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>

namespace otparam
{
namespace
{
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using RK = PowerTestKernel;
using RegularVb = CGAL::Triangulation_vertex_base_with_info_2<int, RK,
  CGAL::Regular_triangulation_vertex_base_2<RK>>;
using RegularTds =
  CGAL::Triangulation_data_structure_2<RegularVb, CGAL::Regular_triangulation_face_base_2<RK>>;
using Regular = CGAL::Regular_triangulation_2<RK, RegularTds>;

// A walk-friendly order: Diracs by rows of a grid, alternating direction (boustrophedon), so
// that consecutive point locations start next to each other.
std::vector<int> rowOrder(const std::vector<Vec2>& points)
{
  Vec2 lo{ INFINITY, INFINITY }, hi{ -INFINITY, -INFINITY };
  for (const Vec2& p : points)
  {
    lo = { std::min(lo.x, p.x), std::min(lo.y, p.y) };
    hi = { std::max(hi.x, p.x), std::max(hi.y, p.y) };
  }
  const double rows = std::max(1.0, std::sqrt(static_cast<double>(points.size())) / 2.0);
  const double height = std::max(hi.y - lo.y, 1e-300) / rows;
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i)
  {
    const long row = std::lround(std::floor((points[i].y - lo.y) / height));
    return std::make_pair(row, (row % 2 ? -1.0 : 1.0) * points[i].x);
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  return order;
}

constexpr double Pi = 3.14159265358979323846;

// Barycentric coordinates of y in the triangle (a, b, c).
std::array<double, 3> barycentric(Vec2 y, Vec2 a, Vec2 b, Vec2 c)
{
  const double area = cross(b - a, c - a);
  const double lb = cross(c - y, a - y) / area, lc = cross(a - y, b - y) / area;
  return { 1.0 - lb - lc, lb, lc };
}

// Mean density of the source, for sizing the cells given back to hidden Diracs: its mass over
// the area of the ellipse inscribed in its box (exact for the disk).
double meanDensity(const SourceMeasure& source)
{
  Vec2 lo, hi;
  source.bounds(lo, hi);
  const double area = 0.25 * Pi * (hi.x - lo.x) * (hi.y - lo.y);
  return area > 0.0 ? source.totalMass() / area : 1.0;
}

// Calls visit(x) for each point x where the segment [a, b] crosses the unit circle.
template <typename Visit>
void circleCrossings(Vec2 a, Vec2 b, Visit&& visit)
{
  // |a + t (b - a)| = 1 for t in [0, 1].
  const Vec2 e = b - a;
  const double qa = dot(e, e), qb = 2.0 * dot(a, e), qc = dot(a, a) - 1.0;
  const double disc = qb * qb - 4.0 * qa * qc;
  if (qa > 0.0 && disc >= 0.0)
  {
    for (const double sign : { -1.0, 1.0 })
    {
      const double t = (-qb + sign * std::sqrt(disc)) / (2.0 * qa);
      if (t >= 0.0 && t <= 1.0)
      {
        visit(a + t * e);
      }
    }
  }
}

// The point of the unit circle in the direction of slope, when it lies in the convex polygon
// (counter-clockwise): there <x, slope> is largest over the circle.
bool circlePointInCell(const std::vector<Vec2>& polygon, Vec2 slope, Vec2& point)
{
  const double length = norm(slope);
  const size_t m = polygon.size();
  if (!(length > 0.0) || m < 3)
  {
    return false;
  }
  point = (1.0 / length) * slope;
  for (size_t k = 0; k < m; ++k)
  {
    if (cross(polygon[(k + 1) % m] - polygon[k], point - polygon[k]) < 0.0)
    {
      return false;
    }
  }
  return true;
}

// The dual potential psi = phi^* of a semi-discrete transport plan from the uniform unit disk:
// phi(x) = max_c <x, y_c> - h_c on the disk, so
//   psi(y) = max over x in the disk of <x, y> - phi(x) = max over x in the disk of min_c
//            (h_c + <x, y - y_c>).
// It is convex, finite everywhere and psi(y_c) = h_c for every Dirac with a cell. Inside a face of
// the regular triangulation whose power vertex v lies in the disk, the maximum is at v and psi
// is the face's linear interpolation of the heights; otherwise the maximum lies on the circle,
// on the arc of one of the cells that reach it.
// Written by hand: CGAL's regular triangulation gives the lower hull, but not this conjugate
// restricted to a disk.
class DiskDualPotential
{
public:
  using Hint = Regular::Face_handle;

  // Returns false when the Diracs do not span the plane.
  bool build(const std::vector<Vec2>& diracs, const std::vector<double>& heights)
  {
    Diracs = diracs;
    Heights = heights;
    const int n = static_cast<int>(diracs.size());
    std::vector<std::pair<Regular::Weighted_point, int>> input;
    input.reserve(n);
    for (int c = 0; c < n; ++c)
    {
      const Vec2 y = diracs[c];
      input.emplace_back(
        Regular::Weighted_point(Regular::Bare_point(y.x, y.y), dot(y, y) - 2.0 * heights[c]), c);
    }
    Triangulation.insert(input.begin(), input.end());
    if (Triangulation.dimension() < 2)
    {
      return false;
    }
    PowerDiagram diagram;
    diagram.build(diracs, std::vector<Height>(heights.begin(), heights.end()));
    PowerCell cell;
    std::vector<double> angles;
    Vec2 unused;
    for (int c = 0; c < n; ++c)
    {
      diagram.cell(c, Vec2{ -1.1, -1.1 }, Vec2{ 1.1, 1.1 }, cell);
      const size_t m = cell.vertices.size();
      angles.clear();
      for (size_t k = 0; k < m; ++k)
      {
        circleCrossings(cell.vertices[k], cell.vertices[(k + 1) % m],
          [&](Vec2 x) { angles.push_back(angleOf(x)); });
      }
      if (m < 3)
      {
        continue;
      }
      if (angles.empty())
      {
        // Only a cell holding the whole disk meets the circle without crossing it.
        if (circlePointInCell(cell.vertices, Vec2{ 1.0, 0.0 }, unused))
        {
          Arcs.push_back(makeArc(c, 0.0, 2.0 * Pi));
        }
        continue;
      }
      // The circle between consecutive crossings lies wholly inside or outside the cell.
      std::sort(angles.begin(), angles.end());
      for (size_t k = 0; k < angles.size(); ++k)
      {
        const double from = angles[k];
        const double length =
          k + 1 < angles.size() ? angles[k + 1] - from : angles[0] + 2.0 * Pi - from;
        const double mid = from + 0.5 * length;
        if (length > 0.0 &&
          circlePointInCell(cell.vertices, Vec2{ std::cos(mid), std::sin(mid) }, unused))
        {
          Arcs.push_back(makeArc(c, from, length));
        }
      }
    }
    std::sort(Arcs.begin(), Arcs.end(), [](const Arc& a, const Arc& b) { return a.from < b.from; });
    const size_t blockSize =
      std::max<size_t>(1, static_cast<size_t>(std::sqrt(static_cast<double>(Arcs.size()))));
    for (size_t begin = 0; begin < Arcs.size(); begin += blockSize)
    {
      Block block{ begin, std::min(Arcs.size(), begin + blockSize), Arcs[begin].from, 0.0,
        INFINITY };
      for (size_t k = block.begin; k < block.end; ++k)
      {
        block.length = std::max(block.length, Arcs[k].from + Arcs[k].length - block.from);
        block.minPhi = std::min(block.minPhi, Arcs[k].minPhi);
      }
      Blocks.push_back(block);
    }
    return true;
  }

  // Thread-safe (CGAL's point location only reads the triangulation); hint: the face found last
  // by this thread.
  long double operator()(Vec2 y, Hint& hint) const
  {
    hint = Triangulation.locate(Regular::Weighted_point(Regular::Bare_point(y.x, y.y), 0.0), hint);
    if (!Triangulation.is_infinite(hint))
    {
      const int a = hint->vertex(0)->info(), b = hint->vertex(1)->info(),
                c = hint->vertex(2)->info();
      const Vec2 u = Diracs[b] - Diracs[a], w = Diracs[c] - Diracs[a];
      const double du = Heights[b] - Heights[a], dw = Heights[c] - Heights[a];
      const double det = cross(u, w);
      // <v, u> = du, <v, w> = dw.
      const Vec2 v{ (du * w.y - dw * u.y) / det, (u.x * dw - w.x * du) / det };
      if (dot(v, v) <= 1.0)
      {
        const auto l = barycentric(y, Diracs[a], Diracs[b], Diracs[c]);
        return l[0] * static_cast<long double>(Heights[a]) +
          l[1] * static_cast<long double>(Heights[b]) + l[2] * static_cast<long double>(Heights[c]);
      }
    }
    else
    {
      hint = Hint(); // walks start from finite faces
    }
    // On the circle, max over the cells' arcs of h_c + <x, y - y_c> = <x, y> - phi(x), searched
    // block by block (~sqrt(#arcs) arcs each): a block can only win where the largest <x, y> over
    // its angles minus the least phi on its arcs beats the best value found so far. The block
    // around the direction of y, where the maximum usually is, goes first (a loop over all
    // arcs dominated the start at 1e6 Diracs).
    const double direction = angleOf(y);
    long double best = -INFINITY;
    auto searchBlock = [&](const Block& block)
    {
      for (size_t k = block.begin; k < block.end; ++k)
      {
        const Arc& arc = Arcs[k];
        const Vec2 slope = y - Diracs[arc.c];
        double largest = std::max(dot(arc.fromPoint, slope), dot(arc.toPoint, slope));
        if (onArc(angleOf(slope), arc.from, arc.length))
        {
          largest = norm(slope);
        }
        best = std::max(best, static_cast<long double>(Heights[arc.c]) + largest);
      }
    };
    size_t first = 0;
    for (size_t b = 0; b < Blocks.size(); ++b)
    {
      if (onArc(direction, Blocks[b].from, Blocks[b].length))
      {
        first = b;
        break;
      }
    }
    if (!Blocks.empty())
    {
      searchBlock(Blocks[first]);
    }
    for (size_t b = 0; b < Blocks.size(); ++b)
    {
      const Block& block = Blocks[b];
      if (b == first)
      {
        continue;
      }
      const double largestDot = onArc(direction, block.from, block.length)
        ? norm(y)
        : std::max(dot(y, pointAt(block.from)), dot(y, pointAt(block.from + block.length)));
      if (static_cast<long double>(largestDot - block.minPhi) > best)
      {
        searchBlock(block);
      }
    }
    return best;
  }

private:
  // The part of cell c on the circle from angle `from`, counter-clockwise over `length`.
  struct Arc
  {
    int c;
    double from, length;
    Vec2 fromPoint, toPoint;
    double minPhi; // least phi(x) = <x, y_c> - h_c on the arc
  };
  struct Block
  {
    size_t begin, end; // its arcs
    double from, length, minPhi;
  };

  static double angleOf(Vec2 v)
  {
    const double a = std::atan2(v.y, v.x);
    return a < 0.0 ? a + 2.0 * Pi : a;
  }
  static Vec2 pointAt(double angle) { return { std::cos(angle), std::sin(angle) }; }
  static bool onArc(double angle, double from, double length)
  {
    double d = angle - from;
    d -= 2.0 * Pi * std::floor(d / (2.0 * Pi));
    return d <= length;
  }

  Arc makeArc(int c, double from, double length) const
  {
    Arc arc{ c, from, length, pointAt(from), pointAt(from + length), 0.0 };
    const Vec2 yc = Diracs[c];
    arc.minPhi = std::min(dot(arc.fromPoint, yc), dot(arc.toPoint, yc));
    if (onArc(angleOf(Vec2{ -yc.x, -yc.y }), from, length))
    {
      arc.minPhi = -norm(yc);
    }
    arc.minPhi -= Heights[c];
    return arc;
  }

  std::vector<Vec2> Diracs;
  std::vector<double> Heights;
  Regular Triangulation;
  std::vector<Arc> Arcs;
  std::vector<Block> Blocks;
};
} // namespace

namespace
{
std::vector<int> coarseSubset(const std::vector<Vec2>& diracs)
{
  const int n = static_cast<int>(diracs.size());
  // The Diracs' convex hull is in the coarse set, so that the coarse cells reach as far out on
  // the circle as the fine ones must.
  std::vector<int> ids = randomSixth(n);
  {
    std::vector<K::Point_2> points;
    points.reserve(n);
    for (const Vec2& y : diracs)
    {
      points.emplace_back(y.x, y.y);
    }
    std::vector<int> hull;
    std::vector<int> all(n);
    std::iota(all.begin(), all.end(), 0);
    CGAL::convex_hull_2(all.begin(), all.end(), std::back_inserter(hull),
      CGAL::Convex_hull_traits_adapter_2<K, CGAL::Pointer_property_map<K::Point_2>::type>(
        CGAL::make_property_map(points)));
    ids.insert(ids.end(), hull.begin(), hull.end());
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

// The stencil's scale (stencilSpacing) from the coarse Delaunay edges.
double coarseSpacing(const Delaunay& dt, const std::vector<Vec2>& coarseDiracs)
{
  const int coarseCount = static_cast<int>(coarseDiracs.size());
  std::vector<double> edgeLengths;
  edgeLengths.reserve(3 * static_cast<size_t>(coarseCount));
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e)
  {
    const int a = e->first->vertex(Delaunay::cw(e->second))->info();
    const int b = e->first->vertex(Delaunay::ccw(e->second))->info();
    edgeLengths.push_back(norm(coarseDiracs[a] - coarseDiracs[b]));
  }
  return stencilSpacing(edgeLengths);
}

// Each fine Dirac's mass goes to its nearest coarse Dirac (walked in row order).
std::vector<double> coarseMasses(const Delaunay& dt, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, const std::vector<int>& order, int coarseCount)
{
  std::vector<double> coarseMass(coarseCount, 0.0);
  Delaunay::Vertex_handle nearest;
  for (const int i : order)
  {
    const Delaunay::Point p(diracs[i].x, diracs[i].y);
    nearest = dt.nearest_vertex(
      p, nearest == Delaunay::Vertex_handle() ? Delaunay::Face_handle() : nearest->face());
    coarseMass[nearest->info()] += nu[i];
  }
  return coarseMass;
}

void smoothedHeights(const DiskDualPotential& psi, const std::vector<Vec2>& diracs,
  const std::vector<int>& order, double medianEdge, std::vector<Height>& h)
{
  const int n = static_cast<int>(diracs.size());
  // Fine heights: psi of the coarse solution, averaged over a small stencil around each fine
  // Dirac. The coarse psi is piecewise linear where the coarse cells lie inside the disk: at its
  // own values the fine Diracs would sit on the coarse lower hull with empty cells. A positive
  // average of translates of a convex function is convex, and this one is curved wherever a
  // crease of psi passes within the stencil, so that every fine Dirac is on the lower hull (none
  // hidden) with a cell of about the right size: grad psi averaged over the stencil sends the
  // fine Diracs between their coarse neighbours' cells. Measured, 1e5 Diracs of contrast 1e4:
  // quadratic models of psi (Jacobians fitted to the coarse centroids) blended over the coarse
  // triangles hid 36% of the fine Diracs, and the repaired start needed 19 Newton iterations;
  // this one hides none, its largest relative mass error is 14 instead of 400, and the fine
  // level needs 8 iterations.
  // The stencil (MultiscaleStart.h): its centre and two hexagons. The small share of |y|^2 / 2
  // (the Voronoi diagram) is curvature everywhere.
  std::vector<std::pair<Vec2, double>> stencil{ { Vec2{ 0.0, 0.0 }, 1.0 } };
  for (int k = 0; k < 6; ++k)
  {
    const double angle = k * Pi / 3.0;
    stencil.push_back(
      { 0.5 * Vec2{ std::cos(angle + Pi / 6.0), std::sin(angle + Pi / 6.0) }, StencilInnerWeight });
    stencil.push_back({ Vec2{ std::cos(angle), std::sin(angle) }, StencilOuterWeight });
  }
  double totalWeight = 0.0;
  for (const auto& point : stencil)
  {
    totalWeight += point.second;
  }
  const double radius = StencilRadiusInSpacings * medianEdge;
  h.assign(n, 0.0L);
#pragma omp parallel
  {
    DiskDualPotential::Hint hint;
#pragma omp for schedule(static)
    for (int k = 0; k < n; ++k)
    {
      const int i = order[k];
      const Vec2 y = diracs[i];
      long double average = 0.0L;
      for (const auto& [offset, weight] : stencil)
      {
        average += weight * psi(y + radius * offset, hint);
      }
      h[i] = (1.0L - StencilVoronoiShare) * average / totalWeight +
        StencilVoronoiShare * 0.5L * static_cast<long double>(dot(y, y));
    }
  }
}
} // namespace

std::vector<int> randomSixth(int n)
{
  // A sixth halves the coarse solve against a quarter and leaves the fine iterations as they
  // were; an eighth was no faster (docs/design.md).
  std::vector<int> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  std::mt19937 rng(12345u);
  std::shuffle(ids.begin(), ids.end(), rng);
  ids.resize(n / 6);
  std::sort(ids.begin(), ids.end());
  return ids;
}

double stencilSpacing(std::vector<double> edgeLengths)
{
  // One radius for all: a radius that varies from place to place breaks the convexity (with each
  // coarse Dirac's mean Delaunay edge, interpolated, 61% of the fine Diracs were hidden).
  // Nor can one radius serve Diracs whose spacing varies much: the stencil would be smaller than
  // the spacing in some places, where fine Diracs then share flat pieces of the smoothed
  // potential (cells of mass ~1e-20, no Newton step possible). Such Diracs start single-level.
  // Measured spread (90th / 10th percentile of the coarse Delaunay edges): random Diracs 4.5;
  // adaptive samples of the brain 11 and of the hand 1657 (stalled coarse-to-fine).
  if (edgeLengths.empty())
  {
    return 0.0;
  }
  std::sort(edgeLengths.begin(), edgeLengths.end());
  const double medianEdge = edgeLengths[edgeLengths.size() / 2];
  const double spread =
    edgeLengths[9 * edgeLengths.size() / 10] / edgeLengths[edgeLengths.size() / 10];
  return spread <= MaximumSpacingSpread ? medianEdge : 0.0;
}

bool coarseToFineHeights(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& h)
{
  const int n = static_cast<int>(diracs.size());
  if (n < MultiscaleMinimumDiracs)
  {
    return false;
  }
  const std::vector<int> ids = coarseSubset(diracs);
  const int coarseCount = static_cast<int>(ids.size());
  std::vector<std::pair<Delaunay::Point, int>> input;
  input.reserve(coarseCount);
  for (int c = 0; c < coarseCount; ++c)
  {
    input.emplace_back(Delaunay::Point(diracs[ids[c]].x, diracs[ids[c]].y), c);
  }
  Delaunay dt;
  dt.insert(input.begin(), input.end());
  if (dt.dimension() < 2 || static_cast<int>(dt.number_of_vertices()) != coarseCount)
  {
    return false;
  }
  std::vector<Vec2> coarseDiracs(coarseCount);
  for (int c = 0; c < coarseCount; ++c)
  {
    coarseDiracs[c] = diracs[ids[c]];
  }
  const double medianEdge = coarseSpacing(dt, coarseDiracs);
  if (!(medianEdge > 0.0))
  {
    return false;
  }
  const std::vector<int> order = rowOrder(diracs);
  const std::vector<double> coarseMass = coarseMasses(dt, diracs, nu, order, coarseCount);
  // The start needs the coarse cells' shape, not their last digits.
  OTOptions coarseOptions;
  coarseOptions.tolerance = 1e-3;
  coarseOptions.maximumNumberOfIterations = 100;
  coarseOptions.coarseToFineStart = true;
  const OTResult coarse = solveSemiDiscreteOT(source, coarseDiracs, coarseMass, coarseOptions);
  if (coarse.heights.size() != static_cast<size_t>(coarseCount) ||
    *std::min_element(coarse.cellMass.begin(), coarse.cellMass.end()) <= 0.0)
  {
    return false;
  }

  DiskDualPotential psi;
  if (!psi.build(coarseDiracs, coarse.heights))
  {
    return false;
  }
  smoothedHeights(psi, diracs, order, medianEdge, h);
  return true;
}

int unhideDiracs(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& h, PowerDiagram& diagram, int maxRounds)
{
  const int n = static_cast<int>(diracs.size());
  const double density = meanDensity(source);
  diagram.build(diracs, h);
  for (int round = 0; round < maxRounds && diagram.hiddenCount() > 0; ++round)
  {
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i)
    {
      if (!diagram.hidden(i))
      {
        continue;
      }
      const Triangle f = diagram.hiddenFace(i);
      if (f[0] < 0)
      {
        continue;
      }
      // The plane of the face's lifted points at y_i, from differences of heights.
      const Vec2 y = diracs[i], ya = diracs[f[0]], yb = diracs[f[1]], yc = diracs[f[2]];
      const auto l = barycentric(y, ya, yb, yc);
      const Height plane = h[f[0]] + l[1] * (h[f[1]] - h[f[0]]) + l[2] * (h[f[2]] - h[f[0]]);
      // Lowered by depth below the plane, Dirac i owns the triangle
      // {x : <x - v, y_i - y_j> >= -depth, j = a, b, c} around the face's power vertex v,
      // of area depth^2 * unitArea: the depth that gives it about its mass.
      const Vec2 u[3] = { y - ya, y - yb, y - yc };
      Vec2 corner[3];
      bool bounded = true;
      for (int k = 0; k < 3; ++k)
      {
        const Vec2 p = u[k], q = u[(k + 1) % 3];
        const double det = cross(p, q);
        if (!(std::abs(det) > 0.0))
        {
          bounded = false;
          break;
        }
        // <w, p> = -1 and <w, q> = -1.
        corner[k] = { (-q.y + p.y) / det, (q.x - p.x) / det };
      }
      const double unitArea =
        bounded ? 0.5 * std::abs(cross(corner[1] - corner[0], corner[2] - corner[0])) : 0.0;
      // A quarter of its mass: lowered more, Diracs hide their neighbours in turn (with all of
      // it, 30 rounds did not end the cascade at 1e5 Diracs of contrast 1e4).
      const double depth = unitArea > 0.0 ? std::sqrt(0.25 * nu[i] / (density * unitArea)) : 0.0;
      // Never less than a safe margin above the rounding of the heights.
      const double margin = 1e-12 * (1.0 + std::abs(static_cast<double>(plane.value())));
      h[i] = plane - std::max(depth, margin);
    }
    diagram.build(diracs, h);
  }
  return diagram.hiddenCount();
}

int pullEmptyCellsIntoDisk(const std::vector<Vec2>& diracs, const std::vector<double>& nu,
  const std::vector<double>& cellMass, const PowerDiagram& diagram, std::vector<Height>& h)
{
  const int n = static_cast<int>(diracs.size());
  const Vec2 lo{ -1.1, -1.1 }, hi{ 1.1, 1.1 };
  const std::vector<Height> before = h;
  int changed = 0;
#pragma omp parallel
  {
    PowerCell cell;
    std::vector<int> ring;
#pragma omp for schedule(dynamic, 64) reduction(+ : changed)
    for (int i = 0; i < n; ++i)
    {
      if (cellMass[i] > 0.0 || diagram.hidden(i))
      {
        continue;
      }
      ring.assign(diagram.neighborsBegin(i), diagram.neighborsEnd(i));
      const size_t firstRing = ring.size();
      for (size_t k = 0; k < firstRing; ++k)
      {
        if (ring[k] >= 0)
        {
          ring.insert(ring.end(), diagram.neighborsBegin(ring[k]), diagram.neighborsEnd(ring[k]));
        }
      }
      std::sort(ring.begin(), ring.end());
      ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      // Largest value of <x, y_i - y_j> + h_j over cell_j ∩ disk, j in the two rings: where
      // Dirac i, lowered, first wins area. A linear function on a convex piece of the disk is
      // largest at a polygon vertex inside the disk, an edge crossing the circle, or the
      // circle point in the direction y_i - y_j.
      Height best = -INFINITY;
      int owner = -1;
      for (const int j : ring)
      {
        if (j < 0 || j == i || diagram.hidden(j) || cellMass[j] <= 0.0)
        {
          continue;
        }
        diagram.cell(j, lo, hi, cell);
        const Vec2 slope = diracs[i] - diracs[j];
        auto consider = [&](Vec2 x)
        {
          const Height value = before[j] + dot(x, slope);
          if (value > best)
          {
            best = value;
            owner = j;
          }
        };
        const size_t m = cell.vertices.size();
        for (size_t k = 0; k < m; ++k)
        {
          const Vec2 a = cell.vertices[k];
          if (dot(a, a) <= 1.0)
          {
            consider(a);
          }
          circleCrossings(a, cell.vertices[(k + 1) % m], consider);
        }
        Vec2 onCircle;
        if (circlePointInCell(cell.vertices, slope, onCircle))
        {
          consider(onCircle);
        }
      }
      if (owner < 0)
      {
        continue;
      }
      // Lowered by depth below that value, Dirac i owns a small region there, of linear size
      // about depth / |y_i - y_owner|: a tenth of its mass, to leave its neighbours be.
      const double depth = norm(diracs[i] - diracs[owner]) * std::sqrt(0.1 * nu[i] / Pi);
      h[i] = best - depth;
      ++changed;
    }
  }
  return changed;
}

} // namespace otparam
