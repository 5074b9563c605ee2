// Delaunay refinement of the unit sphere graded by a density (method.md, Algorithm 2, carried to
// S^2 as sphere.md asks), on CGAL's Delaunay_triangulation_on_sphere_2: its triangulation is the
// convex hull of the samples, and it inserts one point at a time from a nearby face, which the
// worst-first refinement needs. There is no boundary on the sphere, so Chew/Ruppert's rule is
// plain: take the worst triangle (too large: nu-length of its circumradius above eps; or too
// thin: smallest angle below the bound) and insert its circumcentre on the sphere. With a bound
// of 30 degrees this terminates: the circumcentre is at least the circumradius, hence at least
// the shortest edge of a thin triangle, away from every sample.
// Then, as on the plane, Lloyd steps for the density g^2 (a centroidal tessellation for g^2 has
// cells of equal g-mass) even the masses out, samples of too light cells are removed (and Lloyd
// steps again), and a last angles-only refinement repairs the few thin triangles they leave.
// The output is always the repaired one: its smallest angle is the bound (less 0.4 degrees).
#include "Sampling/SphericalSampler.h"

#include "Common/SphericalGeometry.h"
#include "Sampling/SphericalDensityField.h"
#include "Transport/SphericalPowerDiagram.h"

#include <CGAL/Delaunay_triangulation_on_sphere_2.h>
#include <CGAL/Delaunay_triangulation_on_sphere_traits_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_on_sphere_face_base_2.h>
#include <CGAL/Triangulation_on_sphere_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>

namespace otparam
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
using Clock = std::chrono::steady_clock;
struct VertexInfo
{
  double g = 1.0; // density at the sample
  int hint = -1;  // density triangle containing it
};
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Gt = CGAL::Delaunay_triangulation_on_sphere_traits_2<K>;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Gt,
  CGAL::Triangulation_on_sphere_vertex_base_2<Gt>>;
using Fb =
  CGAL::Triangulation_face_base_with_info_2<int, Gt, CGAL::Triangulation_on_sphere_face_base_2<Gt>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using DT = CGAL::Delaunay_triangulation_on_sphere_2<Gt, Tds>;
using FaceHandle = DT::Face_handle;
using VertexHandle = DT::Vertex_handle;

double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Vec3 toVec(const K::Point_3& p)
{
  return { p.x(), p.y(), p.z() };
}

Vec3 pointOf(FaceHandle f, int k)
{
  return toVec(f->vertex(k)->point());
}

// The circumcentre on the sphere of a triangle counter-clockwise seen from outside: the unit
// normal of its plane (differences keep it accurate for tiny triangles).
Vec3 circumcentre(Vec3 a, Vec3 b, Vec3 c)
{
  return normalized(cross(b - a, c - a));
}

// The 12 vertices of the icosahedron: the well-spread start of every refinement.
std::vector<Vec3> icosahedron()
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v;
  for (double s : { -1.0, 1.0 })
  {
    for (double r : { -t, t })
    {
      v.push_back(normalized({ 0.0, s, r }));
      v.push_back(normalized({ s, r, 0.0 }));
      v.push_back(normalized({ r, 0.0, s }));
    }
  }
  return v;
}

