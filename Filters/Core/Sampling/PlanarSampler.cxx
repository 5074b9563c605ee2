// Delaunay refinement graded by a density (method.md, Algorithm 2), written on CGAL's
// Delaunay_triangulation_2 rather than with CGAL's Delaunay_mesher_2, because:
//  - for the unit disk every boundary sample must lie exactly on the circle: an encroached
//    boundary edge is split at its arc midpoint, which the mesher (straight constrained
//    segments, split at their midpoints) cannot do;
//  - the size test needs the largest density over a triangle (a narrow peak of a piecewise-
//    linear density sits at an input point, which a coarse triangle's corners and centre miss);
//  - the count of samples must follow NumberOfSamples, which needs re-runs with a corrected
//    threshold, and the work must be capped and abortable.
// The refinement is Chew/Ruppert's: take the worst triangle (too large: nu-length of its
// circumradius above eps; or too thin: smallest angle below the bound), insert its
// circumcentre, unless that encroaches a boundary edge (lies outside the domain or inside the
// edge's diametral circle), in which case the boundary edge is split instead.
// CGAL's assertions on in this file (whatever NDEBUG says): its mesher, given boundary edges at
// the end of double precision (the crushed tip of a finger crowded beyond it), fails one
// (Refine_edges.h, "n == zone.fh": an edge's inexactly computed midpoint outside the edge's two
// faces) and, with it off, crashed. On, the failure is an exception that sampleDensity turns
// into a message about the domain. Only assertions: with the pre- and postconditions too, 1e6
// samples took 4-7% longer, with assertions alone ~1%. Only this file instantiates the mesher;
// of the CGAL functions it shares with other files (exact arithmetic, spatial sorting) none
// carries a check but the assertion machinery itself (objdump of this object, 2026-11-27), so
// the other files' code does not change with the define.
#define CGAL_DEBUG
#define CGAL_NO_PRECONDITIONS
#define CGAL_NO_POSTCONDITIONS
#define CGAL_NO_WARNINGS
#include "Sampling/PlanarSampler.h"

#include "Transport/PlanarPowerDiagram.h"
#include "Transport/SemiDiscreteOT.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <numeric>
#include <queue>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace otparam
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double MaximumBoundaryArc = Pi / 8.0;
using Clock = std::chrono::steady_clock;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_2;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<double, K>; // info: density there
using Fb = CGAL::Triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
using FaceHandle = DT::Face_handle;
using VertexHandle = DT::Vertex_handle;

double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Vec2 toVec(const Point& p)
{
  return { p.x(), p.y() };
}

// Three boundary samples on a straight boundary edge are collinear only up to rounding: the
// "triangle" they make has no area, and its circumcentre lies far away. Refining it would split
// boundary edges forever; it is left alone, and left out of the output.
bool isSliver(const Point& p, const Point& q, const Point& r)
{
  const double longest = std::max(
    { CGAL::squared_distance(p, q), CGAL::squared_distance(q, r), CGAL::squared_distance(r, p) });
  const double twiceArea =
    std::abs((q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x()));
  return twiceArea <= 1e-10 * longest;
}

class Refinement
{
public:
  Refinement(
    const DensityField& field, const SamplerOptions& options, double epsilon, long long cap)
    : Field(field)
    , Graded(options.mode == SamplingMode::Adaptive)
    , Rule(options.sizeRule)
    , Epsilon(epsilon)
    , SinMinimumAngle(std::sin(options.minimumAngleDegrees * Pi / 180.0))
    , Cap(cap)
  {
  }

  // Returns false when aborted. With `seeds`, refines their triangulation (the first run
  // starts from boundary samples only).
  bool run(
    const std::function<bool(long long)>& keepGoing, const std::vector<Vec2>* seeds = nullptr)
  {
    if (seeds)
    {
      std::vector<std::pair<Point, double>> points;
      for (const Vec2& p : *seeds)
      {
        points.emplace_back(
          Point(p.x, p.y), Graded && std::isfinite(Epsilon) ? Field.value(p) : 1.0);
      }
      Triangulation.insert(points.begin(), points.end());
    }
    else
    {
      placeBoundarySamples();
    }
    RefinementAbortCheck abortCheck(keepGoing);
    const auto stepDone = [&] { return abortCheck.stepDone(Triangulation.number_of_vertices()); };
    for (auto f = Triangulation.finite_faces_begin(); f != Triangulation.finite_faces_end(); ++f)
    {
      consider(f);
      if (!stepDone())
      {
        return false;
      }
    }
    while (!Queue.empty())
    {
      if (static_cast<long long>(Triangulation.number_of_vertices()) >= Cap)
      {
        Capped = true;
        break;
      }
      const Entry entry = Queue.top();
      Queue.pop();
      const FaceHandle f = entry.face;
      // Faces die on insertion; their storage is reused: a face is still ours when it still
      // has the same three vertices (no dereference of a dead face's vertices happens here).
      if (f->vertex(0) != entry.v[0] || f->vertex(1) != entry.v[1] || f->vertex(2) != entry.v[2])
      {
        continue;
      }
      refine(f);
      if (!stepDone())
      {
        return false;
      }
    }
    return keepGoing(Triangulation.number_of_vertices());
  }

  const DT& triangulation() const { return Triangulation; }
  bool capped() const { return Capped; }

private:
  struct Entry
  {
    double priority;
    FaceHandle face;
    std::array<VertexHandle, 3> v;
    bool operator<(const Entry& other) const { return priority < other.priority; }
  };

  // nu-length of a Euclidean length 1 where the density is g.
  double grading(double g) const
  {
    if (!Graded)
    {
      return 1.0;
    }
    return Rule == SizeRule::SqrtDensity ? std::sqrt(g) : g;
  }

  VertexHandle insert(Vec2 p, FaceHandle hint)
  {
    VertexHandle v = Triangulation.insert(Point(p.x, p.y), hint);
    v->info() = Graded && std::isfinite(Epsilon) ? Field.value(p) : 1.0;
    return v;
  }

  // Boundary samples spaced by nu-length eps along the domain's boundary (on the circle for
  // the unit disk), from a fine quadrature of the grading along it.
  void placeBoundarySamples()
  {
    std::vector<Vec2> boundary;
    if (Field.isUnitDisk())
    {
      const int fine = 8192;
      std::vector<double> cumulative(fine + 1, 0.0);
      for (int k = 0; k < fine; ++k)
      {
        const double a = 2.0 * Pi * (k + 0.5) / fine;
        cumulative[k + 1] =
          cumulative[k] + grading(Field.value({ std::cos(a), std::sin(a) })) * 2.0 * Pi / fine;
      }
      const int count = std::max(12, static_cast<int>(std::ceil(cumulative.back() / Epsilon)));
      std::vector<double> angles;
      for (int s = 0; s < count; ++s)
      {
        const double target = cumulative.back() * s / count;
        const int k =
          static_cast<int>(
            std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin()) -
          1;
        const double within = (target - cumulative[k]) / (cumulative[k + 1] - cumulative[k]);
        angles.push_back(2.0 * Pi * (k + within) / fine);
      }
      // Where the density (nearly) vanishes the steps above get long: no arc may span more than
      // MaximumBoundaryArc, so that every boundary edge keeps its arc on the outer side.
      for (size_t s = 0; s < angles.size(); ++s)
      {
        const double from = angles[s];
        const double to = s + 1 < angles.size() ? angles[s + 1] : angles[0] + 2.0 * Pi;
        const int pieces = static_cast<int>(std::ceil((to - from) / MaximumBoundaryArc));
        for (int p = 0; p < pieces; ++p)
        {
          const double a = from + (to - from) * p / pieces;
          boundary.push_back({ std::cos(a), std::sin(a) });
        }
      }
    }
    else
    {
      const auto& hull = Field.boundary();
      for (size_t e = 0; e < hull.size(); ++e)
      {
        const Vec2 a = hull[e], b = hull[(e + 1) % hull.size()];
        const int fine = 1024;
        double length = 0.0;
        for (int k = 0; k < fine; ++k)
        {
          length += grading(Field.value(a + ((k + 0.5) / fine) * (b - a))) * norm(b - a) / fine;
        }
        const int count = std::max(1, static_cast<int>(std::ceil(length / Epsilon)));
        for (int s = 0; s < count; ++s)
        {
          boundary.push_back(a + (static_cast<double>(s) / count) * (b - a));
        }
      }
    }
    std::vector<std::pair<Point, double>> points;
    for (const Vec2& p : boundary)
    {
      points.emplace_back(Point(p.x, p.y), Graded ? Field.value(p) : 1.0);
    }
    Triangulation.insert(points.begin(), points.end());
  }

