// Benchmark of the whole area-preserving parameterization (parameterizeDisk, or parameterizeSphere
// for a closed mesh: the pipelines vtkAreaPreservingParam and the command line run with Domain
// Automatic) on the shared meshes: seconds per stage and in
// total (median of the runs), peak memory, the scorer's figures, and CGAL's iterative authalic map
// from reference-figures.md beside them.
//
//   otparam_param_benchmark [--repeat R] [--samples N] [--correction-decrease F]
//                           [--no-correction] [mesh ...]   (default: every shared mesh)
#include "ForkedRun.h"
#include "MeshFiles.h"
#include "Pipeline/AreaPreservingPipeline.h"

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

struct Row
{
  bool ok;
  double conformal, sampler, transport, composition, total, peak;
  int samples, iterations, converged, sweeps;
  double relativeError, interpolatedArea, area, areaMax, angle;
  long long flipsInterpolated, flips;
};

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
  row.peak = benchmark::peakMiB();
  return row;
}

Row run(const TriangleSoup& mesh, const AreaPreservingOptions& options)
{
  return chooseDomain(mesh) == Domain::Sphere ? rowOf(parameterizeSphere(mesh, options))
                                              : rowOf(parameterizeDisk(mesh, options));
}
} // namespace

int main(int argc, char** argv)
{
  int repeat = 3;
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
    else if (!std::strcmp(argv[i], "--no-correction"))
      options.composition.correctAreas = false;
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
  for (const auto& name : meshes)
  {
    const TriangleSoup mesh = testing::readSoup(testing::sharedMesh(name));
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
  return 0;
}
