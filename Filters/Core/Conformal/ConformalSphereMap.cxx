// The method, and why it is this one.
//
// Two linear passes in the manner of FLASH (Choi, Lam, Lui, SIAM J. Imaging Sci. 2015), with
// the first pass of Angenent et al. / Haker et al. (2000), then a Moebius balancing:
//  1. North pass: solve the cotangent Laplace equation with a point dipole in one triangle
//     (the puncture) as its source: the continuous solution is the conformal map onto the
//     plane that sends the dipole's point to infinity (z ~ 1 / w near it). FLASH pins the
//     puncture's three corners to a similar triangle instead; three pinned values are three
//     charges whose far field is conformal only if that guessed image triangle is exactly
//     right, and otherwise carries an anti-conformal part that does not shrink under
//     refinement (crowded round sphere, 6000 and 24000 points: 0.04 from a rotation with
//     pinned corners, 0.0022 and 0.0006 with the dipole). The dipole's weak form has the exact
//     moment, so its defect is local. Inverse stereographic projection puts the puncture at
//     the north pole.
//  2. Balance the first-pass image roughly (Moebius, see 4), so that "far from the puncture"
//     means the same on every surface.
//  3. South pass: keep the fraction `fixedFraction` of points farthest from the puncture fixed,
//     project stereographically from the antipode of the puncture and solve the cotangent
//     Laplace equation again for the rest, with the fixed points as Dirichlet values: the
//     puncture's triangles become ordinary interior triangles. This is FLASH's quasi-conformal
//     correction in its plainest form (its Beltrami solve, with the Beltrami coefficient of
//     the current map against the surface, is the surface's own Laplace equation written in
//     the current coordinates). A smaller fixed region leaves less of the first pass in the
//     result: 5% (FLASH: 10%) measured best (brain 1.233 / spot 2.927 degrees; 10%: 1.240 /
//     2.919; 1%: 1.231 / 3.011 with a worse maximum; crowded sphere 0.019 / 0.026 / 0.041).
//  4. Moebius balancing: Newton's method on the hyperbolic translation f_c (c in the open unit
//     ball, f_c(c) = 0) that moves the centre of mass of the pushed-forward surface area to the
//     origin (Baden, Crane, Kazhdan 2018): to first order f_c moves the centre by
//     -2 (I - M2) c, M2 the second moment, so c = (I - M2)^-1 m / 2, with backtracking.
// Why not the alternatives: a genus-0 discrete Ricci flow or CETM needs a Newton solve with
// intrinsic re-triangulation; a conformal disk map of the punctured surface (ConformalDiskMap)
// needs ~10 boundary iterations where one harmonic solve does; the sphere's nonlinear
// (tangential) Laplacian flows need many iterations. Two factorizations of a graph Laplacian
// are linear-time in practice.
//
// Orientation: the map is made orientation-consistent for the triangles as given (every
// triangle counter-clockwise seen from outside, det(a, b, c) > 0), whatever way the surface's
// triangles face; the solve fixes nothing about the sign, so the whole image is mirrored when
// the signed image volume comes out negative. `mirrored` reports a surface whose triangles
// face inward (negative enclosed volume), whose map is then the mirror image of the surface.
#include "Conformal/ConformalSphereMap.h"

#include "Conformal/ConformalDiskMap.h"
#include "Conformal/CotangentLaplacian.h"

#include "Mesh/DistortionMetrics.h"
#include "Mesh/IntrinsicDelaunay.h"

#include "Common/SparseCholesky.h"
#include "Common/SphericalGeometry.h"

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <sstream>

