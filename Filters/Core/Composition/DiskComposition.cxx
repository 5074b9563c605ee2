#include "Composition/DiskComposition.h"

#include "Composition/AreaCorrection.h"
#include "Composition/Composition.h"
#include "Composition/SampleInterpolation.h"
#include "Composition/SampleScaleCorrection.h"
#include "Composition/Untangling.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

namespace otparam
{
namespace
{
using namespace composition;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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

namespace
{
// The mean |log area ratio| over the first `measured` triangles (0 = all), each triangle's
// share renormalized over them.
double measuredMeanAbsLogAreaRatio(const SurfaceMesh& surface, const std::vector<Vec2>& uv,
  const std::vector<double>& surfaceFraction, std::size_t measured)
{
  if (measured == 0 || measured >= surface.triangles.size())
  {
    return meanAbsLogAreaRatio(surface.triangles, uv, surfaceFraction);
  }
  const std::vector<Triangle> triangles(
    surface.triangles.begin(), surface.triangles.begin() + static_cast<long>(measured));
  std::vector<double> fraction(
    surfaceFraction.begin(), surfaceFraction.begin() + static_cast<long>(measured));
  const double total = std::accumulate(fraction.begin(), fraction.end(), 0.0);
  for (double& f : fraction)
  {
    f /= total;
  }
  return meanAbsLogAreaRatio(triangles, uv, fraction);
}

std::string checkCompositionInputs(const SurfaceMesh& surface, const std::vector<Vec2>& conformalUv,
  const std::vector<Vec2>& samples, const std::vector<Vec2>& sampleImages,
  const std::vector<double>& sampleHeights)
{
  if (conformalUv.size() != surface.points.size())
  {
    return "the conformal image has " + std::to_string(conformalUv.size()) +
      " points but the surface has " + std::to_string(surface.points.size());
  }
  if (samples.size() < 3 || samples.size() != sampleImages.size())
  {
    return "the transport needs at least 3 samples with one image each (got " +
      std::to_string(samples.size()) + " samples and " + std::to_string(sampleImages.size()) +
      " images)";
  }
  if (!sampleHeights.empty() && sampleHeights.size() != samples.size())
  {
    return "the transport gave " + std::to_string(sampleHeights.size()) + " heights for " +
      std::to_string(samples.size()) + " samples";
  }
  const auto bad = std::find_if(
    sampleHeights.begin(), sampleHeights.end(), [](double h) { return !std::isfinite(h); });
  return bad == sampleHeights.end() ? std::string()
                                    : "the transport's height of sample " +
      std::to_string(bad - sampleHeights.begin()) + " is not a finite number";
}

// Step 1: every point's conformal image through the samples' interpolant, the boundary's
// pushed onto the circle; `corners`, unless null (step 3a will not run), gets each point's
// samples and weights (none for the boundary's). False when `report` asks to abort.
template <class Report>
bool interpolate(const std::vector<Vec2>& conformalUv, const std::vector<int>& boundaryLoop,
  const std::vector<Vec2>& samples, const std::vector<Vec2>& sampleImages,
  const std::vector<double>& sampleHeights, const Report& report, CompositionResult& result,
  std::vector<SampleCorners>* corners)
{
  // The power diagram's weights: |x - y_i|^2 - w_i = |x|^2 - 2 (<x, y_i> - h_i).
  std::vector<double> weights(sampleHeights.empty() ? 0 : samples.size());
  for (size_t i = 0; i < weights.size(); ++i)
  {
    weights[i] = dot(samples[i], samples[i]) - 2.0 * sampleHeights[i];
  }
  SampleInterpolant interpolant(samples, sampleImages, weights);
  std::tie(result.flippedSampleTriangles, result.flippedSampleTrianglesAfterUntangling) =
    interpolant.untangleImages();
  result.interpolatedUv.resize(conformalUv.size());
  if (corners)
  {
    corners->assign(conformalUv.size(), SampleCorners());
  }
  for (size_t v = 0; v < conformalUv.size(); ++v)
  {
    // An abort is honoured every 2^18 points (~0.1 s).
    if ((v & 0x3ffff) == 0x3ffff && !report(0.2 * v / conformalUv.size()))
    {
      return false;
    }
    bool outside = false;
    result.interpolatedUv[v] =
      interpolant(conformalUv[v], outside, corners ? &(*corners)[v] : nullptr);
    result.outsideSampleHull += outside;
  }
  for (int v : boundaryLoop)
  {
    result.interpolatedUv[v] = normalized(result.interpolatedUv[v]);
    if (corners)
    {
      (*corners)[v] = SampleCorners(); // stays on the circle
    }
  }
  return true;
}

// Step 3a: sweeps at the samples' scale (SampleScaleCorrection) until one lowers the mean
// |log area ratio| (over the measured triangles, as the figures) by less than a tenth, at most
// SampleScaleSweeps (on face_choi_bff_17k the first three lower it by 52%, 20% and 6%; more
// sweeps changed the final figures little). The samples on the circle and one pinned at the
// origin with its image (a staged transport's protrusion tip) stay. False when `report` asks
// to abort.
template <class Report>
bool correctAtSampleScale(const SurfaceMesh& surface, const std::vector<int>& boundaryLoop,
  const std::vector<Vec2>& samples, const std::vector<Vec2>& sampleImages,
  const std::vector<SampleCorners>& corners, const std::vector<double>& surfaceFraction,
  std::size_t measuredTriangles, const Report& report, CompositionResult& result)
{
  constexpr int SampleScaleSweeps = 4;
  constexpr double SettledGain = 0.1;
  std::vector<char> movable(samples.size());
  for (size_t i = 0; i < samples.size(); ++i)
  {
    movable[i] = !onCircle(samples[i]) && !pinnedAtOrigin(samples[i], sampleImages[i]);
  }
  const SampleScaleCorrection correction(surface.triangles, corners, movable, surfaceFraction);
  const double totalArea = PlaneGeometry::totalArea(result.uv, boundaryLoop);
  double& mean = result.meanAbsLogAreaRatioSampleScale;
  for (int sweep = 0; sweep < SampleScaleSweeps; ++sweep)
  {
    if (!report(0.3))
    {
      return false;
    }
    ++result.sampleScaleSweeps;
    if (correction.sweep(result.uv, totalArea) == 0)
    {
      break;
    }
    const double now =
      measuredMeanAbsLogAreaRatio(surface, result.uv, surfaceFraction, measuredTriangles);
    const bool settled = mean - now < SettledGain * mean;
    mean = now;
    if (settled)
    {
      break;
    }
  }
  return report(0.3);
}

// Step 3: the area correction of result.uv, and its figure. False when `report` asks to abort.
template <class Report>
bool correct(const SurfaceMesh& surface, const std::vector<int>& boundaryLoop,
  const VertexStars& stars, const std::vector<double>& surfaceFraction,
  const CompositionOptions& options, const Report& report, CompositionResult& result)
{
  AreaCorrection correction(surface, boundaryLoop, stars, surfaceFraction);
  if (!correctAreas(
        correction, result.uv, options,
        [&](const std::vector<Vec2>& uv)
        { return meanAbsLogAreaRatio(surface.triangles, uv, surfaceFraction); },
        report, result.correctionSweeps, result.meanAbsLogAreaRatio))
  {
    return false;
  }
  if (options.measuredTriangles > 0) // else the correction's own last mean is the figure
  {
    result.meanAbsLogAreaRatio =
      measuredMeanAbsLogAreaRatio(surface, result.uv, surfaceFraction, options.measuredTriangles);
  }
  return true;
}
} // namespace

CompositionResult composeWithInverseTransport(const SurfaceMesh& surface,
  const std::vector<Vec2>& conformalUv, const std::vector<int>& boundaryLoop,
  const std::vector<Vec2>& samples, const std::vector<Vec2>& sampleImages,
  const CompositionOptions& options, const std::vector<double>& sampleHeights)
{
  CompositionResult result;
  result.status.error =
    checkCompositionInputs(surface, conformalUv, samples, sampleImages, sampleHeights);
  if (result.status.error.empty())
  {
    result.status.error = checkTargetAreaShares(surface, options);
  }
  if (!result.status.error.empty())
  {
    return result;
  }
  auto report = [&](double fraction)
  {
    if (options.progress && !options.progress(fraction))
    {
      result.status.aborted = true;
    }
    return !result.status.aborted;
  };

  auto start = Clock::now();
  // Where each point lies among the samples, for step 3a only (40 bytes a point).
  const bool atSampleScale = options.correctAreas && options.correctAtSampleScale;
  std::vector<SampleCorners> corners;
  if (!interpolate(conformalUv, boundaryLoop, samples, sampleImages, sampleHeights, report, result,
        atSampleScale ? &corners : nullptr))
  {
    return result;
  }
  result.secondsInterpolation = seconds(start);
  if (!report(0.2))
  {
    return result;
  }

  // Step 2: untangling.
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
  const std::vector<double> surfaceFraction = targetAreaShares(surface, options);
  result.meanAbsLogAreaRatioInterpolated =
    measuredMeanAbsLogAreaRatio(surface, result.uv, surfaceFraction, options.measuredTriangles);
  result.meanAbsLogAreaRatio = result.meanAbsLogAreaRatioInterpolated;
  result.meanAbsLogAreaRatioSampleScale = result.meanAbsLogAreaRatioInterpolated;
  if (!report(0.3))
  {
    result.uv.clear(); // an aborted run has no map
    return result;
  }

  start = Clock::now();
  if (atSampleScale &&
    !correctAtSampleScale(surface, boundaryLoop, samples, sampleImages, corners, surfaceFraction,
      options.measuredTriangles, report, result))
  {
    result.uv.clear(); // an aborted run has no map
    return result;
  }
  result.secondsSampleScale = seconds(start);
  if (options.correctAreas &&
    !correct(surface, boundaryLoop, stars, surfaceFraction, options, report, result))
  {
    result.uv.clear(); // an aborted run has no map
    return result;
  }
  result.secondsCorrection = seconds(start);
  result.flippedTriangles =
    static_cast<std::int64_t>(flippedTriangles(surface.triangles, result.uv).size());
  return result;
}

} // namespace otparam
