// Step 3 of the composition (DiskComposition.h, SphereComposition.h): vertices moved so that
// every triangle gets its surface area fraction, on the disk or the sphere. Private to the
// composition stage.
#ifndef OTPARAM_COMPOSITION_AREACORRECTION_H
#define OTPARAM_COMPOSITION_AREACORRECTION_H

#include "Common/SphericalGeometry.h"
#include "Composition/Composition.h"
#include "Composition/CompositionOptions.h"

#include <array>
#include <limits>
#include <numeric>
#include <type_traits>

namespace otparam
{
namespace composition
{

// What the correction needs of a domain: triangle areas, the gradient of an area with respect to
// one corner in a frame of that corner's tangent plane, and a step taken in that frame.
struct PlaneGeometry
{
  using Point = Vec2;
  struct Frame
  {
  };
  static Frame frame(Point) { return {}; }
  static double area(Point a, Point b, Point c) { return signedArea(a, b, c); }
  // area = cross(b - p, c - p) / 2
  static Vec2 areaGradient(Frame, Point, Point b, Point c)
  {
    const Vec2 d = b - c;
    return { 0.5 * d.y, -0.5 * d.x };
  }
  static Point move(Frame, Point p, Vec2 step) { return p + step; }
  // The sum of the triangles' signed areas: the area inside the boundary loop (shoelace, in the
  // loop's order), whatever the interior vertices do.
  static double totalArea(const std::vector<Point>& points, const std::vector<int>& boundaryLoop)
  {
    double twice = 0.0;
    for (size_t k = 0; k < boundaryLoop.size(); ++k)
    {
      twice += cross(points[boundaryLoop[k]], points[boundaryLoop[(k + 1) % boundaryLoop.size()]]);
    }
    return 0.5 * std::abs(twice);
  }
};

// The unit sphere: spherical triangle areas (Eriksson), steps in the tangent plane pushed back
// onto the sphere.
struct SphereGeometry
{
  using Point = Vec3;
  struct Frame
  {
    Vec3 e1, e2;
  };
  static Frame frame(Point p)
  {
    Frame f;
    tangentFrame(p, f.e1, f.e2);
    return f;
  }
  static double area(Point a, Point b, Point c) { return sphericalTriangleArea(a, b, c); }
  // E = 2 atan2(T, D), T = a.(b x c), D = 1 + a.b + b.c + c.a: dE/da = 2 (D b x c - T (b + c))
  // / (T^2 + D^2), of which the tangent part.
  static Vec2 areaGradient(const Frame& f, Point a, Point b, Point c)
  {
    const Vec3 bc = cross(b, c);
    const double t = dot(a, bc), d = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
    const Vec3 g = (2.0 / (t * t + d * d)) * (d * bc - t * (b + c));
    return { dot(g, f.e1), dot(g, f.e2) };
  }
  static Point move(const Frame& f, Point p, Vec2 step)
  {
    return normalized(p + step.x * f.e1 + step.y * f.e2);
  }
  // The triangles of an untangled map (the only ones corrected) cover the sphere once.
  static double totalArea(const std::vector<Point>&, const std::vector<int>&)
  {
    return 4.0 * 3.14159265358979323846;
  }
};

// Step 3: Gauss-Seidel sweeps of per-vertex Gauss-Newton steps on
// sum_t A*_t log(A_t / A*_t)^2, over-relaxed, each accepted only if it lowers the star's merit
// sum A* (r + 1/r - 2) with every triangle still positive (the merit is infinite at zero area,
// so no step can flip a triangle). A vertex whose triangles are all within SettledLogRatio of their
// targets is skipped until a neighbour moves: late sweeps only touch what is still wrong.
template <class Geometry>
class AreaCorrectionOn
{
public:
  using Point = typename Geometry::Point;

