// The method, and why it is this one.
//
// A conformal map onto the disk is determined by where it puts the boundary: its two
// components are harmonic, so the interior follows from the boundary angles theta by one
// Dirichlet solve with the cotangent Laplacian (factored once). Among boundary angles on the
// circle, the conformal ones minimize the conformal energy E_C = E_Dirichlet - Area (>= 0,
// = 0 exactly for conformal maps; on a triangle mesh it is the LSCM energy). So:
//  1. Start from one step of boundary-first flattening (Sawhney & Crane 2017) with the
//     curvature of a circle as boundary target: one Neumann solve gives boundary scale
//     factors, hence boundary lengths, hence angles.
//  2. Minimize E_C over theta by gradient steps preconditioned with the Dirichlet-to-Neumann
//     operator (one Neumann solve with the same prefactored Laplacian). In Fourier terms the
//     energy's Hessian is ~ (|k| - 1) and the preconditioner ~ |k|, so every mode but the
//     Moebius ones (k = 0, +-1, projected out) contracts by about 1/2 per step, on any mesh
//     size. Boundary points stay exactly on the circle at every step; no circle fitting.
//  3. Fix the Moebius freedom: send the centre vertex to 0 (applied to the boundary angles and
//     re-extended, so the interior stays harmonic) and rotate the align vertex to (1, 0).
// Compared with the alternatives the issue names: BFF alone leaves the boundary only close to
// a circle (1e-4 .. 2e-3 on our meshes), CETM/Ricci flow needs a Newton solve with intrinsic
// re-triangulation, Choi-Lui's method needs a double cover and a Beltrami correction; this is
// linear solves with two factorizations and reaches the same angle errors as Choi-Lui.
//
// Ears (boundary vertices on a single triangle) are sharp boundary corners of the mesh, not
// of the surface; a conformal map must open each to a straight angle, which crushes the ear
// and distorts a whole neighbourhood (on face_maxplanck_partial_32k: mean angle error 1.55
// degrees with its 7 ears, 0.51 without, and a flipped ear). So ears are clipped off before
// the solve and put back on the circle between their two neighbours afterwards.
#include "Conformal/ConformalDiskMap.h"

#include "Conformal/CotangentLaplacian.h"

#include "Mesh/IntrinsicDelaunay.h"

#include "Common/SparseCholesky.h"

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <queue>
#include <sstream>
#include <string>

namespace otparam
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double TwoPi = 2.0 * Pi;
// When one factorization serves the Neumann and the Dirichlet problem (DiskFlattening::factor):
// its dense last block of NB^2 / 2 entries costs NB^3 / 3 flops (Eigen's simplicial LDL^T:
// ~2 GFlop/s here, 10 s at NB = 4000), against ~N^1.5 for the sparse part of a planar mesh
// (shared meshes: NB^3 / N^1.5 = 0.01 .. 2.3; the face subdivided to 1.09M points 2.1). Up to
// 8000 boundary vertices (a dense block of 256 MB).
bool factorTogether(int boundary, int points)
{
  const double nb = boundary, n = points;
  return boundary <= 8000 && nb * nb * nb <= 30.0 * n * std::sqrt(n);
}
using Clock = std::chrono::steady_clock;
using SparseMatrix = Eigen::SparseMatrix<double>;

double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double edgeLength(const SurfaceMesh& mesh, int a, int b)
{
  return norm(mesh.points[a] - mesh.points[b]);
}

// Triangles left after clipping ears, the clipped ears in clipping order (ear, before, after),
// and the remaining boundary loop.
struct ClippedMesh
{
  std::vector<char> keepTriangle;
  std::vector<std::array<int, 3>> ears;
  std::vector<int> loop;
};