  // Pushes the face when it is too large or too thin.
  void consider(FaceHandle f)
  {
    const Point &p = f->vertex(0)->point(), &q = f->vertex(1)->point(), &r = f->vertex(2)->point();
    const Point c = CGAL::circumcenter(p, q, r);
    const double radius = std::sqrt(CGAL::squared_distance(c, p));
    double g = std::max({ f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() });
    if (Graded && std::isfinite(Epsilon)) // an angles-only pass needs no density
    {
      g = Field.maxInsideTriangle(toVec(p), toVec(q), toVec(r), g);
    }
    const double nuRadius = radius * grading(g);
    const double shortest = std::sqrt(std::min({ CGAL::squared_distance(p, q),
      CGAL::squared_distance(q, r), CGAL::squared_distance(r, p) }));
    if (isSliver(p, q, r))
    {
      return;
    }
    const bool tooLarge = nuRadius > Epsilon;
    const bool tooThin = shortest < 2.0 * radius * SinMinimumAngle * (1.0 - 1e-12);
    if (tooLarge || tooThin)
    {
      Queue.push({ nuRadius, f, { f->vertex(0), f->vertex(1), f->vertex(2) } });
    }
  }

  void refine(FaceHandle f)
  {
    const Point c =
      CGAL::circumcenter(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
    // A boundary edge that c encroaches: the hull edge crossed to reach c, or a hull edge of
    // the face containing c whose diametral lens contains c.
    DT::Locate_type type;
    int index = 0;
    const FaceHandle located = Triangulation.locate(c, type, index, f);
    VertexHandle a, b;
    if (Triangulation.is_infinite(located))
    {
      const int infinite = located->index(Triangulation.infinite_vertex());
      a = located->vertex(Triangulation.cw(infinite));
      b = located->vertex(Triangulation.ccw(infinite));
    }
    else
    {
      for (int k = 0; k < 3; ++k)
      {
        if (!Triangulation.is_infinite(located->neighbor(k)))
        {
          continue;
        }
        const Point &p = located->vertex(Triangulation.cw(k))->point(),
                    &q = located->vertex(Triangulation.ccw(k))->point();
        // Diametral lens (Shewchuk): c encroaches pq when pq subtends more than 120 degrees at
        // c. The diametral circle (90 degrees) would also split boundary edges twice as long as
        // the interior ones, which the boundary needs (see boundaryToDrop).
        const Vec2 u = toVec(p) - toVec(c), w = toVec(q) - toVec(c);
        if (dot(u, w) < -0.5 * norm(u) * norm(w))
        {
          a = located->vertex(Triangulation.cw(k));
          b = located->vertex(Triangulation.ccw(k));
          break;
        }
      }
    }
    const auto before = Triangulation.number_of_vertices();
    VertexHandle v;
    if (a != VertexHandle())
    {
      const Vec2 pa = toVec(a->point()), pb = toVec(b->point());
      Vec2 m = 0.5 * (pa + pb);
      if (Field.isUnitDisk())
      {
        m = (1.0 / norm(m)) * m; // the arc midpoint: boundary samples stay on the circle
      }
      v = insert(m, located);
    }
    else
    {
      v = insert(toVec(c), located);
    }
    if (Triangulation.number_of_vertices() == before)
    {
      // The point already existed (an arc or a triangle too small for double precision): leave
      // this triangle as it is rather than queue it again forever.
      return;
    }
    auto face = Triangulation.incident_faces(v), done = face;
    do
    {
      if (!Triangulation.is_infinite(face))
      {
        consider(face);
      }
    } while (++face != done);
  }

  const DensityField& Field;
  const bool Graded;
  const SizeRule Rule;
  const double Epsilon;
  const double SinMinimumAngle;
  const long long Cap;
  DT Triangulation;
  std::priority_queue<Entry> Queue;
  bool Capped = false;
};

double smallestAngleDegrees(const std::vector<Vec2>& p, const std::vector<Triangle>& triangles)
{
  double smallest = 180.0;
  for (const Triangle& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Vec2 o = p[t[k]], u = p[t[(k + 1) % 3]] - o, w = p[t[(k + 2) % 3]] - o;
      smallest = std::min(smallest, std::atan2(std::abs(cross(u, w)), dot(u, w)) * 180.0 / Pi);
    }
  }
  return smallest;
}

// The hull vertices of a triangulation, in order along the hull.
std::vector<VertexHandle> hullVertices(const DT& dt)
{
  std::vector<VertexHandle> hull;
  auto v = dt.incident_vertices(dt.infinite_vertex()), done = v;
  if (v != nullptr)
  {
    do
    {
      hull.push_back(v);
    } while (++v != done);
  }
  return hull;
}

// A sample on the boundary has its Voronoi cell cut in half by the boundary (measured: boundary
// samples carried 0.43 of the mean mass, which alone made the masses' spread 0.15). So every
// other boundary sample is dropped after the refinement (never a corner of a polygon domain):
// the boundary cells become about twice as long along the boundary, and as heavy as the
// interior ones once the relaxation below has moved the first interior layer.
std::unordered_set<const void*> boundaryToDrop(const DT& dt, const DensityField& field)
{
  std::unordered_set<const void*> drop;
  const auto hull = hullVertices(dt);
  auto isCorner = [&](VertexHandle v)
  {
    if (field.isUnitDisk())
    {
      return false;
    }
    for (const Vec2& c : field.boundary())
    {
      if (c.x == v->point().x() && c.y == v->point().y())
      {
        return true;
      }
    }
    return false;
  };
  bool previousDropped = true; // never drop the first one
  for (size_t k = 0; k + 1 < hull.size(); ++k)
  {
    if (!previousDropped && !isCorner(hull[k]))
    {
      drop.insert(&*hull[k]);
      previousDropped = true;
    }
    else
    {
      previousDropped = false;
    }
  }
  return drop;
}

