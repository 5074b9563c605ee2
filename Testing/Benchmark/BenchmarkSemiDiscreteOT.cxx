// Benchmark of the semi-discrete OT solver: n random Diracs in the unit disk with
// Gaussian-mixture masses, uniform disk source, tolerance 1e-10. Each size runs in a child
// process so that its peak memory is its own; the table gives the median of the runs.
//
//   otparam_benchmark [--repeat R] [--contrast C] [--single-level] [--linear-growth] [N ...]
//                                                   (default N: 1000 10000 100000)
#include "Common/SparseCholesky.h"
#include "ForkedRun.h"
#include "OTTestProblems.h"
#include "Transport/PlanarPowerDiagram.h"
#include "Transport/SemiDiscreteOT.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace otparam;

namespace
{
struct Row
{
  double n, iterations, triangulation, integration, assembly, solve, total, reference,
    solversReference, peakMiB, error, converged;
};

double seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Vec2> g_y;
bool g_coarseToFine = true, g_squareRootGrowth = true;
std::vector<double> g_m;

void makeProblem(size_t n, double contrast, unsigned seed)
{
  g_y = testing::randomInDisk(n, seed);
  g_m = testing::mixtureMasses(g_y, contrast);
}

// The floor for one Newton iteration: one regular triangulation plus one sparse factorization
// of its graph Laplacian. `simplicial`: Eigen's SimplicialLDLT, as the speed issue measured it
// (the solver's factorization below 2e5 Diracs); `solvers`: SparseCholesky, the solver's own at
// every size (CHOLMOD from 2e5 Diracs: 3x faster than the simplicial one at 1e6).
void referenceIteration(double& simplicial, double& solvers)
{
  auto t0 = std::chrono::steady_clock::now();
  const int n = static_cast<int>(g_y.size()) - 1;
  Eigen::SparseMatrix<double> L(n, n);
  {
    // The diagram and the triplets die before the factorizations: the peak memory column is
    // the solver's.
    std::vector<Height> h(g_y.size());
    for (size_t i = 0; i < g_y.size(); ++i)
      h[i] = 0.5L * dot(g_y[i], g_y[i]);
    PowerDiagram diagram;
    diagram.build(g_y, h);
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i)
    {
      double diag = 1e-12;
      for (const int* j = diagram.neighborsBegin(i); j != diagram.neighborsEnd(i); ++j)
      {
        if (*j < 0 || *j >= n)
          continue; // the infinite vertex, or the pinned Dirac
        diag += 1.0;
        if (*j < i)
          t.emplace_back(i, *j, -1.0);
      }
      t.emplace_back(i, i, diag);
    }
    L.setFromTriplets(t.begin(), t.end());
  }
  const double triangulation = seconds(t0);
  t0 = std::chrono::steady_clock::now();
  {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt(L);
    simplicial = ldlt.info() == Eigen::Success ? triangulation + seconds(t0) : NAN;
  }
  t0 = std::chrono::steady_clock::now();
  SparseCholesky factor;
  solvers = factor.compute(L) ? triangulation + seconds(t0) : NAN;
}

Row runOnce(size_t n, double contrast, unsigned seed)
{
  makeProblem(n, contrast, seed);
  Row row{};
  row.n = static_cast<double>(n);
  referenceIteration(row.reference, row.solversReference);
  auto disk = makeUnitDiskSource();
  const auto t0 = std::chrono::steady_clock::now();
  OTOptions options;
  options.coarseToFineStart = g_coarseToFine;
  options.squareRootGrowth = g_squareRootGrowth;
  const OTResult r = solveSemiDiscreteOT(*disk, g_y, g_m, options);
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
    else if (!std::strcmp(argv[a], "--single-level"))
      g_coarseToFine = false; // the start from the shrunk Voronoi diagram, for comparison
    else if (!std::strcmp(argv[a], "--linear-growth"))
      g_squareRootGrowth = false; // Newton's rows of mass for every cell, for comparison
    else if (!std::strcmp(argv[a], "--contrast") && a + 1 < argc)
      contrast = std::atof(argv[++a]);
    else if (argv[a][0] != '-' && std::atof(argv[a]) >= 1.0)
      sizes.push_back(static_cast<size_t>(std::atof(argv[a])));
    else
    {
      std::fprintf(stderr,
        "usage: %s [--repeat R] [--contrast C] [--single-level] [--linear-growth] [N ...]\n",
        argv[0]);
      return 2;
    }
  }
  if (sizes.empty())
    sizes = { 1000, 10000, 100000 };

  std::printf("Semi-discrete OT, uniform unit disk -> n random Diracs, Gaussian-mixture masses of "
              "contrast %.0e, tolerance 1e-10, %s start; median of %d runs (seeds 1..%d; peak MiB: "
              "the largest)\n",
    contrast, g_coarseToFine ? "coarse-to-fine" : "single-level (shrunk Voronoi)", repeat, repeat);
  std::printf(
    "(1 RT + 1 factorization: one regular triangulation of the Diracs and one factorization "
    "of its graph Laplacian, by Eigen's simplicial LDL^T as the speed issue measured it, "
    "and by the solver's own SparseCholesky, CHOLMOD from 2e5 Diracs; ratio: s / "
    "iteration over the first; total / floor: the total over each)\n");
  std::printf("| n | Newton its | triangulation s | integration s | assembly s | solve s | total s "
              "| s / iteration | 1 RT + 1 factorization s | ratio | the solver's factorization: "
              "1 RT + 1 factorization s | total / floor | total / the solver's floor | peak MiB | "
              "rel. error | converged |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
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
    const double perIteration = total / std::max(1.0, its), ref = med(&Row::reference);
    const double solversRef = med(&Row::solversReference);
    // A memory bound is about the worst run.
    const double peak = std::max_element(rows.begin(), rows.end(), [](const Row& a, const Row& b)
      { return a.peakMiB < b.peakMiB; })->peakMiB;
    std::printf("| %zu | %.0f | %.3f | %.3f | %.3f | %.3f | %.3f | %.4f | %.4f | %.1f | %.4f | "
                "%.2f | %.2f | %.0f | %.1e | %d/%zu |\n",
      n, its, med(&Row::triangulation), med(&Row::integration), med(&Row::assembly),
      med(&Row::solve), total, perIteration, ref, perIteration / ref, solversRef, total / ref,
      total / solversRef, peak, med(&Row::error),
      static_cast<int>(
        std::count_if(rows.begin(), rows.end(), [](const Row& r) { return r.converged > 0; })),
      rows.size());
    std::fflush(stdout);
  }

  std::printf(
    "\nRadial ground truth (uniform disk -> density (1 + 3 r^2), equal masses on a "
    "sunflower): RMS error of the cell centroids' radii against the analytic inverse map\n"
    "| n | Newton its | seconds | rel. error | RMS centroid radius error |\n"
    "|---|---|---|---|---|\n");
  for (size_t n : sizes)
  {
    const testing::RadialProblem p = testing::radialProblem(static_cast<int>(n));
    auto disk = makeUnitDiskSource();
    const auto t0 = std::chrono::steady_clock::now();
    const OTResult r = solveSemiDiscreteOT(*disk, p.diracs, p.masses);
    std::printf("| %zu | %d | %.3f | %.1e | %.2e |\n", n, r.iterations, seconds(t0),
      r.relativeError, testing::rmsRadiusError(p, r.centroids));
    std::fflush(stdout);
  }
  return 0;
}
