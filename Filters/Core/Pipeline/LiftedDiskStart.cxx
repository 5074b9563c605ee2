#include "Pipeline/LiftedDiskStart.h"

#include "Common/SphericalGeometry.h"
#include "Conformal/TutteEmbedding.h"
#include "Mesh/DiskPatch.h"
#include "Mesh/Folds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace otparam
{

namespace
{
// The triangles outside the patch as a soup of the points they use; `meshPoint` gets each
// soup point's mesh point.
TriangleSoup restOfSurface(
  const SurfaceMesh& mesh, const std::vector<char>& inPatch, std::vector<int>& meshPoint)
{
  TriangleSoup rest;
  std::vector<std::int64_t> id(mesh.points.size(), -1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    if (inPatch[t])
    {
      continue;
    }
    std::array<std::int64_t, 3> corners{};
    for (int k = 0; k < 3; ++k)
    {
      const int v = mesh.triangles[t][k];
      if (id[v] < 0)
      {
        id[v] = static_cast<std::int64_t>(rest.points.size());
        rest.points.push_back(mesh.points[v]);
        meshPoint.push_back(v);
      }
      corners[k] = id[v];
    }
    rest.triangles.push_back(corners);
  }
  return rest;
}

// Lambert's lift of the patch's disk onto the cap around the south pole holding `share`: the
// north cap's lift turned by half a turn about the x axis (which mirrors the disk's angles:
// the patch's disk holds its boundary at -phi where the rest's has it at phi). The patch is a
// wide part of the surface, whose triangles are not thin: bent, they usually stay positive
// (liftBothDisks checks).
Vec3 liftToSouthCap(Vec2 w, double share)
{
  const Vec3 north = liftDiskToCap(w, share);
  return { north.x, -north.y, -north.z };
}

// The rest's disk map (`disk`, whose points are the mesh's `meshPoint`) and the patch's, each
// point lifted onto the sphere from its own disk into start.sphere. "" or what went wrong.
std::string liftBothDisks(const SurfaceMesh& mesh, const std::vector<char>& inPatch,
  const AreaPreservingResult& disk, const std::vector<int>& meshPoint, LiftedDiskStart& start)
{
  std::vector<Vec2> restUv(mesh.points.size()), patchUv(mesh.points.size());
  std::vector<char> onRest(mesh.points.size(), 0);
  for (size_t i = 0; i < disk.composition.uv.size(); ++i)
  {
    const int v = meshPoint[disk.conformal.surface.originalPointIds[i]];
    restUv[v] = disk.composition.uv[i];
    // The patch runs the other way round the boundary: in its own orientation its disk is
    // the mirror image.
    patchUv[v] = { restUv[v].x, -restUv[v].y };
    onRest[v] = 1;
  }
  std::vector<Triangle> patchTriangles;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    if (inPatch[t])
    {
      patchTriangles.push_back(mesh.triangles[t]);
    }
  }
  const std::string error = tutteEmbedding(patchTriangles, onRest, patchUv);
  if (!error.empty())
  {
    return "the patch's embedding failed: " + error;
  }
  // The rest's disk by the gnomonic projection (x, y, 1) / |(x, y, 1)|, which takes straight
  // lines to great circles, so no triangle folds: Lambert's equal-area projection bends them,
  // and the long thin triangles of an area-preserving map of a protrusion (its rings, up to
  // 2 L / rho times longer than wide) folded in its lift (the closed finger at L / rho = 64:
  // 1017 triangles; untangled, 1401). It is not equal-area, so the rest's disk is scaled to the
  // cap of its share where the hemisphere allows (else to GnomonicLargestShare of the sphere),
  // and the last transport moves the difference.
  const double northShare = std::min(1.0 - start.patchShare, GnomonicLargestShare);
  const double radius = std::tan(std::acos(1.0 - 2.0 * northShare)); // the cap's, in the plane
  start.sphere.resize(mesh.points.size());
  for (size_t v = 0; v < mesh.points.size(); ++v)
  {
    start.sphere[v] = onRest[v]
      ? normalized(Vec3{ radius * restUv[v].x, radius * restUv[v].y, 1.0 })
      : liftToSouthCap(patchUv[v], 1.0 - northShare);
  }
  if (anyFolded(start.sphere, mesh.triangles))
  {
    start.sphere.clear();
    return "its lift onto the sphere folds";
  }
  return "";
}
} // namespace

LiftedDiskStart liftedDiskStart(const AreaPreservingOptions& options, const SurfaceMesh& mesh)
{
  LiftedDiskStart start;
  // The disk runs report nothing, only ask whether to go on (at the sphere run's sampling stage,
  // which starts at 0.15 of its progress).
  // The disk's normalization points name ids of the user's disk surface, not of this one.
  AreaPreservingOptions diskOptions = options;
  diskOptions.progress = [&options](const char*, double)
  { return !options.progress || options.progress("sampling", 0.15); };
  diskOptions.conformal.centerPointId = -1;
  diskOptions.conformal.alignPointId = -1;
  // The largest body patch whose rest the disk pipeline maps and whose lift does not fold (on
  // the closed finger at L / rho = 64 a patch of 45% mapped, one of 32% did not).
  for (const double share : LiftedPatchShares)
  {
    const std::vector<char> inPatch = bodyPatch(mesh, share, start.patchCentre);
    if (inPatch.empty())
    {
      start.error = "no disk-shaped patch of its body holds " +
        std::to_string(static_cast<int>(100.0 * share)) + "% of its area";
      continue;
    }
    std::vector<int> meshPoint;
    const AreaPreservingResult disk =
      parameterizeDisk(restOfSurface(mesh, inPatch, meshPoint), diskOptions);
    if (disk.status.aborted)
    {
      start.aborted = true;
      start.error.clear();
      return start;
    }
    double patchArea = 0.0, totalArea = 0.0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
    {
      const double area = triangleArea(mesh, mesh.triangles[t]);
      totalArea += area;
      patchArea += inPatch[t] ? area : 0.0;
    }
    start.patchShare = patchArea / totalArea;
    start.diskStages = disk.transportStages;
    start.error =
      disk.status.ok() ? liftBothDisks(mesh, inPatch, disk, meshPoint, start) : disk.status.error;
    if (start.error.empty())
    {
      break;
    }
  }
  return start;
}

} // namespace otparam
