#include "Composition/DiskComposition.h"

#include "Composition/AreaCorrection.h"
#include "Composition/Composition.h"
#include "Composition/SampleInterpolation.h"
#include "Composition/Untangling.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace otparam
{
namespace
{
using namespace composition;
using Clock = std::chrono::steady_clock;

constexpr double PolishLogRatio = 0.05;
constexpr int PolishSweeps = 50; // measured on hand_choi_53k: the largest error stops falling there

double seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Step 3's sweeps: until the mean |log area ratio| settles, then the polishing of the worst.
template <typename Report>
void correctAreas(AreaCorrection& correction, const SurfaceMesh& surface,
  const std::vector<double>& surfaceFraction, const CompositionOptions& options, Report& report,
  CompositionResult& result)
{
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
    result.status.error = "the conformal image has " + std::to_string(conformalUv.size()) +
      " points but the surface has " + std::to_string(surface.points.size());
    return result;
  }
  if (samples.size() < 3 || samples.size() != sampleImages.size())
  {
    result.status.error = "the transport needs at least 3 samples with one image each (got " +
      std::to_string(samples.size()) + " samples and " + std::to_string(sampleImages.size()) +
      " images)";
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
    correctAreas(correction, surface, surfaceFraction, options, report, result);
  }
  result.secondsCorrection = seconds(start);
  result.flippedTriangles =
    static_cast<std::int64_t>(flippedTriangles(surface.triangles, result.uv).size());
  return result;
}

} // namespace otparam