// Relaxation of the interior samples towards equal masses: Lloyd steps (each interior sample
// moves to the centroid of its cell) on power cells whose offsets grow where a cell is too light
// and shrink where it is too heavy, in the spirit of capacity-constrained Voronoi tessellations
// (de Goes et al., "Blue noise through optimal transport", 2012).
// - Plain Lloyd for the density g^2 (a centroidal tessellation for g^2 has cells of area ~ 1/g,
//   i.e. of equal g-mass) evens out the interior: refinement alone leaves triangles between
//   half and all of the size bound (spread of interior masses 0.16 for a constant density;
//   4 steps 0.10, 8 steps 0.09, 32 steps 0.066). But the boundary samples stay on the boundary,
//   and their cells stay half as heavy as the others (0.5-0.55 of the mean).
// - The offsets make a light boundary cell push its interior neighbours away and steer the
//   interior to equal masses directly (it narrows the spread of the masses for ~5% more time;
//   docs/design.md).
// - Each offset step is one Jacobi step of the mass equations, its relative mass change clamped
//   to 50%: unclamped, cells where g varies a lot within one cell (the mixture's tails) were
//   steered by wrong estimates and swallowed their neighbours. The last step is a plain Lloyd
//   step: straight after a steered one, the Delaunay triangles are thinner and the angle repair
//   below had to insert 3x as many samples (722 instead of 224), whose small cells undid the gain.
// The offsets only steer the positions; the output masses are those of the plain Voronoi cells.
// The paper's R * g rule (density g^4) gets plain Lloyd steps, as the paper's baseline.
constexpr int RelaxationSteps = 4;
constexpr double LargestSteeredMassChange = 0.5;
// d(cell area)/d(offset) of a cell in a regular triangular lattice: 6 edges of length a / sqrt(3)
// at distance a.
constexpr double CellAreaPerOffset = 3.4641016151377544;

// One Jacobi step of "every cell has the mean mass" on the offsets of the power cells measured
// with the density g^power; equalizedPower 1 equalizes g-masses, 0 areas. Returns the
// coefficient of variation of the masses it equalizes (as estimated, before the step).
double steerOffsets(const DensityField& field, double power, double equalizedPower,
  const CellMeasures& cells, std::vector<double>& offset)
{
  const size_t n = offset.size();
  // Each cell's g-mass and area follow from g at its centroid: exact for a constant density,
  // first order otherwise.
  std::vector<double> equalized(n, 0.0), area(n, 0.0);
  // Parallel: one density query (a box-tree search) per cell is the cost of this step.
#pragma omp parallel for schedule(static)
  for (long long i = 0; i < static_cast<long long>(n); ++i)
  {
    const double g = power > 0.0 ? field.value(cells.centroid[i]) : 1.0;
    const double gPower = std::pow(g, power); // 0 where g^power underflows: not steered
    if (gPower > 0.0 && cells.mass[i] > 0.0)
    {
      equalized[i] = cells.mass[i] * std::pow(g, equalizedPower - power);
      area[i] = cells.mass[i] / gPower;
    }
  }
  // Summed in one order: a reduction's order follows the thread count, and so would the
  // samples (and the whole map) in their last digits.
  const double mean =
    std::accumulate(equalized.begin(), equalized.end(), 0.0) / static_cast<double>(n);
  for (size_t i = 0; i < n; ++i)
  {
    if (equalized[i] > 0.0)
    {
      const double change =
        std::clamp(mean / equalized[i] - 1.0, -LargestSteeredMassChange, LargestSteeredMassChange);
      offset[i] += change * area[i] / CellAreaPerOffset;
    }
  }
  return massCoefficientOfVariation(equalized);
}

// What the relaxation did: ran, gave up at once because the unrelaxed masses already spread by
// more than it can help with (see relaxWhereItPays), or was stopped (an error or an abort).
enum class Relaxation
{
  Done,
  NotWorthIt,
  Stopped
};
// The unrelaxed masses' spread above which adaptive sampling does not relax.
constexpr double EvenEnough = 0.3;

// Stopped with `error` set when the density cannot be made a source, or with it empty when the
// progress callback aborts. Adaptive sampling gives up after the first integration (samples
// untouched) when it estimates the unrelaxed g-masses to spread by more than EvenEnough.
Relaxation relax(const DensityField& field, const SamplerOptions& options,
  const SourceMeasure& source, std::vector<Vec2>& samples, const std::vector<char>& onBoundary,
  int& steps, std::string& error)
{
  double power = 0.0;
  if (options.mode == SamplingMode::Adaptive)
  {
    power = options.sizeRule == SizeRule::SqrtDensity ? 2.0 : 4.0;
  }
  const auto density = withMappedDensity(
    source, [power](double g) { return std::pow(g, power); }, error, true);
  if (!density)
  {
    return Relaxation::Stopped;
  }
  const bool steered =
    !(options.mode == SamplingMode::Adaptive && options.sizeRule == SizeRule::Density);
  const double equalizedPower = options.mode == SamplingMode::Adaptive ? 1.0 : 0.0;
  std::vector<double> offset(samples.size(), 0.0);
  std::vector<double> heights(samples.size());
  // From FlipsFromSamples on, kept from step to step: the moved samples are triangulated by
  // flips of the last step's triangulation (1e6 samples: ~1 s a step less than a fresh
  // insertion). Below, a fresh insertion costs milliseconds, and it keeps the masses' last bits
  // (the faces' storage order decides the cells' integration order), which the staged
  // transports' chains of 5000-sample stages follow: with the flips, TestCrowding's finger at
  // L / rho = 120 failed in stage 11's sampling (docs/design.md).
  constexpr std::size_t FlipsFromSamples = 20000;
  PowerDiagram diagram;
  const bool flips = samples.size() >= FlipsFromSamples;
  for (int step = 0; step < RelaxationSteps; ++step)
  {
    // An abort is honoured between steps (each integrates over the whole density mesh: ~1 s at
    // 1M triangles); error stays empty then.
    if (options.progress && !options.progress(0.9))
    {
      return Relaxation::Stopped;
    }
    const bool plainStep = !steered || step == RelaxationSteps - 1;
    for (size_t i = 0; i < samples.size(); ++i)
    {
      heights[i] = 0.5 * dot(samples[i], samples[i]) - (plainStep ? 0.0 : offset[i]);
    }
    const CellMeasures cells = flips ? computeCellMeasures(*density, samples, heights, diagram)
                                     : computeCellMeasures(*density, samples, heights);
    ++steps;
    if (!plainStep)
    {
      const double spread = steerOffsets(field, power, equalizedPower, cells, offset);
      if (step == 0 && options.mode == SamplingMode::Adaptive && spread > EvenEnough)
      {
        return Relaxation::NotWorthIt;
      }
    }
    for (size_t i = 0; i < samples.size(); ++i)
    {
      // A cell clipped to a non-convex domain can have its centroid outside (across a notch).
      if (!onBoundary[i] && cells.mass[i] > 0.0 &&
        (field.isConvex() || field.contains(cells.centroid[i])))
      {
        samples[i] = cells.centroid[i];
      }
    }
  }
  return Relaxation::Done;
}

// The relaxation and the abort check after it, for both sampling paths; Stopped with the
// result's status set (an error, or aborted) when either stops the run.
Relaxation relaxThenCheck(const DensityField& field, const SamplerOptions& options,
  const SourceMeasure& source, std::vector<Vec2>& samples, const std::vector<char>& onBoundary,
  SamplerResult& result)
{
  std::string error;
  const Relaxation outcome =
    relax(field, options, source, samples, onBoundary, result.relaxationSteps, error);
  if (outcome == Relaxation::Stopped)
  {
    result.status.error = error;
    result.status.aborted = error.empty();
    return outcome;
  }
  result.status.aborted = options.progress && !options.progress(0.9);
  return result.status.aborted ? Relaxation::Stopped : outcome;
}

struct Candidate
{
  std::vector<Vec2> samples;
  std::vector<Triangle> triangles;
  std::vector<double> mass;
  double coefficientOfVariation = std::numeric_limits<double>::infinity();
  double secondsMasses = 0.0;
};

