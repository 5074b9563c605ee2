#include "Composition/DiskComposition.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

namespace otparam
{
namespace
{
using Clock = std::chrono::steady_clock;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_2;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>; // info: sample index
using Fb = CGAL::Triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using DT = CGAL::Delaunay_triangulation_2<K, Tds>;

constexpr double OnCircleTolerance = 1e-9;
constexpr double PolishLogRatio = 0.05;
constexpr int PolishSweeps = 50; // measured on hand_choi_53k: the largest error stops falling there

double seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double signedArea(Vec2 a, Vec2 b, Vec2 c)
{
  return 0.5 * cross(b - a, c - a);
}

Vec2 normalized(Vec2 p)
{
  const double r = norm(p);
  return r > 0.0 ? (1.0 / r) * p : Vec2{ 1.0, 0.0 };
}

bool onCircle(Vec2 p)
{
  return std::abs(norm(p) - 1.0) <= OnCircleTolerance;
}

// Incident triangles of every vertex (compressed rows), each with the other two corners in
// the triangle's own (counter-clockwise) order.
struct VertexStars
{
  std::vector<int> offsets;
  std::vector<std::array<int, 3>> entries; // {triangle, next corner, corner after that}

  VertexStars(size_t numberOfPoints, const std::vector<Triangle>& triangles)
    : offsets(numberOfPoints + 1, 0)
  {
    for (const Triangle& t : triangles)
    {
      for (int v : t)
      {
        ++offsets[v + 1];
      }
    }
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    entries.resize(offsets.back());
    std::vector<int> fill(offsets.begin(), offsets.end() - 1);
    for (size_t ti = 0; ti < triangles.size(); ++ti)
    {
      const Triangle& t = triangles[ti];
      for (int k = 0; k < 3; ++k)
      {
        entries[fill[t[k]]++] = { static_cast<int>(ti), t[(k + 1) % 3], t[(k + 2) % 3] };
      }
    }
  }
};

// Area fraction of each triangle on the surface.
std::vector<double> surfaceAreaFractions(const SurfaceMesh& surface)
{
  std::vector<double> fraction(surface.triangles.size());
  double total = 0.0;
  for (size_t t = 0; t < fraction.size(); ++t)
  {
    fraction[t] = triangleArea(surface, surface.triangles[t]);
    total += fraction[t];
  }
  for (double& f : fraction)
  {
    f /= total;
  }
  return fraction;
}

double meanAbsLogAreaRatio(const std::vector<Triangle>& triangles, const std::vector<Vec2>& uv,
  const std::vector<double>& surfaceFraction)
{
  double total = 0.0;
  std::vector<double> area(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    const Triangle& tri = triangles[t];
    area[t] = std::abs(signedArea(uv[tri[0]], uv[tri[1]], uv[tri[2]]));
    total += area[t];
  }
  double mean = 0.0;
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    const double ratio = std::max(area[t], 1e-300) / total / surfaceFraction[t];
    mean += surfaceFraction[t] * std::abs(std::log(ratio));
  }
  return mean;
}

std::vector<int> flippedTriangles(
  const std::vector<Triangle>& triangles, const std::vector<Vec2>& uv)
{
  std::vector<int> flipped;
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    const Triangle& tri = triangles[t];
    if (!(signedArea(uv[tri[0]], uv[tri[1]], uv[tri[2]]) > 0.0))
    {
      flipped.push_back(static_cast<int>(t));
    }
  }
  return flipped;
}

// Step 1: piecewise-linear interpolation of the sample images at every mesh point.
class SampleInterpolant
{
public:
  SampleInterpolant(const std::vector<Vec2>& samples, const std::vector<Vec2>& images)
    : Images(images)
  {
    std::vector<std::pair<Point, int>> points;
    points.reserve(samples.size());
    for (size_t i = 0; i < samples.size(); ++i)
    {
      points.emplace_back(Point(samples[i].x, samples[i].y), static_cast<int>(i));
      if (onCircle(samples[i]))
      {
        // T maps the circle onto the circle: a boundary sample's preimage is on it too.
        this->Images[i] = normalized(images[i]);
      }
    }
    this->Triangulation.insert(points.begin(), points.end());
  }