namespace otparam
{
namespace
{
using Clock = std::chrono::steady_clock;
using SparseMatrix = Eigen::SparseMatrix<double>;
using Complex = std::complex<double>;

double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Eigen::Vector3d toEigen(Vec3 v)
{
  return { v.x, v.y, v.z };
}

Vec3 fromEigen(const Eigen::Vector3d& v)
{
  return { v[0], v[1], v[2] };
}

// CHOLMOD's supernodal factorization from this many unknowns, below SparseCholesky's default
// (measured on the sphere map's Laplacians, brain_choi_closed_48k and its Loop subdivision: at
// 48k points Eigen's simplicial LDL^T takes the conformal stage 0.33-0.34 s against CHOLMOD's
// 0.38-0.39; at 194k 2.45-2.70 s against 1.77-1.79).
constexpr int SphereMapCholmodFrom = 100000;

// The harmonic extension: L_FF X_F = source_F - L_FB X_B for the free rows F (fixed[v] == 0),
// the fixed rows of X given; both columns at once. False when the factorization fails, the
// solution is not finite or `keepGoing` (asked inside the factorization) says stop.
bool solveDirichlet(const SparseMatrix& L, const std::vector<char>& fixed, Eigen::MatrixXd& X,
  const std::function<bool()>& keepGoing, const Eigen::MatrixXd* source = nullptr)
{
  const int n = static_cast<int>(L.rows());
  std::vector<int> local(n, -1);
  int nf = 0;
  for (int v = 0; v < n; ++v)
  {
    local[v] = fixed[v] ? -1 : nf++;
  }
  std::vector<Eigen::Triplet<double>> lower;
  lower.reserve(L.nonZeros() / 2 + n);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf, 2);
  if (source)
  {
    for (int v = 0; v < n; ++v)
    {
      if (!fixed[v])
      {
        rhs.row(local[v]) = source->row(v);
      }
    }
  }
  for (int col = 0; col < n; ++col)
  {
    for (SparseMatrix::InnerIterator it(L, col); it; ++it)
    {
      const int row = static_cast<int>(it.row());
      if (fixed[row])
      {
        continue;
      }
      if (!fixed[col])
      {
        if (row >= col) // local numbering keeps the order: this is the lower triangle
        {
          lower.emplace_back(local[row], local[col], it.value());
        }
      }
      else
      {
        rhs.row(local[row]) -= it.value() * X.row(col);
      }
    }
  }
  if (!rhs.allFinite())
  {
    return false;
  }
  SparseMatrix LFF(nf, nf);
  LFF.setFromTriplets(lower.begin(), lower.end());
  SparseCholesky cholesky(SphereMapCholmodFrom);
  cholesky.allowHalves(true); // on both cores (SparseCholesky.h)
  if (!cholesky.compute(LFF, keepGoing))
  {
    return false;
  }
  const Eigen::MatrixXd solution = cholesky.solve(rhs);
  if (!solution.allFinite())
  {
    return false;
  }
  for (int v = 0; v < n; ++v)
  {
    if (!fixed[v])
    {
      X.row(v) = solution.row(local[v]);
    }
  }
  return true;
}

constexpr double Pi = 3.14159265358979323846;

// Per point, |2 pi - the sum of its corner angles|: how far from flat the surface is there.
// With `only`, of those points alone (the others' stay 2 pi): one cheap pass at 1e6 points.
std::vector<double> angleDefects(const SurfaceMesh& mesh, const std::vector<int>& only = {})
{
  std::vector<double> defect(mesh.points.size(), 2.0 * Pi);
  std::vector<char> wanted(only.empty() ? 0 : mesh.points.size(), 0);
  for (int v : only)
  {
    wanted[v] = 1;
  }
  for (const Triangle& tri : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (!wanted.empty() && !wanted[tri[k]])
      {
        continue;
      }
      const Vec3 p = mesh.points[tri[k]];
      const Vec3 u = mesh.points[tri[(k + 1) % 3]] - p, w = mesh.points[tri[(k + 2) % 3]] - p;
      defect[tri[k]] -= std::atan2(norm(cross(u, w)), dot(u, w));
    }
  }
  for (double& d : defect)
  {
    d = std::abs(d);
  }
  return defect;
}

// A corner this far from flat (a cube's: pi / 2) is a sharp one.
constexpr double SharpCornerDefect = Pi / 4.0;

double regularityScore(const SurfaceMesh& mesh, const Triangle& tri)
{
  const double a = norm(mesh.points[tri[1]] - mesh.points[tri[2]]);
  const double b = norm(mesh.points[tri[2]] - mesh.points[tri[0]]);
  const double c = norm(mesh.points[tri[0]] - mesh.points[tri[1]]);
  const double s = a + b + c;
  return std::abs(a / s - 1.0 / 3.0) + std::abs(b / s - 1.0 / 3.0) + std::abs(c / s - 1.0 / 3.0);
}

