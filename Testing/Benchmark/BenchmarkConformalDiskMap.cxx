// Benchmark of the conformal disk map on the shared meshes: seconds per stage (median of the
// runs), accuracy, and the reference systems' seconds from reference-figures.md.
//
//   otparam_conformal_benchmark [--repeat R] [mesh ...]   (default: every shared mesh)
#include "Conformal/ConformalDiskMap.h"
#include "ForkedRun.h"
#include "MeshFiles.h"
#include "Mesh/DistortionMetrics.h"
#include "Mesh/SurfaceMesh.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace otparam;
using otparam::benchmark::median;

namespace
{
double seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Reference
{
  const char* mesh;
  double cgalSeconds, bffSeconds, fdcpSeconds;
};

// reference-figures.md: CGAL DCM, BFF (CHOLMOD) and Choi-Lui FDCP (Octave), one core.
const Reference References[] = {
  { "hand_stein_810.obj", 0.00, 0.007, 0.09 },
  { "hemisphere_2k.obj", 0.02, 0.013, 0.17 },
  { "face_dense_gpp_5k.obj", 0.04, 0.033, 0.64 },
  { "face_choi_bff_17k.obj", 0.21, 0.16, 2.07 },
  { "chinese_lion_17k.off", 0.28, 0.14, 1.96 },
  { "ogre_face_20k.obj", 0.27, 0.15, 2.21 },
  { "face_maxplanck_partial_32k.obj", 0.52, 0.33, 5.47 },
  { "brain_cortex_cut_48k.off", 1.35, 0.54, 7.16 },
  { "hand_choi_53k.off", 1.92, 0.69, 6.75 },
  { "bust_aphrodite_56k.obj", -1, -1, -1 },
};
} // namespace

int main(int argc, char** argv)
{
  int repeat = 5;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (argv[i][0] == '-')
    {
      std::fprintf(stderr,
        "unknown option %s\nusage: otparam_conformal_benchmark [--repeat R] [mesh ...]\n", argv[i]);
      return 2;
    }
    else
      meshes.push_back(argv[i]);
  }
  if (meshes.empty())
    for (const auto& r : References)
      meshes.push_back(r.mesh);

  std::printf("Conformal disk map, median of %d runs (seconds; check = topology checks,\n"
              "factor = Laplacian assembly + Cholesky factorization(s), iterate = boundary\n"
              "angles + Moebius normalization, metrics = distortion figures + AreaDensity)\n\n",
    repeat);
  std::printf(
    "| mesh | vertices | check | factor | iterate | metrics | total | its | angle | K "
    "| flips | CGAL DCM s | BFF s | FDCP s |\n|---|---|---|---|---|---|---|---|---|---|---|"
    "---|---|---|\n");
  for (const auto& name : meshes)
  {
    SurfaceMesh mesh;
    if (!testing::readOrReport(testing::sharedMesh(name), testing::readMesh, mesh))
    {
      return 2;
    }
    std::vector<double> check, factor, iterate, metrics, total;
    ConformalDiskMapResult map;
    DistortionFigures figures;
    for (int r = 0; r < repeat; ++r)
    {
      auto t0 = std::chrono::steady_clock::now();
      std::vector<int> loop;
      const std::string error = checkDiskTopology(mesh, loop);
      check.push_back(seconds(t0));
      if (!error.empty())
      {
        std::printf("%s: %s\n", name.c_str(), error.c_str());
        return 1;
      }
      map = computeConformalDiskMap(mesh, loop);
      auto t1 = std::chrono::steady_clock::now();
      figures = measureDistortion(mesh, map.uv);
      std::vector<double> perTriangle, perPoint;
      computeAreaDensity(mesh, map.uv, perTriangle, perPoint);
      metrics.push_back(seconds(t1));
      factor.push_back(map.secondsFactorization);
      iterate.push_back(map.secondsIterations);
      total.push_back(seconds(t0));
    }
    const Reference* ref = nullptr;
    for (const auto& r : References)
      if (name == r.mesh)
        ref = &r;
    std::printf("| %s | %zu | %.3f | %.3f | %.3f | %.3f | %.3f | %d | %.3f | %.4f | %lld |",
      name.c_str(), mesh.points.size(), median(check), median(factor), median(iterate),
      median(metrics), median(total), map.iterations, figures.meanAngleDistortionDegrees,
      figures.meanDilatation, static_cast<long long>(figures.flippedTriangles));
    if (ref && ref->cgalSeconds >= 0)
      std::printf(" %.2f | %.3f | %.2f |\n", ref->cgalSeconds, ref->bffSeconds, ref->fdcpSeconds);
    else
      std::printf(" - | - | - |\n");
    std::fflush(stdout);
  }
  return 0;
}
