// The conformal disk map written in polar form around one interior vertex, from the surface's
// Green's function with its pole there. A long protrusion (a finger, a limb) shrinks in the
// conformal image like exp(-L / r) towards its tip; the usual map's Cartesian coordinates come
// from linear solves whose errors are absolute (~1e-17), so beyond L / r ~ 40 its images
// collapse and fold wherever the tip lands (TestCrowding's finger at L / r = 100: 4692
// triangles folded). With the tip at the origin and the radius computed as exp(-2 pi G), G the
// Dirichlet Green's function (a few units, known to ~1e-15), each image keeps relative
// precision down to the smallest doubles: the same finger, 100 radii long, has no fold and its
// tip ring at 4e-44; at 300 radii, 1e-131.
#ifndef OTPARAM_CONFORMAL_GREENDISKMAP_H
#define OTPARAM_CONFORMAL_GREENDISKMAP_H

#include "Common/Status.h"
#include "Mesh/SurfaceMesh.h"

#include <vector>

namespace otparam
{

struct GreenDiskMap
{
  Status status;
  std::vector<Vec2> uv; // per mesh point; the centre at (0, 0), the boundary on the unit circle
  int centerVertex = -1;
};

// The conformal map phi of a disk-like surface onto the unit disk with phi(centre) = 0 and the
// boundary vertex `alignVertex` at angle 0: log |phi| = -2 pi G and arg phi = -2 pi G*, with G
// the discrete Green's function of the surface's intrinsic Delaunay cotangent Laplacian (pole
// at the centre, 0 on the boundary) and G* its discrete harmonic conjugate, constant on each
// triangle (the cotangent weights' Cauchy-Riemann relation: G* changes across an edge by the
// edge's weight times G's change along it; around the pole it turns by exactly one period).
// centre -1: the most secluded interior vertex, where the expected exit time of a random walk
// (the torsion function, L tau = vertex areas) is largest: the tip of the longest protrusion.
// `boundaryLoop` as checkDiskTopology returns it.
GreenDiskMap computeGreenDiskMap(const SurfaceMesh& mesh, const std::vector<int>& boundaryLoop,
  int centerVertex = -1, int alignVertex = -1);

} // namespace otparam

#endif
