#include "MultiscaleStart.h"

#include "SemiDiscreteOT.h"

#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/property_map.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <Eigen/Dense>

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

// Symmetric positive-definite 2x2 matrix [[a, b], [b, c]].
struct Sym2
{
  double a = 0.0, b = 0.0, c = 0.0;
  double quadratic(Vec2 v) const { return a * v.x * v.x + 2.0 * b * v.x * v.y + c * v.y * v.y; }
};

// Least-squares symmetric Jacobian of the inverse transport map at a coarse Dirac, from the
// displacements of its Delaunay neighbours' cell centroids (a gradient map has a symmetric
// Jacobian), with eigenvalues kept positive: the fine heights' convexity comes from it.
Sym2 inverseMapJacobian(Vec2 y, Vec2 x, const std::vector<std::pair<Vec2, Vec2>>& neighbours)
{
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const auto& [yn, xn] : neighbours)
  {
    const Vec2 dy = yn - y, dx = xn - x;
    const double w = 1.0 / std::max(dot(dy, dy), 1e-300); // each direction counts alike
    const Eigen::Vector3d r1(dy.x, dy.y, 0.0), r2(0.0, dy.x, dy.y);
    normal += w * (r1 * r1.transpose() + r2 * r2.transpose());
    rhs += w * (dx.x * r1 + dx.y * r2);
  }
  Sym2 jacobian;
  if (neighbours.size() < 2)
  {
    return jacobian;
  }
  const Eigen::Vector3d p = normal.ldlt().solve(rhs);
  Eigen::Matrix2d m;
  m << p[0], p[1], p[1], p[2];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(m);
  Eigen::Vector2d lambda = eig.eigenvalues();
  const double largest = std::max(lambda[1], 0.0);
  // A floor under the eigenvalues: anisotropy beyond 100 would only come from noise in the
  // centroids, and a zero eigenvalue would put fine Diracs on one line of heights.
  lambda[0] = std::max(lambda[0], 1e-2 * largest);
  lambda[1] = largest;
  const Eigen::Matrix2d s = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
  if (!s.allFinite())
  {
    return Sym2{};
  }
  jacobian.a = s(0, 0);
  jacobian.b = s(0, 1);
  jacobian.c = s(1, 1);
  return jacobian;
}

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
  auto key = [&](int i) {
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

} // namespace

