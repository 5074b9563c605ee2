// The composition step of the area-preserving map (interpolation through the samples,
// untangling, area correction), on planar disks where the answer is known.
#include "Composition/DiskComposition.h"
#include "Mesh/DistortionMetrics.h"
#include "OTTestProblems.h"
#include "RingDisk.h"
#include "Transport/PlanarSource.h"
#include "Transport/SemiDiscreteOT.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace otparam;

namespace
{
SurfaceMesh flatSurface(const otparam::testing::PlanarMesh& disk)
{
  SurfaceMesh surface;
  for (const Vec2& p : disk.points)
  {
    surface.points.push_back({ p.x, p.y, 0.0 });
  }
  surface.triangles = disk.triangles;
  return surface;
}

// Sample images moved at random by up to `amplitude` in each coordinate, except those on the
// circle (|p| >= 0.95), which stay there.
std::vector<Vec2> shakenInside(std::vector<Vec2> images, unsigned seed, double amplitude)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> shake(-amplitude, amplitude);
  for (Vec2& p : images)
  {
    if (norm(p) < 0.95)
    {
      p = p + Vec2{ shake(random), shake(random) };
    }
  }
  return images;
}

std::vector<int> boundaryOf(const SurfaceMesh& surface)
{
  std::vector<int> loop;
  EXPECT_EQ(checkDiskTopology(surface, loop), "");
  return loop;
}

void expectOnCircle(const std::vector<Vec2>& uv, const std::vector<int>& loop)
{
  for (int v : loop)
  {
    EXPECT_NEAR(norm(uv[v]), 1.0, 1e-14) << v;
  }
}
} // namespace

TEST(AreaPreservingComposition, IdentityTransportKeepsTheConformalImage)
{
  // Mesh and samples are different ring disks: mesh vertices fall inside sample triangles and,
  // on the boundary, in the circular segments between boundary samples.
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(13);
  const otparam::testing::PlanarMesh samples = otparam::testing::makePlanarDisk(7);
  const SurfaceMesh surface = flatSurface(mesh);
  const std::vector<int> loop = boundaryOf(surface);
  CompositionOptions options;
  options.correctAreas = false;
  const CompositionResult result = composeWithInverseTransport(
    surface, mesh.points, loop, samples.points, samples.points, options);
  ASSERT_EQ(result.status.error, "");
  EXPECT_GT(result.outsideSampleHull, 0);
  EXPECT_EQ(result.flippedAfterInterpolation, 0);
  for (size_t v = 0; v < mesh.points.size(); ++v)
  {
    EXPECT_NEAR(result.uv[v].x, mesh.points[v].x, 1e-13) << v;
    EXPECT_NEAR(result.uv[v].y, mesh.points[v].y, 1e-13) << v;
  }
}

TEST(AreaPreservingComposition, LinearImagesAreInterpolatedExactly)
{
  // A rotation of the disk: interior points follow it exactly, boundary points stay on the
  // circle at the rotated angle.
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(11);
  const otparam::testing::PlanarMesh samples = otparam::testing::makePlanarDisk(6);
  const double c = std::cos(0.3), s = std::sin(0.3);
  std::vector<Vec2> images;
  for (const Vec2& p : samples.points)
  {
    images.push_back({ c * p.x - s * p.y, s * p.x + c * p.y });
  }
  const SurfaceMesh surface = flatSurface(mesh);
  const CompositionResult result =
    composeWithInverseTransport(surface, mesh.points, boundaryOf(surface), samples.points, images);
  ASSERT_EQ(result.status.error, "");
  for (size_t v = 0; v < mesh.points.size(); ++v)
  {
    const Vec2 p = mesh.points[v];
    EXPECT_NEAR(result.uv[v].x, c * p.x - s * p.y, 1e-12) << v;
    EXPECT_NEAR(result.uv[v].y, s * p.x + c * p.y, 1e-12) << v;
  }
  // Already area-preserving: the correction has nothing to do.
  EXPECT_LE(result.meanAbsLogAreaRatio, 1e-12);
}

