// Benchmark of the whole area-preserving parameterization (parameterizeDisk, or parameterizeSphere
// for a closed mesh: the pipelines vtkAreaPreservingParam and the command line run with Domain
// Automatic) on the shared meshes: seconds per stage and in
// total (median of the runs), peak memory, the scorer's figures, and CGAL's iterative authalic map
// from reference-figures.md beside them.
//
// With --progress-gaps, a second table: per stage, how often the pipeline asked whether to go
// on (its progress callback, where vtkAreaPreservingParam checks AbortExecute) and the longest
// time between two such checks, i.e. how long an abort can take in that stage. With
// --composition-steps, a table of the composition's steps: interpolation, untangling, the sweeps
// at the samples' scale and the per-vertex sweeps (count and seconds). --subdivide K applies K
// steps of Loop subdivision (CGAL) to each mesh first (the large-surface figures).
//
//   otparam_param_benchmark [--repeat R] [--samples N] [--correction-decrease F]
//                           [--thorough-correction] [--no-correction]
//                           [--no-sample-scale-correction] [--linear-growth] [--subdivide K]
//                           [--progress-gaps]
//                           [--composition-steps] [mesh ...]   (default: every shared mesh)
#include "ForkedRun.h"
#include "MeshFiles.h"
#include "Pipeline/AreaPreservingPipeline.h"

#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace otparam;
using otparam::benchmark::medianOf;

namespace
{
struct Reference
{
  const char* mesh;
  double iaArea, iaSeconds; // CGAL iterative authalic: mean |log area ratio|, seconds
};

const Reference References[] = {
  { "hand_stein_810.obj", 0.690, 0.07 },
  { "hemisphere_2k.obj", 0.040, 0.31 },
  { "face_dense_gpp_5k.obj", 0.117, 0.92 },
  { "face_choi_bff_17k.obj", 0.137, 6.74 },
  { "chinese_lion_17k.off", 0.159, 6.61 },
  { "ogre_face_20k.obj", 0.143, 8.31 },
  { "face_maxplanck_partial_32k.obj", 0.073, 19.24 },
  { "brain_cortex_cut_48k.off", 0.415, 45.50 },
  { "hand_choi_53k.off", 0.632, 53.55 },
  { "bust_aphrodite_56k.obj", -1, -1 },
  { "spot_closed_3k.obj", -1, -1 }, // the sphere (no CGAL anchor; see README's table)
  { "brain_choi_closed_48k.off", -1, -1 },
};

// The stages as the pipeline names them in its progress callback.
const char* const Stages[] = { "conformal", "sampling", "transport", "composition" };
constexpr int StageCount = 4;

struct Row
{
  bool ok;
  int checks[StageCount];
  double longestGap[StageCount]; // seconds between two progress checks, by the later's stage
  double gapFrom[StageCount], gapTo[StageCount]; // the pipeline's progress at its two ends
  double conformal, sampler, transport, composition, total, peak;
  int samples, iterations, converged, sweeps;
  double relativeError, interpolatedArea, area, areaMax, angle;
  long long flipsInterpolated, flips;
  // The composition's steps (seconds; the per-vertex sweeps' are the correction's less step 3a's).
  double interpolation, untangling, sampleScale, perVertex;
  int sampleScaleSweeps;
};

// Step 3a runs on the disk only.
void sampleScaleOf(const CompositionResult& c, Row& row)
{
  row.sampleScale = c.secondsSampleScale;
  row.sampleScaleSweeps = c.sampleScaleSweeps;
}
void sampleScaleOf(const SphereCompositionResult&, Row&) {}

template <class Map>
Row rowOf(const Map& map)
{
  Row row{};
  row.ok = map.status.ok();
  row.conformal = map.secondsConformal;
  row.sampler = map.secondsSampling;
  row.transport = map.secondsTransport;
  row.composition = map.secondsComposition;
  row.total = map.secondsTotal;
  row.samples = static_cast<int>(map.sampling.result.samples.size());
  row.iterations = map.transport.result.iterations;
  row.converged = map.transport.result.converged;
  row.relativeError = map.transport.result.relativeError;
  row.sweeps = map.composition.correctionSweeps;
  row.interpolatedArea = map.composition.meanAbsLogAreaRatioInterpolated;
  row.flipsInterpolated = map.composition.flippedAfterInterpolation;
  row.area = map.figures.meanAbsLogAreaRatio;
  row.areaMax = map.figures.maximumAbsLogAreaRatio;
  row.angle = map.figures.meanAngleDistortionDegrees;
  row.flips = map.figures.flippedTriangles;
  row.interpolation = map.composition.secondsInterpolation;
  row.untangling = map.composition.secondsUntangling;
  sampleScaleOf(map.composition, row);
  row.perVertex = map.composition.secondsCorrection - row.sampleScale;
  row.peak = benchmark::peakMiB();
  return row;
}

int stageIndex(const char* stage)
{
  for (int k = 0; k < StageCount; ++k)
  {
    if (std::strstr(stage, Stages[k]))
    {
      return k;
    }
  }
  return StageCount - 1;
}

Row run(const TriangleSoup& mesh, AreaPreservingOptions options)
{
  using Clock = std::chrono::steady_clock;
  int checks[StageCount] = {};
  double longest[StageCount] = {}, from[StageCount] = {}, to[StageCount] = {};
  Clock::time_point last = Clock::now();
  int lastStage = 0;
  double lastFraction = 0.0;
  options.progress = [&](const char* stage, double fraction)
  {
    const Clock::time_point now = Clock::now();
    const int k = stageIndex(stage);
    ++checks[k];
    const double gap = std::chrono::duration<double>(now - last).count();
    if (gap > longest[k])
    {
      longest[k] = gap;
      from[k] = lastFraction;
      to[k] = fraction;
    }
    last = now;
    lastStage = k;
    lastFraction = fraction;
    return true;
  };
  Row row = chooseDomain(mesh) == Domain::Sphere ? rowOf(parameterizeSphere(mesh, options))
                                                 : rowOf(parameterizeDisk(mesh, options));
  // From the last check to the end: the composition's figures, counted as the last stage's.
  const double tail = std::chrono::duration<double>(Clock::now() - last).count();
  if (tail > longest[lastStage])
  {
    longest[lastStage] = tail;
    from[lastStage] = lastFraction;
    to[lastStage] = 1.0;
  }
  std::copy(checks, checks + StageCount, row.checks);
  std::copy(longest, longest + StageCount, row.longestGap);
  std::copy(from, from + StageCount, row.gapFrom);
  std::copy(to, to + StageCount, row.gapTo);
  return row;
}

// K steps of CGAL's Loop subdivision (the surface is smoothed; a boundary stays a boundary).
TriangleSoup loopSubdivided(const TriangleSoup& soup, int steps)
{
  using Kernel = CGAL::Simple_cartesian<double>;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  std::vector<Kernel::Point_3> points;
  for (const Vec3& p : soup.points)
  {
    points.emplace_back(p.x, p.y, p.z);
  }
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : soup.triangles)
  {
    polygons.push_back({ static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
      static_cast<std::size_t>(t[2]) });
  }
  Mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(steps));
  TriangleSoup out;
  std::vector<int> id(mesh.number_of_vertices(), -1);
  for (const auto v : mesh.vertices())
  {
    id[v.idx()] = static_cast<int>(out.points.size());
    const auto& p = mesh.point(v);
    out.points.push_back({ p.x(), p.y(), p.z() });
  }
  for (const auto f : mesh.faces())
  {
    std::array<std::int64_t, 3> t{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
    {
      t[k++] = id[v.idx()];
    }
    out.triangles.push_back(t);
  }
  return out;
}
} // namespace

