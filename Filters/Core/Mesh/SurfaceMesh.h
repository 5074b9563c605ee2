// Triangle surfaces and the checks that make a surface a topological disk.
#ifndef OTPARAM_MESH_SURFACEMESH_H
#define OTPARAM_MESH_SURFACEMESH_H

#include "Common/Geometry.h"

#include <cstdint>
#include <string>
#include <vector>

namespace otparam
{

struct SurfaceMesh
{
  std::vector<Vec3> points;
  std::vector<Triangle> triangles;
};

// A triangle surface as files and VTK hold it: any point ids, possibly unreferenced points.
struct TriangleSoup
{
  std::vector<Vec3> points;
  std::vector<std::array<std::int64_t, 3>> triangles;
};

// The referenced part of a triangle soup: points used by no triangle are dropped.
struct CompactedMesh
{
  SurfaceMesh mesh;
  std::vector<std::int64_t> originalPointIds; // mesh.points[i] == input point originalPointIds[i]
  std::int64_t unreferencedPoints = 0;
};

// Fails (returns a message) on triangles that use a point id outside [0, numberOfPoints) or
// the same point twice.
std::string compactMesh(const std::vector<Vec3>& points,
  const std::vector<std::array<std::int64_t, 3>>& triangles, CompactedMesh& result);

// What a manifold, consistently oriented triangle surface is made of.
struct SurfaceTopology
{
  size_t components = 0;
  std::vector<std::vector<int>> boundaryLoops; // each in the triangles' orientation
  long long eulerCharacteristic = 0;
  // Points at exactly the coordinates of another point, counted when there is more than one
  // component: triangles that touch without sharing their points (an unmerged soup).
  size_t coincidentPoints = 0;
};

// Per entry of `ids`: whether another entry names a point at exactly the same coordinates (the
// points of a triangle soup, or of a seam whose two sides do not share them).
std::vector<char> coincidentAmong(const std::vector<Vec3>& points, const std::vector<int>& ids);

// Checks what every surface the pipelines take must be (finite coordinates, no degenerate
// triangles, manifold and consistently oriented, no unreferenced point) and, when it is,
// reports its components, boundary loops and Euler characteristic; "" or the message (ids
// mapped through `reportedIds` when given). The disk, the sphere and the surface with holes
// each judge the topology in their own check.
std::string analyzeSurface(const SurfaceMesh& mesh, SurfaceTopology& topology,
  const std::vector<std::int64_t>* reportedIds = nullptr);

// A disk: finite coordinates, no degenerate triangles, manifold and consistently oriented,
// connected, exactly one boundary loop, Euler characteristic 1. Returns "" when it is one
// (and its boundary loop, in the direction of the triangles' orientation), else a message that
// says what is wrong and where (ids are those of `mesh`).
// `reportedIds` (optional) maps mesh point ids to the ids the messages should name.
std::string checkDiskTopology(const SurfaceMesh& mesh, std::vector<int>& boundaryLoop,
  const std::vector<std::int64_t>* reportedIds = nullptr);

// checkDiskTopology's judgement of a surface analyzeSurface has passed (its boundary loop
// moved into `boundaryLoop`): a pipeline that analyzed its input once tells problems of the mesh
// from problems of its topology.
std::string diskTopologyError(SurfaceTopology& topology, std::vector<int>& boundaryLoop);

// A closed surface of genus 0, the sphere's domain (sphere.md): what analyzeSurface checks,
// connected, no boundary loop, Euler characteristic 2. Returns "" when it is one, else a
// message that says what is wrong (the number of components, boundary loops or the genus).
std::string checkSphereTopology(
  const SurfaceMesh& mesh, const std::vector<std::int64_t>* reportedIds = nullptr);

// checkSphereTopology's judgement of a surface analyzeSurface has passed.
std::string sphereTopologyError(const SurfaceTopology& topology);

double triangleArea(const SurfaceMesh& mesh, const Triangle& t);

} // namespace otparam

#endif