ClippedMesh clipEars(const SurfaceMesh& mesh, const std::vector<int>& boundaryLoop)
{
  const size_t nv = mesh.points.size();
  ClippedMesh result;
  result.keepTriangle.assign(mesh.triangles.size(), 1);
  std::vector<int> degree(nv, 0), someTriangle(nv, -1);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    for (int v : mesh.triangles[t])
    {
      ++degree[v];
      someTriangle[v] = static_cast<int>(t);
    }
  }
  std::vector<int> next(nv, -1), prev(nv, -1);
  const size_t nb = boundaryLoop.size();
  for (size_t i = 0; i < nb; ++i)
  {
    next[boundaryLoop[i]] = boundaryLoop[(i + 1) % nb];
    prev[boundaryLoop[(i + 1) % nb]] = boundaryLoop[i];
  }
  // Clipping the triangles of a vertex's fan one by one: keep a per-vertex set of live
  // triangles only where needed (degree 1 after clipping) by rescanning the vertex's fan.
  std::vector<std::vector<int>> fan(nv);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    for (int v : mesh.triangles[t])
    {
      if (next[v] >= 0)
      {
        fan[v].push_back(static_cast<int>(t));
      }
    }
  }
  std::queue<int> candidates;
  for (int v : boundaryLoop)
  {
    if (degree[v] == 1)
    {
      candidates.push(v);
    }
  }
  size_t liveTriangles = mesh.triangles.size();
  size_t loopSize = nb;
  while (!candidates.empty())
  {
    const int ear = candidates.front();
    candidates.pop();
    // Keep at least a triangle, and never make the loop shorter than a triangle's.
    if (degree[ear] != 1 || liveTriangles <= 1 || loopSize <= 3)
    {
      continue;
    }
    int t = -1;
    for (int f : fan[ear])
    {
      if (result.keepTriangle[f])
      {
        t = f;
      }
    }
    const int before = prev[ear], after = next[ear];
    result.keepTriangle[t] = 0;
    --liveTriangles;
    --loopSize;
    degree[ear] = 0;
    --degree[before];
    --degree[after];
    next[before] = after;
    prev[after] = before;
    next[ear] = prev[ear] = -1;
    result.ears.push_back({ ear, before, after });
    for (int v : { before, after })
    {
      if (degree[v] == 1)
      {
        candidates.push(v);
      }
    }
  }
  // The remaining loop, starting where the input loop starts (or after it, if clipped).
  int start = -1;
  for (int v : boundaryLoop)
  {
    if (next[v] >= 0)
    {
      start = v;
      break;
    }
  }
  for (int v = start; result.loop.empty() || v != start; v = next[v])
  {
    result.loop.push_back(v);
  }
  return result;
}

// The flattening problem on the clipped mesh, in local numbering: boundary vertices first
// (in loop order), then interior vertices.
class DiskFlattening
{
public:
  DiskFlattening(const SurfaceMesh& mesh, const ClippedMesh& clipped, LaplacianWeights weights)
  {
    // At CHOLMOD's sizes, in two halves on both cores (SparseCholesky.h): the face at 1.09M
    // points factored in 6.0 s against 9.8 s in one run.
    Dirichlet.allowHalves(true);
    Neumann.allowHalves(true);
    const size_t nv = mesh.points.size();
    Local.assign(nv, -1);
    for (int v : clipped.loop)
    {
      Local[v] = static_cast<int>(Vertices.size());
      Vertices.push_back(v);
    }
    NB = static_cast<int>(Vertices.size());
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
    {
      if (!clipped.keepTriangle[t])
      {
        continue;
      }
      for (int v : mesh.triangles[t])
      {
        if (Local[v] < 0)
        {
          Local[v] = static_cast<int>(Vertices.size());
          Vertices.push_back(v);
        }
      }
    }
    N = static_cast<int>(Vertices.size());
    NI = N - NB;

    // Angle sums from the mesh; the cotangent Laplacian (positive semi-definite) from the mesh,
    // from the intrinsic Delaunay triangulation of its metric (no negative weight, so the
    // harmonic extension does not fold that triangulation; see IntrinsicDelaunay.h), or the
    // mesh's with its weights floored (none of the mesh's own triangles folds).
    AngleSum.assign(N, 0.0);
    std::vector<Triangle> kept;
    std::vector<std::array<double, 3>> lengths;
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
    {
      if (!clipped.keepTriangle[t])
      {
        continue;
      }
      const auto& tri = mesh.triangles[t];
      for (int k = 0; k < 3; ++k)
      {
        const int o = tri[k], i = tri[(k + 1) % 3], j = tri[(k + 2) % 3];
        const Vec3 u = mesh.points[i] - mesh.points[o], w = mesh.points[j] - mesh.points[o];
        AngleSum[Local[o]] += std::atan2(norm(cross(u, w)), dot(u, w));
      }
      kept.push_back({ Local[tri[0]], Local[tri[1]], Local[tri[2]] });
      lengths.push_back({ edgeLength(mesh, tri[1], tri[2]), edgeLength(mesh, tri[2], tri[0]),
        edgeLength(mesh, tri[0], tri[1]) });
    }
    L = laplacianOf(kept, lengths, N, weights, IntrinsicFlips);

    BoundaryLength.resize(NB);
    for (int i = 0; i < NB; ++i)
    {
      BoundaryLength[i] = edgeLength(mesh, Vertices[i], Vertices[(i + 1) % NB]);
    }
  }

