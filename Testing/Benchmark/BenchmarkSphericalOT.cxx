// Benchmark of the spherical OT solver (sphere.md): n random Diracs on the unit sphere with
// masses log-uniform of contrast C at random (or, --bumps, a smooth four-bump density), uniform
// sphere source, tolerance 1e-10, the default start (--single-level: the Voronoi start). Each size
// runs in a child process so that its peak memory is its own; the table gives the median of the
// runs. The reference is one iteration's floor, measured in the same run: one 3D hull of the Diracs
// (the diagram's build) plus one sparse factorization of its graph Laplacian.
//
//   otparam_sphere_benchmark [--repeat R] [--contrast C] [--bumps] [--single-level] [N ...]
//   (default N: 1e4 1e5 1e6)
#include "Common/SparseCholesky.h"
#include "ForkedRun.h"
#include "Transport/SphericalOT.h"
#include "Transport/SphericalPowerDiagram.h"

#include <Eigen/Sparse>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

using namespace otparam;

namespace
{
struct Row
{
  double n, iterations, triangulation, integration, assembly, solve, total, hull, factorization,
    peakMiB, error, converged;
};

double seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Vec3> randomDiracs(size_t n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Vec3> y(n);
  for (Vec3& p : y)
  {
    p = normalized({ normal(rng), normal(rng), normal(rng) });
  }
  return y;
}

// Masses log-uniform in [1, contrast], independent of position. (A smooth density as on the
// disk, two Gaussian bumps over a floor, fails Alexandrov's condition on the sphere at this
// contrast: most of the mass in one small cap needs more than a hemisphere of source; the
// solver then reports cells reaching 90 degrees.)
std::vector<double> randomMasses(size_t n, double contrast, unsigned seed)
{
  std::mt19937 rng(seed + 1000);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> m(n);
  for (double& v : m)
  {
    v = std::pow(contrast, uniform(rng));
  }
  return m;
}

// A smooth density of contrast C: four narrow bumps at the vertices of a regular tetrahedron
// over a floor (each bump holds under a quarter of the mass, so Alexandrov's condition holds).
std::vector<double> bumpMasses(const std::vector<Vec3>& y, double contrast)
{
  const Vec3 centres[4] = { normalized({ 1, 1, 1 }), normalized({ 1, -1, -1 }),
    normalized({ -1, 1, -1 }), normalized({ -1, -1, 1 }) };
  std::vector<double> m(y.size(), 1.0 / contrast);
  for (size_t i = 0; i < y.size(); ++i)
    for (const Vec3& c : centres)
      m[i] += std::exp(-(1.0 - dot(c, y[i])) / 0.02);
  return m;
}

bool g_bumps = false, g_singleLevel = false, g_squareRootGrowth = true;

// One hull (the Voronoi diagram's build) and one factorization of its graph Laplacian with one
// Dirac pinned, timed separately.
void referenceIteration(const std::vector<Vec3>& y, Row& row)
{
  auto t0 = std::chrono::steady_clock::now();
  SphericalPowerDiagram diagram;
  diagram.build(y, std::vector<Height>(y.size()));
  row.hull = seconds(t0);
  t0 = std::chrono::steady_clock::now();
  const int n = static_cast<int>(y.size()) - 1;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i)
  {
    double diag = 1e-12;
    for (const int* j = diagram.neighborsBegin(i);
         j != diagram.neighborsBegin(i) + (diagram.ringEnd(i) - diagram.ringBegin(i)); ++j)
    {
      if (*j >= n)
        continue; // the pinned Dirac
      diag += 1.0;
      if (*j < i)
        t.emplace_back(i, *j, -1.0);
    }
    t.emplace_back(i, i, diag);
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  SparseCholesky factor;
  row.factorization = factor.compute(L) ? seconds(t0) : NAN;
}

Row runOnce(size_t n, double contrast, unsigned seed)
{
  std::vector<Vec3> y = randomDiracs(n, seed);
  const std::vector<double> m = g_bumps ? bumpMasses(y, contrast) : randomMasses(n, contrast, seed);
  Row row{};
  row.n = static_cast<double>(n);
  referenceIteration(y, row);
  const auto t0 = std::chrono::steady_clock::now();
  OTOptions options;
  options.coarseToFineStart = !g_singleLevel;
  options.squareRootGrowth = g_squareRootGrowth;
  const SphericalOTResult r = solveSphericalOT(y, m, options);
  row.total = seconds(t0);
  row.iterations = r.iterations;
  row.triangulation = r.secondsTriangulation;
  row.integration = r.secondsIntegration;
  row.assembly = r.secondsAssembly;
  row.solve = r.secondsSolve;
  row.error = r.relativeError;
  row.converged = r.converged;
  if (!r.converged)
    std::fprintf(stderr, "n = %zu, seed %u: %s\n", n, seed, r.message.c_str());
  row.peakMiB = benchmark::peakMiB();
  return row;
}
} // namespace