// Indices of the points in Z order on the cube map (face, then interleaved bits of the two
// face coordinates): consecutive insertions are near each other, so each locate is short.
std::vector<int> spatialOrder(const std::vector<Vec3>& points)
{
  std::vector<std::pair<unsigned long long, int>> keys(points.size());
  for (size_t i = 0; i < points.size(); ++i)
  {
    const Vec3 x = points[i];
    const double ax = std::abs(x.x), ay = std::abs(x.y), az = std::abs(x.z);
    unsigned long long face;
    double u, v, w;
    if (ax >= ay && ax >= az)
      face = x.x > 0 ? 0 : 1, u = x.y, v = x.z, w = ax;
    else if (ay >= az)
      face = x.y > 0 ? 2 : 3, u = x.z, v = x.x, w = ay;
    else
      face = x.z > 0 ? 4 : 5, u = x.x, v = x.y, w = az;
    const auto q = [w](double c)
    { return static_cast<unsigned>(std::clamp((c / w + 1.0) * 0.5 * 1048576.0, 0.0, 1048575.0)); };
    const unsigned qu = q(u), qv = q(v);
    unsigned long long code = 0;
    for (int b = 19; b >= 0; --b)
    {
      code = (code << 2) | (((qu >> b) & 1u) << 1) | ((qv >> b) & 1u);
    }
    keys[i] = { (face << 40) | code, static_cast<int>(i) };
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> order;
  for (const auto& k : keys)
  {
    order.push_back(k.second);
  }
  return order;
}

// nu-length of a length 1 where the density is g.
struct Grading
{
  bool graded;
  SizeRule rule;
  double operator()(double g) const
  {
    return !graded ? 1.0 : rule == SizeRule::SqrtDensity ? std::sqrt(g) : g;
  }
};

class Refinement
{
public:
  Refinement(const SphericalDensityField& field, const SamplerOptions& options, double epsilon,
    long long cap)
    : Field(field)
    , Grade{ options.mode == SamplingMode::Adaptive, options.sizeRule }
    , Epsilon(epsilon)
    , SinMinimumAngle(std::sin(options.minimumAngleDegrees * Pi / 180.0))
    , Cap(cap)
  {
  }

  // Inserts the seeds (with their density triangles when known), then refines until no
  // triangle is too large or too thin. Returns false when aborted.
  bool run(const std::vector<Vec3>& seeds, const std::vector<int>& hints,
    const std::function<bool(long long)>& keepGoing)
  {
    FaceHandle near;
    for (int i : spatialOrder(seeds))
    {
      const VertexHandle v = insert(seeds[i], near, hints.empty() ? -1 : hints[i]);
      near = v != VertexHandle() ? v->face() : near;
    }
    RefinementAbortCheck abortCheck(keepGoing);
    const auto stepDone = [&] { return abortCheck.stepDone(Triangulation.number_of_vertices()); };
    for (auto f = Triangulation.all_faces_begin(); f != Triangulation.all_faces_end(); ++f)
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
      // Faces die on insertion and their storage is reused. A dead face keeps its vertices
      // (CGAL keeps its free list in neighbour 0), so liveness is asked of the container; a
      // reused slot is ours when it has the same three vertices.
      if (!Triangulation.tds().faces().is_used(f) || f->vertex(0) != entry.v[0] ||
        f->vertex(1) != entry.v[1] || f->vertex(2) != entry.v[2])
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

  DT& triangulation() { return Triangulation; } // diagramOf numbers its faces
  bool capped() const { return Capped; }

private:
  struct Entry
  {
    double priority;
    FaceHandle face;
    std::array<VertexHandle, 3> v;
    bool operator<(const Entry& other) const { return priority < other.priority; }
  };

  bool needsDensity() const { return Grade.graded && std::isfinite(Epsilon); }

  // Null when CGAL refuses the point (closer than 2^-23 to a sample: it returns that sample).
  VertexHandle insert(Vec3 p, FaceHandle near, int hint)
  {
    const auto before = Triangulation.number_of_vertices();
    const VertexHandle v = Triangulation.insert(K::Point_3(p.x, p.y, p.z), near);
    if (v == VertexHandle() || Triangulation.number_of_vertices() == before)
    {
      return VertexHandle();
    }
    if (needsDensity())
    {
      v->info().hint = Field.locate(p, hint);
      v->info().g = Field.density()[v->info().hint];
    }
    return v;
  }

  // Pushes the face when it is too large or too thin.
  void consider(FaceHandle f)
  {
    if (Triangulation.is_ghost(f))
    {
      return;
    }
    const Vec3 a = pointOf(f, 0), b = pointOf(f, 1), c = pointOf(f, 2);
    const Vec3 normal = cross(b - a, c - a);
    const double twiceArea = norm(normal);
    if (!(twiceArea > 0.0))
    {
      return;
    }
    const Vec3 centre = (1.0 / twiceArea) * normal;
    const double ab = norm(b - a), bc = norm(c - b), ca = norm(a - c);
    const double flatRadius = ab * bc * ca / (2.0 * twiceArea);
    const double shortest = std::min({ ab, bc, ca });
    double g = 1.0;
    if (needsDensity())
    {
      // The largest of the density at the corners and at the circumcentre: a coarse triangle
      // over a peak sees it at one of them at least as soon as the peak is between samples.
      const double g0 = f->vertex(0)->info().g, g1 = f->vertex(1)->info().g,
                   g2 = f->vertex(2)->info().g, gc = Field.value(centre, f->vertex(0)->info().hint);
      g = std::max({ g0, g1, g2, gc });
      // Near the threshold the mean of the four values decides: their largest over-refines
      // where g jumps between the density mesh's triangles, leaving light cells (spot at 5000
      // samples: spread 0.18 -> 0.16 after relaxation and repair, brain 0.16 -> 0.12). Far above
      // it the largest decides, so coarse triangles still see narrow peaks. (The exact mean over
      // the triangle did as well but cost 1.3 s of refinement for brain at 5000 samples.)
      const double radius = sphericalDistance(centre, a);
      if (radius * Grade(g) > Epsilon && radius * Grade(g) < AverageBand * Epsilon)
      {
        g = 0.25 * (g0 + g1 + g2 + gc);
      }
    }
    const double nuRadius = sphericalDistance(centre, a) * Grade(g);
    const bool tooLarge = nuRadius > Epsilon;
    const bool tooThin = shortest < 2.0 * flatRadius * SinMinimumAngle * (1.0 - 1e-12);
    if (tooLarge || tooThin)
    {
      Queue.push({ nuRadius, f, { f->vertex(0), f->vertex(1), f->vertex(2) } });
    }
  }

  void refine(FaceHandle f)
  {
    const Vec3 centre = circumcentre(pointOf(f, 0), pointOf(f, 1), pointOf(f, 2));
    const VertexHandle v = insert(centre, f, f->vertex(0)->info().hint);
    if (v == VertexHandle())
    {
      return; // refused (too close): the face is left as it is
    }
    auto face = Triangulation.incident_faces(v), done = face;
    do
    {
      consider(face);
    } while (++face != done);
  }

  const SphericalDensityField& Field;
  Grading Grade;
  double Epsilon;
  double SinMinimumAngle;
  long long Cap;
  DT Triangulation;
  std::priority_queue<Entry> Queue;
  bool Capped = false;
  static constexpr double AverageBand = 3.0;
};

// Samples, their triangulation and the Voronoi cells, read off a triangulation on the sphere.
struct Diagram
{
  std::vector<Vec3> samples;
  std::vector<int> hints; // density triangle of each sample (-1: unknown)
  std::vector<Triangle> triangles;
  std::vector<std::vector<Vec3>> cells; // counter-clockwise from outside
};

Diagram diagramOf(DT& dt)
{
  if (dt.dimension() < 2)
  {
    // No faces to circulate: the samples lie on one great circle (or are fewer than 4).
    throw std::runtime_error("the samples lie on one great circle (" +
      std::to_string(dt.number_of_vertices()) +
      " samples left): raise NumberOfSamples or lower the density's range");
  }
  Diagram d;
  std::unordered_map<const void*, int> id;
  for (auto v = dt.vertices_begin(); v != dt.vertices_end(); ++v)
  {
    id[&*v] = static_cast<int>(d.samples.size());
    d.samples.push_back(toVec(v->point()));
    d.hints.push_back(v->info().hint);
  }
  std::vector<Vec3> centres;
  for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f)
  {
    f->info() = static_cast<int>(centres.size());
    centres.push_back(circumcentre(pointOf(f, 0), pointOf(f, 1), pointOf(f, 2)));
    d.triangles.push_back({ id[&*f->vertex(0)], id[&*f->vertex(1)], id[&*f->vertex(2)] });
  }
  // The faces around a vertex circulate counter-clockwise (as the faces are oriented): their
  // circumcentres are the cell's corners in order.
  d.cells.resize(d.samples.size());
  for (auto v = dt.vertices_begin(); v != dt.vertices_end(); ++v)
  {
    auto& cell = d.cells[id[&*v]];
    auto f = dt.incident_faces(v), done = f;
    do
    {
      cell.push_back(centres[f->info()]);
    } while (++f != done);
  }
  return d;
}

// A fresh triangulation of the points (all of them, unless two are within 2^-23).
Diagram triangulate(const std::vector<Vec3>& points, const std::vector<int>& hints)
{
  DT dt;
  DT::Face_handle near;
  for (int i : spatialOrder(points))
  {
    const VertexHandle v = dt.insert(K::Point_3(points[i].x, points[i].y, points[i].z), near);
    if (v != VertexHandle())
    {
      v->info().hint = hints.empty() ? -1 : hints[i];
      near = v->face();
    }
  }
  return diagramOf(dt);
}

// Integrals of g^power (and of x g^power) over every cell.
void integrateCells(const SphericalDensityField& field, Diagram& d, double power,
  std::vector<double>& mass, std::vector<Vec3>* moment)
{
  const long long n = static_cast<long long>(d.samples.size());
  mass.assign(n, 0.0);
  if (moment)
  {
    moment->assign(n, Vec3{});
  }
#pragma omp parallel
  {
    SphericalDensityField::Scratch scratch;
#pragma omp for schedule(dynamic, 256)
    for (long long i = 0; i < n; ++i)
    {
      field.integrate(d.cells[i], d.samples[i], d.hints[i], power, scratch, mass[i],
        moment ? &(*moment)[i] : nullptr);
    }
  }
}

// Relaxation towards equal masses, as on the plane (PlanarSampler.cxx, relax): Lloyd steps for
// g^power (power 2: a centroidal tessellation for g^2 has cells of equal g-mass to first
// order; 0: the area) on cells whose heights are steered, one Jacobi step of "every cell has
// the mean mass" per step (measured on a zonal density of contrast 1e3, 1000 samples: plain
// Lloyd left a spread of 0.19 after 4 steps and 0.16 after 16, because g varies within a cell).
// The last steps are plain Lloyd steps on the Voronoi cells. Raising psi_i shrinks cell i by
// about 3.46 times the change over the cell's area (regular hexagons; sphere.md's Hessian).
// The cells are the spherical power diagram's (one Triangulation_3 hull in spatial order: 1e5
// samples relax in ~1.5 s less than with convex_hull_3 and coordinate maps).
// Step counts measured on the conformal densities of spot and brain (3000/5000 samples, spread
// after the angle repair): the Jacobi step is unstable undamped (after 4-6 steps groups of
// hundreds of cells empty out), so it is halved and stopped after 4; then up to 8 plain steps
// (4 -> 8: brain 3000 0.181 -> 0.160, spot 5000 0.182 -> 0.171). More steered steps, or g
// instead of g^2 in them, did worse.
constexpr double LargestSteeredMassChange = 0.5;
constexpr double CellAreaPerHeight = 3.4641016151377544;
constexpr double SteeringGain = 0.5;
constexpr int SteeredSteps = 4;
constexpr int PlainSteps = 8;
// Below this spread of the Voronoi masses (before the repair) the plain steps and the
// removal rounds stop.
constexpr double SpreadGoal = 0.08;
// Rounds of: the samples of cells lighter than this fraction of the mean (at the edges of the
// steepest density: spot's legs and horns, where the 30-degree grading cannot follow g) are
// removed, then plain steps spread their neighbours out. Spread after the repair, spot
// 3000/5000: none 0.27/0.17; one round at 0.5 0.16/0.16; three at 0.6 0.136/0.131; at 0.65
// 0.147/0.120 with the cheap size rule (brain 0.135/0.114).
constexpr double LightCellFraction = 0.65;
constexpr int PlainStepsAfterRemoval = 4;
constexpr int RemovalRounds = 3;
constexpr double RepairAngleSlackDegrees = 0.4;
// Returns false when `keepGoing` (asked before each step: a step integrates over the whole
// density mesh, ~0.5 s at 1.5e6 triangles) says stop.
bool relax(const SphericalDensityField& field, double power, bool equalizeMass, int steeredSteps,
  int plainSteps, std::vector<Vec3>& samples, std::vector<int>& hints,
  const std::function<bool()>& keepGoing)
{
  const long long n = static_cast<long long>(samples.size());
  std::vector<Height> psi(n, Height(0.0L));
  SphericalPowerDiagram diagram;
  std::vector<double> weighted(n), mass(n), area(n);
  std::vector<Vec3> moment(n);
  double previousSpread = std::numeric_limits<double>::infinity();
  for (int step = 0; step < steeredSteps + plainSteps; ++step)
  {
    if (!keepGoing())
    {
      return false;
    }
    const bool plainStep = step >= steeredSteps;
    if (plainStep)
    {
      psi.assign(n, Height(0.0L));
    }
    diagram.build(samples, psi);
    std::fill(weighted.begin(), weighted.end(), 0.0);
    std::fill(mass.begin(), mass.end(), 0.0);
    std::fill(area.begin(), area.end(), 0.0);
#pragma omp parallel
    {
      SphericalDensityField::Scratch scratch;
      std::vector<Vec3> cell;
#pragma omp for schedule(dynamic, 256)
      for (long long i = 0; i < n; ++i)
      {
        cell.clear();
        for (const int* f = diagram.ringBegin(i); f != diagram.ringEnd(i); ++f)
        {
          cell.push_back(diagram.cellVertices()[*f]);
        }
        moment[i] = Vec3{};
        if (cell.size() >= 3)
        {
          field.integrate(cell, samples[i], hints[i], power, scratch, weighted[i], &moment[i],
            &mass[i], &area[i]);
        }
      }
    }
    bool last = false;
    if (plainStep)
    {
      // Plain steps stop when the spread of the Voronoi masses no longer drops, or is below the
      // goal (1e5 samples: it is there after the steered steps, and each step costs ~0.4 s).
      const double spread = massCoefficientOfVariation(equalizeMass ? mass : area);
      last = spread >= previousSpread || spread <= SpreadGoal;
      previousSpread = spread;
    }
    if (!plainStep)
    {
      double total = 0.0;
      for (long long i = 0; i < n; ++i)
      {
        total += equalizeMass ? mass[i] : area[i];
      }
      const double mean = total / static_cast<double>(n);
      for (long long i = 0; i < n; ++i)
      {
        const double measured = equalizeMass ? mass[i] : area[i];
        if (measured > 0.0)
        {
          const double change =
            std::clamp(mean / measured - 1.0, -LargestSteeredMassChange, LargestSteeredMassChange);
          psi[i] -= SteeringGain * change * area[i] / CellAreaPerHeight;
        }
        else
        {
          psi[i] -= 1e-3; // an empty cell: bring its point back onto the hull
        }
      }
    }
    for (long long i = 0; i < n; ++i)
    {
      if (weighted[i] > 0.0 && norm(moment[i]) > 0.0 && std::isfinite(norm(moment[i])))
      {
        samples[i] = normalized(moment[i]);
      }
    }
    if (last)
    {
      break;
    }
  }
  return true;
}

// Drops the samples whose Voronoi cell holds less than `fraction` of the mean mass, none next to
// another dropped one, unless the masses already spread by less than SpreadGoal. Returns how
// many.
long long removeLight(const SphericalDensityField& field, double fraction,
  std::vector<Vec3>& samples, std::vector<int>& hints)
{
  const long long n = static_cast<long long>(samples.size());
  SphericalPowerDiagram diagram;
  diagram.build(samples, std::vector<Height>(n, Height(0.0L)));
  std::vector<double> mass(n, 0.0);
#pragma omp parallel
  {
    SphericalDensityField::Scratch scratch;
    std::vector<Vec3> cell;
#pragma omp for schedule(dynamic, 256)
    for (long long i = 0; i < n; ++i)
    {
      cell.clear();
      for (const int* f = diagram.ringBegin(i); f != diagram.ringEnd(i); ++f)
      {
        cell.push_back(diagram.cellVertices()[*f]);
      }
      if (cell.size() >= 3)
      {
        field.integrate(cell, samples[i], hints[i], 1.0, scratch, mass[i], nullptr);
      }
    }
  }
  if (massCoefficientOfVariation(mass) <= SpreadGoal)
  {
    return 0;
  }
  const double mean = std::accumulate(mass.begin(), mass.end(), 0.0) / static_cast<double>(n);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return mass[a] < mass[b]; });
  std::vector<char> state(n, 0); // 1 removed, 2 kept for a removed neighbour
  long long removed = 0;
  for (int i : order)
  {
    if (mass[i] >= fraction * mean)
    {
      break;
    }
    if (state[i] != 0)
    {
      continue;
    }
    state[i] = 1;
    ++removed;
    const int k = static_cast<int>(diagram.ringEnd(i) - diagram.ringBegin(i));
    for (int j = 0; j < k; ++j)
    {
      const int nb = diagram.neighborsBegin(i)[j];
      state[nb] = state[nb] == 1 ? 1 : 2;
    }
  }
  long long out = 0;
  for (long long i = 0; i < n; ++i)
  {
    if (state[i] != 1)
    {
      samples[out] = samples[i];
      hints[out] = hints[i];
      ++out;
    }
  }
  samples.resize(out);
  hints.resize(out);
  return removed;
}

