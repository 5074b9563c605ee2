// Benchmark of the adaptive density sampler on the unit disk with a Gaussian-mixture density of
// contrast 1e6 (piecewise linear on a ring mesh of ~68k points): seconds, peak memory, spread
// of the masses and smallest angle per target count; each run in a child process, median of R.
//
//   otparam_sampler_benchmark [--repeat R] [--contrast C] [--uniform] [N ...]
//                                                        (default N: 10000 100000)
#include "Sampling/PlanarSampler.h"
#include "Sampling/PlanarDensityField.h"
#include "ForkedRun.h"
#include "RingDisk.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

using namespace otparam;

namespace
{
struct Row
{
  double samples, runs, refinement, masses, total, peakMiB, cv, angle, capped;
};

Row runOnce(long long n, double contrast, SamplingMode mode)
{
  const testing::PlanarMesh disk = testing::makePlanarDisk(150);
  std::vector<double> g;
  for (const Vec2& p : disk.points)
    g.push_back(testing::gaussianMixture(p, contrast));
  std::string error;
  const auto field = DensityField::create(disk.points, disk.triangles, g, {}, error);
  SamplerOptions options;
  options.mode = mode;
  options.numberOfSamples = n;
  const auto t0 = std::chrono::steady_clock::now();
  const SamplerResult r = sampleDensity(*field, options);
  Row row{};
  row.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  row.samples = static_cast<double>(r.samples.size());
  row.runs = r.refinementRuns;
  row.refinement = r.secondsRefinement;
  row.masses = r.secondsMasses;
  row.peakMiB = benchmark::peakMiB();
  row.cv = r.massCoefficientOfVariation;
  row.angle = r.minimumAngleDegrees;
  row.capped = r.capped;
  return row;
}

} // namespace

int main(int argc, char** argv)
{
  int repeat = 3;
  double contrast = 1e6;
  SamplingMode mode = SamplingMode::Adaptive;
  std::vector<long long> sizes;
  for (int a = 1; a < argc; ++a)
  {
    if (!std::strcmp(argv[a], "--repeat") && a + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++a]));
    else if (!std::strcmp(argv[a], "--contrast") && a + 1 < argc)
      contrast = std::atof(argv[++a]);
    else if (!std::strcmp(argv[a], "--uniform"))
      mode = SamplingMode::Uniform;
    else
      sizes.push_back(static_cast<long long>(std::atof(argv[a])));
  }
  if (sizes.empty())
    sizes = { 10000, 100000 };
  std::printf("%s sampling of a Gaussian mixture of contrast %.0e on the unit disk, median of %d "
              "runs\n| target | samples | refinement runs | refinement s | masses s | total s | "
              "peak MiB | mass CV | smallest angle |\n|---|---|---|---|---|---|---|---|---|\n",
    mode == SamplingMode::Adaptive ? "Adaptive" : "Uniform", contrast, repeat);
  for (long long n : sizes)
  {
    std::vector<Row> rows;
    for (int k = 0; k < repeat; ++k)
    {
      Row row;
      if (benchmark::runInChild([&] { return runOnce(n, contrast, mode); }, row))
        rows.push_back(row);
    }
    if (rows.empty())
    {
      std::printf("| %lld | failed |\n", n);
      continue;
    }
    auto med = [&](double Row::*field) { return benchmark::medianOf(rows, field); };
    std::printf("| %lld | %.0f | %.0f | %.2f | %.2f | %.2f | %.0f | %.3f | %.1f%s |\n", n,
      med(&Row::samples), med(&Row::runs), med(&Row::refinement), med(&Row::masses),
      med(&Row::total), med(&Row::peakMiB), med(&Row::cv), med(&Row::angle),
      med(&Row::capped) > 0 ? " (capped)" : "");
    std::fflush(stdout);
  }
  return 0;
}