int main(int argc, char** argv)
{
  int repeat = 3;
  double contrast = 1e4;
  std::vector<size_t> sizes;
  for (int a = 1; a < argc; ++a)
  {
    if (!std::strcmp(argv[a], "--repeat") && a + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++a]));
    else if (!std::strcmp(argv[a], "--contrast") && a + 1 < argc)
      contrast = std::atof(argv[++a]);
    else if (!std::strcmp(argv[a], "--bumps"))
      g_bumps = true;
    else if (!std::strcmp(argv[a], "--single-level"))
      g_singleLevel = true;
    else if (!std::strcmp(argv[a], "--linear-growth"))
      g_squareRootGrowth = false;
    else if (argv[a][0] != '-' && std::atof(argv[a]) >= 4.0)
      sizes.push_back(static_cast<size_t>(std::atof(argv[a])));
    else
    {
      std::fprintf(stderr,
        "usage: %s [--repeat R] [--contrast C] [--bumps] [--single-level] [--linear-growth] [N "
        "...]\n",
        argv[0]);
      return 2;
    }
  }
  if (sizes.empty())
    sizes = { 10000, 100000, 1000000 };
  std::printf("Spherical OT, uniform sphere -> n random Diracs, %s of contrast %.0e, tolerance "
              "1e-10, %s start; median of %d runs (seeds 1..%d)\n",
    g_bumps ? "four-bump smooth masses" : "log-uniform random masses", contrast,
    g_singleLevel ? "Voronoi" : "default (coarse-to-fine where it pays)", repeat, repeat);
  std::printf("| n | Newton its | hull s | integration s | assembly s | solve s | total s | "
              "s / iteration | 1 hull + 1 factorization s | ratio | peak MiB | rel. error | "
              "converged |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (size_t n : sizes)
  {
    std::vector<Row> rows;
    for (int k = 0; k < repeat; ++k)
    {
      Row row;
      if (benchmark::runInChild(
            [&] { return runOnce(n, contrast, static_cast<unsigned>(k + 1)); }, row))
        rows.push_back(row);
    }
    if (rows.empty())
    {
      std::printf("| %zu | failed |\n", n);
      continue;
    }
    auto med = [&](double Row::*field) { return benchmark::medianOf(rows, field); };
    const double its = med(&Row::iterations), total = med(&Row::total);
    const double perIteration = total / std::max(1.0, its);
    const double reference = med(&Row::hull) + med(&Row::factorization);
    std::printf("| %zu | %.0f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f + %.3f | %.1f | "
                "%.0f | %.1e | %d/%zu |\n",
      n, its, med(&Row::triangulation), med(&Row::integration), med(&Row::assembly),
      med(&Row::solve), total, perIteration, med(&Row::hull), med(&Row::factorization),
      perIteration / reference, med(&Row::peakMiB), med(&Row::error),
      static_cast<int>(
        std::count_if(rows.begin(), rows.end(), [](const Row& r) { return r.converged > 0; })),
      rows.size());
    std::fflush(stdout);
  }
  return 0;
}