// Masses: the density over each sample's Voronoi cell clipped to the domain, exactly,
// normalized to the source mass.
Candidate massesOf(const SourceMeasure& source, const std::vector<Vec2>& samples, double sourceMass)
{
  Candidate c;
  std::vector<double> heights(samples.size());
  for (size_t i = 0; i < heights.size(); ++i)
  {
    heights[i] = 0.5 * dot(samples[i], samples[i]);
  }
  const CellMeasures cells = computeCellMeasures(source, samples, heights);
  const double total = std::accumulate(cells.mass.begin(), cells.mass.end(), 0.0);
  c.mass.resize(cells.mass.size());
  double variance = 0.0;
  const double mean = sourceMass / static_cast<double>(c.mass.size());
  for (size_t i = 0; i < cells.mass.size(); ++i)
  {
    c.mass[i] = cells.mass[i] * sourceMass / total;
    variance += (c.mass[i] - mean) * (c.mass[i] - mean);
  }
  c.coefficientOfVariation = std::sqrt(variance / static_cast<double>(c.mass.size())) / mean;
  return c;
}

// Samples with their triangles, and their masses (timed).
Candidate measuredCandidate(const SourceMeasure& source, std::vector<Vec2> points,
  std::vector<Triangle> triangles, double sourceMass)
{
  const auto t0 = Clock::now();
  Candidate c = massesOf(source, points, sourceMass);
  c.secondsMasses = secondsSince(t0);
  c.samples = std::move(points);
  c.triangles = std::move(triangles);
  return c;
}

// One more refinement pass for angles only (a size bound nothing exceeds): dropping boundary
// samples and relaxing can leave a few thin triangles. Then the masses.
Candidate finishCandidate(const DensityField& field, const SamplerOptions& options,
  const SourceMeasure& source, const std::vector<Vec2>& samples, double sourceMass)
{
  Refinement repair(field, options, std::numeric_limits<double>::infinity(),
    refinementLimit(options, static_cast<double>(samples.size())));
  repair.run([](long long) { return true; }, &samples);
  const DT& dt = repair.triangulation();
  std::vector<Vec2> points;
  std::vector<Triangle> triangles;
  std::unordered_map<const void*, int> id;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
  {
    id[&*v] = static_cast<int>(points.size());
    points.push_back(toVec(v->point()));
  }
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
  {
    if (!isSliver(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()))
    {
      triangles.push_back({ id[&*f->vertex(0)], id[&*f->vertex(1)], id[&*f->vertex(2)] });
    }
  }
  return measuredCandidate(source, std::move(points), std::move(triangles), sourceMass);
}

void adopt(SamplerResult& result, Candidate c, bool relaxed)
{
  result.relaxed = relaxed;
  result.secondsMasses = c.secondsMasses;
  result.samples = std::move(c.samples);
  result.triangles = std::move(c.triangles);
  result.mass = std::move(c.mass);
  result.massCoefficientOfVariation = c.coefficientOfVariation;
}

// Lloyd steps even out the masses of densities the samples resolve, but where the density
// varies faster than the samples can follow (a conformal image with crowded or singular parts)
// they make things worse. Adaptive sampling keeps the relaxed samples when their masses spread
// by at most EvenEnough (0.3), or by less than the unrelaxed ones; and it does not relax at all
// when its first integration estimates the unrelaxed masses to spread by more than that: on
// the shared meshes such a relaxation made them more even in none of the 8 cases
// (hand_choi_53k 0.33 -> 0.40, face_maxplanck_partial_32k 0.44 -> 1.16, ...) and cost three
// more integrations over the density mesh and a candidate, 40-50% of the sampler (relaxed:
// bust_aphrodite_56k 0.28 -> 0.25, hemisphere_2k 0.17 -> 0.10, the face at 1.09M points and
// 21599 samples 0.25 -> 0.21). Uniform sampling (a sampling of the area) always relaxes.
// makeRelaxed relaxes and finishes a candidate; makeUnrelaxed finishes the unrelaxed samples.
void relaxWhereItPays(SamplerResult& result, bool adaptive,
  const std::function<Relaxation(Candidate&)>& makeRelaxed,
  const std::function<Candidate()>& makeUnrelaxed)
{
  Candidate relaxed;
  const Relaxation outcome = makeRelaxed(relaxed);
  if (outcome == Relaxation::Stopped)
  {
    return;
  }
  if (outcome == Relaxation::NotWorthIt)
  {
    adopt(result, makeUnrelaxed(), false);
    return;
  }
  if (adaptive && relaxed.coefficientOfVariation > EvenEnough)
  {
    Candidate unrelaxed = makeUnrelaxed();
    if (unrelaxed.coefficientOfVariation < relaxed.coefficientOfVariation)
    {
      adopt(result, std::move(unrelaxed), false);
      return;
    }
  }
  adopt(result, std::move(relaxed), true);
}

// ---- Domains that are not convex (holes, several components, concavities): the same graded
// refinement, on CGAL's constrained Delaunay mesher. Here the boundary is polygonal (a circle
// is always convex), so the mesher's straight constrained edges, split at their midpoints, are
// what is needed, and it already handles what the convex path does by hand: constrained edges
// that keep triangles out of holes, encroachment, and small input angles (clusters).

// Thrown, before the triangulation changes, where CGAL's mesher would loop forever or corrupt
// the triangulation on a point double precision cannot place (MeshTraits, StarChecked below).
struct UnplaceableRefinementPoint
{
};

// K, but for the mesher's one translation. CGAL's cluster split (split_cluster_point in
// Refine_edges_with_clusters.h) doubles a vector from an edge's end until it passes the edge's
// midpoint. For an edge one unit in the last place long, the midpoint is that end, the vector
// is zero, and the loop never ends, inside one refinement step where no cap is checked (a
// peeled stage of two square tubes hung there: robustness.md, finding 11). A zero translation
// is only ever that loop, so it throws, and the refinement stops as stalled.
struct MeshTraits : K
{
  struct Construct_translated_point_2
  {
    Point operator()(const Point& p, const K::Vector_2& v) const
    {
      if (v.x() == 0.0 && v.y() == 0.0)
      {
        throw UnplaceableRefinementPoint{};
      }
      return K::Construct_translated_point_2()(p, v);
    }
  };
  Construct_translated_point_2 construct_translated_point_2_object() const { return {}; }
};
using MeshFb = CGAL::Delaunay_mesh_face_base_2<MeshTraits>;
using MeshTds =
  CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_2<MeshTraits>, MeshFb>;
using CDT =
  CGAL::Constrained_Delaunay_triangulation_2<MeshTraits, MeshTds, CGAL::Exact_predicates_tag>;

// The mesher's size criterion on edge lengths, replaced by the nu-length of the circumradius
// against eps (the convex path's test), with the largest density over the triangle.
class GradedCriteria : public CGAL::Delaunay_mesh_size_criteria_2<CDT>
{
  using Base = CGAL::Delaunay_mesh_size_criteria_2<CDT>;

public:
  using Quality = Base::Quality;
  struct Grading
  {
    const DensityField* field;
    bool graded;
    SizeRule rule;
    double epsilon; // infinite: angles only
  };

  // The angle bound lives in a virtual base: it must be initialized here, or it stays CGAL's
  // default of 20.7 degrees.
  GradedCriteria(double sinMinimumAngle, const Grading& grading)
    : CGAL::Delaunay_mesh_criteria_2<CDT>(sinMinimumAngle * sinMinimumAngle)
    , Base(sinMinimumAngle * sinMinimumAngle, 0.0)
    , Sizes(grading)
  {
  }

