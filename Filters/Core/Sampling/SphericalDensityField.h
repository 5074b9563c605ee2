// A piecewise-constant density on the unit sphere: a closed triangle mesh whose points lie on
// the sphere (triangles counter-clockwise seen from outside, covering the sphere once), one
// value g > 0 per spherical triangle. Point queries by walking the mesh, and exact integrals of
// powers of g (and of x g dA) over convex spherical polygons.
#ifndef OTPARAM_SAMPLING_SPHERICALDENSITYFIELD_H
#define OTPARAM_SAMPLING_SPHERICALDENSITYFIELD_H

#include "Common/Geometry.h"

#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace otparam
{

class SphericalDensityField
{
public:
  // Points within 1e-9 of the unit sphere (they are normalized), triangles with valid ids,
  // each edge shared by exactly two triangles in opposite directions, every spherical triangle
  // counter-clockwise and their areas summing to 4 pi (the mesh covers the sphere once), one
  // finite value > 0 per triangle. Returns nullptr and sets error otherwise (the message names
  // the offending ids).
  static std::unique_ptr<SphericalDensityField> create(const std::vector<Vec3>& points,
    const std::vector<Triangle>& triangles, const std::vector<double>& perTriangle,
    std::string& error);

  // The triangle containing the direction x (unit), walking from `hint` when it is a triangle
  // id (a nearby one makes this O(1)), else from a cube-map table of starting triangles.
  int locate(Vec3 x, int hint = -1) const;
  double value(Vec3 x, int hint = -1) const { return PerTriangle[locate(x, hint)]; }

  // Integrals over a convex spherical polygon (counter-clockwise from outside, within a
  // hemisphere) of g^power dA (mass) and of x g^power dA (moment), exactly: the polygon is
  // clipped by every triangle it overlaps, found by walking from the triangle at `inside` (a
  // point of the polygon; `hint` as for locate, updated to it). Scratch is the caller's (one
  // per thread).
  struct Scratch
  {
    std::vector<int> stamp;
    std::vector<int> stack;
    std::vector<Vec3> polygonNormals; // cross(a, b) of the polygon's edges: inside when >= 0
    std::vector<Vec3> piece, clipped;
    int current = 0;
  };
  // Optionally also the integrals of g (gMass) and of 1 (area) in the same pass.
  void integrate(const std::vector<Vec3>& polygon, Vec3 inside, int& hint, double power,
    Scratch& scratch, double& mass, Vec3* moment, double* gMass = nullptr,
    double* area = nullptr) const;

  double integral() const { return Integral; } // sum of g times spherical area
  const std::vector<Vec3>& points() const { return Points; }
  const std::vector<Triangle>& triangles() const { return Triangles; }
  const std::vector<double>& density() const { return PerTriangle; }
  double sphericalArea(int t) const { return Area[t]; }

private:
  SphericalDensityField() = default;
  std::string checkAndBuild();
  std::string buildNeighboursAndAreas(
    const std::unordered_map<long long, std::pair<int, int>>& directedEdges);
  int walk(Vec3 x, int start, int maximumSteps) const;
  bool contains(int t, Vec3 x) const;
  bool clipToTriangle(int t, const std::vector<Vec3>& polygon, Scratch& scratch) const;
  int tableCell(Vec3 x) const;
  void buildStartTable();

  std::vector<Vec3> Points;
  std::vector<Triangle> Triangles;
  std::vector<double> PerTriangle;
  std::vector<double> Area;
  std::vector<Vec3> Moment;                    // of each whole triangle (its integral of x dA)
  std::vector<std::array<int, 3>> Neighbor;    // across the edge opposite vertex k
  std::vector<std::array<Vec3, 3>> EdgeNormal; // cross(a, b) of edge k: inside when >= 0
  std::vector<int> StartTable; // cube map: 6 faces x TableSize^2 cells -> a triangle near it
  int TableSize = 1;
  double Integral = 0.0;
};

} // namespace otparam

#endif
