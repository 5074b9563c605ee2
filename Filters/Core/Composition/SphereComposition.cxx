#include "Composition/SphereComposition.h"

#include "Common/SphericalGeometry.h"
#include "Composition/AreaCorrection.h"
#include "Composition/Composition.h"
#include "Composition/Untangling.h"

#include <chrono>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace otparam
{
namespace
{
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double det(const Vec3& a, const Vec3& b, const Vec3& c)
{
  return dot(a, cross(b, c));
}

// Point location in the samples' spherical Delaunay triangulation by walking: from the last
// triangle found (mesh points come in spatially coherent order), cross the edge that x lies
// beyond until x is inside. Delaunay walks end; a cap on the steps falls back to a scan.
class SphericalLocator
{
public:
  SphericalLocator(const std::vector<Vec3>& samples, const std::vector<Triangle>& triangles)
    : Samples(samples)
    , Triangles(triangles)
    , Across(triangles.size(), { -1, -1, -1 })
  {
    std::unordered_map<std::int64_t, int> edgeOwner;
    edgeOwner.reserve(3 * triangles.size());
    auto key = [&](int a, int b) { return static_cast<std::int64_t>(a) * samples.size() + b; };
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        edgeOwner[key(triangles[t][(k + 1) % 3], triangles[t][(k + 2) % 3])] = static_cast<int>(t);
      }
    }
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        const auto it = edgeOwner.find(key(triangles[t][(k + 2) % 3], triangles[t][(k + 1) % 3]));
        this->Across[t][k] = it == edgeOwner.end() ? -1 : it->second;
      }
    }
  }

  // The triangle containing direction x and x's weights there (l_a a + l_b b + l_c c = x).
  int locate(const Vec3& x, std::array<double, 3>& weights)
  {
    int t = this->Last;
    for (int step = 0; step < 100000; ++step)
    {
      if (this->inside(t, x, weights))
      {
        return this->Last = t;
      }
      int worst = 0;
      for (int k = 1; k < 3; ++k)
      {
        worst = weights[k] < weights[worst] ? k : worst;
      }
      if (this->Across[t][worst] < 0)
      {
        break;
      }
      t = this->Across[t][worst];
    }
    for (t = 0; t < static_cast<int>(this->Triangles.size()); ++t)
    {
      if (this->inside(t, x, weights))
      {
        return this->Last = t;
      }
    }
    return -1;
  }

private:
  bool inside(int t, const Vec3& x, std::array<double, 3>& weights) const
  {
    const Vec3 a = this->Samples[this->Triangles[t][0]], b = this->Samples[this->Triangles[t][1]],
               c = this->Samples[this->Triangles[t][2]];
    const double whole = det(a, b, c);
    weights = { det(x, b, c) / whole, det(a, x, c) / whole, det(a, b, x) / whole };
    // Only the hemisphere of the triangle: the antipodal triangle has the same signs negated.
    return weights[0] >= 0.0 && weights[1] >= 0.0 && weights[2] >= 0.0;
  }

  const std::vector<Vec3>& Samples;
  const std::vector<Triangle>& Triangles;
  std::vector<std::array<int, 3>> Across;
  int Last = 0;
};

std::vector<int> flippedOnSphere(const SurfaceMesh& surface, const std::vector<Vec3>& sphere)
{
  std::vector<int> flipped;
  for (size_t t = 0; t < surface.triangles.size(); ++t)
  {
    const Triangle& tri = surface.triangles[t];
    if (!(det(sphere[tri[0]], sphere[tri[1]], sphere[tri[2]]) > 0.0))
    {
      flipped.push_back(static_cast<int>(t));
    }
  }
  return flipped;
}

// The gnomonic chart at a unit vector: great circles become lines, and a chordal triangle's
// orientation seen from outside is the sign of its planar area there. Points must lie well
// within the chart's hemisphere (`contains`).
struct GnomonicChart
{
  explicit GnomonicChart(const Vec3& centre)
    : Centre(centre)
    , Frame(composition::SphereGeometry::frame(centre))
  {
  }
  bool contains(const Vec3& p) const { return dot(p, this->Centre) > 0.05; }
  Vec2 toChart(const Vec3& p) const
  {
    const double height = dot(p, this->Centre);
    return { dot(p, this->Frame.e1) / height, dot(p, this->Frame.e2) / height };
  }
  Vec3 toSphere(Vec2 q) const
  {
    return normalized(this->Centre + q.x * this->Frame.e1 + q.y * this->Frame.e2);
  }