  // Factors the Dirichlet (interior) and the Neumann (boundary vertex 0 pinned) Laplacians in
  // one factorization: the Neumann Laplacian's with its interior vertices first, whose leading
  // block is the Dirichlet one (SparseCholesky::computeWithLeadingBlock), and whose last block
  // is a dense factor of the boundary's Dirichlet-to-Neumann map, on which the iterations run
  // without solves (boundaryFlux). That last block costs NB^3 / 3 flops: for long boundaries
  // (factorTogether) the two Laplacians are factored apart, Eigen's
  // side by side (one per core), CHOLMOD's one after the other, asking `keepGoing` between the
  // steps: side by side, each on OpenBLAS's default threads, they oversubscribed the two cores
  // (1.09M points: 7.8 s against 6.6 s in turn), and OpenBLAS's thread count cannot be changed
  // safely at run time (design.md).
  bool factor(const std::function<bool()>& keepGoing)
  {
    Combined = NI > 0 && factorTogether(NB, N);
    // Combined: interior vertices (local NB..N-1) first, then boundary vertices 1..NB-1.
    auto neumannRow = [this](int local) {
      return !Combined ? local - 1 : local >= NB ? local - NB : NI + local - 1;
    };
    std::vector<Eigen::Triplet<double>> interior, pinned;
    for (int col = 0; col < N; ++col)
    {
      for (SparseMatrix::InnerIterator it(L, col); it; ++it)
      {
        const int row = static_cast<int>(it.row());
        if (row < col)
        {
          continue; // lower triangle
        }
        if (row >= NB && col >= NB)
        {
          if (!Combined) // else the leading block of LN
          {
            interior.emplace_back(row - NB, col - NB, it.value());
          }
        }
        else if (row >= NB && col < NB)
        {
          InteriorBoundaryEntries.emplace_back(row - NB, col, it.value());
        }
        if (row > 0 && col > 0)
        {
          const int r = neumannRow(row), c = neumannRow(col);
          pinned.emplace_back(std::max(r, c), std::min(r, c), it.value());
        }
      }
    }
    LIB.resize(NI, NB);
    LIB.setFromTriplets(InteriorBoundaryEntries.begin(), InteriorBoundaryEntries.end());
    SparseMatrix LN(N - 1, N - 1);
    LN.setFromTriplets(pinned.begin(), pinned.end());
    if (Combined)
    {
      if (!Neumann.computeWithLeadingBlock(LN, NI, keepGoing))
      {
        return false;
      }
      BoundaryOperator = Neumann.trailingSchurFactor();
      return true;
    }
    SparseMatrix LII(NI, NI);
    LII.setFromTriplets(interior.begin(), interior.end());
    if (N - 1 >= SparseCholesky::CholmodThreshold)
    {
      return (NI == 0 || Dirichlet.compute(LII, keepGoing)) && keepGoing() &&
        Neumann.compute(LN, keepGoing);
    }
    bool dirichletOk = true, neumannOk = true;
#pragma omp parallel sections num_threads(2)
    {
#pragma omp section
      dirichletOk = NI == 0 || Dirichlet.compute(LII);
#pragma omp section
      neumannOk = Neumann.compute(LN);
    }
    return dirichletOk && neumannOk;
  }

  // u with L u = rhs, u = 0 at the pinned vertex; rhs must sum to zero.
  Eigen::VectorXd solveNeumann(const Eigen::VectorXd& rhs) const
  {
    Eigen::VectorXd u(N);
    if (!Combined)
    {
      u << 0.0, Neumann.solve(rhs.tail(N - 1));
      return u;
    }
    Eigen::VectorXd ordered(N - 1);
    ordered << rhs.tail(NI), rhs.segment(1, NB - 1);
    const Eigen::VectorXd solution = Neumann.solve(ordered);
    u << 0.0, solution.tail(NB - 1), solution.head(NI);
    return u;
  }

  // w with X(v) = w . X_B for the harmonic extension X of any boundary values X_B (v interior):
  // X_I = -L_II^-1 L_IB X_B, so w = -L_BI L_II^-1 e_v.
  Eigen::VectorXd harmonicWeights(int v) const
  {
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(NI);
    unit[v - NB] = 1.0;
    const Eigen::VectorXd z = solveDirichlet(unit);
    return -(LIB.transpose() * z);
  }

  // Interior values of L_II x = rhs (NI rows).
  Eigen::MatrixXd solveDirichlet(const Eigen::MatrixXd& rhs) const
  {
    return Combined ? Neumann.solveLeading(rhs) : Dirichlet.solve(rhs);
  }