  // Returns the image of p; `outsideHull` tells whether p lay outside the samples' hull.
  Vec2 operator()(Vec2 p, bool& outsideHull)
  {
    DT::Locate_type type;
    int li = 0;
    const Point q(p.x, p.y);
    DT::Face_handle face = this->Triangulation.locate(q, type, li, this->Hint);
    outsideHull = false;
    if (type == DT::VERTEX)
    {
      this->Hint = face;
      return this->Images[face->vertex(li)->info()];
    }
    if (this->Triangulation.is_infinite(face) && type == DT::EDGE)
    {
      face = face->neighbor(li); // on a hull edge: use the finite side
    }
    if (!this->Triangulation.is_infinite(face))
    {
      this->Hint = face;
      const Vec2 a = this->position(face, 0), b = this->position(face, 1),
                 c = this->position(face, 2);
      const double area = cross(b - a, c - a);
      const double wa = cross(b - p, c - p) / area, wb = cross(c - p, a - p) / area;
      const double wc = 1.0 - wa - wb;
      return wa * this->image(face, 0) + wb * this->image(face, 1) + wc * this->image(face, 2);
    }
    outsideHull = true;
    const int infiniteIndex = face->index(this->Triangulation.infinite_vertex());
    const int ia = DT::ccw(infiniteIndex), ib = DT::cw(infiniteIndex);
    this->Hint = face->neighbor(infiniteIndex);
    return this->beyondHullEdge(p, this->position(face, ia), this->position(face, ib),
      this->image(face, ia), this->image(face, ib));
  }

private:
  Vec2 position(DT::Face_handle f, int k) const
  {
    const Point& q = f->vertex(k)->point();
    return { q.x(), q.y() };
  }
  Vec2 image(DT::Face_handle f, int k) const { return this->Images[f->vertex(k)->info()]; }

  // p lies beyond the hull edge ab. When a and b are on the circle, p is in the circular
  // segment they cut off: it goes along the chord like the interpolant (so the map stays
  // continuous) and radially from the image chord to the circle in the same proportion (so
  // points on the circle stay on it). Otherwise the nearest point of the edge is used.
  static Vec2 beyondHullEdge(Vec2 p, Vec2 a, Vec2 b, Vec2 imageA, Vec2 imageB)
  {
    const Vec2 ab = b - a;
    if (onCircle(a) && onCircle(b) && std::abs(cross(ab, p)) > 0.0)
    {
      const double scale = cross(ab, a) / cross(ab, p); // p * scale is on the chord
      const Vec2 onChord = scale * p;
      const double along = std::clamp(dot(onChord - a, ab) / dot(ab, ab), 0.0, 1.0);
      const Vec2 imageOnChord = (1.0 - along) * imageA + along * imageB;
      const double chordRadius = norm(onChord), imageChordRadius = norm(imageOnChord);
      const double blend = chordRadius < 1.0
        ? std::clamp((norm(p) - chordRadius) / (1.0 - chordRadius), 0.0, 1.0)
        : 1.0;
      const double radius = imageChordRadius + blend * (1.0 - imageChordRadius);
      return radius * normalized(imageOnChord);
    }
    const double along = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
    return (1.0 - along) * imageA + along * imageB;
  }

  DT Triangulation;
  std::vector<Vec2> Images;
  DT::Face_handle Hint;
};

// Step 2: optimization-based untangling (Freitag and Plassmann): each vertex of a flipped
// triangle moves to the point of its star that maximizes the smallest signed area of its
// triangles, which lies in the kernel of the star's rim whenever that kernel is not empty.
// A vertex whose rim is itself tangled cannot be fixed alone, so the set grows by one ring
// every few rounds. Returns the number of vertices moved.
class Untangler
{
public:
  Untangler(
    const SurfaceMesh& surface, const std::vector<int>& boundaryLoop, const VertexStars& stars)
    : Surface(surface)
    , Stars(stars)
    , Previous(surface.points.size(), -1)
    , Next(surface.points.size(), -1)
  {
    for (size_t k = 0; k < boundaryLoop.size(); ++k)
    {
      const int v = boundaryLoop[k];
      this->Previous[v] = boundaryLoop[(k + boundaryLoop.size() - 1) % boundaryLoop.size()];
      this->Next[v] = boundaryLoop[(k + 1) % boundaryLoop.size()];
    }
  }

