// Real scans have holes: a genus-0 surface with several boundary loops is made a disk for the
// computation by closing every loop but the longest (the one that becomes the circle), and a
// closed surface with small holes (an organ scan) is closed for the sphere.
#ifndef OTPARAM_MESH_HOLEFILLING_H
#define OTPARAM_MESH_HOLEFILLING_H

#include "Mesh/SurfaceMesh.h"

#include <string>
#include <vector>

namespace otparam
{

struct FilledSurface
{
  // The input's points and triangles first, in their order, then the fill's: the input part
  // of any per-point or per-triangle result is its leading part.
  SurfaceMesh mesh;
  std::vector<int> boundaryLoop; // fillHolesButLongest's kept loop, in the triangles' orientation
  int filledHoles = 0;
  double fillAreaFraction = 0.0; // the fill's share of the filled surface's area
};

// The messages below name points by `reportedIds[v]` when given (the input's ids of a mesh
// compacted of its unreferenced points), else by their index.

// "" or the first loop but loops[kept] that is a slit rather than a hole (most of its points
// exactly on other boundary points: a seam whose points are not shared), with what to do.
// fillHoles checks it first.
std::string slitAmongHoles(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops,
  std::size_t kept, const std::vector<std::int64_t>* reportedIds = nullptr);

// Index of the longest loop by surface (3D) length.
std::size_t longestLoop(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops);

// The area of a round disk with the longest loop's length, as a fraction of the surface's area:
// how much of the surface the largest hole would cover (0 without loops). Not the fill's own
// area, which needs the fill: a saddle-shaped loop spans little vector area (bust_aphrodite_56k:
// 0.0) but a real hole (0.36 by this measure).
double largestHoleFraction(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops);

// `mesh` must be a connected, manifold, oriented surface of genus 0 with the boundary loops
// `loops` (as analyzeSurface reports them). Closes every loop but the longest with CGAL's
// hole filling (triangulate, refine to the rim's edge lengths, fair), and returns "" or a
// message naming the hole that could not be closed.
std::string fillHolesButLongest(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops,
  FilledSurface& filled, const std::vector<std::int64_t>* reportedIds = nullptr);

// The same closing every loop but loops[kept] (kept >= loops.size(): every loop, which makes a
// genus-0 surface closed).
std::string fillHoles(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops,
  std::size_t kept, FilledSurface& filled, const std::vector<std::int64_t>* reportedIds = nullptr);

} // namespace otparam

#endif