double smallestAngleDegrees(const std::vector<Vec3>& p, const std::vector<Triangle>& triangles)
{
  // Angles of the flat (hull) triangles: a little below the spherical ones, the conservative
  // figure.
  double smallest = 180.0;
  for (const Triangle& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Vec3 a = p[t[k]], b = p[t[(k + 1) % 3]], c = p[t[(k + 2) % 3]];
      const double angle = std::atan2(norm(cross(b - a, c - a)), dot(b - a, c - a));
      smallest = std::min(smallest, angle * 180.0 / Pi);
    }
  }
  return smallest;
}

struct Candidate
{
  Diagram diagram;
  std::vector<double> mass; // unnormalized
  double cv = std::numeric_limits<double>::infinity();
  double secondsMasses = 0.0;
};

Candidate measure(const SphericalDensityField& field, Diagram d)
{
  const auto t0 = Clock::now();
  Candidate c;
  integrateCells(field, d, 1.0, c.mass, nullptr);
  c.secondsMasses = secondsSince(t0);
  c.cv = massCoefficientOfVariation(c.mass);
  c.diagram = std::move(d);
  return c;
}

// The samples after an angles-only refinement pass (relaxation can leave thin triangles).
Diagram repairAngles(const SphericalDensityField& field, const SamplerOptions& options,
  const std::vector<Vec3>& samples, const std::vector<int>& hints)
{
  // The bound less 0.4 degrees: triangles just under 30 degrees after the relaxation are
  // many, and each insertion leaves a light cell (brain, 5000 samples: spread 0.123 -> 0.116).
  SamplerOptions repairOptions = options;
  repairOptions.minimumAngleDegrees = std::max(
    0.5 * options.minimumAngleDegrees, options.minimumAngleDegrees - RepairAngleSlackDegrees);
  Refinement repair(field, repairOptions, std::numeric_limits<double>::infinity(),
    refinementLimit(options, static_cast<double>(samples.size())));
  repair.run(samples, hints, [](long long) { return true; });
  return diagramOf(repair.triangulation());
}

