// Semi-discrete optimal transport on the unit sphere (sphere.md): from the uniform measure on
// S^2 to Diracs y_i with masses nu_i, cost -log <x, y>. The variables are the log-heights
// psi_i of the spherical power diagram (SphericalPowerDiagram.h); the damped Newton iteration
// is the plane's (DampedNewton.h).
#ifndef OTPARAM_TRANSPORT_SPHERICALOT_H
#define OTPARAM_TRANSPORT_SPHERICALOT_H

#include "Common/Geometry.h"
#include "Transport/SemiDiscreteOT.h"

#include <string>
#include <vector>

namespace otparam
{

struct SphericalOTResult : NewtonReport
{
  std::vector<double> mass;             // target masses after rescaling to 4 pi
  std::vector<double> heights;          // psi_i = log h_i, the gauge fixed by mean 0
  std::vector<double> cellMass;         // achieved cell areas
  std::vector<Vec3> centroids;          // centroid of each cell pushed onto the sphere
  double largestTransportDegrees = 0.0; // largest angle between a Dirac and a point of its cell
};

// Validates Diracs (finite, on the unit sphere to 1e-6, distinct after normalization, not all
// in one closed hemisphere) and masses (finite, positive): "" or a message naming the ids.
// The Diracs are normalized in place.
std::string validateSphericalDiracs(std::vector<Vec3>& diracs, const std::vector<double>& masses);

// Solves for log-heights psi such that every cell W_i has area masses[i] (rescaled to 4 pi).
// Options as on the plane: the start is the spherical Voronoi diagram, or, for many Diracs, a
// coarse-to-fine start (MultiscaleStart.h). The Diracs must have passed validateSphericalDiracs.
SphericalOTResult solveSphericalOT(const std::vector<Vec3>& diracs,
  const std::vector<double>& masses, const OTOptions& options = OTOptions());

// Cell areas, centroids (on the sphere) and Hessian couplings at given log-heights, for tests.
struct SphericalCellMeasures
{
  std::vector<double> area;
  std::vector<Vec3> centroid;
  std::vector<double> coupling; // dense n x n, row-major: d area_i / d psi_j for i != j
};
SphericalCellMeasures computeSphericalCellMeasures(
  const std::vector<Vec3>& diracs, const std::vector<double>& psi, bool denseCouplings = false);

// Geometry of the diagram for display and for the VTK outputs.
struct SphericalPowerDiagramGeometry
{
  std::vector<std::vector<Vec3>> cells;        // cell boundaries on the sphere (arcs sampled), CCW
  std::vector<int> cellDirac;                  // Dirac of each entry of cells
  std::vector<Triangle> triangles;             // the dual hull's triangles (Dirac ids)
  std::vector<Vec3> polytopeVertices;          // vertices of Q(h), one per triangle
  std::vector<std::vector<int>> polytopeFaces; // facet of Q(h) of each Dirac (vertex ids), CCW
  std::vector<int> polytopeFaceDirac;
  std::vector<Vec3> hullPoints; // p_i = y_i / h_i (hidden Diracs included)
};
SphericalPowerDiagramGeometry computeSphericalPowerDiagramGeometry(const std::vector<Vec3>& diracs,
  const std::vector<double>& psi, double maxArcAngle = DefaultMaximumArcAngle);

} // namespace otparam

#endif