  std::int64_t run(std::vector<Vec2>& uv) const
  {
    const size_t n = uv.size();
    std::vector<char> moved(n, 0), inSet(n, 0);
    constexpr int MaximumRounds = 60;
    for (int round = 0; round < MaximumRounds; ++round)
    {
      const std::vector<int> flipped = flippedTriangles(this->Surface.triangles, uv);
      if (flipped.empty())
      {
        break;
      }
      std::vector<int> set;
      for (int t : flipped)
      {
        for (int v : this->Surface.triangles[t])
        {
          if (!inSet[v])
          {
            inSet[v] = 1;
            set.push_back(v);
          }
        }
      }
      for (int ring = 0; ring < round / 4; ++ring)
      {
        const size_t count = set.size();
        for (size_t r = 0; r < count; ++r)
        {
          for (int e = this->Stars.offsets[set[r]]; e < this->Stars.offsets[set[r] + 1]; ++e)
          {
            for (int k = 1; k < 3; ++k)
            {
              const int w = this->Stars.entries[e][k];
              if (!inSet[w])
              {
                inSet[w] = 1;
                set.push_back(w);
              }
            }
          }
        }
      }
      for (int v : set)
      {
        inSet[v] = 0;
        const Vec2 before = uv[v];
        uv[v] = this->Previous[v] >= 0 ? this->bestOnCircle(v, uv) : this->bestInPlane(v, uv);
        moved[v] |= (uv[v].x != before.x || uv[v].y != before.y);
      }
    }
    return std::count(moved.begin(), moved.end(), 1);
  }

private:
  double smallestArea(int v, Vec2 p, const std::vector<Vec2>& uv) const
  {
    double smallest = HUGE_VAL;
    for (int e = this->Stars.offsets[v]; e < this->Stars.offsets[v + 1]; ++e)
    {
      const auto& entry = this->Stars.entries[e];
      smallest = std::min(smallest, signedArea(p, uv[entry[1]], uv[entry[2]]));
    }
    return smallest;
  }

  // max over p of min_k area_k(p), each area_k linear in p: a linear program in (p, t) whose
  // optimum has three active constraints, found by trying every triple (stars are small).
  Vec2 bestInPlane(int v, const std::vector<Vec2>& uv) const
  {
    struct Plane
    {
      double gx, gy, c; // area(p) = gx * p.x + gy * p.y + c
    };
    std::vector<Plane> planes;
    for (int e = this->Stars.offsets[v]; e < this->Stars.offsets[v + 1]; ++e)
    {
      const Vec2 b = uv[this->Stars.entries[e][1]], c = uv[this->Stars.entries[e][2]];
      // area = (cross(b, c) + cross(p, b - c)) / 2
      planes.push_back({ 0.5 * (b.y - c.y), -0.5 * (b.x - c.x), 0.5 * cross(b, c) });
    }
    Vec2 best = uv[v];
    double bestValue = this->smallestArea(v, best, uv);
    const size_t m = std::min<size_t>(planes.size(), 16);
    for (size_t i = 0; i < m; ++i)
    {
      for (size_t j = i + 1; j < m; ++j)
      {
        for (size_t k = j + 1; k < m; ++k)
        {
          // area_i(p) = area_j(p) = area_k(p): two linear equations in p.
          const Plane& a = planes[i];
          const Plane& b = planes[j];
          const Plane& c = planes[k];
          const double a11 = a.gx - b.gx, a12 = a.gy - b.gy, r1 = b.c - a.c;
          const double a21 = a.gx - c.gx, a22 = a.gy - c.gy, r2 = c.c - a.c;
          const double det = a11 * a22 - a12 * a21;
          if (std::abs(det) <= 1e-300)
          {
            continue;
          }
          const Vec2 p = { (r1 * a22 - a12 * r2) / det, (a11 * r2 - a21 * r1) / det };
          const double value = this->smallestArea(v, p, uv);
          if (value > bestValue)
          {
            bestValue = value;
            best = p;
          }
        }
      }
    }
    return best;
  }