// Adaptive/Uniform: refinement runs calibrated to the target count, Lloyd steps, removal of
// light cells, angle repair; the unrelaxed samples are kept instead when the relaxed masses spread
// by more than 0.3 and the unrelaxed ones less (as on the plane).
Candidate sampleRefined(
  const SphericalDensityField& field, const SamplerOptions& options, SphericalSamplerResult& result)
{
  const Grading grade{ options.mode == SamplingMode::Adaptive, options.sizeRule };
  double gradedArea = 0.0;
  for (size_t t = 0; t < field.triangles().size(); ++t)
  {
    const double s = grade(field.density()[t]);
    gradedArea += field.sphericalArea(static_cast<int>(t)) * s * s;
  }
  if (options.progress && !options.progress(0.0))
  {
    result.status.aborted = true;
    return {};
  }
  std::unique_ptr<Refinement> refinement;
  const double target = static_cast<double>(options.numberOfSamples);
  RefinementProgress progress(options);
  const auto refine = [&](double epsilon) -> double
  {
    refinement =
      std::make_unique<Refinement>(field, options, epsilon, refinementLimit(options, target));
    const bool finished = refinement->run(icosahedron(), {}, progress.ofRun());
    result.capped = refinement->capped();
    return finished ? static_cast<double>(refinement->triangulation().number_of_vertices()) : -1.0;
  };
  // Tighter than 10%: the angle repair after the relaxation adds a few samples.
  if (!refineToTargetCount(options, gradedArea, 0.05, refine, result))
  {
    return {};
  }
  Diagram refined = diagramOf(refinement->triangulation());
  refinement.reset();
  double power = 0.0;
  if (options.mode == SamplingMode::Adaptive)
  {
    power = options.sizeRule == SizeRule::SqrtDensity ? 2.0 : 4.0;
  }
  std::vector<Vec3> samples = refined.samples;
  std::vector<int> hints = refined.hints;
  const bool equalizeMass = options.mode == SamplingMode::Adaptive;
  const auto keepGoing = [&]
  {
    result.status.aborted = options.progress && !options.progress(0.9);
    return !result.status.aborted;
  };
  if (!relax(field, power, equalizeMass, SteeredSteps, PlainSteps, samples, hints, keepGoing))
  {
    return {};
  }
  for (int round = 0; round < RemovalRounds; ++round)
  {
    if (!equalizeMass || removeLight(field, LightCellFraction, samples, hints) == 0)
    {
      break;
    }
    if (!relax(field, power, equalizeMass, 0, PlainStepsAfterRemoval, samples, hints, keepGoing))
    {
      return {};
    }
  }
  if (!keepGoing())
  {
    return {};
  }
  // Always the repaired samples: keeping the relaxed ones where the repair made the masses less
  // even reported thin triangles (spot, 3000 samples: 19.4 degrees; brain: 10.1).
  Candidate best = measure(field, repairAngles(field, options, samples, hints));
  result.relaxed = true;
  if (options.mode == SamplingMode::Adaptive && best.cv > 0.3)
  {
    Candidate unrelaxed = measure(field, std::move(refined));
    if (unrelaxed.cv < best.cv)
    {
      best = std::move(unrelaxed);
      result.relaxed = false;
    }
  }
  return best;
}