int main(int argc, char** argv)
{
  int repeat = 3, subdivide = 0;
  bool progressGaps = false, compositionSteps = false;
  AreaPreservingOptions options; // vtkAreaPreservingParam's defaults
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--samples") && i + 1 < argc)
      options.sampling.numberOfSamples = std::atoll(argv[++i]);
    else if (!std::strcmp(argv[i], "--correction-decrease") && i + 1 < argc)
      options.composition.correctionRelativeDecrease = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--thorough-correction"))
      makeCorrectionThorough(options.composition);
    else if (!std::strcmp(argv[i], "--no-correction"))
      options.composition.correctAreas = false;
    else if (!std::strcmp(argv[i], "--no-sample-scale-correction"))
      options.composition.correctAtSampleScale = false;
    else if (!std::strcmp(argv[i], "--linear-growth"))
      options.transport.squareRootGrowth = false;
    else if (!std::strcmp(argv[i], "--subdivide") && i + 1 < argc)
      subdivide = std::max(0, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--progress-gaps"))
      progressGaps = true;
    else if (!std::strcmp(argv[i], "--composition-steps"))
      compositionSteps = true;
    else if (argv[i][0] == '-')
    {
      std::fprintf(stderr,
        "unknown option %s\nusage: otparam_param_benchmark [--repeat R] [--samples N] "
        "[--correction-decrease F] [--thorough-correction] [--no-correction] "
        "[--no-sample-scale-correction] [--linear-growth] [--subdivide K] [--progress-gaps] "
        "[--composition-steps] [mesh ...]\n",
        argv[i]);
      return 2;
    }
    else
      meshes.push_back(argv[i]);
  }
  if (meshes.empty())
    for (const auto& r : References)
      meshes.push_back(r.mesh);

  std::printf("Area-preserving parameterization, %lld samples requested, median of %d runs\n"
              "(seconds; conformal = topology checks + conformal map + AreaDensity, sampler =\n"
              "density field + adaptive sampling, transport = semi-discrete OT to 1e-10,\n"
              "composition = interpolation + untangling + area correction; area = mean |log area\n"
              "ratio| before (interp) and after the correction; peak memory of the process)\n\n",
    options.sampling.numberOfSamples, repeat);
  std::printf("| mesh | vertices | samples | conformal | sampler | transport | composition | total "
              "| MiB | its | rel. error | flips interp/final | area interp | area | area max | "
              "angle | sweeps | CGAL IA area | CGAL IA s |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  struct Gaps
  {
    std::string mesh;
    std::size_t points;
    Row row;
  };
  std::vector<Gaps> gaps;
  struct Steps
  {
    std::string mesh;
    std::size_t points;
    double interpolation, untangling, sampleScale, perVertex, composition;
    int sampleScaleSweeps, sweeps;
  };
  std::vector<Steps> steps;
  for (const auto& name : meshes)
  {
    TriangleSoup mesh;
    if (!testing::readOrReport(testing::sharedMesh(name), testing::readSoup, mesh))
    {
      return 2;
    }
    if (subdivide > 0)
    {
      mesh = loopSubdivided(mesh, subdivide);
    }
    std::vector<Row> rows;
    for (int r = 0; r < repeat; ++r)
    {
      Row row{};
      if (!benchmark::runInChild([&] { return run(mesh, options); }, row) || !row.ok)
      {
        std::printf("| %s | failed |\n", name.c_str());
        break;
      }
      rows.push_back(row);
    }
    if (rows.empty())
      continue;
    const Row& last = rows.back();
    gaps.push_back({ name, mesh.points.size(), last });
    steps.push_back({ name, mesh.points.size(), medianOf(rows, &Row::interpolation),
      medianOf(rows, &Row::untangling), medianOf(rows, &Row::sampleScale),
      medianOf(rows, &Row::perVertex), medianOf(rows, &Row::composition), last.sampleScaleSweeps,
      last.sweeps });
    const Reference* ref = nullptr;
    for (const auto& r : References)
      if (name == r.mesh)
        ref = &r;
    std::printf("| %s | %zu | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %d | %.1e | %lld/%lld "
                "| %.4f | %.4f | %.2f | %.2f | %d |",
      name.c_str(), mesh.points.size(), last.samples, medianOf(rows, &Row::conformal),
      medianOf(rows, &Row::sampler), medianOf(rows, &Row::transport),
      medianOf(rows, &Row::composition), medianOf(rows, &Row::total), medianOf(rows, &Row::peak),
      last.iterations, last.relativeError, last.flipsInterpolated, last.flips,
      last.interpolatedArea, last.area, last.areaMax, last.angle, last.sweeps);
    if (ref && ref->iaSeconds >= 0)
      std::printf(" %.3f | %.2f |\n", ref->iaArea, ref->iaSeconds);
    else
      std::printf(" - | - |\n");
    std::fflush(stdout);
  }
  if (progressGaps)
  {
    std::printf(
      "\nAbort latency: per stage, the progress checks (where AbortExecute is read) and the "
      "longest time between two of them, seconds, with the pipeline's progress at its two "
      "ends (last run)\n\n"
      "| mesh | vertices | conformal | sampling | transport | composition |\n"
      "|---|---|---|---|---|---|\n");
    for (const auto& [name, points, row] : gaps)
    {
      std::printf("| %s | %zu |", name.c_str(), points);
      for (int k = 0; k < StageCount; ++k)
      {
        std::printf(" %d checks, %.2f s (%.3f-%.3f) |", row.checks[k], row.longestGap[k],
          row.gapFrom[k], row.gapTo[k]);
      }
      std::printf("\n");
    }
  }
  if (compositionSteps)
  {
    std::printf("\nThe composition's steps (seconds, medians; sweeps of the last run): "
                "interpolation, untangling, sweeps at the samples' scale (the disk's), per-vertex "
                "sweeps (with the polishing)\n\n"
                "| mesh | vertices | interpolation | untangling | sample-scale sweeps | s | "
                "per-vertex sweeps | s | composition |\n"
                "|---|---|---|---|---|---|---|---|---|\n");
    for (const Steps& s : steps)
    {
      std::printf("| %s | %zu | %.3f | %.3f | %d | %.3f | %d | %.3f | %.3f |\n", s.mesh.c_str(),
        s.points, s.interpolation, s.untangling, s.sampleScaleSweeps, s.sampleScale, s.sweeps,
        s.perVertex, s.composition);
    }
  }
  return 0;
}