// A crowded finger's tip at the origin (the staged transport's centred start): mesh rings down
// to 1e-140 around a sample pinned at the origin with its image there. Each point keeps its
// relative position: the weights sum to 1 through the pinned corner (1 minus two weights near
// 1 and 0 would round the deep rings onto the origin).
TEST(AreaPreservingComposition, PointsNearASamplePinnedAtTheOriginKeepTheirRelativePrecision)
{
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(13);
  std::vector<Vec2> uv;
  for (const Vec2& p : mesh.points)
  {
    const double r = norm(p);
    uv.push_back(r > 0.0 && r < 1.0 ? (std::exp(-350.0 * (1.0 - r)) / r) * p : p);
  }
  const otparam::testing::PlanarMesh samples = otparam::testing::makePlanarDisk(6);
  ASSERT_EQ(norm(samples.points[0]), 0.0);
  const double c = std::cos(0.3), s = std::sin(0.3);
  std::vector<Vec2> images;
  for (const Vec2& p : samples.points)
  {
    images.push_back({ c * p.x - s * p.y, s * p.x + c * p.y });
  }
  SurfaceMesh surface = flatSurface(mesh);
  CompositionOptions options;
  options.correctAreas = false;
  const CompositionResult result =
    composeWithInverseTransport(surface, uv, boundaryOf(surface), samples.points, images, options);
  ASSERT_EQ(result.status.error, "");
  EXPECT_EQ(result.flippedTriangles, 0);
  double worst = 0.0, deepest = 1.0;
  for (size_t v = 0; v < uv.size(); ++v)
  {
    const Vec2 p = uv[v], rotated = { c * p.x - s * p.y, s * p.x + c * p.y };
    if (norm(p) > 0.0)
    {
      worst = std::max(worst, norm(result.uv[v] - rotated) / norm(p));
      deepest = std::min(deepest, norm(p));
    }
  }
  EXPECT_LT(deepest, 1e-130);
  EXPECT_LT(worst, 1e-12);
}

TEST(AreaPreservingComposition, InterpolatesOverThePowerDiagramsDual)
{
  // Diracs crowded by masses of contrast 1e4 (OTTestProblems.h): the samples' Delaunay
  // triangles also join Diracs whose cells do not touch, and their cells' centroids then often
  // come in the other order; the regular triangulation of the transport's weights joins
  // exactly the Diracs whose cells meet.
  const std::unique_ptr<SourceMeasure> disk = makeUnitDiskSource();
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(60);
  const SurfaceMesh surface = flatSurface(mesh);
  const std::vector<int> loop = boundaryOf(surface);
  CompositionOptions options;
  options.correctAreas = false;
  const std::vector<Vec2> diracs = otparam::testing::randomInDisk(3000, 5, 0.95);
  const OTResult crowded =
    solveSemiDiscreteOT(*disk, diracs, otparam::testing::mixtureMasses(diracs, 1e4));
  ASSERT_TRUE(crowded.converged);
  const CompositionResult regular = composeWithInverseTransport(
    surface, mesh.points, loop, diracs, crowded.centroids, options, crowded.heights);
  const CompositionResult delaunay =
    composeWithInverseTransport(surface, mesh.points, loop, diracs, crowded.centroids, options);
  std::printf("sample triangles flipped by the centroids: regular %lld, Delaunay %lld\n",
    static_cast<long long>(regular.flippedSampleTriangles),
    static_cast<long long>(delaunay.flippedSampleTriangles));
  EXPECT_LT(regular.flippedSampleTriangles, delaunay.flippedSampleTriangles / 2);

  // A transport whose inverse is known everywhere: the uniform disk onto Diracs of equal mass
  // on a sunflower spiral of the radial density (1 + a r^2) / (1 + a / 2), T^-1(p) =
  // sqrt(F(|p|)) p / |p| with F(r) = r^2 (1 + a r^2 / 2) / (1 + a / 2).
  const double a = 30.0;
  const otparam::testing::RadialProblem problem = otparam::testing::radialProblem(2000, a);
  const OTResult radial = solveSemiDiscreteOT(*disk, problem.diracs, problem.masses);
  ASSERT_TRUE(radial.converged);
  const CompositionResult exact = composeWithInverseTransport(
    surface, mesh.points, loop, problem.diracs, radial.centroids, options, radial.heights);
  ASSERT_EQ(exact.status.error, "");
  double largest = 0.0;
  for (size_t v = 0; v < mesh.points.size(); ++v)
  {
    const Vec2 p = mesh.points[v];
    const double r = norm(p);
    if (r > 0.0 && r < 0.9) // inside the Diracs' hull
    {
      const double image = std::sqrt(r * r * (1.0 + a * r * r / 2.0) / (1.0 + a / 2.0));
      largest = std::max(largest, norm(exact.uv[v] - (image / r) * p));
    }
  }
  std::printf("largest distance to T^-1 within radius 0.9: %.2e\n", largest);
  EXPECT_LE(largest, 5e-3);

  std::vector<double> wrong = radial.heights;
  wrong.pop_back();
  EXPECT_NE(composeWithInverseTransport(
              surface, mesh.points, loop, problem.diracs, radial.centroids, options, wrong)
              .status.error.find("heights"),
    std::string::npos);
  wrong.push_back(std::nan(""));
  EXPECT_NE(composeWithInverseTransport(
              surface, mesh.points, loop, problem.diracs, radial.centroids, options, wrong)
              .status.error.find("not a finite number"),
    std::string::npos);
}