  Vec3 Centre;
  composition::SphereGeometry::Frame Frame;
};

// The unit vector p that maximizes min_k det(p, b_k, c_k) = p . n_k over a star's rim edges
// (b_k, c_k), n_k = b_k x c_k: every chordal triangle (p, b_k, c_k) positive seen from outside,
// with no chart, so for stars that span more than a hemisphere (a coarse cone's long fan
// triangles), where the gnomonic chart cannot hold the rim. The optimum over the sphere has one,
// two or three active n_k (Lagrange: p is a positive combination of them), so every such
// candidate is tried (stars are small), as maximizeSmallestArea does in the plane. `start` is
// kept unless some direction does better.
Vec3 maximizeSmallestVolume(const std::vector<Vec3>& normals, const Vec3& start)
{
  auto smallest = [&normals](const Vec3& p)
  {
    double value = HUGE_VAL;
    for (const Vec3& n : normals)
    {
      value = std::min(value, dot(p, n));
    }
    return value;
  };
  Vec3 best = start;
  double bestValue = smallest(best);
  auto consider = [&](Vec3 p)
  {
    const double length = norm(p);
    if (!(length > 1e-300))
    {
      return;
    }
    p = (1.0 / length) * p;
    const double value = smallest(p);
    if (value > bestValue)
    {
      bestValue = value;
      best = p;
    }
  };
  const size_t m = std::min<size_t>(normals.size(), 16);
  for (size_t i = 0; i < m; ++i)
  {
    consider(normals[i]);
    for (size_t j = i + 1; j < m; ++j)
    {
      // In the plane of n_i and n_j, the direction equally far along both.
      const Vec3 d = normals[i] - normals[j];
      const double dd = dot(d, d);
      if (dd > 0.0)
      {
        consider(normals[i] - (dot(normals[i], d) / dd) * d);
      }
      for (size_t k = j + 1; k < m; ++k)
      {
        const Vec3 p = cross(d, normals[i] - normals[k]); // p . n_i = p . n_j = p . n_k
        consider(dot(p, normals[i]) >= 0.0 ? p : -1.0 * p);
      }
    }
  }
  return best;
}

// How many times the rim of u's star winds around u's image: the signed angles, seen from
// outside, between consecutive rim vertices' directions in the tangent plane at u, over 2 pi.
int windingAround(int u, const composition::VertexStars& stars, const std::vector<Vec3>& sphere)
{
  const Vec3 a = sphere[u];
  double turn = 0.0;
  for (int e = stars.offsets[u]; e < stars.offsets[u + 1]; ++e)
  {
    const Vec3 b = sphere[stars.entries[e][1]], c = sphere[stars.entries[e][2]];
    turn += std::atan2(det(a, b, c), dot(b, c) - dot(b, a) * dot(c, a));
  }
  return static_cast<int>(std::lround(turn / (2.0 * M_PI)));
}

// Vertex v moved by maximizeSmallestVolume where that makes its whole star positive, winding
// once around it, and leaves each rim vertex's star winding once or as before: positive
// triangles alone allow a star that wraps twice around its vertex, and moves free of any chart
// made maps that covered the sphere 2 or 14 times (VTK's cylinder and cone at resolution 60,
// subdivided once). Returns whether v moved.
bool freeStarByVolume(int v, const composition::VertexStars& stars, std::vector<Vec3>& sphere)
{
  std::vector<Vec3> normals;
  std::vector<std::pair<int, int>> rimWindings;
  for (int e = stars.offsets[v]; e < stars.offsets[v + 1]; ++e)
  {
    const int b = stars.entries[e][1];
    normals.push_back(cross(sphere[b], sphere[stars.entries[e][2]]));
    rimWindings.emplace_back(b, windingAround(b, stars, sphere));
  }
  const Vec3 best = maximizeSmallestVolume(normals, sphere[v]);
  for (const Vec3& n : normals)
  {
    if (!(dot(best, n) > 0.0))
    {
      return false;
    }
  }
  const Vec3 before = sphere[v];
  sphere[v] = best;
  bool windsOnce = windingAround(v, stars, sphere) == 1;
  for (const auto& [b, winding] : rimWindings)
  {
    const int after = windingAround(b, stars, sphere);
    windsOnce = windsOnce && (after == 1 || after == winding);
  }
  if (!windsOnce)
  {
    sphere[v] = before;
  }
  return windsOnce;
}