  // Boundary angles from one boundary-first-flattening step towards a circle.
  Eigen::VectorXd initialAngles() const
  {
    Eigen::VectorXd rhs(N);
    double dualTotal = 0.0;
    for (int i = 0; i < NB; ++i)
    {
      dualTotal += BoundaryLength[i];
    }
    for (int v = 0; v < N; ++v)
    {
      if (v < NB)
      {
        // Target geodesic curvature of a circle: proportional to the dual boundary length.
        const double dual = 0.5 * (BoundaryLength[v] + BoundaryLength[(v + NB - 1) % NB]);
        rhs[v] = TwoPi * dual / dualTotal - (Pi - AngleSum[v]);
      }
      else
      {
        rhs[v] = -(TwoPi - AngleSum[v]); // flat interior
      }
    }
    rhs.array() -= rhs.mean(); // exact Gauss-Bonnet balance despite rounding
    const Eigen::VectorXd u = solveNeumann(rhs);
    Eigen::VectorXd length(NB);
    for (int i = 0; i < NB; ++i)
    {
      length[i] = BoundaryLength[i] * std::exp(0.5 * (u[i] + u[(i + 1) % NB]));
    }
    return anglesFromLengths(length);
  }

  static Eigen::VectorXd anglesFromLengths(const Eigen::VectorXd& length)
  {
    const double total = length.sum();
    Eigen::VectorXd theta(length.size());
    double run = 0.0;
    for (Eigen::Index i = 0; i < length.size(); ++i)
    {
      theta[i] = TwoPi * run / total;
      run += length[i];
    }
    return theta;
  }

  // Boundary points at angles theta (NB x 2).
  Eigen::MatrixXd boundaryPoints(const Eigen::VectorXd& theta) const
  {
    Eigen::MatrixXd XB(NB, 2);
    XB.col(0) = theta.array().cos();
    XB.col(1) = theta.array().sin();
    return XB;
  }

  // Harmonic extension of boundary points at angles theta (N x 2, local numbering).
  Eigen::MatrixXd extend(const Eigen::VectorXd& theta) const
  {
    Eigen::MatrixXd X(N, 2);
    X.topRows(NB) = boundaryPoints(theta);
    if (NI > 0)
    {
      const Eigen::MatrixXd rhs = -(LIB * X.topRows(NB));
      if ((Combined ? Neumann : Dirichlet).concurrentSolvesAreSafe())
      {
        // u and v are independent solves: one per core.
#pragma omp parallel for num_threads(2)
        for (int c = 0; c < 2; ++c)
        {
          X.col(c).tail(NI) = solveDirichlet(rhs.col(c));
        }
      }
      else
      {
        X.bottomRows(NI) = solveDirichlet(rhs);
      }
    }
    return X;
  }

  // (L X) on the boundary for the harmonic extension X of the boundary points at angles theta:
  // the Dirichlet-to-Neumann map, which the combined factorization holds as a dense factor of
  // its Schur complement (O(NB^2), no solve over the interior).
  Eigen::MatrixXd boundaryFlux(const Eigen::VectorXd& theta) const
  {
    if (!Combined)
    {
      return (L * extend(theta)).topRows(NB);
    }
    // The pinned vertex 0's row and column follow from the rows summing to zero.
    const Eigen::MatrixXd XB = boundaryPoints(theta);
    const Eigen::MatrixXd relative = XB.bottomRows(NB - 1).rowwise() - XB.row(0);
    Eigen::MatrixXd flux(NB, 2);
    flux.bottomRows(NB - 1) = BoundaryOperator.apply(relative);
    flux.row(0) = -flux.bottomRows(NB - 1).colwise().sum();
    return flux;
  }

  // u on the boundary with L u = rhs (rhs zero inside, summing to zero), u = 0 at vertex 0.
  Eigen::VectorXd solveNeumannOnBoundary(const Eigen::VectorXd& boundaryRhs) const
  {
    if (!Combined)
    {
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(N);
      rhs.head(NB) = boundaryRhs;
      return solveNeumann(rhs).head(NB);
    }
    Eigen::VectorXd u(NB);
    u << 0.0, BoundaryOperator.solve(boundaryRhs.tail(NB - 1));
    return u;
  }

  // E_C of the harmonic extension, from its boundary flux (X . L X = XB . flux when L X = 0
  // inside).
  double conformalEnergy(const Eigen::VectorXd& theta, const Eigen::MatrixXd& flux) const
  {
    const Eigen::MatrixXd XB = boundaryPoints(theta);
    double dirichlet = 0.5 * (XB.col(0).dot(flux.col(0)) + XB.col(1).dot(flux.col(1)));
    double area = 0.0;
    for (int i = 0; i < NB; ++i)
    {
      area += 0.5 * std::sin(gap(theta, i));
    }
    return dirichlet - area;
  }

  // Angle from boundary vertex i to i + 1.
  double gap(const Eigen::VectorXd& theta, int i) const
  {
    return i + 1 < NB ? theta[i + 1] - theta[i] : theta[0] + TwoPi - theta[i];
  }