  // Boundary vertices stay on the circle, between their boundary neighbours: the best of a
  // dense set of angles there, refined once around the winner.
  Vec2 bestOnCircle(int v, const std::vector<Vec2>& uv) const
  {
    const Vec2 a = uv[this->Previous[v]], b = uv[this->Next[v]];
    double span = std::atan2(cross(a, b), dot(a, b));
    if (span <= 0.0)
    {
      span += 2.0 * 3.14159265358979323846;
    }
    const double start = std::atan2(a.y, a.x);
    Vec2 best = uv[v];
    double bestValue = this->smallestArea(v, best, uv);
    double low = 0.0, high = 1.0;
    for (int level = 0; level < 3; ++level)
    {
      constexpr int Steps = 32;
      double bestFraction = -1.0;
      for (int s = 1; s < Steps; ++s)
      {
        const double fraction = low + (high - low) * s / Steps;
        const double angle = start + fraction * span;
        const Vec2 p = { std::cos(angle), std::sin(angle) };
        const double value = this->smallestArea(v, p, uv);
        if (value > bestValue)
        {
          bestValue = value;
          best = p;
          bestFraction = fraction;
        }
      }
      if (bestFraction < 0.0)
      {
        break;
      }
      const double width = (high - low) / Steps;
      low = std::max(0.0, bestFraction - width);
      high = std::min(1.0, bestFraction + width);
    }
    return best;
  }

  const SurfaceMesh& Surface;
  const VertexStars& Stars;
  std::vector<int> Previous, Next;
};

// Step 3: Gauss-Seidel sweeps of per-vertex Gauss-Newton steps on
// sum_t A*_t log(A_t / A*_t)^2, over-relaxed, each accepted only if it lowers the star's merit
// sum A* (r + 1/r - 2) with every triangle still positive (the merit is infinite at zero area,
// so no step can flip a triangle). A vertex whose triangles are all within SettledLogRatio of their
// targets is skipped until a neighbour moves: late sweeps only touch what is still wrong.
class AreaCorrection
{
public:
  AreaCorrection(const SurfaceMesh& surface, const std::vector<int>& boundaryLoop,
    const VertexStars& stars, const std::vector<double>& surfaceFraction)
    : Surface(surface)
    , Stars(stars)
    , SurfaceFraction(surfaceFraction)
    , OnBoundary(surface.points.size(), 0)
    , Active(surface.points.size(), 1)
  {
    for (int v : boundaryLoop)
    {
      this->OnBoundary[v] = Pinned;
    }
    // Boundary vertices carry the transport's own boundary map (T takes the circle onto the
    // circle), which converges to the exact one; only the corners of ears (triangles with
    // three boundary vertices, whose area no interior vertex can change) slide along the
    // circle, and when polishing, vertices with a triangle still off by more than 5%.
    // Measured on hemisphere_2k: sliding every boundary vertex takes the largest distance to
    // Lambert's projection from 0.006 to 0.008-0.011 for 10% less area error.
    for (const Triangle& t : surface.triangles)
    {
      if (this->OnBoundary[t[0]] && this->OnBoundary[t[1]] && this->OnBoundary[t[2]])
      {
        for (int v : t)
        {
          this->OnBoundary[v] = Sliding;
        }
      }
    }
    // Greedy colouring: vertices of one colour share no triangle, so they move in parallel
    // with exactly the result of a sequential sweep in colour order.
    std::vector<int> colour(surface.points.size(), -1);
    for (size_t v = 0; v < colour.size(); ++v)
    {
      std::vector<char> taken;
      for (int e = stars.offsets[v]; e < stars.offsets[v + 1]; ++e)
      {
        for (int k = 1; k < 3; ++k)
        {
          const int c = colour[stars.entries[e][k]];
          if (c >= 0)
          {
            taken.resize(std::max(taken.size(), static_cast<size_t>(c) + 1), 0);
            taken[c] = 1;
          }
        }
      }
      int c = 0;
      while (c < static_cast<int>(taken.size()) && taken[c])
      {
        ++c;
      }
      colour[v] = c;
      if (c >= static_cast<int>(this->ColourClasses.size()))
      {
        this->ColourClasses.resize(c + 1);
      }
      this->ColourClasses[c].push_back(static_cast<int>(v));
    }
  }

