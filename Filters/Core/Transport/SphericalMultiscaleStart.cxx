// The sphere's coarse-to-fine start (MultiscaleStart.h): the plane's idea carried to the
// support functions of spherical power diagrams.
#include "Transport/MultiscaleStart.h"

#include "Common/SphericalGeometry.h"
#include "Transport/SphericalOT.h"
#include "Transport/SphericalPowerDiagram.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace otparam
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// Diracs in a space-filling-curve order, so that consecutive searches start next to each other.
std::vector<int> spatialOrder(const std::vector<Vec3>& diracs)
{
  std::vector<Kernel::Point_3> points;
  points.reserve(diracs.size());
  for (const Vec3& y : diracs)
  {
    points.emplace_back(y.x, y.y, y.z);
  }
  std::vector<std::size_t> order(diracs.size());
  std::iota(order.begin(), order.end(), 0);
  using Traits =
    CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::Pointer_property_map<Kernel::Point_3>::type>;
  CGAL::spatial_sort(order.begin(), order.end(), Traits(CGAL::make_property_map(points)));
  return std::vector<int>(order.begin(), order.end());
}

// Climbs from start to a node where score is largest among its neighbours. On the graphs used
// here that local maximum is the global one: the Delaunay graph for the nearest Dirac (a
// Dirac not nearest has a Delaunay neighbour nearer), and the edge graph of a convex polytope for
// a linear function (the simplex method's argument).
template <typename Score, typename Neighbours>
int climb(int start, Score&& score, Neighbours&& neighbours)
{
  int node = start;
  double best = score(node);
  for (bool moved = true; moved;)
  {
    moved = false;
    for (const int next : neighbours(node))
    {
      const double value = score(next);
      if (value > best)
      {
        best = value;
        node = next;
        moved = true;
      }
    }
  }
  return node;
}

struct NeighbourRange
{
  const int *first, *last;
  const int* begin() const { return first; }
  const int* end() const { return last; }
};

// The support function h_Q(z) = max over Q of <x, z> of the polytope Q = {x : <x, y_c> <= h_c}
// of a solved coarse diagram, found by climbing over Q's vertices (one per dual triangle).
class SupportFunction
{
public:
  explicit SupportFunction(const SphericalPowerDiagram& diagram)
    : Diagram(diagram)
  {
    const int triangleCount = static_cast<int>(diagram.triangles().size());
    for (int f = 0; f < triangleCount; ++f)
    {
      this->Vertices.push_back(diagram.polytopeVertex(f));
    }
    // Triangles k and k + 1 around Dirac c share the edge from c to its k-th neighbour; each
    // edge is recorded from its smaller end.
    this->Adjacent.assign(triangleCount, { -1, -1, -1 });
    std::vector<int> filled(triangleCount, 0);
    for (int c = 0; c < diagram.size(); ++c)
    {
      const int* ring = diagram.ringBegin(c);
      const int degree = static_cast<int>(diagram.ringEnd(c) - ring);
      for (int k = 0; k < degree; ++k)
      {
        if (c < diagram.neighborsBegin(c)[k])
        {
          const int f = ring[k], g = ring[(k + 1) % degree];
          this->Adjacent[f][filled[f]++ % 3] = g;
          this->Adjacent[g][filled[g]++ % 3] = f;
        }
      }
    }
  }

  // A triangle of coarse Dirac c, where a search near c can start.
  int triangleOf(int c) const { return *this->Diagram.ringBegin(c); }

  double operator()(const Vec3& z, int& triangle) const
  {
    triangle = climb(
      triangle, [&](int f) { return dot(this->Vertices[f], z); },
      [&](int f)
      {
        const std::array<int, 3>& next = this->Adjacent[f];
        return NeighbourRange{ next.data(), next.data() + 3 };
      });
    return dot(this->Vertices[triangle], z);
  }

private:
  const SphericalPowerDiagram& Diagram;
  std::vector<Vec3> Vertices;
  std::vector<std::array<int, 3>> Adjacent;
};