  bool ordered(const Eigen::VectorXd& theta) const
  {
    for (int i = 0; i < NB; ++i)
    {
      if (!(gap(theta, i) > 0.0))
      {
        return false;
      }
    }
    return true;
  }

  // Preconditioned descent direction of the conformal energy in theta, Moebius modes removed.
  Eigen::VectorXd descentDirection(const Eigen::VectorXd& theta, const Eigen::MatrixXd& flux) const
  {
    Eigen::VectorXd gradient(NB), weight(NB);
    for (int i = 0; i < NB; ++i)
    {
      const double before = gap(theta, (i + NB - 1) % NB), after = gap(theta, i);
      gradient[i] = -std::sin(theta[i]) * flux(i, 0) + std::cos(theta[i]) * flux(i, 1) -
        0.5 * (std::cos(before) - std::cos(after));
      weight[i] = 0.5 * (before + after);
    }
    Eigen::VectorXd d = solveNeumannOnBoundary(gradient.array() - gradient.mean());
    // Rotations and Moebius maps barely change the energy: remove {1, cos, sin} from the step
    // (weighted least squares over the circle) so the iteration does not drift along them.
    Eigen::MatrixXd modes(NB, 3);
    modes.col(0).setOnes();
    modes.col(1) = theta.array().cos();
    modes.col(2) = theta.array().sin();
    const Eigen::MatrixXd weighted = weight.asDiagonal() * modes;
    const Eigen::Vector3d coefficients =
      (modes.transpose() * weighted).ldlt().solve(weighted.transpose() * d);
    d -= modes * coefficients;
    return -d;
  }

  int N = 0, NB = 0, NI = 0;
  std::vector<int> Vertices; // local -> mesh
  std::vector<int> Local;    // mesh -> local (-1: clipped ear)
  int IntrinsicFlips = 0;    // edge flips to the intrinsic Delaunay triangulation
  std::vector<double> AngleSum;
  std::vector<double> BoundaryLength; // boundary edge i -> i + 1
  SparseMatrix L, LIB;
  std::vector<Eigen::Triplet<double>> InteriorBoundaryEntries;
  SparseCholesky Dirichlet, Neumann;
  bool Combined = false; // Neumann's factor also solves the Dirichlet problem
  SparseCholesky::SchurFactor BoundaryOperator; // Combined: the pinned Dirichlet-to-Neumann map
};

std::complex<double> moebius(std::complex<double> z, std::complex<double> a)
{
  return (z - a) / (1.0 - std::conj(a) * z);
}

// The automatic centre: the Moebius normalization that puts the centre of mass of the surface
// area (triangle centroids in the disk, weighted by surface area) at the origin, then the
// interior vertex nearest to it. A vertex "farthest from the boundary" would be a finger tip
// on a hand, leaving the palm squeezed against the circle; the area barycentre balances the
// area distortion that the sampler and the OT solver face. Fixed-point iteration of the
// Douady-Earle kind: compose with the Moebius map of the current barycentre until it is 0.
// -1 when no interior vertex is at a finite distance from it (weights or images not finite).
int areaBarycentreVertex(const SurfaceMesh& mesh, const ClippedMesh& clipped,
  const DiskFlattening& disk, const Eigen::MatrixXd& X)
{
  std::vector<std::complex<double>> centroid;
  std::vector<double> weight;
  double total = 0.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    if (!clipped.keepTriangle[t])
    {
      continue;
    }
    std::complex<double> c = 0.0;
    for (int v : mesh.triangles[t])
    {
      const int l = disk.Local[v];
      c += std::complex<double>(X(l, 0), X(l, 1)) / 3.0;
    }
    centroid.push_back(c);
    weight.push_back(triangleArea(mesh, mesh.triangles[t]));
    total += weight.back();
  }
  std::complex<double> a = 0.0;
  for (int it = 0; it < 200; ++it)
  {
    std::complex<double> b = 0.0;
    for (size_t t = 0; t < centroid.size(); ++t)
    {
      b += weight[t] / total * moebius(centroid[t], a);
    }
    if (std::abs(b) < 1e-12)
    {
      break;
    }
    // moebius(., b) o moebius(., a) sends moebius^-1(b, a) to 0: the new normalization point.
    a = (b + a) / (1.0 + std::conj(a) * b);
  }
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (int l = disk.NB; l < disk.N; ++l)
  {
    const double d = std::abs(moebius(std::complex<double>(X(l, 0), X(l, 1)), a));
    if (d < bestDistance)
    {
      bestDistance = d;
      best = l;
    }
  }
  return best;
}

std::int64_t foldedTriangles(const SurfaceMesh& mesh, const std::vector<Vec2>& uv)
{
  std::int64_t folded = 0;
  for (const Triangle& t : mesh.triangles)
  {
    folded += !(cross(uv[t[1]] - uv[t[0]], uv[t[2]] - uv[t[0]]) > 0.0);
  }
  return folded;
}