TEST(AreaPreservingComposition, UntanglesFlipsAndCorrectsAreas)
{
  // Sample images shaken hard enough to fold the interpolant over: flipped sample triangles to
  // untangle, areas far off to correct; the boundary must stay on the circle throughout.
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(20);
  const otparam::testing::PlanarMesh samples = otparam::testing::makePlanarDisk(9);
  const std::vector<Vec2> images = shakenInside(samples.points, 7, 0.06);
  const SurfaceMesh surface = flatSurface(mesh);
  const std::vector<int> loop = boundaryOf(surface);
  const CompositionResult result =
    composeWithInverseTransport(surface, mesh.points, loop, samples.points, images);
  ASSERT_EQ(result.status.error, "");
  std::printf("flipped sample triangles %lld -> %lld, mesh triangles after interpolation %lld, "
              "untangled vertices %lld\n",
    static_cast<long long>(result.flippedSampleTriangles),
    static_cast<long long>(result.flippedSampleTrianglesAfterUntangling),
    static_cast<long long>(result.flippedAfterInterpolation),
    static_cast<long long>(result.untangledVertices));
  // The folds are undone on the samples, so far fewer mesh triangles are flipped (only those
  // spanning several sample triangles where the map bends): 0 here.
  EXPECT_GT(result.flippedSampleTriangles, 0);
  EXPECT_EQ(result.flippedSampleTrianglesAfterUntangling, 0);
  EXPECT_EQ(result.flippedAfterInterpolation, 0);
  EXPECT_EQ(result.flippedTriangles, 0);
  const DistortionFigures figures = measureDistortion(surface, result.uv);
  EXPECT_EQ(figures.flippedTriangles, 0);
  EXPECT_NEAR(figures.meanAbsLogAreaRatio, result.meanAbsLogAreaRatio, 1e-12);
  EXPECT_LE(result.meanAbsLogAreaRatio, 0.2 * result.meanAbsLogAreaRatioInterpolated)
    << "interpolated " << result.meanAbsLogAreaRatioInterpolated;
  EXPECT_LE(result.meanAbsLogAreaRatio, 0.03);
  expectOnCircle(result.uv, loop);
}

// An area error at the samples' scale (sample images pushed outwards by r -> r^1.3, a smooth
// map with area ratios from 0 at the centre to 1.3^2 at the rim): the sweeps that move one
// sample image with its whole star halve it (0.211 -> 0.099), and the per-vertex sweeps after
// them end with less shear than from the interpolated map (mean angle distortion 13.0 -> 9.7
// degrees, area 0.0088 -> 0.0073, 99 -> 57 sweeps).
TEST(AreaPreservingComposition, SampleScaleSweepsRemoveASmoothError)
{
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(40);
  const otparam::testing::PlanarMesh samples = otparam::testing::makePlanarDisk(10);
  std::vector<Vec2> images;
  for (const Vec2& p : samples.points)
  {
    images.push_back(std::pow(norm(p), 0.3) * p);
  }
  const SurfaceMesh surface = flatSurface(mesh);
  const std::vector<int> loop = boundaryOf(surface);
  CompositionOptions options;
  options.correctAtSampleScale = false;
  const CompositionResult vertexOnly =
    composeWithInverseTransport(surface, mesh.points, loop, samples.points, images, options);
  const CompositionResult both =
    composeWithInverseTransport(surface, mesh.points, loop, samples.points, images);
  ASSERT_EQ(both.status.error, "");
  const DistortionFigures before = measureDistortion(surface, vertexOnly.uv);
  const DistortionFigures after = measureDistortion(surface, both.uv);
  std::printf("interpolated %.4f, after %d sample-scale sweeps %.4f; final area / angle: "
              "per-vertex sweeps only %.4f / %.2f (%d sweeps), both %.4f / %.2f (%d sweeps)\n",
    both.meanAbsLogAreaRatioInterpolated, both.sampleScaleSweeps,
    both.meanAbsLogAreaRatioSampleScale, before.meanAbsLogAreaRatio,
    before.meanAngleDistortionDegrees, vertexOnly.correctionSweeps, after.meanAbsLogAreaRatio,
    after.meanAngleDistortionDegrees, both.correctionSweeps);
  EXPECT_EQ(vertexOnly.sampleScaleSweeps, 0);
  EXPECT_GE(both.sampleScaleSweeps, 1);
  EXPECT_LE(both.meanAbsLogAreaRatioSampleScale, 0.5 * both.meanAbsLogAreaRatioInterpolated);
  EXPECT_LT(after.meanAngleDistortionDegrees, before.meanAngleDistortionDegrees);
  EXPECT_LE(after.meanAbsLogAreaRatio, before.meanAbsLogAreaRatio);
  EXPECT_EQ(after.flippedTriangles, 0);
  expectOnCircle(both.uv, loop);
}