  class Is_bad
  {
  public:
    Is_bad(double bound, const Grading& grading)
      : B(bound)
      , G(grading)
    {
    }
    CGAL::Mesh_2::Face_badness operator()(const Quality& q) const
    {
      if (q.size() > 1.0)
      {
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      }
      return q.sine() < B ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }
    CGAL::Mesh_2::Face_badness operator()(const CDT::Face_handle& f, Quality& q) const
    {
      const Point &p = f->vertex(0)->point(), &r = f->vertex(1)->point(),
                  &s = f->vertex(2)->point();
      if (isSliver(p, r, s))
      {
        // Boundary samples on one straight input edge (see isSliver): refining their flat
        // "triangle" would split the edge forever.
        q = Quality(1.0, 0.0);
        return CGAL::Mesh_2::NOT_BAD;
      }
      const double a = CGAL::squared_distance(r, s), b = CGAL::squared_distance(s, p),
                   c = CGAL::squared_distance(p, r);
      const double twiceArea = std::abs(CGAL::area(p, r, s)) * 2.0;
      // Squared sine of the smallest angle, as CGAL's criteria compute it.
      const double largest = std::max({ a, b, c });
      const double middle = a + b + c - largest - std::min({ a, b, c });
      q.first = twiceArea * twiceArea / (largest * middle);
      q.second = 0.0;
      if (std::isfinite(G.epsilon))
      {
        const double radius = std::sqrt(CGAL::squared_distance(CGAL::circumcenter(p, r, s), p));
        double g = 1.0;
        if (G.graded)
        {
          const Vec2 vp = toVec(p), vr = toVec(r), vs = toVec(s);
          g = G.field->maxInsideTriangle(
            vp, vr, vs, std::max({ G.field->value(vp), G.field->value(vr), G.field->value(vs) }));
          g = G.rule == SizeRule::SqrtDensity ? std::sqrt(g) : g;
        }
        const double ratio = radius * g / G.epsilon;
        q.second = ratio * ratio;
      }
      return operator()(q);
    }

  private:
    double B;
    Grading G;
  };

  Is_bad is_bad_object() const { return Is_bad(this->bound(), Sizes); }

private:
  Grading Sizes;
};

// A mesher level whose insertions first check what CGAL's star_hole assumes: the new point lies
// in the region it re-triangulates (a face of the conflict zone, or an edge between two). An
// edge's midpoint computed in doubles can miss both of the edge's faces when one is thinner
// than the rounding (boundaries at double precision's end, finding 11 of robustness.md): CGAL
// then inserts it anyway, the faces around the new vertex no longer close up, and the mesher
// circled around it forever. Only the edge level may land on a vertex; the face level's
// circumcentre there is a no-op CGAL already handles.
template <typename Level, bool EdgeLevel>
class StarChecked : public Level
{
public:
  using Level::Level;

  template <typename Zone>
  CDT::Vertex_handle insert_impl(const Point& p, Zone& zone)
  {
    const auto inZone = [&](const CDT::Face_handle& f)
    { return std::find(zone.faces.begin(), zone.faces.end(), f) != zone.faces.end(); };
    bool holds = false;
    switch (zone.locate_type)
    {
      case CDT::FACE:
      case CDT::OUTSIDE_CONVEX_HULL:
        holds = inZone(zone.fh);
        break;
      case CDT::EDGE:
        holds = inZone(zone.fh) && inZone(zone.fh->neighbor(zone.i));
        break;
      case CDT::VERTEX:
        holds = !EdgeLevel;
        break;
      default:
        break;
    }
    if (!holds)
    {
      throw UnplaceableRefinementPoint{};
    }
    return Level::insert_impl(p, zone);
  }
};

// CGAL's Delaunay_mesher_2, composed of the same levels, checked (StarChecked). Its levels are
// fixed inside Delaunay_mesher_2, hence this copy of its composition.
class Mesher
{
  using Gabriel = CGAL::Mesh_2::Is_locally_conforming_Gabriel<CDT>;
  using EdgesBase = StarChecked<CGAL::Mesh_2::Refine_edges_base_with_clusters<CDT, Gabriel>, true>;
  using Edges = CGAL::Mesh_2::Refine_edges_with_clusters<CDT, Gabriel, EdgesBase>;
  using FacesBase = StarChecked<CGAL::Mesh_2::Refine_faces_base<CDT, GradedCriteria, Edges>, false>;
  using Faces = CGAL::Mesh_2::Refine_faces<CDT, GradedCriteria, Edges, FacesBase>;

public:
  // The domain's faces must be marked (markDomain) before.
  Mesher(CDT& cdt, const GradedCriteria& criteria)
    : Criteria(criteria)
    , Clusters(cdt)
    , EdgeLevel(cdt, Clusters, NullLevel)
    , FaceLevel(cdt, Criteria, EdgeLevel)
    , Visitor(FaceLevel, EdgeLevel, NullVisitor)
  {
    Clusters.create_clusters();
    EdgeLevel.scan_triangulation();
    FaceLevel.scan_triangulation();
  }

  // False when done. Throws UnplaceableRefinementPoint, the triangulation unchanged by the step.
  bool try_one_step_refine_mesh() { return FaceLevel.one_step(Visitor); }

private:
  GradedCriteria Criteria;
  CGAL::Null_mesher_level NullLevel;
  CGAL::Null_mesh_visitor NullVisitor;
  CGAL::Mesh_2::Clusters<CDT> Clusters;
  Edges EdgeLevel;
  Faces FaceLevel;
  CGAL::Mesh_2::Refine_edges_visitor_from_faces<Faces> Visitor;
};

// Faces of the constrained triangulation inside the domain: those an odd number of constrained
// edges away from the outside (the domain's boundary loops are the constraints). The mesher's
// own marks are not trusted after a refinement: splitting a hole's boundary edge marks the new
// faces on both sides as inside.
void markDomain(CDT& cdt)
{
  if (cdt.dimension() < 2)
  {
    return; // no faces (and no infinite face to flood from)
  }
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
  {
    f->set_in_domain(false);
  }
  std::unordered_set<const void*> reached;
  std::vector<CDT::Face_handle> frontier{ cdt.infinite_face() }, next;
  reached.insert(&*cdt.infinite_face());
  for (int level = 0; !frontier.empty(); ++level)
  {
    next.clear();
    // Flood this level's region; faces across a constrained edge start the next level.
    while (!frontier.empty())
    {
      const CDT::Face_handle f = frontier.back();
      frontier.pop_back();
      f->set_in_domain(level % 2 == 1);
      for (int k = 0; k < 3; ++k)
      {
        const CDT::Face_handle n = f->neighbor(k);
        if (reached.count(&*n))
        {
          continue;
        }
        if (f->is_constrained(k))
        {
          next.push_back(n);
        }
        else
        {
          reached.insert(&*n);
          frontier.push_back(n);
        }
      }
    }
    for (const CDT::Face_handle& n : next)
    {
      if (reached.insert(&*n).second)
      {
        frontier.push_back(n);
      }
    }
  }
}

// CGAL's mesher steps that insert nothing (a rejected point, a face no longer bad) are few
// between insertions; on a domain reaching 1e300 its constructions overflow and it stepped for
// minutes without a new vertex.
constexpr long long StalledMesherSteps = 4096;