// What is wrong with the normalization vertices or the stopping rule, or "".
std::string checkOptions(
  const ConformalDiskMapOptions& options, const std::vector<char>& onBoundary, int nv)
{
  std::ostringstream msg;
  if (options.centerVertex >= nv || options.centerVertex < -1)
  {
    msg << "the centre vertex " << options.centerVertex << " is not a point id in [0, " << nv
        << ")";
  }
  else if (options.centerVertex >= 0 && onBoundary[options.centerVertex])
  {
    msg << "the centre vertex " << options.centerVertex
        << " is on the boundary; it must be an interior vertex (it goes to the disk's centre)";
  }
  else if (options.alignVertex >= nv || options.alignVertex < -1)
  {
    msg << "the align vertex " << options.alignVertex << " is not a point id in [0, " << nv << ")";
  }
  else if (options.alignVertex >= 0 && !onBoundary[options.alignVertex])
  {
    msg << "the align vertex " << options.alignVertex
        << " is not on the boundary; it must be a boundary vertex (it goes to (1, 0))";
  }
  else if (!(options.tolerance > 0.0) || options.maximumNumberOfIterations < 0)
  {
    msg << "the tolerance must be positive and the iteration count non-negative";
  }
  return msg.str();
}

// Descent on the boundary angles theta: the conformal energy decreases at every accepted
// step. Returns false when the progress callback aborts.
bool minimizeConformalEnergy(const DiskFlattening& disk, const ConformalDiskMapOptions& options,
  const std::function<bool(double)>& keepGoing, Eigen::VectorXd& theta,
  ConformalDiskMapResult& result)
{
  Eigen::MatrixXd flux = disk.boundaryFlux(theta);
  double energy = disk.conformalEnergy(theta, flux);
  for (int it = 0; it < options.maximumNumberOfIterations; ++it)
  {
    const Eigen::VectorXd direction = disk.descentDirection(theta, flux);
    // The preconditioned Hessian's spectrum is ~[1/2, 1): 4/3 is the best fixed step (each
    // mode contracts by <= 1/3); measured 8-12 iterations instead of 11-18 with step 1.
    double step = 4.0 / 3.0;
    bool accepted = false;
    Eigen::VectorXd trial;
    Eigen::MatrixXd trialFlux;
    double trialEnergy = energy;
    for (int halving = 0; halving < 12 && !accepted; ++halving, step *= 0.5)
    {
      trial = theta + step * direction;
      if (!disk.ordered(trial))
      {
        continue;
      }
      trialFlux = disk.boundaryFlux(trial);
      trialEnergy = disk.conformalEnergy(trial, trialFlux);
      accepted = trialEnergy <= energy;
    }
    if (!accepted)
    {
      break; // the energy is flat to rounding: converged
    }
    step *= 2.0; // undo the loop's last halving
    result.iterations = it + 1;
    result.lastAngleUpdate = step * direction.cwiseAbs().maxCoeff();
    theta = trial;
    flux = trialFlux;
    energy = trialEnergy;
    if (!keepGoing(0.2 + 0.6 * (it + 1) / std::max(1, options.maximumNumberOfIterations)))
    {
      return false;
    }
    if (result.lastAngleUpdate < options.tolerance)
    {
      break;
    }
  }
  result.conformalEnergy = energy;
  if (result.iterations == options.maximumNumberOfIterations &&
    !(result.lastAngleUpdate < options.tolerance))
  {
    std::ostringstream msg;
    msg << "The boundary angles did not settle in MaximumNumberOfIterations = "
        << options.maximumNumberOfIterations << " iterations (the last one moved an angle by "
        << result.lastAngleUpdate << " rad, above Tolerance = " << options.tolerance
        << "): the map is less conformal than asked; raise MaximumNumberOfIterations.";
    result.status.warnings.push_back(msg.str());
  }
  return true;
}