// The untangling and the correction's sweeps move vertices on both cores (colour by colour in
// both kinds of sweeps): the map is the same bit for bit on one thread and on two.
TEST(AreaPreservingComposition, SameBitsWithOneAndTwoThreads)
{
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(60);
  const otparam::testing::PlanarMesh samples = otparam::testing::makePlanarDisk(15);
  const std::vector<Vec2> images = shakenInside(samples.points, 11, 0.03);
  const SurfaceMesh surface = flatSurface(mesh);
  const std::vector<int> loop = boundaryOf(surface);
  std::vector<CompositionResult> runs;
  for (int threads : { 2, 1 })
  {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    runs.push_back(composeWithInverseTransport(surface, mesh.points, loop, samples.points, images));
  }
#ifdef _OPENMP
  omp_set_num_threads(omp_get_num_procs());
#endif
  ASSERT_EQ(runs[0].status.error, "");
  EXPECT_GT(runs[0].correctionSweeps, 10);
  EXPECT_GT(runs[0].sampleScaleSweeps, 0);
  EXPECT_EQ(runs[1].correctionSweeps, runs[0].correctionSweeps);
  ASSERT_EQ(runs[1].uv.size(), runs[0].uv.size());
  for (size_t v = 0; v < runs[0].uv.size(); ++v)
  {
    ASSERT_TRUE(runs[1].uv[v].x == runs[0].uv[v].x && runs[1].uv[v].y == runs[0].uv[v].y)
      << "vertex " << v << " differs between 1 and 2 threads";
  }
}

TEST(AreaPreservingComposition, UntanglesAPatchCollapsedToAPoint)
{
  // A round patch of the map collapsed onto one point (the limit of a crowded patch whose
  // images came out of the interpolation as a thin tangled band, as bunny_holes_35k's did once
  // in 16 sample sets): the rim of each of its vertices is degenerate too, so no single vertex
  // can move to a better place (without the re-embedding: 216 triangles left flipped, mean
  // |log area ratio| 27). The patch is laid out again as a Tutte embedding inside its rim.
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(30);
  std::vector<Vec2> conformal = mesh.points;
  const Vec2 centre = { 0.4, 0.1 };
  for (Vec2& p : conformal)
  {
    if (norm(p - centre) < 0.2)
    {
      p = centre;
    }
  }
  const SurfaceMesh surface = flatSurface(mesh);
  const std::vector<int> loop = boundaryOf(surface);
  const CompositionResult result = composeWithInverseTransport(
    surface, conformal, loop, mesh.points, mesh.points); // the identity transport
  ASSERT_EQ(result.status.error, "");
  std::printf("flipped after interpolation %lld, untangled vertices %lld, final area %.4f\n",
    static_cast<long long>(result.flippedAfterInterpolation),
    static_cast<long long>(result.untangledVertices), result.meanAbsLogAreaRatio);
  EXPECT_GT(result.flippedAfterInterpolation, 50);
  EXPECT_EQ(result.flippedTriangles, 0);
  EXPECT_EQ(measureDistortion(surface, result.uv).flippedTriangles, 0);
  EXPECT_LE(result.meanAbsLogAreaRatio, 0.05);
}