// Refines cdt (its boundary already constrained, plus any interior points) until no triangle of
// the domain is too large or too thin, or `cap` vertices (capped), or StalledMesherSteps steps
// without a new vertex or an edge too short to split (stalled, capped too). Returns false when
// aborted.
bool refineSupport(CDT& cdt, const DensityField& field, const SamplerOptions& options,
  double epsilon, long long cap, bool& capped, bool& stalled,
  const std::function<bool(long long)>& keepGoing)
{
  markDomain(cdt);
  GradedCriteria::Grading grading{ &field, options.mode == SamplingMode::Adaptive, options.sizeRule,
    epsilon };
  Mesher mesher(cdt, GradedCriteria(std::sin(options.minimumAngleDegrees * Pi / 180.0), grading));
  long long steps = 0, stepOfLastVertex = 0;
  auto vertices = cdt.number_of_vertices();
  while (true)
  {
    try
    {
      if (!mesher.try_one_step_refine_mesh())
      {
        break;
      }
    }
    catch (const UnplaceableRefinementPoint&)
    {
      // Thrown before the step changed the triangulation: it stays valid, refined this far.
      capped = stalled = true;
      break;
    }
    if (static_cast<long long>(cdt.number_of_vertices()) >= cap)
    {
      capped = true;
      break;
    }
    if (cdt.number_of_vertices() > vertices)
    {
      vertices = cdt.number_of_vertices();
      stepOfLastVertex = steps;
    }
    else if (steps - stepOfLastVertex > StalledMesherSteps)
    {
      capped = stalled = true;
      break;
    }
    if (++steps % 4096 == 0 && !keepGoing(static_cast<long long>(cdt.number_of_vertices())))
    {
      return false;
    }
  }
  markDomain(cdt);
  return true;
}