// The most nearly equilateral triangle (FLASH's choice of puncture; the dipole's local defect
// is smallest on a well-shaped triangle), the first of equally regular ones, unless that one
// touches a sharp corner: then the one of them whose corners are flattest. The dipole's
// solution z ~ 1 / w is that of a flat neighbourhood; at a pyramid's base corner (the first of
// its grid's right triangles) it left 45 triangles folded, 1 from a grid triangle inside.
int mostRegularTriangle(const SurfaceMesh& mesh)
{
  int best = 0;
  double bestScore = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const double score = regularityScore(mesh, mesh.triangles[t]);
    if (score < bestScore)
    {
      bestScore = score;
      best = static_cast<int>(t);
    }
  }
  const Triangle& first = mesh.triangles[best];
  std::vector<double> defect = angleDefects(mesh, { first[0], first[1], first[2] });
  auto sharpness = [&](int t)
  {
    const Triangle& tri = mesh.triangles[t];
    return std::max({ defect[tri[0]], defect[tri[1]], defect[tri[2]] });
  };
  if (sharpness(best) <= SharpCornerDefect)
  {
    return best;
  }
  defect = angleDefects(mesh);
  double bestSharpness = sharpness(best);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const int candidate = static_cast<int>(t);
    if (regularityScore(mesh, mesh.triangles[t]) <= bestScore + 1e-12 &&
      sharpness(candidate) < bestSharpness)
    {
      bestSharpness = sharpness(candidate);
      best = candidate;
    }
  }
  return best;
}

// Inverse stereographic projection from the north pole: z = infinity is (0, 0, 1).
Vec3 inverseStereographic(Complex z)
{
  const double s = std::norm(z);
  if (!std::isfinite(s))
  {
    return { 0.0, 0.0, 1.0 };
  }
  return { 2.0 * z.real() / (1.0 + s), 2.0 * z.imag() / (1.0 + s), (s - 1.0) / (1.0 + s) };
}

// The hyperbolic translation of the ball that sends c (|c| < 1) to 0, on a unit vector.
Vec3 moebiusTranslation(Vec3 x, Vec3 c)
{
  const Vec3 d = x - c;
  const Vec3 y = ((1.0 - dot(c, c)) / dot(d, d)) * d - c;
  return normalized(y);
}

// Centre of mass and second moment of the pushed-forward measure: weight[t] (summing to 1)
// spread uniformly over the spherical image of triangle t.
void momentsOf(const std::vector<Triangle>& triangles, const std::vector<double>& weight,
  const std::vector<Vec3>& sphere, Eigen::Vector3d& centre, Eigen::Matrix3d* second)
{
  centre.setZero();
  if (second)
  {
    second->setZero();
  }
  std::vector<Vec3> polygon(3);
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    if (weight[t] == 0.0)
    {
      continue;
    }
    const auto& tri = triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      polygon[k] = sphere[tri[k]];
    }
    const double area = sphericalTriangleArea(polygon[0], polygon[1], polygon[2]);
    // The exact mean of x over the image triangle; for tiny (or flipped) images the normalized
    // centroid, which differs by O(area) and avoids the moment's cancellation.
    const Vec3 mean = area > 1e-10 ? (1.0 / area) * sphericalPolygonMoment(polygon)
                                   : normalized(polygon[0] + polygon[1] + polygon[2]);
    const Eigen::Vector3d x = toEigen(mean);
    centre += weight[t] * x;
    if (second)
    {
      *second += weight[t] * x * x.transpose();
    }
  }
}

struct BalanceOutcome
{
  int iterations = 0;
  double residual = 0.0;
};

// Moebius maps applied to `sphere` (and to `tracked`) until the pushed-forward centre of mass
// is below `tolerance`.
BalanceOutcome balance(const std::vector<Triangle>& triangles, const std::vector<double>& weight,
  std::vector<Vec3>& sphere, Vec3& tracked, double tolerance, int maximumIterations)
{
  BalanceOutcome outcome;
  Eigen::Vector3d m;
  Eigen::Matrix3d M2;
  momentsOf(triangles, weight, sphere, m, &M2);
  std::vector<Vec3> trial(sphere.size());
  for (; outcome.iterations < maximumIterations && m.norm() > tolerance; ++outcome.iterations)
  {
    Eigen::Vector3d c =
      0.5 * (Eigen::Matrix3d::Identity() - M2).ldlt().solve(m); // I - M2 is positive definite
    // Large steps leave the region where the linear model holds: |c| <= 1/2 moves a point by
    // at most a factor 3 in scale.
    if (c.norm() > 0.5)
    {
      c *= 0.5 / c.norm();
    }
    bool accepted = false;
    Eigen::Vector3d trialCentre;
    Eigen::Matrix3d trialSecond;
    for (int halving = 0; halving < 30 && !accepted; ++halving, c *= 0.5)
    {
      const Vec3 cv = fromEigen(c);
      for (size_t v = 0; v < sphere.size(); ++v)
      {
        trial[v] = moebiusTranslation(sphere[v], cv);
      }
      momentsOf(triangles, weight, trial, trialCentre, &trialSecond);
      accepted = trialCentre.norm() < m.norm();
      if (accepted)
      {
        tracked = moebiusTranslation(tracked, cv);
      }
    }
    if (!accepted)
    {
      break; // no Moebius step lowers the offset: it is at rounding level
    }
    sphere.swap(trial);
    m = trialCentre;
    M2 = trialSecond;
  }
  outcome.residual = m.norm();
  return outcome;
}