// MeshVertices: the density mesh's points (input order) with its triangles; the masses of the
// points' Voronoi cells.
Candidate sampleMeshVertices(const SphericalDensityField& field, SphericalSamplerResult& result)
{
  std::vector<int> hints(field.points().size(), -1);
  for (size_t t = 0; t < field.triangles().size(); ++t)
  {
    for (int v : field.triangles()[t])
    {
      hints[v] = static_cast<int>(t);
    }
  }
  Candidate c = measure(field, triangulate(field.points(), hints));
  if (c.diagram.samples.size() != field.points().size())
  {
    result.status.error = "Some points of the density mesh are closer than 1e-7 to each other "
                          "(or unused): their Voronoi cells cannot be told apart; use the "
                          "Adaptive or Uniform mode.";
    return c;
  }
  // Back to input order (the triangulation sorted them).
  {
    std::map<std::tuple<double, double, double>, int> id;
    for (size_t i = 0; i < field.points().size(); ++i)
    {
      const Vec3 p = field.points()[i];
      id[{ p.x, p.y, p.z }] = static_cast<int>(i);
    }
    std::vector<double> mass(c.mass.size());
    for (size_t k = 0; k < c.diagram.samples.size(); ++k)
    {
      const Vec3 p = c.diagram.samples[k];
      mass[id.at({ p.x, p.y, p.z })] = c.mass[k];
    }
    c.mass = std::move(mass);
  }
  c.diagram.samples = field.points();
  c.diagram.triangles = field.triangles();
  return c;
}
} // namespace