  // Polishing: only vertices with a triangle off by more than `settled` move, all of them
  // candidates again.
  void polishFrom(double settled)
  {
    this->SettledLogRatio = settled;
    this->Polishing = true;
    std::fill(this->Active.begin(), this->Active.end(), 1);
  }

  // Returns the number of vertices moved.
  std::int64_t sweep(std::vector<Vec2>& uv)
  {
    double total = 0.0;
    for (const Triangle& t : this->Surface.triangles)
    {
      total += signedArea(uv[t[0]], uv[t[1]], uv[t[2]]);
    }
    this->TotalArea = total;
    std::vector<char> moved(uv.size(), 0);
    for (const std::vector<int>& vertices : this->ColourClasses)
    {
      const std::int64_t count = static_cast<std::int64_t>(vertices.size());
#pragma omp parallel for schedule(static)
      for (std::int64_t k = 0; k < count; ++k)
      {
        const int v = vertices[k];
        if (this->Active[v])
        {
          moved[v] = this->OnBoundary[v] == Sliding ? this->moveOnCircle(v, uv)
            : this->OnBoundary[v] == Pinned         ? this->Polishing && this->moveOnCircle(v, uv)
                                                    : this->moveInPlane(v, uv);
        }
      }
    }
    std::fill(this->Active.begin(), this->Active.end(), 0);
    std::int64_t movedCount = 0;
    for (size_t v = 0; v < uv.size(); ++v)
    {
      if (moved[v])
      {
        ++movedCount;
        this->Active[v] = 1;
        for (int e = this->Stars.offsets[v]; e < this->Stars.offsets[v + 1]; ++e)
        {
          this->Active[this->Stars.entries[e][1]] = 1;
          this->Active[this->Stars.entries[e][2]] = 1;
        }
      }
    }
    return movedCount;
  }

private:
  static constexpr double Overrelaxation = 1.8; // measured: 1.0 needs twice the sweeps
  double SettledLogRatio = 1e-3;
  bool Polishing = false;
  enum : char
  {
    Interior = 0,
    Pinned = 1,
    Sliding = 2
  };

  // The merit function of the line search: sum A* (r + 1/r - 2), like log(r)^2 symmetric in
  // log r, minimal at r = 1 and infinite at r = 0, but without a logarithm (the sweeps spent
  // a fifth of their time in std::log). +infinity if a triangle would not be positive.
  static double merit(double area, double target)
  {
    const double r = area / target;
    return target * (r + 1.0 / r - 2.0);
  }

  double starMerit(int v, Vec2 p, const std::vector<Vec2>& uv) const
  {
    double total = 0.0;
    for (int e = this->Stars.offsets[v]; e < this->Stars.offsets[v + 1]; ++e)
    {
      const auto& entry = this->Stars.entries[e];
      const double target = this->SurfaceFraction[entry[0]] * this->TotalArea;
      const double area = signedArea(p, uv[entry[1]], uv[entry[2]]);
      if (!(area > 0.0))
      {
        return HUGE_VAL;
      }
      total += merit(area, target);
    }
    return total;
  }

  bool moveInPlane(int v, std::vector<Vec2>& uv) const
  {
    const Vec2 p = uv[v];
    double gx = 0.0, gy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0, energy = 0.0, worst = 0.0;
    for (int e = this->Stars.offsets[v]; e < this->Stars.offsets[v + 1]; ++e)
    {
      const auto& entry = this->Stars.entries[e];
      const Vec2 b = uv[entry[1]], c = uv[entry[2]];
      const double target = this->SurfaceFraction[entry[0]] * this->TotalArea;
      const double area = signedArea(p, b, c);
      if (!(area > 0.0))
      {
        return false; // only an untangled star can be corrected
      }
      // d(log area)/dp for area = cross(b - p, c - p) / 2
      const Vec2 d = b - c;
      const double ax = 0.5 * d.y / area, ay = -0.5 * d.x / area;
      const double residual = std::log(area / target);
      energy += merit(area, target);
      worst = std::max(worst, std::abs(residual));
      gx += target * residual * ax;
      gy += target * residual * ay;
      hxx += target * ax * ax;
      hxy += target * ax * ay;
      hyy += target * ay * ay;
    }
    const double det = hxx * hyy - hxy * hxy;
    if (worst < SettledLogRatio || !(det > 1e-12 * (hxx * hyy)) || !(hxx > 0.0))
    {
      return false;
    }
    const Vec2 step = { -(hyy * gx - hxy * gy) / det, -(-hxy * gx + hxx * gy) / det };
    return this->acceptDecrease(v, uv, energy, [&](double lambda) { return p + lambda * step; });
  }