bool coarseToFineHeights(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& h)
{
  const int n = static_cast<int>(diracs.size());
  if (n < MultiscaleMinimumDiracs)
  {
    return false;
  }
  // A random quarter (fixed seed: runs are reproducible) carries the masses of the Diracs
  // nearest to it.
  // The Diracs' convex hull is in the coarse set, so that every fine Dirac lies in a coarse
  // triangle: models extrapolated beyond the coarse hull put cells outside the domain.
  std::vector<int> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  std::mt19937 rng(12345u);
  std::shuffle(ids.begin(), ids.end(), rng);
  ids.resize(n / 4);
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
  const std::vector<int> order = rowOrder(diracs);
  std::vector<int> parent(n);
  std::vector<double> coarseMass(coarseCount, 0.0);
  Delaunay::Vertex_handle hint;
  for (const int i : order)
  {
    const Delaunay::Point p(diracs[i].x, diracs[i].y);
    hint = dt.nearest_vertex(p, hint == Delaunay::Vertex_handle() ? Delaunay::Face_handle() : hint->face());
    parent[i] = hint->info();
    coarseMass[parent[i]] += nu[i];
  }

  std::vector<Vec2> coarseDiracs(coarseCount);
  for (int c = 0; c < coarseCount; ++c)
  {
    coarseDiracs[c] = diracs[ids[c]];
  }
  // The start needs the coarse cells' shape, not their last digits.
  OTOptions coarseOptions;
  coarseOptions.tolerance = 1e-3;
  coarseOptions.maxIterations = 100;
  coarseOptions.coarseToFineStart = true;
  const OTResult coarse = solveSemiDiscreteOT(source, coarseDiracs, coarseMass, coarseOptions);
  if (coarse.heights.size() != static_cast<size_t>(coarseCount) ||
    *std::min_element(coarse.cellMass.begin(), coarse.cellMass.end()) <= 0.0)
  {
    return false;
  }

  // Local quadratic models of the dual potential psi (h_i = psi(y_i), grad psi = inverse map):
  // psi(y) ~ h_c + <x_c, y - y_c> + (y - y_c)^T A_c (y - y_c) / 2 around each coarse Dirac c,
  // x_c its cell's centroid and A_c the inverse map's Jacobian.
  std::vector<Sym2> jacobian(coarseCount);
  std::vector<Delaunay::Vertex_handle> vertexOf(coarseCount);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
  {
    vertexOf[v->info()] = v;
  }
#pragma omp parallel
  {
    std::vector<std::pair<Vec2, Vec2>> neighbours;
#pragma omp for schedule(static)
    for (int c = 0; c < coarseCount; ++c)
    {
      neighbours.clear();
      auto vc = dt.incident_vertices(vertexOf[c]), done = vc;
      do
      {
        if (!dt.is_infinite(vc))
        {
          const int k = vc->info();
          neighbours.emplace_back(coarseDiracs[k], coarse.centroids[k]);
        }
      } while (++vc != done);
      jacobian[c] = inverseMapJacobian(coarseDiracs[c], coarse.centroids[c], neighbours);
    }
  }
  auto model = [&](int c, Vec2 y) {
    const Vec2 d = y - coarseDiracs[c];
    return static_cast<Height>(coarse.heights[c]) +
      static_cast<Height>(dot(coarse.centroids[c], d) + 0.5 * jacobian[c].quadratic(d));
  };

  // Fine heights: the three models of the coarse Delaunay triangle around y_i, blended by
  // barycentric weights (a partition of unity: the coarse Diracs keep their own heights).
  h.assign(n, 0.0L);
  Delaunay::Face_handle face;
  for (const int i : order)
  {
    const Vec2 y = diracs[i];
    face = dt.locate(Delaunay::Point(y.x, y.y), face);
    if (dt.is_infinite(face))
    {
      h[i] = model(parent[i], y);
      continue;
    }
    const int a = face->vertex(0)->info(), b = face->vertex(1)->info(), c = face->vertex(2)->info();
    const auto l = barycentric(y, coarseDiracs[a], coarseDiracs[b], coarseDiracs[c]);
    h[i] = l[0] * model(a, y) + l[1] * model(b, y) + l[2] * model(c, y);
  }
  for (int c = 0; c < coarseCount; ++c)
  {
    h[ids[c]] = static_cast<Height>(coarse.heights[c]);
  }
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
      const double margin = 1e-12 * (1.0 + std::abs(static_cast<double>(plane)));
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
        auto consider = [&](Vec2 x) {
          const Height value = static_cast<Height>(dot(x, slope)) + before[j];
          if (value > best)
          {
            best = value;
            owner = j;
          }
        };
        const size_t m = cell.vertices.size();
        bool directionInside = norm(slope) > 0.0;
        const Vec2 u = directionInside ? (1.0 / norm(slope)) * slope : Vec2{};
        for (size_t k = 0; k < m; ++k)
        {
          const Vec2 a = cell.vertices[k], b = cell.vertices[(k + 1) % m];
          if (dot(a, a) <= 1.0)
          {
            consider(a);
          }
          directionInside = directionInside && cross(b - a, u - a) >= 0.0;
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
                consider(a + t * e);
              }
            }
          }
        }
        if (directionInside && m >= 3)
        {
          consider(u);
        }
      }
      if (owner < 0)
      {
        continue;
      }
      // Lowered by depth below that value, Dirac i owns a small region there, of linear size
      // about depth / |y_i - y_owner|: a tenth of its mass, to leave its neighbours be.
      const double depth =
        norm(diracs[i] - diracs[owner]) * std::sqrt(0.1 * nu[i] / Pi);
      h[i] = best - static_cast<Height>(depth);
      ++changed;
    }
  }
  return changed;
}

} // namespace otparam