// Rotation of z by angle about the unit axis (Rodrigues).
Vec3 rotated(const Vec3& z, const Vec3& axis, double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return c * z + s * cross(axis, z) + ((1.0 - c) * dot(axis, z)) * axis;
}

// The median geodesic length of the coarse Delaunay edges, or 0 when it cannot serve as one
// stencil radius (stencilSpacing).
double coarseSpacing(const SphericalPowerDiagram& voronoi, const std::vector<Vec3>& coarseDiracs)
{
  std::vector<double> edgeLengths;
  for (int c = 0; c < voronoi.size(); ++c)
  {
    const int degree = static_cast<int>(voronoi.ringEnd(c) - voronoi.ringBegin(c));
    for (int k = 0; k < degree; ++k)
    {
      const int d = voronoi.neighborsBegin(c)[k];
      if (c < d)
      {
        edgeLengths.push_back(sphericalDistance(coarseDiracs[c], coarseDiracs[d]));
      }
    }
  }
  return stencilSpacing(edgeLengths);
}

// True when the masses vary from a Dirac to its neighbours more than a coarse level can see: the
// median over the Diracs of |log(nu_i / mean mass of its coarse group)| exceeds log 2. The
// start then predicts every cell as its neighbours' mean and is no better than the Voronoi one.
// Measured at 1e5 Diracs of contrast 1e4: masses log-uniform at random, independent of position
// (median 1.8): 22 Newton iterations from this start, 19 from the Voronoi one; a smooth density
// of four bumps (median 0.004): 9 from this start, 22 from the Voronoi one.
bool massesVaryWithinGroups(const std::vector<double>& nu, const std::vector<int>& group,
  const std::vector<double>& groupMass)
{
  std::vector<int> groupSize(groupMass.size(), 0);
  for (const int c : group)
  {
    ++groupSize[c];
  }
  std::vector<double> deviation(nu.size());
  for (size_t i = 0; i < nu.size(); ++i)
  {
    deviation[i] = std::abs(std::log(nu[i] * groupSize[group[i]] / groupMass[group[i]]));
  }
  std::nth_element(deviation.begin(), deviation.begin() + deviation.size() / 2, deviation.end());
  return deviation[deviation.size() / 2] > std::log(2.0);
}

// Fine log-heights: the coarse support function averaged over rotations of each fine Dirac, as
// the plane averages its dual potential over translates. An average of support functions of
// rotated copies of Q is the support function of their Minkowski mean, a convex body, and this
// one is rounded wherever an edge of Q passes within the stencil, so that every fine Dirac keeps
// a cell (none hidden) of about its share. The stencil: the Dirac and its rotations by r / 2 and
// r both ways about six axes (the icosahedron's diagonals, so that every direction moves in
// several directions), weights as the plane's rings. The small share of the unit ball (the
// Voronoi diagram) rounds the rest.
std::vector<Height> smoothedLogHeights(const SupportFunction& support,
  const std::vector<Vec3>& diracs, const std::vector<int>& order,
  const std::vector<int>& nearestCoarse, double spacing)
{
  const double golden = 0.5 * (1.0 + std::sqrt(5.0));
  const std::array<Vec3, 6> axes{ normalized({ 0.0, 1.0, golden }),
    normalized({ 0.0, 1.0, -golden }), normalized({ 1.0, golden, 0.0 }),
    normalized({ 1.0, -golden, 0.0 }), normalized({ golden, 0.0, 1.0 }),
    normalized({ -golden, 0.0, 1.0 }) };
  const double radius = StencilRadiusInSpacings * spacing;
  struct Rotation
  {
    Vec3 axis;
    double angle, weight;
  };
  std::vector<Rotation> stencil;
  for (const Vec3& axis : axes)
  {
    for (const double sign : { -1.0, 1.0 })
    {
      stencil.push_back({ axis, 0.5 * sign * radius, StencilInnerWeight / 2.0 });
      stencil.push_back({ axis, sign * radius, StencilOuterWeight / 2.0 });
    }
  }
  double totalWeight = 1.0;
  for (const Rotation& r : stencil)
  {
    totalWeight += r.weight;
  }
  const int n = static_cast<int>(diracs.size());
  std::vector<Height> psi(n);
#pragma omp parallel
  {
    int triangle = -1;
#pragma omp for schedule(static)
    for (int k = 0; k < n; ++k)
    {
      const int i = order[k];
      if (triangle < 0)
      {
        triangle = support.triangleOf(nearestCoarse[i]);
      }
      int centre = triangle;
      double average = support(diracs[i], centre);
      for (const Rotation& r : stencil)
      {
        int start = centre;
        average += r.weight * support(rotated(diracs[i], r.axis, r.angle), start);
      }
      triangle = centre;
      psi[i] = std::log((1.0 - StencilVoronoiShare) * average / totalWeight + StencilVoronoiShare);
    }
  }
  return psi;
}
} // namespace