TEST(AreaPreservingComposition, CorrectsTowardsGivenTargetShares)
{
  // A staged transport's stage corrects towards its clamped density's shares, not the
  // surface's: here the identity transport of a flat disk, whose triangles should get shares
  // growing 9-fold from left to right. The map ends within 2.5% of them on average (0.017: the
  // boundary keeps its points, so the rim's triangles cannot all follow), its boundary on the
  // circle, no triangle flipped; the figure is measured against the targets.
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(20);
  const SurfaceMesh surface = flatSurface(mesh);
  const std::vector<int> loop = boundaryOf(surface);
  CompositionOptions options;
  double total = 0.0;
  for (const Triangle& t : surface.triangles)
  {
    const Vec2 a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
    const double x = (a.x + b.x + c.x) / 3.0;
    options.targetAreaShares.push_back((5.0 + 4.0 * x) * 0.5 * cross(b - a, c - a));
    total += options.targetAreaShares.back();
  }
  for (double& share : options.targetAreaShares)
  {
    share /= total;
  }
  const CompositionResult result =
    composeWithInverseTransport(surface, mesh.points, loop, mesh.points, mesh.points, options);
  ASSERT_EQ(result.status.error, "");
  std::printf("mean |log area / target|: %.4f interpolated, %.4f corrected\n",
    result.meanAbsLogAreaRatioInterpolated, result.meanAbsLogAreaRatio);
  EXPECT_GE(result.meanAbsLogAreaRatioInterpolated, 0.2);
  EXPECT_LE(result.meanAbsLogAreaRatio, 0.025);
  EXPECT_EQ(result.flippedTriangles, 0);
  double mean = 0.0, area = 0.0;
  for (size_t t = 0; t < surface.triangles.size(); ++t)
  {
    const Triangle& tri = surface.triangles[t];
    area +=
      0.5 * cross(result.uv[tri[1]] - result.uv[tri[0]], result.uv[tri[2]] - result.uv[tri[0]]);
  }
  for (size_t t = 0; t < surface.triangles.size(); ++t)
  {
    const Triangle& tri = surface.triangles[t];
    const double a =
      0.5 * cross(result.uv[tri[1]] - result.uv[tri[0]], result.uv[tri[2]] - result.uv[tri[0]]);
    mean +=
      options.targetAreaShares[t] * std::abs(std::log(a / area / options.targetAreaShares[t]));
  }
  EXPECT_NEAR(mean, result.meanAbsLogAreaRatio, 1e-12);
  expectOnCircle(result.uv, loop);

  options.targetAreaShares.pop_back();
  EXPECT_NE(
    composeWithInverseTransport(surface, mesh.points, loop, mesh.points, mesh.points, options)
      .status.error.find("target shares"),
    std::string::npos);
  options.targetAreaShares.push_back(-1.0);
  EXPECT_NE(
    composeWithInverseTransport(surface, mesh.points, loop, mesh.points, mesh.points, options)
      .status.error.find("not a positive number"),
    std::string::npos);
}

TEST(AreaPreservingComposition, RejectsMismatchedInputsAndHonoursAbort)
{
  const otparam::testing::PlanarMesh mesh = otparam::testing::makePlanarDisk(5);
  const SurfaceMesh surface = flatSurface(mesh);
  const std::vector<int> loop = boundaryOf(surface);
  std::vector<Vec2> shorter(mesh.points.begin(), mesh.points.end() - 1);
  EXPECT_NE(
    composeWithInverseTransport(surface, shorter, loop, mesh.points, mesh.points).status.error, "");
  EXPECT_NE(
    composeWithInverseTransport(surface, mesh.points, loop, mesh.points, shorter).status.error, "");
  const std::vector<Vec2> two(mesh.points.begin(), mesh.points.begin() + 2);
  EXPECT_NE(composeWithInverseTransport(surface, mesh.points, loop, two, two).status.error, "");

  CompositionOptions options;
  options.progress = [](double) { return false; };
  const CompositionResult aborted =
    composeWithInverseTransport(surface, mesh.points, loop, mesh.points, mesh.points, options);
  EXPECT_TRUE(aborted.status.aborted);
}

TEST(AreaPreservingComposition, BoundaryArcMidpoint)
{
  auto cellWithArc = [](double from, double to)
  {
    std::vector<Vec2> cell = { { 0.5 * std::cos(0.5 * (from + to)),
      0.5 * std::sin(0.5 * (from + to)) } };
    for (int k = 0; k <= 8; ++k)
    {
      const double angle = from + (to - from) * k / 8.0;
      cell.push_back({ std::cos(angle), std::sin(angle) });
    }
    return cell;
  };
  Vec2 middle = boundaryArcMidpoint(cellWithArc(0.2, 0.6));
  EXPECT_NEAR(middle.x, std::cos(0.4), 1e-14);
  EXPECT_NEAR(middle.y, std::sin(0.4), 1e-14);
  middle = boundaryArcMidpoint(cellWithArc(3.0, 3.4)); // across the +-pi cut
  EXPECT_NEAR(middle.x, std::cos(3.2), 1e-14);
  EXPECT_NEAR(middle.y, std::sin(3.2), 1e-14);
  EXPECT_TRUE(std::isnan(boundaryArcMidpoint({ { 0.0, 0.0 }, { 0.5, 0.0 }, { 0.0, 0.5 } }).x));
}
