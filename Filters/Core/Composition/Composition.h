// What the steps of the composition T^-1 o phi share: the stars of the mesh's vertices, the
// surface area fractions the map must give every triangle, and the figures of a map. The
// steps themselves: SampleInterpolation.h, Untangling.h, AreaCorrection.h; the disk's driver:
// DiskComposition.h. Private to the composition stage.
#ifndef OTPARAM_COMPOSITION_COMPOSITION_H
#define OTPARAM_COMPOSITION_COMPOSITION_H

#include "Common/Geometry.h"
#include "Composition/CompositionOptions.h"
#include "Mesh/SurfaceMesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

namespace otparam
{
namespace composition
{

constexpr double OnCircleTolerance = 1e-9;

inline double signedArea(Vec2 a, Vec2 b, Vec2 c)
{
  return 0.5 * cross(b - a, c - a);
}

inline Vec2 normalized(Vec2 p)
{
  const double r = norm(p);
  return r > 0.0 ? (1.0 / r) * p : Vec2{ 1.0, 0.0 };
}

inline bool onCircle(Vec2 p)
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

// Where a mesh point lies in the samples' triangulation (step 1 finds it, step 3a uses it): its
// samples and their barycentric weights (sample -1: none; a point with no sample takes no part
// in the sample-scale moves).
struct SampleCorners
{
  std::array<int, 3> sample = { -1, -1, -1 };
  std::array<double, 3> weight = { 0.0, 0.0, 0.0 };
};

// A sample pinned at the origin with its image there (a staged transport's protrusion tip,
// SamplerOptions::sampleAtOrigin): the interpolation keeps its neighbourhood's relative
// precision and the sample-scale moves leave it.
inline bool pinnedAtOrigin(Vec2 sample, Vec2 image)
{
  return sample.x == 0.0 && sample.y == 0.0 && image.x == 0.0 && image.y == 0.0;
}

// Area fraction of each triangle on the surface.
inline std::vector<double> surfaceAreaFractions(const SurfaceMesh& surface)
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

// The shares the area correction aims at: the options' targets, or the surface's own.
inline std::vector<double> targetAreaShares(
  const SurfaceMesh& surface, const CompositionOptions& options)
{
  return options.targetAreaShares.empty() ? surfaceAreaFractions(surface)
                                          : options.targetAreaShares;
}

// "" or what is wrong with the options' target shares (one positive value per triangle).
inline std::string checkTargetAreaShares(
  const SurfaceMesh& surface, const CompositionOptions& options)
{
  const std::vector<double>& shares = options.targetAreaShares;
  if (shares.empty())
  {
    return {};
  }
  if (shares.size() != surface.triangles.size())
  {
    return "the area correction has " + std::to_string(shares.size()) + " target shares for " +
      std::to_string(surface.triangles.size()) + " triangles";
  }
  const auto bad = std::find_if(
    shares.begin(), shares.end(), [](double s) { return !(s > 0.0) || !std::isfinite(s); });
  return bad == shares.end() ? std::string()
                             : "the area correction's target share of triangle " +
      std::to_string(bad - shares.begin()) + " is not a positive number";
}

// The merit function of the corrections' line searches: sum A* (r + 1/r - 2) = (A - A*)^2 / A,
// like log(r)^2 symmetric in log r, minimal at r = 1 and infinite at r = 0, but without a
// logarithm (the sweeps spent a fifth of their time in std::log). A caller makes the sum
// +infinity when a triangle would not be positive.
inline double areaMerit(double area, double target)
{
  const double d = area - target;
  return d * d / area;
}

// log(A / A*) for the corrections' Gauss-Newton steps, by its atanh series where the sweeps
// spend their time (|s| <= 0.05: truncation below 4e-12 of the log): the step needs no more,
// the merit decides. 273k points: composition 1.73 -> 1.45 s, the same sweeps and figures.
inline double logAreaRatio(double area, double target)
{
  const double s = (area - target) / (area + target);
  if (std::abs(s) > 0.05)
  {
    return std::log(area / target);
  }
  const double s2 = s * s;
  return 2.0 * s * (1.0 + s2 * (1.0 / 3.0 + s2 * (0.2 + s2 * (1.0 / 7.0))));
}

inline double meanAbsLogAreaRatio(const std::vector<Triangle>& triangles,
  const std::vector<Vec2>& uv, const std::vector<double>& surfaceFraction)
{
  // The terms in parallel, each sum in one order: the same bits at any thread count.
  const auto count = static_cast<std::int64_t>(triangles.size());
  std::vector<double> term(triangles.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < count; ++t)
  {
    const Triangle& tri = triangles[t];
    term[t] = std::abs(signedArea(uv[tri[0]], uv[tri[1]], uv[tri[2]]));
  }
  const double total = std::accumulate(term.begin(), term.end(), 0.0);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < count; ++t)
  {
    const double ratio = std::max(term[t], 1e-300) / total / surfaceFraction[t];
    term[t] = surfaceFraction[t] * std::abs(std::log(ratio));
  }
  return std::accumulate(term.begin(), term.end(), 0.0);
}

inline std::vector<int> flippedTriangles(
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

} // namespace composition
} // namespace otparam

#endif