bool sphericalCoarseToFineLogHeights(
  const std::vector<Vec3>& diracs, const std::vector<double>& nu, std::vector<Height>& psi)
{
  const int n = static_cast<int>(diracs.size());
  if (n < MultiscaleMinimumDiracs)
  {
    return false;
  }
  const std::vector<int> ids = randomSixth(n);
  const int coarseCount = static_cast<int>(ids.size());
  std::vector<Vec3> coarseDiracs(coarseCount);
  for (int c = 0; c < coarseCount; ++c)
  {
    coarseDiracs[c] = diracs[ids[c]];
  }
  SphericalPowerDiagram voronoi;
  if (!voronoi.build(coarseDiracs, std::vector<Height>(coarseCount)) || voronoi.hiddenCount() > 0)
  {
    return false;
  }
  const double spacing = coarseSpacing(voronoi, coarseDiracs);
  if (!(spacing > 0.0))
  {
    return false;
  }

  // Each fine Dirac's mass goes to its nearest coarse Dirac.
  const std::vector<int> order = spatialOrder(diracs);
  std::vector<int> nearestCoarse(n);
  std::vector<double> coarseMass(coarseCount, 0.0);
  int nearest = 0;
  for (const int i : order)
  {
    nearest = climb(
      nearest, [&](int c) { return dot(coarseDiracs[c], diracs[i]); },
      [&](int c)
      {
        return NeighbourRange{ voronoi.neighborsBegin(c),
          voronoi.neighborsBegin(c) + (voronoi.ringEnd(c) - voronoi.ringBegin(c)) };
      });
    nearestCoarse[i] = nearest;
    coarseMass[nearest] += nu[i];
  }
  if (massesVaryWithinGroups(nu, nearestCoarse, coarseMass))
  {
    return false;
  }

  // The start needs the coarse cells' shape, not their last digits.
  OTOptions coarseOptions;
  coarseOptions.tolerance = 1e-3;
  coarseOptions.maximumNumberOfIterations = 100;
  const SphericalOTResult coarse = solveSphericalOT(coarseDiracs, coarseMass, coarseOptions);
  if (coarse.heights.size() != static_cast<size_t>(coarseCount) ||
    *std::min_element(coarse.cellMass.begin(), coarse.cellMass.end()) <= 0.0)
  {
    return false;
  }
  SphericalPowerDiagram diagram;
  const std::vector<Height> coarsePsi(coarse.heights.begin(), coarse.heights.end());
  if (!diagram.build(coarseDiracs, coarsePsi) || diagram.hiddenCount() > 0)
  {
    return false;
  }
  psi = smoothedLogHeights(SupportFunction(diagram), diracs, order, nearestCoarse, spacing);
  return true;
}

} // namespace otparam