  bool moveOnCircle(int v, std::vector<Vec2>& uv) const
  {
    const Vec2 p = uv[v];
    const double angle = std::atan2(p.y, p.x);
    const Vec2 tangent = { -p.y, p.x };
    double first = 0.0, second = 0.0, energy = 0.0, worst = 0.0;
    for (int e = this->Stars.offsets[v]; e < this->Stars.offsets[v + 1]; ++e)
    {
      const auto& entry = this->Stars.entries[e];
      const Vec2 b = uv[entry[1]], c = uv[entry[2]];
      const double target = this->SurfaceFraction[entry[0]] * this->TotalArea;
      const double area = signedArea(p, b, c);
      if (!(area > 0.0))
      {
        return false;
      }
      const Vec2 d = b - c;
      const double slope = dot(Vec2{ 0.5 * d.y, -0.5 * d.x }, tangent) / area; // d log(area)
      const double residual = std::log(area / target);
      energy += merit(area, target);
      worst = std::max(worst, std::abs(residual));
      first += target * residual * slope;
      second += target * slope * slope;
    }
    if (worst < this->SettledLogRatio || !(second > 0.0))
    {
      return false;
    }
    const double step = -first / second;
    return this->acceptDecrease(v, uv, energy,
      [&](double lambda) {
        return Vec2{ std::cos(angle + lambda * step), std::sin(angle + lambda * step) };
      });
  }

  template <typename Trial>
  bool acceptDecrease(int v, std::vector<Vec2>& uv, double before, const Trial& trial) const
  {
    for (double lambda = Overrelaxation; lambda > 1e-3; lambda *= 0.5)
    {
      const Vec2 candidate = trial(lambda);
      if (this->starMerit(v, candidate, uv) < before)
      {
        uv[v] = candidate;
        return true;
      }
    }
    return false;
  }

  const SurfaceMesh& Surface;
  const VertexStars& Stars;
  const std::vector<double>& SurfaceFraction;
  std::vector<char> OnBoundary, Active;
  std::vector<std::vector<int>> ColourClasses;
  double TotalArea = 0.0;
};

} // namespace

Vec2 boundaryArcMidpoint(const std::vector<Vec2>& cell)
{
  const size_t n = cell.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  size_t start = n;
  for (size_t k = 0; k < n; ++k)
  {
    if (!onCircle(cell[k]) && onCircle(cell[(k + 1) % n]))
    {
      start = (k + 1) % n; // a run begins here
      break;
    }
  }
  if (start == n)
  {
    return { nan, nan }; // no vertex on the circle, or all of them (the cell is the disk)
  }
  double bestSpan = -1.0, bestMiddle = 0.0;
  for (size_t step = 0; step < n;)
  {
    size_t k = (start + step) % n;
    if (!onCircle(cell[k]))
    {
      ++step;
      continue;
    }
    const double first = std::atan2(cell[k].y, cell[k].x);
    double span = 0.0;
    while (step + 1 < n && onCircle(cell[(start + step + 1) % n]))
    {
      const Vec2 a = cell[(start + step) % n], b = cell[(start + step + 1) % n];
      span += std::atan2(cross(a, b), dot(a, b));
      ++step;
    }
    ++step;
    if (std::abs(span) > bestSpan)
    {
      bestSpan = std::abs(span);
      bestMiddle = first + 0.5 * span;
    }
  }
  return { std::cos(bestMiddle), std::sin(bestMiddle) };
}