// Moves vertex v to the point of the gnomonic chart at its image that maximizes the smallest
// signed area of its star (Untangling.h), then back onto the sphere. A star whose rim that chart
// cannot hold (wider than a hemisphere, as around a coarse cone's long fan triangles, or a vertex
// on the far side of its rim) goes where maximizeSmallestVolume frees it, if anywhere and if
// `wideStars`. Returns whether v moved.
bool untangleVertex(
  int v, const composition::VertexStars& stars, bool wideStars, std::vector<Vec3>& sphere)
{
  const GnomonicChart chart(sphere[v]);
  std::vector<std::pair<Vec2, Vec2>> rim;
  for (int e = stars.offsets[v]; e < stars.offsets[v + 1]; ++e)
  {
    const Vec3 b = sphere[stars.entries[e][1]], c = sphere[stars.entries[e][2]];
    if (!chart.contains(b) || !chart.contains(c))
    {
      return wideStars && freeStarByVolume(v, stars, sphere);
    }
    rim.emplace_back(chart.toChart(b), chart.toChart(c));
  }
  const Vec2 best = composition::maximizeSmallestArea(rim, Vec2{ 0.0, 0.0 });
  if (best.x == 0.0 && best.y == 0.0)
  {
    return false;
  }
  sphere[v] = chart.toSphere(best);
  return true;
}

// The patch around the flipped triangles re-embedded (Untangling.h) in the gnomonic chart at
// its mean image; its rim must lie within that chart. Kept only if fewer triangles are flipped
// after it. Returns the vertices moved. (Measured: a closed surface with a finger of length
// 30 radii, whose first staged transport left 471 triangles flipped.)
std::int64_t reembedOnSphere(const SurfaceMesh& surface, const composition::VertexStars& stars,
  const std::vector<int>& flipped, int rings, std::vector<Vec3>& sphere)
{
  std::vector<int> unknown(sphere.size(), -1);
  const std::vector<int> patch = composition::patchAround(
    flipped, rings, surface.triangles, stars, [](int) { return true; }, unknown);
  Vec3 sum{ 0.0, 0.0, 0.0 };
  for (int v : patch)
  {
    sum = sum + sphere[v];
  }
  if (patch.empty() || 2 * patch.size() > sphere.size() || !(norm(sum) > 0.0))
  {
    return 0; // no hemisphere holds the patch
  }
  const GnomonicChart chart(normalized(sum));
  bool rimInChart = true;
  std::vector<Vec2> layout;
  const bool solved = composition::tutteLayout(
    stars, patch, unknown,
    [&](int u)
    {
      rimInChart = rimInChart && chart.contains(sphere[u]);
      return chart.toChart(sphere[u]);
    },
    layout);
  if (!solved || !rimInChart)
  {
    return 0;
  }
  std::vector<Vec3> before(patch.size());
  for (size_t r = 0; r < patch.size(); ++r)
  {
    before[r] = sphere[patch[r]];
    sphere[patch[r]] = chart.toSphere(layout[r]);
  }
  if (flippedOnSphere(surface, sphere).size() < flipped.size())
  {
    return static_cast<std::int64_t>(patch.size());
  }
  for (size_t r = 0; r < patch.size(); ++r)
  {
    sphere[patch[r]] = before[r];
  }
  return 0;
}

// Step 2: vertex by vertex, then patches re-embedded where that is not enough.
std::int64_t untangleOnSphere(const SurfaceMesh& surface, const composition::VertexStars& stars,
  bool wideStars, std::vector<Vec3>& sphere)
{
  const size_t n = sphere.size();
  auto untangleLocally = [&]
  {
    return composition::untangleInRings(
      stars, n, [&] { return flippedOnSphere(surface, sphere); },
      [&](int v) { return untangleVertex(v, stars, wideStars, sphere); },
      [&](int t) { return surface.triangles[t]; });
  };
  const std::int64_t moved = untangleLocally();
  return moved +
    composition::reembedWhereCollapsed([&] { return flippedOnSphere(surface, sphere); },
      [&](const std::vector<int>& flipped, int rings)
      { return reembedOnSphere(surface, stars, flipped, rings, sphere); },
      untangleLocally);
}
} // namespace