// Moebius normalization on the boundary angles, the interior following as the harmonic
// extension; the discrete map is not exactly Moebius-equivariant, so a few rounds take the
// centre's offset down (by ~500x per round, measured); the last bit is applied to the points.
// Returns false when `keepGoing` aborts (checked every round).
bool centreByMoebius(const DiskFlattening& disk, int center,
  const std::function<bool(double)>& keepGoing, Eigen::VectorXd& theta, Eigen::MatrixXd& X)
{
  // The centre's image is a fixed combination of the boundary points (one solve): the rounds
  // then need no extension, only the last one.
  const Eigen::VectorXd weight = disk.harmonicWeights(center);
  for (int round = 0; round < 8; ++round)
  {
    if (!keepGoing(0.8 + 0.02 * round))
    {
      return false;
    }
    const Eigen::MatrixXd XB = disk.boundaryPoints(theta);
    const std::complex<double> a(weight.dot(XB.col(0)), weight.dot(XB.col(1)));
    if (std::abs(a) < 1e-9)
    {
      break;
    }
    Eigen::VectorXd moved(disk.NB);
    for (int i = 0; i < disk.NB; ++i)
    {
      moved[i] = std::arg(moebius(std::polar(1.0, theta[i]), a));
    }
    // Unwrap so that the angles increase from moved[0].
    for (int i = 1; i < disk.NB; ++i)
    {
      while (moved[i] <= moved[i - 1])
      {
        moved[i] += TwoPi;
      }
    }
    if (!disk.ordered(moved))
    {
      break; // the centre is so close to the circle that angles collapse in double precision
    }
    theta = moved;
  }
  X = disk.extend(theta);
  return true;
}

// Results per mesh point: the solve's points, clipped ears between their neighbours, with the
// exact final rotation and centring.
void placePoints(const SurfaceMesh& mesh, const ClippedMesh& clipped, const DiskFlattening& disk,
  const Eigen::VectorXd& theta, const Eigen::MatrixXd& X, int center,
  const std::vector<char>& onBoundary, ConformalDiskMapResult& result)
{
  const int nv = static_cast<int>(mesh.points.size());
  std::vector<double> angle(nv, 0.0);
  for (int i = 0; i < disk.NB; ++i)
  {
    angle[disk.Vertices[i]] = theta[i];
  }
  for (auto it = clipped.ears.rbegin(); it != clipped.ears.rend(); ++it)
  {
    const auto [ear, before, after] = *it;
    double span = std::remainder(angle[after] - angle[before], TwoPi);
    if (span <= 0.0)
    {
      span += TwoPi;
    }
    const double a = edgeLength(mesh, before, ear), b = edgeLength(mesh, ear, after);
    angle[ear] = angle[before] + span * a / (a + b);
  }
  // Exact final rotation and centring: the remaining centre offset is below 1e-9, so the
  // Moebius map applied to the points themselves changes the triangles negligibly.
  const std::complex<double> a(X(center, 0), X(center, 1));
  const double alignAngle = std::arg(moebius(std::polar(1.0, angle[result.alignVertex]), a));
  const std::complex<double> rotation = std::polar(1.0, -alignAngle);
  result.uv.assign(nv, Vec2());
  for (int v = 0; v < nv; ++v)
  {
    if (onBoundary[v])
    {
      // Exactly on the circle: cos/sin of the final angle, (1, 0) for the align vertex.
      const double final = v == result.alignVertex
        ? 0.0
        : std::arg(moebius(std::polar(1.0, angle[v]), a)) - alignAngle;
      result.uv[v] = { std::cos(final), std::sin(final) };
    }
    else
    {
      const int local = disk.Local[v];
      const std::complex<double> z =
        rotation * moebius(std::complex<double>(X(local, 0), X(local, 1)), a);
      result.uv[v] = { z.real(), z.imag() };
    }
  }
  result.uv[result.centerVertex] = { 0.0, 0.0 };
}