CompositionResult composeWithInverseTransport(const SurfaceMesh& surface,
  const std::vector<Vec2>& conformalUv, const std::vector<int>& boundaryLoop,
  const std::vector<Vec2>& samples, const std::vector<Vec2>& sampleImages,
  const CompositionOptions& options)
{
  CompositionResult result;
  if (conformalUv.size() != surface.points.size())
  {
    result.error = "the conformal image has " + std::to_string(conformalUv.size()) +
      " points but the surface has " + std::to_string(surface.points.size());
    return result;
  }
  if (samples.size() < 3 || samples.size() != sampleImages.size())
  {
    result.error = "the transport needs at least 3 samples with one image each (got " +
      std::to_string(samples.size()) + " samples and " + std::to_string(sampleImages.size()) +
      " images)";
    return result;
  }
  auto report = [&](double fraction)
  {
    if (options.progress && !options.progress(fraction))
    {
      result.aborted = true;
    }
    return !result.aborted;
  };

  auto start = Clock::now();
  SampleInterpolant interpolant(samples, sampleImages);
  result.interpolatedUv.resize(conformalUv.size());
  for (size_t v = 0; v < conformalUv.size(); ++v)
  {
    bool outside = false;
    result.interpolatedUv[v] = interpolant(conformalUv[v], outside);
    result.outsideSampleHull += outside;
  }
  for (int v : boundaryLoop)
  {
    result.interpolatedUv[v] = normalized(result.interpolatedUv[v]);
  }
  result.secondsInterpolation = seconds(start);
  if (!report(0.2))
  {
    return result;
  }

  start = Clock::now();
  const VertexStars stars(surface.points.size(), surface.triangles);
  result.uv = result.interpolatedUv;
  result.flippedAfterInterpolation =
    static_cast<std::int64_t>(flippedTriangles(surface.triangles, result.uv).size());
  if (result.flippedAfterInterpolation > 0)
  {
    result.untangledVertices = Untangler(surface, boundaryLoop, stars).run(result.uv);
  }
  result.secondsUntangling = seconds(start);
  const std::vector<double> surfaceFraction = surfaceAreaFractions(surface);
  result.meanAbsLogAreaRatioInterpolated =
    meanAbsLogAreaRatio(surface.triangles, result.uv, surfaceFraction);
  result.meanAbsLogAreaRatio = result.meanAbsLogAreaRatioInterpolated;
  if (!report(0.3))
  {
    return result;
  }

  start = Clock::now();
  if (options.correctAreas)
  {
    AreaCorrection correction(surface, boundaryLoop, stars, surfaceFraction);
    // The mean is measured every few sweeps only: it costs a logarithm per triangle.
    constexpr int SweepsPerCheck = 4;
    for (int sweep = 0; sweep < options.maximumCorrectionSweeps; ++sweep)
    {
      const std::int64_t moved = correction.sweep(result.uv);
      ++result.correctionSweeps;
      if (moved > 0 && (sweep + 1) % SweepsPerCheck != 0)
      {
        continue;
      }
      const double mean = meanAbsLogAreaRatio(surface.triangles, result.uv, surfaceFraction);
      const bool settled = moved == 0 ||
        result.meanAbsLogAreaRatio - mean <
          SweepsPerCheck * options.correctionRelativeDecrease * mean;
      result.meanAbsLogAreaRatio = mean;
      if (settled ||
        !report(0.3 + 0.6 * (sweep + 1.0) / std::max(1, options.maximumCorrectionSweeps)))
      {
        break;
      }
    }
    // The mean settles long before the worst triangles (the sweeps spread corrections slowly
    // and the few vertices around an untangled knot need many): sweeps over just the vertices
    // that still have a triangle off by more than 5% finish them cheaply (hand_choi_53k: the
    // largest |log area ratio| 3.3 -> 0.6 for 0.3 s).
    correction.polishFrom(PolishLogRatio);
    for (int sweep = 0; sweep < std::min(options.maximumCorrectionSweeps, PolishSweeps); ++sweep)
    {
      ++result.correctionSweeps;
      if (correction.sweep(result.uv) == 0)
      {
        break;
      }
    }
    result.meanAbsLogAreaRatio = meanAbsLogAreaRatio(surface.triangles, result.uv, surfaceFraction);
  }
  result.secondsCorrection = seconds(start);
  result.flippedTriangles =
    static_cast<std::int64_t>(flippedTriangles(surface.triangles, result.uv).size());
  return result;
}

} // namespace otparam