namespace
{
// The area-weighted mean |log area ratio| of the sphere map against `fraction` (shares summing
// to 1) over the first `count` triangles.
double meanAbsLogAreaRatioAgainst(const SurfaceMesh& surface, const std::vector<Vec3>& sphere,
  const std::vector<double>& fraction, std::size_t count)
{
  // With a hole fill (count < all) the surface shares are renormalized over the measured
  // triangles, while the sphere's stay of 4 pi, as param_metrics.py --sphere scores the output
  // (the fill's share of the sphere then shows as a uniform error of |log(1 - share)|).
  double surfaceShare = 1.0;
  if (count < fraction.size())
  {
    surfaceShare =
      std::accumulate(fraction.begin(), fraction.begin() + static_cast<long>(count), 0.0);
  }
  const double sphereShare = 4.0 * M_PI;
  double mean = 0.0;
  for (size_t t = 0; t < count; ++t)
  {
    const Triangle& tri = surface.triangles[t];
    const double area = sphericalTriangleArea(sphere[tri[0]], sphere[tri[1]], sphere[tri[2]]);
    const double ratio = std::max(area, 1e-300) / sphereShare / (fraction[t] / surfaceShare);
    mean += fraction[t] / surfaceShare * std::abs(std::log(ratio));
  }
  return mean;
}
} // namespace

double sphereMeanAbsLogAreaRatio(
  const SurfaceMesh& surface, const std::vector<Vec3>& sphere, std::size_t measured)
{
  const std::vector<double> fraction = composition::surfaceAreaFractions(surface);
  const std::size_t count = measured == 0 ? fraction.size() : std::min(measured, fraction.size());
  return meanAbsLogAreaRatioAgainst(surface, sphere, fraction, count);
}

namespace
{
// Step 1: every point's conformal image through the samples' spherical interpolant. False when
// `report` asks to abort or a point lies in no sample triangle (result.status says which).
template <class Report>
bool interpolateOnSphere(const std::vector<Vec3>& conformal, const std::vector<Vec3>& samples,
  const std::vector<Triangle>& sampleTriangles, const std::vector<Vec3>& sampleImages,
  const Report& report, SphereCompositionResult& result)
{
  SphericalLocator locator(samples, sampleTriangles);
  const size_t n = conformal.size();
  result.interpolated.resize(n);
  for (size_t v = 0; v < n; ++v)
  {
    // An abort is honoured every 2^18 points (~0.1 s).
    if ((v & 0x3ffff) == 0x3ffff && !report(0.2 * v / n))
    {
      result.status.aborted = true;
      return false;
    }
    std::array<double, 3> w{};
    const int t = locator.locate(conformal[v], w);
    if (t < 0)
    {
      result.status.error = "a mesh point's conformal image lies in no triangle of the samples "
                            "(the samples do not cover the sphere)";
      return false;
    }
    const Triangle& tri = sampleTriangles[t];
    result.interpolated[v] = normalized(
      w[0] * sampleImages[tri[0]] + w[1] * sampleImages[tri[1]] + w[2] * sampleImages[tri[2]]);
  }
  return true;
}

// Step 3: the area correction of result.sphere, and its figure. False when `report` asks to
// abort.
template <class Report>
bool correctOnSphere(const SurfaceMesh& surface, const composition::VertexStars& stars,
  const CompositionOptions& options, const Report& report, SphereCompositionResult& result)
{
  const std::vector<double> targets = composition::targetAreaShares(surface, options);
  composition::AreaCorrectionOn<composition::SphereGeometry> correction(
    surface, {}, stars, targets);
  if (!composition::correctAreas(
        correction, result.sphere, options,
        [&](const std::vector<Vec3>& sphere)
        { return meanAbsLogAreaRatioAgainst(surface, sphere, targets, targets.size()); },
        report, result.correctionSweeps, result.meanAbsLogAreaRatio))
  {
    return false;
  }
  if (options.measuredTriangles > 0) // else the correction's own last mean is the figure
  {
    result.meanAbsLogAreaRatio =
      sphereMeanAbsLogAreaRatio(surface, result.sphere, options.measuredTriangles);
  }
  return true;
}

// Where the untangling left triangles flipped and the start map has none, the map starts over
// from the start map (CompositionOptions::startOverWhereTangled). Returns the options its
// correction runs with: started over, it has the whole way from the start map's areas to go
// (the conformal map's: a mean |log area ratio| of 0.5-5 on the meshes that need it), not a
// polish, so it is the thorough correction, until a sweep gains less than 0.01%, with up to ten
// times the sweeps while they are cheap (2e7 vertex moves in all). VTK's cone at resolution 60 /
// 200, cylinder at 200, a closed grid with four 40-cell limbs: 0.054 / 1.48 / 2.29 / 0.128 with
// the default correction, 0.0011 / 0.15 / 0.12 / 0.015 so (549-1122 sweeps).
CompositionOptions startOverWhereTangled(const SurfaceMesh& surface, const std::vector<Vec3>& start,
  std::size_t stillFlipped, const CompositionOptions& options, SphereCompositionResult& result)
{
  CompositionOptions correction = options;
  if (stillFlipped == 0 || !options.correctAreas || !options.startOverWhereTangled ||
    !flippedOnSphere(surface, start).empty())
  {
    return correction;
  }
  result.flippedBeforeStartingOver = static_cast<std::int64_t>(stillFlipped);
  result.sphere = start;
  makeCorrectionThorough(correction);
  correction.correctionRelativeDecrease = 1e-4;
  const double affordable = 2e7 / static_cast<double>(surface.points.size());
  correction.maximumCorrectionSweeps = std::max(options.maximumCorrectionSweeps,
    static_cast<int>(std::min(10.0 * options.maximumCorrectionSweeps, affordable)));
  return correction;
}
} // namespace