  AreaCorrectionOn(const SurfaceMesh& surface, const std::vector<int>& boundaryLoop,
    const VertexStars& stars, const std::vector<double>& surfaceFraction)
    : BoundaryLoop(boundaryLoop)
  {
    const size_t n = surface.points.size();
    std::vector<char> onBoundary(n, Interior);
    for (int v : boundaryLoop)
    {
      onBoundary[v] = Pinned;
    }
    // Boundary vertices carry the transport's own boundary map (T takes the circle onto the
    // circle), which converges to the exact one; only the corners of ears (triangles with
    // three boundary vertices, whose area no interior vertex can change) slide along the
    // circle, and when polishing, vertices with a triangle still off by more than 5%.
    // Measured on hemisphere_2k: sliding every boundary vertex takes the largest distance to
    // Lambert's projection from 0.006 to 0.008-0.011 for 10% less area error.
    for (const Triangle& t : surface.triangles)
    {
      if (onBoundary[t[0]] && onBoundary[t[1]] && onBoundary[t[2]])
      {
        for (int v : t)
        {
          onBoundary[v] = Sliding;
        }
      }
    }
    this->renumberByColour(stars, surfaceFraction, onBoundary);
  }

  void setOverrelaxation(double factor) { this->Overrelaxation = factor; }

  // Polishing: only vertices with a triangle off by more than `settled` move, all of them
  // candidates again.
  void polishFrom(double settled)
  {
    this->SettledLogRatio = settled;
    this->Polishing = true;
    std::fill(this->Active.begin(), this->Active.end(), 1);
  }

  // The sweeps move their own copy of the points (numbered colour by colour): `load` takes the
  // caller's points, `store` gives them back. Copying them in and out at every sweep cost two
  // passes over the points in scattered order, also in the polishing sweeps that move few.
  void load(const std::vector<Point>& uv)
  {
    for (size_t v = 0; v < this->OriginalIndex.size(); ++v)
    {
      this->Points[v] = uv[this->OriginalIndex[v]];
    }
  }
  void store(std::vector<Point>& uv) const
  {
    for (size_t v = 0; v < this->OriginalIndex.size(); ++v)
    {
      uv[this->OriginalIndex[v]] = this->Points[v];
    }
  }

  // The largest |log(area / target)| over the stars of the next sweep's candidates (infinite
  // where one is not positive), in the sweeps' copy of the points, leaving out triangles whose
  // target is below `negligibleShare` times the mean (slivers: a marching-cubes mesh's stay off
  // by e^13 whatever the sweeps do).
  double largestCandidateLogRatio(double negligibleShare) const
  {
    // The targets sum to 1 over the triangles, each listed once per corner in Entries.
    const double negligible = negligibleShare * 3.0 / static_cast<double>(this->Entries.size());
    double largest = 0.0;
    for (size_t v = 0; v < this->Active.size(); ++v)
    {
      for (int e = this->Offsets[v]; this->Active[v] && e < this->Offsets[v + 1]; ++e)
      {
        const StarEntry& entry = this->Entries[e];
        if (entry.fraction < negligible)
        {
          continue;
        }
        const double area =
          Geometry::area(this->Points[v], this->Points[entry.b], this->Points[entry.c]);
        if (!(area > 0.0))
        {
          return HUGE_VAL;
        }
        largest = std::max(largest, std::abs(logAreaRatio(area, entry.fraction * this->TotalArea)));
      }
    }
    return largest;
  }