// The boundary vertices of the refined triangulation, loop by loop, with the domain on the left.
std::vector<std::vector<Vec2>> boundaryLoopsOf(const CDT& cdt)
{
  std::map<std::pair<double, double>, Vec2> next;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
  {
    if (!f->is_in_domain())
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      if (f->is_constrained(k))
      {
        const Point& from = f->vertex(CDT::ccw(k))->point();
        next[{ from.x(), from.y() }] = toVec(f->vertex(CDT::cw(k))->point());
      }
    }
  }
  std::vector<std::vector<Vec2>> loops;
  std::set<std::pair<double, double>> done;
  for (const auto& [start, unused] : next)
  {
    if (done.count(start))
    {
      continue;
    }
    std::vector<Vec2> loop;
    std::pair<double, double> v = start;
    while (!done.count(v) && next.count(v))
    {
      done.insert(v);
      loop.push_back({ v.first, v.second });
      const Vec2 w = next.at(v);
      v = { w.x, w.y };
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

// Corners of a boundary loop: where it turns by more than 10 degrees. Between corners the
// boundary is sampled as one curve, so that a circle given as a fine polygon is not sampled at
// least once per input edge whatever the sample count.
std::vector<char> loopCorners(const std::vector<Vec2>& loop)
{
  const size_t n = loop.size();
  std::vector<char> corner(n, 0);
  for (size_t k = 0; k < n; ++k)
  {
    const Vec2 u = loop[k] - loop[(k + n - 1) % n], w = loop[(k + 1) % n] - loop[k];
    corner[k] =
      dot(u, w) < 0.0 || std::abs(cross(u, w)) > std::sin(10.0 * Pi / 180.0) * norm(u) * norm(w);
  }
  return corner;
}

// As boundaryToDrop for the convex path: every other boundary sample goes, except the corners of
// the input's boundary, so that boundary cells are not half as heavy as interior ones.
std::vector<std::vector<Vec2>> thinBoundary(
  const std::vector<std::vector<Vec2>>& loops, const DensityField& field)
{
  std::set<std::pair<double, double>> corners;
  for (const auto& loop : field.boundaryLoops())
  {
    const std::vector<char> isCorner = loopCorners(loop);
    for (size_t k = 0; k < loop.size(); ++k)
    {
      if (isCorner[k])
      {
        corners.insert({ loop[k].x, loop[k].y });
      }
    }
  }
  std::vector<std::vector<Vec2>> thinned;
  for (const auto& loop : loops)
  {
    std::vector<Vec2> kept;
    bool previousDropped = true;
    for (const Vec2& v : loop)
    {
      if (!previousDropped && !corners.count({ v.x, v.y }) && loop.size() > 8)
      {
        previousDropped = true;
        continue;
      }
      kept.push_back(v);
      previousDropped = false;
    }
    thinned.push_back(std::move(kept));
  }
  return thinned;
}

void insertLoops(CDT& cdt, const std::vector<std::vector<Vec2>>& loops)
{
  for (const auto& loop : loops)
  {
    std::vector<Point> points;
    for (const Vec2& v : loop)
    {
      points.emplace_back(v.x, v.y);
    }
    cdt.insert_constraint(points.begin(), points.end(), true);
  }
}

// Samples and the triangles of the domain, angles repaired, with their masses.
Candidate finishSupportCandidate(const DensityField& field, const SamplerOptions& options,
  const SourceMeasure& source, const std::vector<std::vector<Vec2>>& loops,
  const std::vector<Vec2>& interior, double sourceMass)
{
  CDT cdt;
  insertLoops(cdt, loops);
  for (const Vec2& p : interior)
  {
    cdt.insert(Point(p.x, p.y));
  }
  bool capped = false, stalled = false;
  refineSupport(cdt, field, options, std::numeric_limits<double>::infinity(),
    refinementLimit(options, static_cast<double>(cdt.number_of_vertices())), capped, stalled,
    [](long long) { return true; });
  // As after the main refinement: boundary samples the repair added go back on the boundary.
  std::unordered_set<const void*> onBoundary;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
  {
    for (int k = 0; f->is_in_domain() && k < 3; ++k)
    {
      if (f->is_constrained(k))
      {
        onBoundary.insert(&*f->vertex(CDT::cw(k)));
        onBoundary.insert(&*f->vertex(CDT::ccw(k)));
      }
    }
  }
  std::vector<Vec2> points;
  std::vector<Triangle> triangles;
  std::unordered_map<const void*, int> id;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
  {
    if (!f->is_in_domain() ||
      isSliver(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()))
    {
      continue;
    }
    Triangle t;
    for (int k = 0; k < 3; ++k)
    {
      const auto inserted = id.emplace(&*f->vertex(k), static_cast<int>(points.size()));
      if (inserted.second)
      {
        const Vec2 p = toVec(f->vertex(k)->point());
        points.push_back(onBoundary.count(&*f->vertex(k)) ? field.nearestBoundaryPoint(p) : p);
      }
      t[k] = inserted.first->second;
    }
    triangles.push_back(t);
  }
  return measuredCandidate(source, std::move(points), std::move(triangles), sourceMass);
}

// The whole sampling of a non-convex domain: boundary samples along every loop spaced by
// nu-length eps, graded refinement with eps calibrated to the target count, every other
// boundary sample dropped, Lloyd steps, masses. Fills result like sampleDensity does.
// Samples along one boundary loop: from corner to corner (from point 0 round the whole loop
// when it has none), spaced evenly in nu-length along the polyline. False when that would take
// more than `most` samples (samples is then incomplete).
bool sampleLoop(const std::vector<Vec2>& loop, const std::function<double(Vec2)>& grading,
  double epsilon, long long most, std::vector<Vec2>& samples)
{
  const size_t n = loop.size();
  const std::vector<char> corner = loopCorners(loop);
  size_t first = 0;
  while (first < n && !corner[first])
  {
    ++first;
  }
  first = first == n ? 0 : first;
  samples.clear();
  for (size_t piece = first, walked = 0; walked < n;)
  {
    std::vector<Vec2> path{ loop[piece] };
    std::vector<double> cumulative{ 0.0 };
    size_t k = piece;
    do
    {
      const Vec2 a = loop[k], b = loop[(k + 1) % n];
      const int fine = 16;
      for (int q = 0; q < fine; ++q)
      {
        const Vec2 from = a + (static_cast<double>(q) / fine) * (b - a);
        const Vec2 to = a + (static_cast<double>(q + 1) / fine) * (b - a);
        cumulative.push_back(cumulative.back() + grading(0.5 * (from + to)) * norm(to - from));
        path.push_back(to);
      }
      k = (k + 1) % n;
      ++walked;
    } while (k != first && !corner[k]);
    const double pieceCount = std::max(1.0, std::ceil(cumulative.back() / epsilon));
    if (!(pieceCount <= static_cast<double>(most) - static_cast<double>(samples.size())))
    {
      return false;
    }
    const int count = static_cast<int>(pieceCount);
    for (int q = 0; q < count; ++q)
    {
      const double at = cumulative.back() * q / count;
      const size_t j =
        static_cast<size_t>(
          std::upper_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin()) -
        1;
      const double step = cumulative[j + 1] - cumulative[j];
      const double within = step > 0.0 ? (at - cumulative[j]) / step : 0.0;
      samples.push_back(q == 0 ? path[0] : path[j] + within * (path[j + 1] - path[j]));
    }
    piece = k;
  }
  return true;
}

// Vertices of the faces inside the domain.
std::size_t verticesInDomain(const CDT& cdt)
{
  std::unordered_set<const void*> seen;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
  {
    for (int k = 0; f->is_in_domain() && k < 3; ++k)
    {
      seen.insert(&*f->vertex(k));
    }
  }
  return seen.size();
}

// Interior samples: vertices of domain faces that are not on a boundary loop.
std::vector<Vec2> interiorSamples(const CDT& cdt, const std::vector<std::vector<Vec2>>& loops)
{
  std::set<std::pair<double, double>> onLoop;
  for (const auto& loop : loops)
  {
    for (const Vec2& v : loop)
    {
      onLoop.insert({ v.x, v.y });
    }
  }
  std::vector<Vec2> interior;
  std::unordered_set<const void*> seen;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
  {
    for (int k = 0; f->is_in_domain() && k < 3; ++k)
    {
      const Point& p = f->vertex(k)->point();
      if (seen.insert(&*f->vertex(k)).second && !onLoop.count({ p.x(), p.y() }))
      {
        interior.push_back(toVec(p));
      }
    }
  }
  return interior;
}

// The boundary loops sampled at spacing epsilon / grading, at most `limit` samples in all.
// Returns "" or what is wrong.
std::string sampleBoundaryLoops(const DensityField& field, const SamplerOptions& options,
  const std::function<double(Vec2)>& grading, double epsilon, long long limit,
  std::vector<std::vector<Vec2>>& boundary)
{
  long long boundarySamples = 0;
  for (const auto& loop : field.boundaryLoops())
  {
    boundary.emplace_back();
    if (!sampleLoop(loop, grading, epsilon, limit - boundarySamples, boundary.back()))
    {
      std::ostringstream text;
      text << "the domain's boundary alone needs more than " << limit
           << " samples for a run aiming at " << options.numberOfSamples
           << ": it is too long or too fine for so few samples (a spike, a sliver); check the "
              "domain's geometry"
           << (limit == options.maximumNumberOfSamples ? " or raise MaximumNumberOfSamples" : "");
      return text.str();
    }
    boundarySamples += static_cast<long long>(boundary.back().size());
  }
  return {};
}

std::size_t sampleCount(const std::vector<std::vector<Vec2>>& loops)
{
  std::size_t count = 0;
  for (const auto& loop : loops)
  {
    count += loop.size();
  }
  return count;
}

// The field's source measure (for the relaxation's integrals), built on a second thread while
// the refinement, which is sequential, runs on this one; both only read the field.
class SourceInBackground
{
public:
  explicit SourceInBackground(const DensityField& field)
    : Build(
        std::async(std::launch::async, [&field, this] { return field.makeSource(this->Error); }))
  {
  }
  // Waits for the build; null with `error` set when it failed.
  std::unique_ptr<SourceMeasure> get(std::string& error)
  {
    std::unique_ptr<SourceMeasure> source = this->Build.get();
    error = this->Error;
    return source;
  }

private:
  std::string Error; // before Build: written by the build's thread
  std::future<std::unique_ptr<SourceMeasure>> Build;
};

void sampleSupport(
  const DensityField& field, const SamplerOptions& options, double integral, SamplerResult& result)
{
  const double target = static_cast<double>(options.numberOfSamples);
  const bool graded = options.mode == SamplingMode::Adaptive;
  const std::function<double(Vec2)> grading = [&](Vec2 x)
  {
    if (!graded)
    {
      return 1.0;
    }
    const double g = field.value(x);
    return options.sizeRule == SizeRule::SqrtDensity ? std::sqrt(g) : g;
  };
  SourceInBackground sourceBuild(field);
  std::unique_ptr<CDT> cdt;
  std::vector<std::vector<Vec2>> refinedLoops, loops; // all boundary samples; the kept ones
  RefinementProgress progress(options);
  // Tighter than the convex path's 5%: the angle repair after the relaxation adds up to 5%
  // more samples along polygonal boundaries (band of zero density, 500 samples: 539 -> 565),
  // and a run here costs little.
  const bool finished = refineToTargetCount(
    options, integral, 0.04,
    [&](double epsilon)
    {
      cdt = std::make_unique<CDT>();
      const long long limit = refinementLimit(options, target);
      std::vector<std::vector<Vec2>> boundary;
      result.status.error = sampleBoundaryLoops(field, options, grading, epsilon, limit, boundary);
      if (!result.status.error.empty())
      {
        return -1.0;
      }
      insertLoops(*cdt, boundary);
      if (!refineSupport(
            *cdt, field, options, epsilon, limit, result.capped, result.stalled, progress.ofRun()))
      {
        return -1.0;
      }
      refinedLoops = boundaryLoopsOf(*cdt);
      loops = thinBoundary(refinedLoops, field);
      const std::size_t dropped = sampleCount(refinedLoops) - sampleCount(loops);
      return static_cast<double>(verticesInDomain(*cdt) - dropped);
    },
    result);
  if (!finished)
  {
    return;
  }
  // The refinement splits boundary edges at their midpoints, which for a curved boundary given
  // as a polygon lie on chords: put them back on the boundary (a move of the chord's sagitta).
  for (auto& loop : loops)
  {
    for (Vec2& v : loop)
    {
      v = field.nearestBoundaryPoint(v);
    }
  }
  const std::vector<Vec2> interior = interiorSamples(*cdt, refinedLoops);
  std::string error;
  const auto source = sourceBuild.get(error);
  if (!source)
  {
    result.status.error = error;
    return;
  }
  relaxWhereItPays(
    result, graded,
    [&](Candidate& relaxed)
    {
      // Lloyd steps on every sample, the boundary ones held fixed.
      std::vector<Vec2> all;
      std::vector<char> fixed;
      for (const auto& loop : loops)
      {
        all.insert(all.end(), loop.begin(), loop.end());
        fixed.insert(fixed.end(), loop.size(), 1);
      }
      all.insert(all.end(), interior.begin(), interior.end());
      fixed.insert(fixed.end(), interior.size(), 0);
      const Relaxation outcome = relaxThenCheck(field, options, *source, all, fixed, result);
      if (outcome == Relaxation::Done)
      {
        const std::vector<Vec2> interiorRelaxed(
          all.begin() + static_cast<long>(all.size() - interior.size()), all.end());
        relaxed = finishSupportCandidate(
          field, options, *source, loops, interiorRelaxed, result.sourceMass);
      }
      return outcome;
    },
    [&] {
      return finishSupportCandidate(field, options, *source, loops, interior, result.sourceMass);
    });
}
// MeshVertices mode: the used points in input order (so that the input's point arrays line
// up) with the input's triangles.
void takeMeshVertices(const DensityField& field, SamplerResult& result)
{
  // The used points in input order, so that the input's point arrays line up.
  std::vector<int> id(field.points().size(), -1);
  for (const Triangle& t : field.triangles())
  {
    for (int v : t)
    {
      id[v] = 0;
    }
  }
  for (size_t v = 0; v < id.size(); ++v)
  {
    if (id[v] == 0)
    {
      id[v] = static_cast<int>(result.samples.size());
      result.samples.push_back(field.points()[v]);
    }
  }
  for (const Triangle& t : field.triangles())
  {
    result.triangles.push_back({ id[t[0]], id[t[1]], id[t[2]] });
  }
}

// The nu-area of the domain: the integral of the grading squared, from which eps follows.
double gradedArea(const DensityField& field, const SamplerOptions& options)
{
  double integral = 0.0;
  const auto& pts = field.points();
  const auto& triangles = field.triangles();
  for (std::size_t k = 0; k < triangles.size(); ++k)
  {
    const Triangle& t = triangles[k];
    const double area = 0.5 * std::abs(cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]));
    if (!(area > 0.0))
    {
      continue; // no barycentric coordinates
    }
    const double g = options.mode == SamplingMode::Adaptive ? field.valueAtCentroid(k) : 1.0;
    const double grade = options.sizeRule == SizeRule::SqrtDensity ? std::sqrt(g) : g;
    integral += area * grade * grade;
  }
  return integral;
}