//------------------------------------------------------------------------------
std::int64_t untangleSphereMap(const SurfaceMesh& surface, std::vector<Vec3>& sphere)
{
  const composition::VertexStars stars(sphere.size(), surface.triangles);
  return untangleOnSphere(surface, stars, true, sphere);
}

SphereCompositionResult composeOnSphere(const SurfaceMesh& surface,
  const std::vector<Vec3>& conformal, const std::vector<Vec3>& samples,
  const std::vector<Triangle>& sampleTriangles, const std::vector<Vec3>& sampleImages,
  const CompositionOptions& options)
{
  auto report = [&options](double fraction)
  { return !options.progress || options.progress(fraction); };
  SphereCompositionResult result;
  result.status.error = composition::checkTargetAreaShares(surface, options);
  if (!result.status.error.empty())
  {
    return result;
  }
  auto t0 = Clock::now();
  if (!interpolateOnSphere(conformal, samples, sampleTriangles, sampleImages, report, result))
  {
    return result;
  }
  result.secondsInterpolation = secondsSince(t0);
  if (!report(0.2))
  {
    result.status.aborted = true;
    return result;
  }
  result.flippedAfterInterpolation =
    static_cast<std::int64_t>(flippedOnSphere(surface, result.interpolated).size());

  // Step 2: untangling.
  t0 = Clock::now();
  result.sphere = result.interpolated;
  const composition::VertexStars stars(conformal.size(), surface.triangles);
  result.untangledVertices =
    untangleOnSphere(surface, stars, options.untangleWideStars, result.sphere);
  result.secondsUntangling = secondsSince(t0);
  // As on the disk: the untangled map before the correction.
  result.meanAbsLogAreaRatioInterpolated =
    sphereMeanAbsLogAreaRatio(surface, result.sphere, options.measuredTriangles);
  result.meanAbsLogAreaRatio = result.meanAbsLogAreaRatioInterpolated;
  if (!report(0.3))
  {
    result.sphere.clear(); // an aborted run has no map
    result.status.aborted = true;
    return result;
  }

  const std::size_t stillFlipped = flippedOnSphere(surface, result.sphere).size();
  const CompositionOptions correction =
    startOverWhereTangled(surface, conformal, stillFlipped, options, result);
  t0 = Clock::now();
  // Only an untangled map is corrected: the correction keeps every triangle positive.
  const bool untangled = stillFlipped == 0 || result.flippedBeforeStartingOver > 0;
  if (options.correctAreas && untangled &&
    !correctOnSphere(surface, stars, correction, report, result))
  {
    result.sphere.clear(); // an aborted run has no map
    result.status.aborted = true;
    return result;
  }
  result.secondsCorrection = secondsSince(t0);
  result.flippedTriangles =
    static_cast<std::int64_t>(flippedOnSphere(surface, result.sphere).size());
  return result;
}

} // namespace otparam
