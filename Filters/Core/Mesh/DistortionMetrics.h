// How far a disk parameterization of a surface is from conformal and from area-preserving,
// per triangle and in summary, with the definitions of ../shared/docs/reference-figures.md
// (both the surface and the disk image scaled to the same total area).
#ifndef OTPARAM_MESH_DISTORTIONMETRICS_H
#define OTPARAM_MESH_DISTORTIONMETRICS_H

#include "Mesh/SurfaceMesh.h"

namespace otparam
{

struct DistortionFigures
{
  std::int64_t flippedTriangles = 0;       // signed disk area <= 0
  double meanAngleDistortionDegrees = 0.0; // mean over corners of |disk angle - surface angle|
  double maximumAngleDistortionDegrees = 0.0;
  double meanDilatation = 0.0; // area-weighted mean of sigma_max / sigma_min
  double maximumDilatation = 0.0;
  double meanAbsLogAreaRatio = 0.0; // area-weighted mean of |log(disk / surface area fraction)|
  double maximumAbsLogAreaRatio = 0.0;

  // Per triangle.
  std::vector<double> angleDistortion; // mean |log(disk corner angle / surface corner angle)|
  std::vector<double> dilatation;
  std::vector<double> logAreaRatio; // log(disk area fraction / surface area fraction)
};

DistortionFigures measureDistortion(const SurfaceMesh& surface, const std::vector<Vec2>& uv);

// Surface area element over disk area element after scaling the surface to total area pi:
// per triangle (the exact ratio of the two areas) and per point (ratio of the areas of the
// triangles around it). Flipped or collapsed disk triangles get the largest finite ratio.
void computeAreaDensity(const SurfaceMesh& surface, const std::vector<Vec2>& uv,
  std::vector<double>& perTriangle, std::vector<double>& perPoint);

// The same figures for a map onto the unit sphere (sphere.md), as param_metrics.py --sphere
// scores it: `sphere` holds a point per surface point (normalized before use); area fractions
// are spherical triangle areas over 4 pi, angles and dilatations those of the image's straight
// (chordal) triangles, a flip is a triangle clockwise seen from outside (det(a, b, c) <= 0).
DistortionFigures measureSphereDistortion(
  const SurfaceMesh& surface, const std::vector<Vec3>& sphere);

// Surface area element over spherical area element after scaling the surface to total area
// 4 pi: per triangle (surface area / spherical triangle area, exact) and per point (ratio of
// the areas of the triangles around it). Flipped or collapsed triangles get the largest finite
// ratio. Over non-flipped images, sum of perTriangle * spherical area = 4 pi.
void computeSphereAreaDensity(const SurfaceMesh& surface, const std::vector<Vec3>& sphere,
  std::vector<double>& perTriangle, std::vector<double>& perPoint);

// Beyond this range (largest over smallest) of a map's area density, the map crowds part of the
// surface (a long protrusion, where the density grows like exp(2 L / r)) past what one transport
// resolves (the pipeline transports in stages), and a fold there is double precision's, not a
// coarse mesh's.
constexpr double CrowdedDensityRange = 1e12;

// The largest over the smallest of a density's values (1 for none).
double rangeOf(const std::vector<double>& density);

// The densities below which lie the given shares of the surface: triangles taken by increasing
// `density` (one value per triangle of `surface`), each weighing its area on the surface;
// `shares` increasing.
std::vector<double> densitiesAtAreaShares(const SurfaceMesh& surface,
  const std::vector<double>& density, const std::vector<double>& shares);

// The share of the surface, at its least dense end, that the crowding measures leave out: a
// triangle that holds next to nothing of the surface can set the density's range by itself (a
// sliver of a marching-cubes mesh, tiny on the surface but not in the map, lies 1e5 below the
// rest; a stage's composition can leave such triangles too). Measured on procedural quadrupeds
// (docs/design.md, "Crowding by the bulk of the surface").
constexpr double CrowdingLowShare = 0.01;

// How far a map crowds the surface: its largest density over its density at `lowShare`
// (CrowdingLowShare; 0: the smallest) of the surface's area. That is never above rangeOf,
// which is returned where it is within CrowdedDensityRange (no sort).
double crowdingRange(const SurfaceMesh& surface, const std::vector<double>& density,
  double lowShare = CrowdingLowShare);

} // namespace otparam

#endif