SphericalSamplerResult sampleSphere(const std::vector<Vec3>& spherePoints,
  const std::vector<Triangle>& triangles, const std::vector<double>& triangleDensity,
  const SamplerOptions& options)
{
  SphericalSamplerResult result;
  result.status.error = checkSamplerOptions(options);
  if (!result.status.error.empty())
  {
    return result;
  }
  std::string error;
  const auto field = SphericalDensityField::create(spherePoints, triangles, triangleDensity, error);
  if (!field)
  {
    result.status.error = error;
    return result;
  }
  result.densityIntegral = field->integral();
  if (options.progress && !options.progress(0.0)) // the field's search structures took a while
  {
    result.status.aborted = true;
    return result;
  }
  const auto t0 = Clock::now();
  Candidate c = options.mode == SamplingMode::MeshVertices ? sampleMeshVertices(*field, result)
                                                           : sampleRefined(*field, options, result);
  if (!result.status.ok())
  {
    return result;
  }
  result.secondsMasses = c.secondsMasses;
  result.secondsRefinement = secondsSince(t0) - c.secondsMasses;
  const double raw = std::accumulate(c.mass.begin(), c.mass.end(), 0.0);
  result.massSumRelativeError = std::abs(raw - result.densityIntegral) / result.densityIntegral;
  result.mass.resize(c.mass.size());
  for (size_t i = 0; i < c.mass.size(); ++i)
  {
    result.mass[i] = c.mass[i] * result.sourceMass / raw;
  }
  result.massCoefficientOfVariation = massCoefficientOfVariation(result.mass);
  result.samples = std::move(c.diagram.samples);
  result.triangles = std::move(c.diagram.triangles);
  result.minimumAngleDegrees = smallestAngleDegrees(result.samples, result.triangles);
  if (options.mode != SamplingMode::MeshVertices)
  {
    const std::string warning = sampleCountWarning(
      static_cast<long long>(result.samples.size()), options.numberOfSamples, result.capped);
    if (!warning.empty())
    {
      result.status.warnings.push_back(warning);
    }
  }
  if (options.progress && !options.progress(1.0))
  {
    result.status.aborted = true;
  }
  return result;
}

} // namespace otparam