ConformalDiskMapResult computeWithLaplacian(const SurfaceMesh& mesh,
  const std::vector<int>& boundaryLoop, const ConformalDiskMapOptions& options,
  LaplacianWeights weights)
{
  ConformalDiskMapResult result;
  const int nv = static_cast<int>(mesh.points.size());
  std::vector<char> onBoundary(nv, 0);
  for (int v : boundaryLoop)
  {
    onBoundary[v] = 1;
  }
  result.status.error = checkOptions(options, onBoundary, nv);
  if (!result.status.error.empty())
  {
    return result;
  }
  auto keepGoing = [&](double fraction)
  {
    result.status.aborted = options.progress && !options.progress(fraction);
    return !result.status.aborted;
  };

  result.alignVertex = options.alignVertex >= 0
    ? options.alignVertex
    : *std::min_element(boundaryLoop.begin(), boundaryLoop.end());
  if (static_cast<size_t>(nv) == boundaryLoop.size())
  {
    result.status.error = "the surface has no interior vertex to send to the disk's centre (all " +
      std::to_string(nv) +
      " of its points are on its boundary): subdivide it until it has interior points (e.g. "
      "vtkLoopSubdivisionFilter, ParaView's Loop Subdivision)";
    return result;
  }

  auto t0 = Clock::now();
  const ClippedMesh clipped = clipEars(mesh, boundaryLoop);
  result.clippedEars = static_cast<int>(clipped.ears.size());
  DiskFlattening disk(mesh, clipped, weights);
  result.intrinsicFlips = disk.IntrinsicFlips;
  if (!keepGoing(0.05))
  {
    return result;
  }
  double fraction = 0.05;
  const bool factored = disk.factor([&] { return keepGoing(fraction += 0.04); });
  if (result.status.aborted)
  {
    return result;
  }
  if (!factored)
  {
    result.status.error = "the cotangent Laplacian could not be factored (degenerate triangles?)";
    return result;
  }
  result.secondsFactorization = secondsSince(t0);
  if (!keepGoing(0.2))
  {
    return result;
  }

  t0 = Clock::now();
  Eigen::VectorXd theta = disk.initialAngles();
  if (!disk.ordered(theta) || !theta.allFinite())
  {
    // Lengths are positive, so this only happens on overflow: fall back to arc length.
    Eigen::Map<const Eigen::VectorXd> lengths(disk.BoundaryLength.data(), disk.NB);
    theta = DiskFlattening::anglesFromLengths(lengths);
  }
  if (!minimizeConformalEnergy(disk, options, keepGoing, theta, result))
  {
    return result;
  }
  Eigen::MatrixXd X = disk.extend(theta);
  const int barycentre =
    options.centerVertex >= 0 ? -1 : areaBarycentreVertex(mesh, clipped, disk, X);
  if (options.centerVertex < 0 && barycentre < 0)
  {
    // Found by the fuzzer: a disk squashed onto a line passes the mesh checks, but its
    // flattening (and so every distance to the area barycentre) is not finite.
    result.status.error = "the flattened surface is not finite: the surface is too thin, too "
                          "large or too small for double precision (a collapsed dimension? "
                          "rescale the coordinates to a size near 1)";
    return result;
  }
  result.centerVertex =
    options.centerVertex >= 0 ? options.centerVertex : disk.Vertices[barycentre];
  const int center = disk.Local[result.centerVertex];
  if (!centreByMoebius(disk, center, keepGoing, theta, X))
  {
    return result;
  }
  result.secondsIterations = secondsSince(t0);
  placePoints(mesh, clipped, disk, theta, X, center, onBoundary, result);
  keepGoing(1.0);
  return result;
}
} // namespace

namespace
{
// The seconds of the map `from` added to those of `into` (a fallback dropped, or the one kept
// counting the maps tried before it).
void addSeconds(const ConformalDiskMapResult& from, ConformalDiskMapResult& into)
{
  into.secondsFactorization += from.secondsFactorization;
  into.secondsIterations += from.secondsIterations;
}
} // namespace

// The mesh's own cotangent Laplacian gives the most faithful angles on the mesh's triangles,
// but its weights go negative across obtuse triangles, and where they do the harmonic map can
// fold (a height field with steep bumps: 200 flipped triangles). The intrinsic Delaunay
// Laplacian cannot fold, but on scans full of slivers it is less faithful to their triangles
// (face_maxplanck_partial_32k: mean angle error 1.53 instead of 0.51 degrees). So it is the
// fallback, kept when it folds fewer triangles. It folds the mesh's triangles where it leaves a
// point two neighbours; the floored weights then cannot fold them (CotangentLaplacian.h).
ConformalDiskMapResult computeConformalDiskMap(const SurfaceMesh& mesh,
  const std::vector<int>& boundaryLoop, const ConformalDiskMapOptions& options)
{
  ConformalDiskMapResult result =
    computeWithLaplacian(mesh, boundaryLoop, options, LaplacianWeights::Mesh);
  if (!result.status.error.empty() || result.status.aborted)
  {
    return result;
  }
  result.foldedWithMeshLaplacian = foldedTriangles(mesh, result.uv);
  ConformalDiskMapOptions again = options;
  if (options.progress)
  {
    // Progress already reached 1: the other solves only check for an abort.
    again.progress = [&options](double) { return options.progress(1.0); };
  }
  tryFallbackLaplacians(
    result.foldedWithMeshLaplacian,
    [&](LaplacianWeights weights)
    { return computeWithLaplacian(mesh, boundaryLoop, again, weights); },
    [&](const ConformalDiskMapResult& other) -> std::int64_t
    { return other.status.error.empty() ? foldedTriangles(mesh, other.uv) : -1; },
    [&](ConformalDiskMapResult&& other, LaplacianWeights weights)
    {
      other.intrinsicLaplacian = weights == LaplacianWeights::IntrinsicDelaunay;
      other.flooredWeights = weights == LaplacianWeights::Floored;
      other.foldedWithMeshLaplacian = result.foldedWithMeshLaplacian;
      addSeconds(result, other);
      result = std::move(other);
    },
    [&](const ConformalDiskMapResult& other) { addSeconds(other, result); });
  return result;
}

} // namespace otparam