  // One sweep over the loaded points. Returns the number of vertices moved.
  std::int64_t sweep()
  {
    // From the boundary alone: a sum over every triangle was ~7% of a sweep (a third of a
    // polishing sweep) at 273k points.
    this->TotalArea = Geometry::totalArea(this->Points, this->BoundaryLoop);
    const std::int64_t n = static_cast<std::int64_t>(this->OriginalIndex.size());
    this->Moved.assign(n, 0);
    std::int64_t movedCount = 0;
    // One parallel region per sweep, not per colour: under OMP_WAIT_POLICY=passive each region
    // wakes the sleeping threads (hand_choi_53k: ~900 regions of 0.3 ms per correction).
    // Dynamic chunks: late sweeps move few vertices, bunched around what is still wrong, which
    // static halves gave mostly to one core. Vertices of one colour are independent, so any
    // schedule gives the same bits.
#pragma omp parallel reduction(+ : movedCount)
    {
      for (size_t c = 0; c + 1 < this->ClassStarts.size(); ++c)
      {
        const std::int64_t first = this->ClassStarts[c], last = this->ClassStarts[c + 1];
#pragma omp for schedule(dynamic, 512)
        for (std::int64_t v = first; v < last; ++v)
        {
          if (this->Active[v])
          {
            this->Moved[v] = this->move(static_cast<int>(v), this->Points);
          }
        }
      }
      // Next sweep's candidates: a vertex that moved or shares a triangle with one that did
      // (stars are symmetric), gathered per vertex so that both cores can do it.
#pragma omp for schedule(static)
      for (std::int64_t v = 0; v < n; ++v)
      {
        char active = this->Moved[v];
        movedCount += active;
        for (int e = this->Offsets[v]; e < this->Offsets[v + 1] && !active; ++e)
        {
          active = this->Moved[this->Entries[e].b] | this->Moved[this->Entries[e].c];
        }
        this->Active[v] = active;
      }
    }
    return movedCount;
  }

private:
  // CompositionOptions::correctionOverrelaxation, set by correctAreas (measured: 1.0 needs
  // twice the sweeps of the default 1.8).
  double Overrelaxation = CompositionOptions{}.correctionOverrelaxation;
  double SettledLogRatio = 1e-3;
  bool Polishing = false;
  enum : char
  {
    Interior = 0,
    Pinned = 1,
    Sliding = 2
  };

  // Interior vertices move freely; on the disk's circle, ear corners slide along it, and so
  // does any boundary vertex when polishing (the sphere has no boundary).
  bool move(int v, std::vector<Point>& uv) const
  {
    if constexpr (std::is_same<Point, Vec2>::value)
    {
      if (this->OnBoundary[v] == Sliding || this->OnBoundary[v] == Pinned)
      {
        return (this->OnBoundary[v] == Sliding || this->Polishing) && this->moveOnCircle(v, uv);
      }
    }
    return this->moveFreely(v, uv);
  }

  double starMerit(int v, Point p, const std::vector<Point>& uv) const
  {
    double total = 0.0;
    for (int e = this->Offsets[v]; e < this->Offsets[v + 1]; ++e)
    {
      const StarEntry& entry = this->Entries[e];
      const double target = entry.fraction * this->TotalArea;
      const double area = Geometry::area(p, uv[entry.b], uv[entry.c]);
      if (!(area > 0.0))
      {
        return HUGE_VAL;
      }
      total += areaMerit(area, target);
    }
    return total;
  }