std::vector<double> areaWeights(const SurfaceMesh& mesh)
{
  std::vector<double> weight(mesh.triangles.size());
  double total = 0.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    weight[t] = triangleArea(mesh, mesh.triangles[t]);
    total += weight[t];
  }
  for (double& w : weight)
  {
    w /= total;
  }
  return weight;
}

double signedVolume(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles)
{
  double volume = 0.0;
  for (const Triangle& t : triangles)
  {
    volume += dot(points[t[0]], cross(points[t[1]], points[t[2]]));
  }
  return volume / 6.0;
}

std::string checkOptions(const ConformalSphereMapOptions& options, const SurfaceMesh& mesh)
{
  std::ostringstream msg;
  const auto nt = static_cast<long long>(mesh.triangles.size());
  const auto nv = static_cast<long long>(mesh.points.size());
  if (options.punctureTriangle < -1 || options.punctureTriangle >= nt)
  {
    msg << "the puncture triangle " << options.punctureTriangle << " is not a triangle id in [0, "
        << nt << ")";
  }
  else if (!(options.fixedFraction > 0.0 && options.fixedFraction < 1.0))
  {
    msg << "the fixed fraction must lie strictly between 0 and 1; got " << options.fixedFraction;
  }
  else if (!(options.balanceTolerance > 0.0) || options.maximumBalanceIterations < 0)
  {
    msg << "the balance tolerance must be positive and the iteration count non-negative";
  }
  // A closed triangle surface of genus 0 has V - 3F/2 + F = 2 (checkSphereTopology says more).
  else if (nv < 4 || 2 * nv - nt != 4)
  {
    msg << "the surface is not a closed genus-0 triangle surface (" << nv << " points, " << nt
        << " triangles; a sphere has 2 + triangles / 2 points): run checkSphereTopology first";
  }
  return msg.str();
}

// The north pass's source: the discrete dipole at the puncture's centroid, whose continuous
// solution is 1 / w (w a complex coordinate of the triangle's plane): in weak form, corner k
// gets 2 pi (d/dx - i d/dy) of its hat function (constant factors dropped: the scale is fixed
// by scaleLikeFlash).
Eigen::MatrixXd punctureDipole(const SurfaceMesh& mesh, const Triangle& puncture)
{
  Eigen::MatrixXd dipole = Eigen::MatrixXd::Zero(static_cast<int>(mesh.points.size()), 2);
  const Vec3 A = mesh.points[puncture[0]], B = mesh.points[puncture[1]],
             C = mesh.points[puncture[2]];
  const Vec3 normal = normalized(cross(B - A, C - A));
  const Vec3 e1 = normalized(B - A), e2 = cross(normal, e1);
  // Hat-function gradients up to the common factor 1 / (2 area): normal x opposite edge.
  const Vec3 gradient[3] = { cross(normal, C - B), cross(normal, A - C), cross(normal, B - A) };
  for (int k = 0; k < 3; ++k)
  {
    dipole.row(puncture[k]) << dot(gradient[k], e1), -dot(gradient[k], e2);
  }
  return dipole;
}

// The Neumann problem's gauge: one point pinned at 0, any point off the puncture (the source
// sums to zero, so the dropped equation holds by itself).
int gaugePoint(const Triangle& puncture)
{
  int gauge = 0;
  while (gauge == puncture[0] || gauge == puncture[1] || gauge == puncture[2])
  {
    ++gauge;
  }
  return gauge;
}