// A convex domain: refinement runs whose eps is corrected from the count each reached, then
// the relaxation towards equal masses (kept only when it makes the masses more even).
void sampleConvex(
  const DensityField& field, const SamplerOptions& options, double integral, SamplerResult& result)
{
  const double target = static_cast<double>(options.numberOfSamples);
  SourceInBackground sourceBuild(field);
  RefinementProgress progress(options);
  std::unique_ptr<Refinement> refinement;
  std::unordered_set<const void*> drop; // boundary samples dropped from the last run
  const bool finished = refineToTargetCount(
    options, integral, 0.05,
    [&](double epsilon)
    {
      refinement =
        std::make_unique<Refinement>(field, options, epsilon, refinementLimit(options, target));
      if (!refinement->run(progress.ofRun()))
      {
        return -1.0;
      }
      drop = boundaryToDrop(refinement->triangulation(), field);
      result.capped = refinement->capped();
      return static_cast<double>(refinement->triangulation().number_of_vertices() - drop.size());
    },
    result);
  if (!finished)
  {
    return;
  }
  result.capped = refinement->capped();
  const DT& dt = refinement->triangulation();
  std::unordered_set<const void*> hull;
  for (VertexHandle v : hullVertices(dt))
  {
    hull.insert(&*v);
  }
  std::vector<char> onBoundary;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
  {
    if (!drop.count(&*v))
    {
      result.samples.push_back(toVec(v->point()));
      onBoundary.push_back(hull.count(&*v) ? 1 : 0);
    }
  }
  const std::vector<Vec2> refined = result.samples;
  std::string error;
  const auto source = sourceBuild.get(error);
  if (!source)
  {
    result.status.error = error;
    return;
  }
  relaxWhereItPays(
    result, options.mode == SamplingMode::Adaptive,
    [&](Candidate& relaxed)
    {
      std::vector<Vec2> samples = refined;
      const Relaxation outcome =
        relaxThenCheck(field, options, *source, samples, onBoundary, result);
      if (outcome == Relaxation::Done)
      {
        relaxed = finishCandidate(field, options, *source, samples, result.sourceMass);
      }
      return outcome;
    },
    [&] { return finishCandidate(field, options, *source, refined, result.sourceMass); });
}
// The masses of the result's samples as they are (their Voronoi cells' integrals). False with
// the result's error set when the source cannot be built.
bool integrateMasses(const DensityField& field, SamplerResult& result)
{
  std::string error;
  const auto source = field.makeSource(error);
  if (!source)
  {
    result.status.error = error;
    return false;
  }
  const Candidate c = massesOf(*source, result.samples, result.sourceMass);
  result.mass = c.mass;
  result.massCoefficientOfVariation = c.coefficientOfVariation;
  return true;
}

// SamplerOptions::sampleAtOrigin: the sample nearest the origin moved onto it, the masses
// integrated again. False with the result's error set when the source cannot be built.
bool moveNearestSampleToOrigin(const DensityField& field, SamplerResult& result)
{
  if (result.samples.empty())
  {
    return true;
  }
  const auto nearest = std::min_element(result.samples.begin(), result.samples.end(),
    [](const Vec2& a, const Vec2& b) { return dot(a, a) < dot(b, b); });
  *nearest = Vec2{ 0.0, 0.0 };
  return integrateMasses(field, result);
}
} // namespace

SamplerResult sampleDensity(const DensityField& field, const SamplerOptions& options)
{
  SamplerResult result;
  result.status.error = checkSamplerOptions(options);
  if (!result.status.error.empty())
  {
    return result;
  }
  result.sourceMass = field.isUnitDisk() ? Pi : field.area();
  auto t0 = Clock::now();
  field.prepareForQueries(options.numberOfSamples);

  if (options.mode == SamplingMode::MeshVertices)
  {
    takeMeshVertices(field, result);
  }
  else
  {
    // eps from the target count (refineToTargetCount).
    const double integral = gradedArea(field, options);
    if (options.progress && !options.progress(0.0))
    {
      result.status.aborted = true;
      return result;
    }
    const double target = static_cast<double>(options.numberOfSamples);
    try
    {
      if (field.isConvex())
      {
        sampleConvex(field, options, integral, result);
      }
      else
      {
        sampleSupport(field, options, integral, result);
      }
    }
    catch (const CGAL::Failure_exception&)
    {
      result.status.error =
        "the refinement met features too fine for double precision (points or edges a few "
        "units in the last place apart: a spike, a sliver, a crushed part of a map); check the "
        "domain's geometry";
      return result;
    }
    if (result.status.aborted || !result.status.error.empty())
    {
      return result;
    }
    if (options.sampleAtOrigin && !moveNearestSampleToOrigin(field, result))
    {
      return result;
    }
    result.secondsRefinement = secondsSince(t0) - result.secondsMasses;
    const double reached = static_cast<double>(result.samples.size());
    if (!result.capped && std::abs(reached / target - 1.0) > 0.1)
    {
      std::ostringstream text;
      text << "NumberOfSamples = " << options.numberOfSamples << " not met: reached "
           << result.samples.size() << " samples for a target of " << options.numberOfSamples
           << ": the density varies too fast for so few samples at this minimum angle (the "
              "graded refinement needs that many).";
      result.status.warnings.push_back(text.str());
    }
  }
  if (options.mode == SamplingMode::MeshVertices)
  {
    result.secondsRefinement = secondsSince(t0);
    t0 = Clock::now();
    if (!integrateMasses(field, result))
    {
      return result;
    }
    result.secondsMasses = secondsSince(t0);
  }
  result.minimumAngleDegrees = smallestAngleDegrees(result.samples, result.triangles);
  if (options.progress && !options.progress(1.0))
  {
    result.status.aborted = true;
  }
  return result;
}

} // namespace otparam