  bool moveFreely(int v, std::vector<Point>& uv) const
  {
    const Point p = uv[v];
    const typename Geometry::Frame frame = Geometry::frame(p);
    double gx = 0.0, gy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0, energy = 0.0, worst = 0.0;
    for (int e = this->Offsets[v]; e < this->Offsets[v + 1]; ++e)
    {
      const StarEntry& entry = this->Entries[e];
      const Point b = uv[entry.b], c = uv[entry.c];
      const double target = entry.fraction * this->TotalArea;
      const double area = Geometry::area(p, b, c);
      if (!(area > 0.0))
      {
        return false; // only an untangled star can be corrected
      }
      const Vec2 gradient = Geometry::areaGradient(frame, p, b, c); // d(log area) = that / area
      const double ax = gradient.x / area, ay = gradient.y / area;
      const double residual = logAreaRatio(area, target);
      energy += areaMerit(area, target);
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
    return this->acceptDecrease(
      v, uv, energy, [&](double lambda) { return Geometry::move(frame, p, lambda * step); });
  }

  bool moveOnCircle(int v, std::vector<Vec2>& uv) const
  {
    const Vec2 p = uv[v];
    const double angle = std::atan2(p.y, p.x);
    const Vec2 tangent = { -p.y, p.x };
    double first = 0.0, second = 0.0, energy = 0.0, worst = 0.0;
    for (int e = this->Offsets[v]; e < this->Offsets[v + 1]; ++e)
    {
      const StarEntry& entry = this->Entries[e];
      const Vec2 b = uv[entry.b], c = uv[entry.c];
      const double target = entry.fraction * this->TotalArea;
      const double area = signedArea(p, b, c);
      if (!(area > 0.0))
      {
        return false;
      }
      const Vec2 d = b - c;
      const double slope = dot(Vec2{ 0.5 * d.y, -0.5 * d.x }, tangent) / area; // d log(area)
      const double residual = logAreaRatio(area, target);
      energy += areaMerit(area, target);
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
  bool acceptDecrease(int v, std::vector<Point>& uv, double before, const Trial& trial) const
  {
    for (double lambda = Overrelaxation; lambda > 1e-3; lambda *= 0.5)
    {
      const Point candidate = trial(lambda);
      if (this->starMerit(v, candidate, uv) < before)
      {
        uv[v] = candidate;
        return true;
      }
    }
    return false;
  }

  std::vector<int> BoundaryLoop; // in the sweeps' numbering (the sphere's is empty)
  // A triangle of a vertex's star: its target share of the domain and the next two corners.
  struct StarEntry
  {
    double fraction;
    int b, c;
  };

  // Greedy colouring: vertices of one colour share no triangle, so they move in parallel with
  // exactly the result of a sequential sweep in colour order. Returns each vertex's colour and
  // counts each colour's vertices in `classSizes`.
  static std::vector<int> greedyColours(
    const VertexStars& stars, size_t n, std::vector<int>& classSizes)
  {
    std::vector<int> colour(n, -1);
    classSizes.clear();
    for (size_t v = 0; v < n; ++v)
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
      classSizes.resize(std::max(classSizes.size(), static_cast<size_t>(c) + 1), 0);
      ++classSizes[c];
    }
    return colour;
  }

  // The sweeps work on a copy of the points numbered colour by colour (in the surface's order
  // within a colour), each star entry holding its triangle's share: a parallel loop then reads
  // its vertices' stars in storage order instead of gathering the shares and stars across the
  // whole surface. The same bits; with the single region per sweep, hand_choi_53k's correction
  // 0.39 -> 0.30 s on a quiet machine (docs/performance.md).
  void renumberByColour(const VertexStars& stars, const std::vector<double>& surfaceFraction,
    const std::vector<char>& onBoundary)
  {
    const size_t n = onBoundary.size();
    std::vector<int> classSizes;
    const std::vector<int> colour = greedyColours(stars, n, classSizes);
    this->ClassStarts.assign(classSizes.size() + 1, 0);
    std::partial_sum(classSizes.begin(), classSizes.end(), this->ClassStarts.begin() + 1);
    std::vector<int> next(this->ClassStarts.begin(), this->ClassStarts.end() - 1);
    std::vector<int> newIndex(n);
    this->OriginalIndex.resize(n);
    for (size_t v = 0; v < n; ++v)
    {
      newIndex[v] = next[colour[v]]++;
      this->OriginalIndex[newIndex[v]] = static_cast<int>(v);
    }
    this->Offsets.assign(n + 1, 0);
    this->Entries.reserve(stars.entries.size());
    this->OnBoundary.resize(n);
    for (size_t i = 0; i < n; ++i)
    {
      const int v = this->OriginalIndex[i];
      this->OnBoundary[i] = onBoundary[v];
      for (int e = stars.offsets[v]; e < stars.offsets[v + 1]; ++e)
      {
        const std::array<int, 3>& entry = stars.entries[e];
        this->Entries.push_back(
          { surfaceFraction[entry[0]], newIndex[entry[1]], newIndex[entry[2]] });
      }
      this->Offsets[i + 1] = static_cast<int>(this->Entries.size());
    }
    for (int& v : this->BoundaryLoop)
    {
      v = newIndex[v];
    }
    this->Active.assign(n, 1);
    this->Points.resize(n);
  }

  std::vector<int> Offsets, ClassStarts, OriginalIndex;
  std::vector<StarEntry> Entries;
  std::vector<char> OnBoundary, Active, Moved;
  std::vector<Point> Points; // the sweeps' copy, numbered colour by colour
  double TotalArea = 0.0;
};

using AreaCorrection = AreaCorrectionOn<PlaneGeometry>;

constexpr double PolishLogRatio = 0.05;
// Measured 2026-11-28 (largest |log area ratio| after 1 / 20 / 50 polishing sweeps): still
// falling at 50 where an untangled knot sits (bunny_holes_35k 2.35 / 0.90 / 0.59,
// face_dense_gpp_5k 3.01 / 0.98 / 0.43), flat from ~20 elsewhere (hand_choi_53k 0.67 / 0.67 /
// 0.67), where the late sweeps move few vertices and cost little.
constexpr int PolishSweeps = 50;
// Past PolishSweeps the polishing goes on (up to MaximumCorrectionSweeps) while a candidate's
// triangle is still off by more than e^KnotLogRatio: a knot the untangling left. Measured on a
// procedural quadruped opened at the neck (crowding_meshes.quadruped, 1192 triangles flipped by
// the last interpolation): one triangle 450 times too large after 50 sweeps, mean |log area
// ratio| 0.127 -> 0.041 after 200 (docs/design.md). A map with no such knot stops at 50 as
// before, and so do a staged transport's stages (CompositionOptions::polishKnots), whose chain
// TestCrowding's stage counts were measured with.
constexpr double KnotLogRatio = 1.0;
// Triangles whose share of the domain is below this times the mean are not knots but slivers.
constexpr double SliverShare = 1e-3;

// Step 3's sweeps, for either domain: until the mean |log area ratio| (`mean(points)`) settles,
// then the polishing of the worst. `report(fraction)` returns false to abort. Counts the sweeps
// and leaves the final mean in `meanAbsLogAreaRatio`. Returns false when aborted.
template <class Geometry, class Mean, class Report>
bool correctAreas(AreaCorrectionOn<Geometry>& correction,
  std::vector<typename Geometry::Point>& points, const CompositionOptions& options,
  const Mean& mean, const Report& report, int& sweeps, double& meanAbsLogAreaRatio)
{
  // The mean is measured every few sweeps only: it costs a logarithm per triangle.
  constexpr int SweepsPerCheck = 4;
  correction.setOverrelaxation(options.correctionOverrelaxation);
  correction.load(points);
  for (int sweep = 0; sweep < options.maximumCorrectionSweeps; ++sweep)
  {
    const std::int64_t moved = correction.sweep();
    ++sweeps;
    if (moved > 0 && (sweep + 1) % SweepsPerCheck != 0)
    {
      continue;
    }
    correction.store(points);
    const double now = mean(points);
    const bool settled = moved == 0 ||
      meanAbsLogAreaRatio - now < SweepsPerCheck * options.correctionRelativeDecrease * now;
    meanAbsLogAreaRatio = now;
    if (!report(0.3 + 0.6 * (sweep + 1.0) / std::max(1, options.maximumCorrectionSweeps)))
    {
      return false;
    }
    if (settled)
    {
      break;
    }
  }
  // The mean settles long before the worst triangles (the sweeps spread corrections slowly
  // and the few vertices around an untangled knot need many): sweeps over just the vertices
  // that still have a triangle off by more than 5% finish them cheaply (PolishSweeps).
  correction.polishFrom(PolishLogRatio);
  for (int sweep = 0; sweep < options.maximumCorrectionSweeps; ++sweep)
  {
    if (sweep >= PolishSweeps &&
      !(options.polishKnots && correction.largestCandidateLogRatio(SliverShare) > KnotLogRatio))
    {
      break;
    }
    ++sweeps;
    if (correction.sweep() == 0)
    {
      break;
    }
    if (!report(0.9))
    {
      correction.store(points);
      return false;
    }
  }
  correction.store(points);
  meanAbsLogAreaRatio = mean(points);
  return true;
}

} // namespace composition
} // namespace otparam

#endif