// Scale so that the puncture (near infinity) and the triangle nearest 0 have comparable sizes
// on the sphere, as FLASH does: else the far side of the surface can sit in a speck around the
// south pole whose shape double precision barely resolves.
void scaleLikeFlash(const SurfaceMesh& mesh, int punctureTriangle, std::vector<Complex>& z)
{
  auto side = [&](const Triangle& t, auto coordinate)
  {
    return (std::abs(coordinate(t[0]) - coordinate(t[1])) +
             std::abs(coordinate(t[1]) - coordinate(t[2])) +
             std::abs(coordinate(t[2]) - coordinate(t[0]))) /
      3.0;
  };
  int inner = -1;
  double innerSize = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const auto& tri = mesh.triangles[t];
    const double size = std::abs(z[tri[0]]) + std::abs(z[tri[1]]) + std::abs(z[tri[2]]);
    if (static_cast<int>(t) != punctureTriangle && size < innerSize)
    {
      innerSize = size;
      inner = static_cast<int>(t);
    }
  }
  const double north = side(mesh.triangles[punctureTriangle], [&](int v) { return z[v]; });
  const double south = side(mesh.triangles[inner], [&](int v) { return 1.0 / std::conj(z[v]); });
  const double scale = std::sqrt(south / north);
  if (std::isfinite(scale) && scale > 0.0)
  {
    for (Complex& w : z)
    {
      w *= scale;
    }
  }
}

// The north pass's plane coordinates, centred, scaled and projected onto the sphere (the
// puncture at the north pole).
std::vector<Vec3> northPassSphere(
  const SurfaceMesh& mesh, int punctureTriangle, const Eigen::MatrixXd& X)
{
  const int nv = static_cast<int>(X.rows());
  std::vector<Complex> z(nv);
  Complex mean = 0.0;
  for (int v = 0; v < nv; ++v)
  {
    z[v] = Complex(X(v, 0), X(v, 1));
    mean += z[v] / static_cast<double>(nv);
  }
  for (Complex& w : z)
  {
    w -= mean;
  }
  scaleLikeFlash(mesh, punctureTriangle, z);
  std::vector<Vec3> sphere(nv);
  for (int v = 0; v < nv; ++v)
  {
    sphere[v] = inverseStereographic(z[v]);
  }
  return sphere;
}

// The south pass's Dirichlet points: the `count` points farthest from the puncture (lowest
// along `north`). The puncture's corners are always solved again (on a tiny surface they
// would otherwise be among the "farthest" points).
std::vector<char> farthestFromPuncture(
  const std::vector<Vec3>& sphere, const Triangle& puncture, Vec3 north, int count)
{
  const int nv = static_cast<int>(sphere.size());
  std::vector<double> height(nv);
  std::vector<int> order;
  for (int v = 0; v < nv; ++v)
  {
    height[v] = dot(sphere[v], north);
    if (v != puncture[0] && v != puncture[1] && v != puncture[2])
    {
      order.push_back(v);
    }
  }
  std::nth_element(order.begin(), order.begin() + std::max(0, count - 1), order.end(),
    [&](int a, int b) { return height[a] < height[b]; });
  std::vector<char> fixed(nv, 0);
  for (int i = 0; i < count; ++i)
  {
    fixed[order[i]] = 1;
  }
  return fixed;
}

// The south pass: the points not fixed are solved again in the stereographic plane of the
// puncture's antipode, the fixed ones as Dirichlet values.
bool solveSouthPass(const SparseMatrix& L, const std::vector<char>& fixed, Vec3 north,
  std::vector<Vec3>& sphere, const std::function<bool()>& keepGoing)
{
  const Vec3 helper = std::abs(north.x) < 0.6 ? Vec3{ 1.0, 0.0, 0.0 } : Vec3{ 0.0, 1.0, 0.0 };
  const Vec3 e1 = normalized(cross(helper, north));
  const Vec3 e2 = cross(north, e1);
  const int nv = static_cast<int>(sphere.size());
  Eigen::MatrixXd X(nv, 2);
  for (int v = 0; v < nv; ++v)
  {
    // 1 + x.n = |x + n|^2 / 2 keeps its precision near the projection's pole -n.
    const Vec3 s = sphere[v] + north;
    const double denominator = 0.5 * dot(s, s);
    X(v, 0) = dot(sphere[v], e1) / denominator;
    X(v, 1) = dot(sphere[v], e2) / denominator;
  }
  if (!solveDirichlet(L, fixed, X, keepGoing))
  {
    return false;
  }
  for (int v = 0; v < nv; ++v)
  {
    if (!fixed[v])
    {
      const double u = X(v, 0), w = X(v, 1), s = u * u + w * w;
      sphere[v] = normalized(
        (2.0 * u / (1.0 + s)) * e1 + (2.0 * w / (1.0 + s)) * e2 + ((1.0 - s) / (1.0 + s)) * north);
    }
  }
  return true;
}

