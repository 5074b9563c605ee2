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
#include "AdaptiveSampler.h"

#include "SemiDiscreteOT.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <queue>
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
  const double longest = std::max({ CGAL::squared_distance(p, q), CGAL::squared_distance(q, r),
    CGAL::squared_distance(r, p) });
  const double twiceArea =
    std::abs((q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x()));
  return twiceArea <= 1e-10 * longest;
}

class Refinement
{
public:
  Refinement(const DensityField& field, const SamplerOptions& options, double epsilon)
    : Field(field)
    , Graded(options.mode == SamplingMode::Adaptive)
    , Rule(options.sizeRule)
    , Epsilon(epsilon)
    , SinMinimumAngle(std::sin(options.minimumAngleDegrees * Pi / 180.0))
    , Cap(options.maximumNumberOfSamples)
  {
  }

  // Returns false when aborted. With `seeds`, refines their triangulation (the first run
  // starts from boundary samples only).
  bool run(const std::function<bool(long long)>& keepGoing, const std::vector<Vec2>* seeds = nullptr)
  {
    if (seeds)
    {
      std::vector<std::pair<Point, double>> points;
      for (const Vec2& p : *seeds)
      {
        points.emplace_back(Point(p.x, p.y), Graded && std::isfinite(Epsilon) ? Field.value(p) : 1.0);
      }
      Triangulation.insert(points.begin(), points.end());
    }
    else
    {
      placeBoundarySamples();
    }
    for (auto f = Triangulation.finite_faces_begin(); f != Triangulation.finite_faces_end(); ++f)
    {
      consider(f);
    }
    long long insertions = 0;
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
      if (++insertions % 4096 == 0 && !keepGoing(Triangulation.number_of_vertices()))
      {
        return false;
      }
    }
    return true;
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
        const int k = static_cast<int>(
          std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin()) - 1;
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
    const Point &p = f->vertex(0)->point(), &q = f->vertex(1)->point(),
                &r = f->vertex(2)->point();
    const Point c = CGAL::circumcenter(p, q, r);
    const double radius = std::sqrt(CGAL::squared_distance(c, p));
    double g = std::max({ f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() });
    if (Graded && std::isfinite(Epsilon)) // an angles-only pass needs no density
    {
      g = std::max(g, Field.maxInsideTriangle(toVec(p), toVec(q), toVec(r)));
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
    const Point c = CGAL::circumcenter(
      f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
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
  auto isCorner = [&](VertexHandle v) {
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

// Lloyd relaxation of the interior samples towards a centroidal Voronoi tessellation for the
// density g^2 (Adaptive, R * sqrt(g) rule; g^4 for the R * g rule; 1 for Uniform): in 2D such a
// tessellation has cells of area ~ density^(-1/2) = 1 / g, i.e. of equal g-mass. Delaunay
// refinement alone leaves triangles between about half and all of the size bound (measured
// spread of interior masses 0.16 for a constant density); 8 Lloyd steps bring it to 0.09 (32:
// 0.066; Lloyd converges slowly). Boundary samples stay where they are (on the circle for the
// unit disk), so their cells stay about half as heavy as interior ones (measured 0.5-0.55).
constexpr int RelaxationSteps = 4;

bool relax(const DensityField& field, const SamplerOptions& options, std::vector<Vec2>& samples,
  const std::vector<char>& onBoundary, std::string& error)
{
  double power = 0.0;
  if (options.mode == SamplingMode::Adaptive)
  {
    power = options.sizeRule == SizeRule::SqrtDensity ? 2.0 : 4.0;
  }
  const auto density = field.makeSource(error, power);
  if (!density)
  {
    return false;
  }
  std::vector<double> heights(samples.size());
  for (int step = 0; step < RelaxationSteps; ++step)
  {
    for (size_t i = 0; i < samples.size(); ++i)
    {
      heights[i] = 0.5 * dot(samples[i], samples[i]);
    }
    const CellMeasures cells = computeCellMeasures(*density, samples, heights);
    for (size_t i = 0; i < samples.size(); ++i)
    {
      if (!onBoundary[i] && cells.mass[i] > 0.0)
      {
        samples[i] = cells.centroid[i];
      }
    }
  }
  return true;
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

// One more refinement pass for angles only (a size bound nothing exceeds): dropping boundary
// samples and relaxing can leave a few thin triangles. Then the masses.
Candidate finishCandidate(const DensityField& field, const SamplerOptions& options,
  const SourceMeasure& source, const std::vector<Vec2>& samples, double sourceMass)
{
  Refinement repair(field, options, std::numeric_limits<double>::infinity());
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
  const auto t0 = Clock::now();
  Candidate c = massesOf(source, points, sourceMass);
  c.secondsMasses = secondsSince(t0);
  c.samples = std::move(points);
  c.triangles = std::move(triangles);
  return c;
}
} // namespace

SamplerResult sampleDensity(const DensityField& field, const SamplerOptions& options)
{
  SamplerResult result;
  if (options.numberOfSamples < 3 || options.maximumNumberOfSamples < options.numberOfSamples)
  {
    result.error = "the number of samples must be at least 3 and at most the maximum";
    return result;
  }
  if (!(options.minimumAngleDegrees > 0.0 && options.minimumAngleDegrees <= 35.0))
  {
    result.error = "the minimum angle must be in (0, 35] degrees";
    return result;
  }
  result.sourceMass = field.isUnitDisk() ? Pi : field.area();
  auto t0 = Clock::now();

  if (options.mode == SamplingMode::MeshVertices)
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
  else
  {
    // eps from the target count: the count scales like 1 / eps^2, so one run at a sixteenth of
    // the target calibrates the constant, and one or two more land within 10% of the target.
    double integral = 0.0; // integral of grading^2, the nu-area of the domain
    {
      const auto& pts = field.points();
      for (const Triangle& t : field.triangles())
      {
        const Vec2 c = (1.0 / 3.0) * (pts[t[0]] + pts[t[1]] + pts[t[2]]);
        const double area = 0.5 * std::abs(cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]));
        const double g = options.mode == SamplingMode::Adaptive ? field.value(c) : 1.0;
        const double grade = options.sizeRule == SizeRule::SqrtDensity ? std::sqrt(g) : g;
        integral += area * grade * grade;
      }
    }
    const double target = static_cast<double>(options.numberOfSamples);
    double runTarget = target >= 4000.0 ? target / 4.0 : target;
    double epsilon = std::sqrt(integral / runTarget);
    double done = 0.0;
    std::unique_ptr<Refinement> refinement;
    std::unordered_set<const void*> drop; // boundary samples dropped from the last run
    for (int run = 0; run < 5; ++run)
    {
      refinement = std::make_unique<Refinement>(field, options, epsilon);
      ++result.refinementRuns;
      const double share = runTarget / (target * 2.2); // rough share of the total work
      const bool finished = refinement->run([&](long long count) {
        return !options.progress ||
          options.progress(std::min(0.9, done + 0.9 * share * count / runTarget));
      });
      done = std::min(0.9, done + 0.9 * share);
      if (!finished)
      {
        result.aborted = true;
        return result;
      }
      drop = boundaryToDrop(refinement->triangulation(), field);
      const double count =
        static_cast<double>(refinement->triangulation().number_of_vertices() - drop.size());
      result.epsilon = epsilon;
      if (refinement->capped())
      {
        break;
      }
      epsilon *= std::sqrt(count / target);
      if (runTarget == target && std::abs(count / target - 1.0) <= 0.08)
      {
        break;
      }
      runTarget = target;
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
    std::string error;
    const auto source = field.makeSource(error);
    if (!source)
    {
      result.error = error;
      return result;
    }
    // Lloyd steps even out the masses of well-resolved densities, but on a density that varies
    // faster than the samples can follow (a conformal image with singular corners sampled by a
    // few hundred points) they can make things worse: when the relaxed masses spread by more
    // than 0.3, the unrelaxed samples are tried too and the more even set is kept (Uniform mode
    // always relaxes: it is a sampling of the area).
    const std::vector<Vec2> refined = result.samples;
    std::vector<Vec2> relaxed = refined;
    if (!relax(field, options, relaxed, onBoundary, error))
    {
      result.error = error;
      return result;
    }
    if (options.progress && !options.progress(0.9))
    {
      result.aborted = true;
      return result;
    }
    Candidate best = finishCandidate(field, options, *source, relaxed, result.sourceMass);
    result.relaxed = true;
    if (options.mode == SamplingMode::Adaptive && best.coefficientOfVariation > 0.3)
    {
      Candidate unrelaxed = finishCandidate(field, options, *source, refined, result.sourceMass);
      if (unrelaxed.coefficientOfVariation < best.coefficientOfVariation)
      {
        best = std::move(unrelaxed);
        result.relaxed = false;
      }
    }
    result.secondsMasses = best.secondsMasses;
    result.samples = std::move(best.samples);
    result.triangles = std::move(best.triangles);
    result.mass = std::move(best.mass);
    result.massCoefficientOfVariation = best.coefficientOfVariation;
    result.secondsRefinement = secondsSince(t0) - result.secondsMasses;
    const double reached = static_cast<double>(result.samples.size());
    if (!result.capped && std::abs(reached / target - 1.0) > 0.1)
    {
      std::ostringstream text;
      text << "reached " << result.samples.size() << " samples for a target of "
           << options.numberOfSamples
           << ": the density varies too fast for so few samples at this minimum angle (the "
              "graded refinement needs that many)";
      result.warning = text.str();
    }
  }
  if (options.mode == SamplingMode::MeshVertices)
  {
    result.secondsRefinement = secondsSince(t0);
    t0 = Clock::now();
    std::string error;
    const auto source = field.makeSource(error);
    if (!source)
    {
      result.error = error;
      return result;
    }
    const Candidate c = massesOf(*source, result.samples, result.sourceMass);
    result.mass = c.mass;
    result.massCoefficientOfVariation = c.coefficientOfVariation;
    result.secondsMasses = secondsSince(t0);
  }
  result.minimumAngleDegrees = smallestAngleDegrees(result.samples, result.triangles);
  if (options.progress)
  {
    options.progress(1.0);
  }
  return result;
}

} // namespace otparam