// Step 4: the image made orientation-consistent, then balanced (`weight`: areaWeights(mesh)).
void orientAndBalance(const SurfaceMesh& mesh, const std::vector<double>& weight,
  const ConformalSphereMapOptions& options, Vec3 north, std::vector<Vec3>& sphere,
  ConformalSphereMapResult& result)
{
  if (signedVolume(sphere, mesh.triangles) < 0.0)
  {
    for (Vec3& p : sphere)
    {
      p.y = -p.y;
    }
  }
  result.mirrored = signedVolume(mesh.points, mesh.triangles) < 0.0;
  const BalanceOutcome outcome = balance(mesh.triangles, weight, sphere, north,
    options.balanceTolerance, options.maximumBalanceIterations);
  result.balanceIterations = outcome.iterations;
  result.balanceResidual = outcome.residual;
  if (outcome.residual > 1e-6)
  {
    std::ostringstream msg;
    msg << "the Moebius balancing stopped with the area's centre of mass at " << outcome.residual
        << " from the origin (asked: " << options.balanceTolerance << ")";
    result.status.warnings.push_back(msg.str());
  }
}

// The map, if finite, and its figures.
void keepFinite(const SurfaceMesh& mesh, std::vector<Vec3> sphere, ConformalSphereMapResult& result)
{
  for (const Vec3& p : sphere)
  {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    {
      result.status.error = "the spherical conformal map has non-finite coordinates (the "
                            "cotangent Laplacian is too ill-conditioned on this surface)";
      return;
    }
  }
  result.sphere = std::move(sphere);
  const DistortionFigures figures = measureSphereDistortion(mesh, result.sphere);
  result.flippedTriangles = figures.flippedTriangles;
  result.meanAngleDistortionDegrees = figures.meanAngleDistortionDegrees;
  result.maximumAngleDistortionDegrees = figures.maximumAngleDistortionDegrees;
}

using Weights = LaplacianWeights;

ConformalSphereMapResult computeWithLaplacian(
  const SurfaceMesh& mesh, const ConformalSphereMapOptions& options, Weights weights)
{
  ConformalSphereMapResult result;
  auto keepGoing = [&](double fraction)
  {
    result.status.aborted = options.progress && !options.progress(fraction);
    return !result.status.aborted;
  };
  auto failed = [&]
  {
    result.status.error = result.status.aborted
      ? ""
      : "the cotangent Laplacian could not be factored (degenerate or badly shaped triangles?)";
    return result;
  };
  const int nv = static_cast<int>(mesh.points.size());

  // 1. North pass: the dipole's harmonic potential, onto the sphere.
  auto t0 = Clock::now();
  const SparseMatrix L = laplacianOf(
    mesh.triangles, edgeLengthsOf(mesh.points, mesh.triangles), nv, weights, result.intrinsicFlips);
  result.punctureTriangle =
    options.punctureTriangle >= 0 ? options.punctureTriangle : mostRegularTriangle(mesh);
  const Triangle puncture = mesh.triangles[result.punctureTriangle];
  std::vector<char> gauge(nv, 0);
  gauge[gaugePoint(puncture)] = 1;
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(nv, 2);
  const Eigen::MatrixXd dipole = punctureDipole(mesh, puncture);
  if (!solveDirichlet(
        L, gauge, X, [&] { return keepGoing(0.25); }, &dipole))
  {
    return failed();
  }
  result.secondsFactorization = secondsSince(t0);
  if (!keepGoing(0.3))
  {
    return result;
  }
  t0 = Clock::now();
  std::vector<Vec3> sphere = northPassSphere(mesh, result.punctureTriangle, X);

  // 2. Balance the first pass (the puncture's own image is the complement of a triangle: left
  // out), tracking the image of the north pole, the puncture's direction. Roughly: it only
  // chooses the second pass's pole and fixed points.
  Vec3 north{ 0.0, 0.0, 1.0 };
  const std::vector<double> weight = areaWeights(mesh);
  std::vector<double> firstWeight = weight;
  firstWeight[result.punctureTriangle] = 0.0;
  balance(mesh.triangles, firstWeight, sphere, north, 1e-3, 50);
  if (!keepGoing(0.4))
  {
    return result;
  }
  result.secondsSolve = secondsSince(t0);

  // 3. South pass: the points farthest from the puncture stay, the rest is solved again. A
  // harmonic extension needs boundary values around the free region: at least 3 fixed points
  // (with 1, the extension is constant). Below 6 points the first pass stands alone.
  t0 = Clock::now();
  north = normalized(north);
  result.fixedPoints =
    nv < 6 ? 0 : std::clamp(static_cast<int>(std::lround(options.fixedFraction * nv)), 3, nv - 3);
  if (result.fixedPoints > 0 &&
    !solveSouthPass(L, farthestFromPuncture(sphere, puncture, north, result.fixedPoints), north,
      sphere, [&] { return keepGoing(0.6); }))
  {
    return failed();
  }
  result.secondsFactorization += secondsSince(t0);
  if (!keepGoing(0.7))
  {
    return result;
  }

  // 4. Orientation, then the final balancing.
  t0 = Clock::now();
  orientAndBalance(mesh, weight, options, north, sphere, result);
  result.secondsBalance = secondsSince(t0);
  keepFinite(mesh, std::move(sphere), result);
  if (result.status.ok())
  {
    keepGoing(1.0);
  }
  return result;
}

// The last fallback, which cannot fold the surface's triangles but its puncture's: the surface
// less its puncture triangle is a disk whose conformal map (ConformalDiskMap, with floored
// weights where both cotangent Laplacians fold: Tutte) folds none of them; lifted by inverse
// stereographic projection with the disk's rim at height 0.8 (the puncture the cap above),
// oriented and balanced as the two passes are. Measured where the passes fold (coarse sharp
// corners): VTK's capped cone and cylinder at resolution 24, a pyramid with a low apex.
ConformalSphereMapResult throughTheDisk(
  const SurfaceMesh& mesh, const ConformalSphereMapOptions& options, int puncture)
{
  ConformalSphereMapResult result;
  result.punctureTriangle = puncture;
  SurfaceMesh punctured = mesh;
  punctured.triangles.erase(punctured.triangles.begin() + puncture);
  std::vector<int> loop;
  result.status.error = checkDiskTopology(punctured, loop);
  if (!result.status.error.empty())
  {
    return result;
  }
  ConformalDiskMapOptions diskOptions;
  diskOptions.progress = options.progress;
  const ConformalDiskMapResult disk = computeConformalDiskMap(punctured, loop, diskOptions);
  result.status = disk.status;
  if (!result.status.ok())
  {
    return result;
  }
  std::vector<Vec3> sphere(mesh.points.size());
  for (size_t v = 0; v < sphere.size(); ++v)
  {
    sphere[v] = inverseStereographic(3.0 * Complex(disk.uv[v].x, disk.uv[v].y));
  }
  orientAndBalance(mesh, areaWeights(mesh), options, Vec3{ 0.0, 0.0, 1.0 }, sphere, result);
  keepFinite(mesh, std::move(sphere), result);
  return result;
}
} // namespace

Vec3 pushedAreaCentre(const SurfaceMesh& mesh, const std::vector<Vec3>& sphere)
{
  Eigen::Vector3d centre;
  momentsOf(mesh.triangles, areaWeights(mesh), sphere, centre, nullptr);
  return fromEigen(centre);
}

namespace
{
// Where every Laplacian folds, why: a map that crowds a long protrusion past double precision
// (TestCrowdingSphere's closed fingers, two tubes of 60 cells: 368 folds), or a mesh too coarse
// around a sharp feature (VTK's cone at resolution 60 subdivided once).
std::string foldWarning(const SurfaceMesh& mesh, const ConformalSphereMapResult& result)
{
  std::vector<double> density, perPoint;
  computeSphereAreaDensity(mesh, result.sphere, density, perPoint);
  const double range = rangeOf(density);
  std::ostringstream msg;
  msg << result.flippedTriangles
      << " triangle(s) are flipped on the sphere (clockwise seen from outside) in the map kept "
         "after trying the mesh's cotangent Laplacian, the intrinsic Delaunay one, the mesh's "
         "with its weights made positive, and the punctured surface's disk map lifted onto the "
         "sphere. ";
  if (range > CrowdedDensityRange)
  {
    msg << "The map crowds part of the surface (its area density spans " << range
        << ": a long protrusion such as a finger, a limb or a tail) beyond what double precision "
           "resolves there.";
  }
  else
  {
    msg << "The mesh is too coarse around a sharp feature: refine it (e.g. with a linear or "
           "Loop subdivision).";
  }
  return msg.str();
}

// The lifted map is kept where it flips nothing, or where it flips fewer triangles than `folded`
// on a surface that map does not crowd (area density range at most CrowdedDensityRange): the
// pipeline's untangling then has fewer to free (VTK's cone at resolution 60 subdivided once: 69
// flipped, 172 after untangling, refused; lifted 3, then none). A crowded surface's folds are
// its stages' to heal.
bool betterLift(const SurfaceMesh& mesh, const ConformalSphereMapResult& lifted,
  const ConformalSphereMapResult& folded)
{
  if (lifted.flippedTriangles == 0)
  {
    return true;
  }
  if (lifted.flippedTriangles >= folded.flippedTriangles)
  {
    return false;
  }
  std::vector<double> density, perPoint;
  computeSphereAreaDensity(mesh, folded.sphere, density, perPoint);
  return rangeOf(density) <= CrowdedDensityRange;
}

// The seconds of the map `from` added to those of `into`: a map tried and dropped, or the map
// kept counts the maps tried before it.
void addSeconds(const ConformalSphereMapResult& from, ConformalSphereMapResult& into)
{
  into.secondsFactorization += from.secondsFactorization;
  into.secondsSolve += from.secondsSolve;
  into.secondsBalance += from.secondsBalance;
}
} // namespace

// As in the disk map: the mesh's own cotangent Laplacian is the most faithful to its triangles
// but can fold across obtuse ones (negative weights); the intrinsic Delaunay Laplacian cannot
// fold its own triangulation, so it is the first fallback, kept when it flips fewer of the
// mesh's triangles. Then the floored weights, kept only if nothing flips, and last the disk map
// lifted (throughTheDisk), kept if nothing flips or, on a surface the map does not crowd, if
// fewer triangles flip (betterLift): coarse sharp corners; a crowded surface's folds are its
// stages' to heal.
ConformalSphereMapResult computeConformalSphereMap(
  const SurfaceMesh& mesh, const ConformalSphereMapOptions& options)
{
  ConformalSphereMapResult result;
  result.status.error = checkOptions(options, mesh);
  if (!result.status.error.empty())
  {
    return result;
  }
  result = computeWithLaplacian(
    mesh, options, options.intrinsicLaplacian ? Weights::IntrinsicDelaunay : Weights::Mesh);
  result.intrinsicLaplacian = options.intrinsicLaplacian;
  if (!result.status.ok() || options.intrinsicLaplacian)
  {
    return result;
  }
  result.flippedWithMeshLaplacian = result.flippedTriangles;
  ConformalSphereMapOptions again = options;
  if (options.progress)
  {
    // Progress already reached 1: the other solves only check for an abort.
    again.progress = [&options](double) { return options.progress(1.0); };
  }
  tryFallbackLaplacians(
    result.flippedTriangles,
    [&](Weights weights) { return computeWithLaplacian(mesh, again, weights); },
    [](const ConformalSphereMapResult& other) -> std::int64_t
    { return other.status.error.empty() ? other.flippedTriangles : -1; },
    [&](ConformalSphereMapResult&& other, Weights weights)
    {
      other.intrinsicLaplacian = weights == Weights::IntrinsicDelaunay;
      other.flooredWeights = weights == Weights::Floored;
      other.flippedWithMeshLaplacian = result.flippedWithMeshLaplacian;
      addSeconds(result, other);
      result = std::move(other);
    },
    [&](const ConformalSphereMapResult& other) { addSeconds(other, result); });
  if (result.status.ok() && result.flippedTriangles > 0)
  {
    ConformalSphereMapResult lifted = throughTheDisk(mesh, again, result.punctureTriangle);
    if (lifted.status.aborted || (lifted.status.error.empty() && betterLift(mesh, lifted, result)))
    {
      lifted.liftedFromTheDisk = true;
      lifted.flippedWithMeshLaplacian = result.flippedWithMeshLaplacian;
      addSeconds(result, lifted);
      result = std::move(lifted); // kept with fewer flips, it is warned about as any other
    }
  }
  if (result.status.ok() && result.flippedTriangles > 0)
  {
    result.status.warnings.push_back(foldWarning(mesh, result));
  }
  return result;
}

//------------------------------------------------------------------------------
double balanceMeasure(const std::vector<Triangle>& triangles, const std::vector<double>& weight,
  std::vector<Vec3>& sphere, double tolerance, int maximumIterations)
{
  Vec3 untracked{ 0.0, 0.0, 1.0 };
  return balance(triangles, weight, sphere, untracked, tolerance, maximumIterations).residual;
}

} // namespace otparam
