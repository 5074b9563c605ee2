#include "Transport/SphericalOT.h"

#include "Common/SphericalGeometry.h"
#include "Transport/DampedNewton.h"
#include "Transport/MultiscaleStart.h"
#include "Transport/SphericalPowerDiagram.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>

namespace otparam
{
namespace
{
using Clock = std::chrono::steady_clock;

int maximumThreads()
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

int threadNumber()
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct Evaluation : NewtonEvaluation
{
  std::vector<Vec3> moment;
  bool covers = false; // the origin is inside the hull: the cells cover the sphere
};

// The Hessian coupling of neighbours i, j whose cells share the arc from p to q:
// (1 / |a_i - a_j|) * integral over the arc of <x, a_j> ds with a = y / h (sphere.md). The
// integral of x over the arc is its chord length times its mid-direction, which keeps its
// precision for short arcs; the factors e^-psi_j of both terms cancel.
double coupling(const Vec3& yi, const Vec3& yj, const Height& psiI, const Height& psiJ,
  const Vec3& p, const Vec3& q)
{
  const Vec3 sum = p + q;
  const double sumLength = norm(sum);
  if (sumLength == 0.0)
  {
    return 0.0;
  }
  const double arcMoment = norm(q - p) * dot(yj, sum) / sumLength;
  return arcMoment / norm(scaledDifference(yi, yj, psiI, psiJ));
}

// Cell areas, moments and Hessian couplings at log-heights psi. When the diagram hides a Dirac
// or does not cover the sphere, every mass is 0 (a Newton trial is then rejected).
// previous, when given, is the diagram of the same Diracs at other heights, flipped into this one.
void evaluate(const std::vector<Vec3>& diracs, const std::vector<Height>& psi,
  SphericalPowerDiagram& diagram, Evaluation& ev, NewtonReport& timing,
  const SphericalPowerDiagram* previous = nullptr)
{
  const int n = static_cast<int>(diracs.size());
  auto t0 = Clock::now();
  ev.covers = previous ? diagram.buildFrom(*previous, diracs, psi) : diagram.build(diracs, psi);
  timing.secondsTriangulation += secondsSince(t0);
  ev.cellMass.assign(n, 0.0);
  ev.moment.assign(n, Vec3{});
  ev.coupling.clear();
  ev.emptyCells = diagram.hiddenCount();
  ev.minMass = 0.0;
  if (!ev.covers || diagram.hiddenCount() > 0)
  {
    ev.emptyCells = std::max(ev.emptyCells, 1);
    return;
  }
  t0 = Clock::now();
  const std::vector<Vec3>& vertices = diagram.cellVertices();
  // Each thread takes one contiguous block of Diracs, and the blocks' couplings are joined in
  // order: the couplings come in the order of a serial loop whatever the number of threads, so
  // that the Newton system (and the run) is reproducible without sorting them.
  std::vector<std::vector<Eigen::Triplet<double>>> blocks(maximumThreads());
#pragma omp parallel
  {
    std::vector<Eigen::Triplet<double>>& local = blocks[threadNumber()];
    std::vector<Vec3> polygon;
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i)
    {
      diagram.cell(i, polygon);
      ev.cellMass[i] = std::max(0.0, sphericalPolygonArea(polygon));
      ev.moment[i] = sphericalPolygonMoment(polygon);
      const int* ring = diagram.ringBegin(i);
      const int degree = static_cast<int>(diagram.ringEnd(i) - ring);
      for (int k = 0; k < degree; ++k)
      {
        const int j = diagram.neighborsBegin(i)[k];
        if (j > i)
        {
          const double c = coupling(diracs[i], diracs[j], psi[i], psi[j], vertices[ring[k]],
            vertices[ring[(k + 1) % degree]]);
          if (c > 0.0)
          {
            local.emplace_back(i, j, c);
          }
        }
      }
    }
  }
  for (const auto& block : blocks)
  {
    ev.coupling.insert(ev.coupling.end(), block.begin(), block.end());
  }
  ev.minMass = n ? *std::min_element(ev.cellMass.begin(), ev.cellMass.end()) : 0.0;
  ev.emptyCells = static_cast<int>(std::count(ev.cellMass.begin(), ev.cellMass.end(), 0.0));
  timing.secondsIntegration += secondsSince(t0);
}

class SphericalNewtonProblem final : public NewtonProblem
{
public:
  SphericalNewtonProblem(
    const std::vector<Vec3>& diracs, SphericalPowerDiagram& diagram, Evaluation& ev)
    : Diracs(diracs)
    , Diagram(diagram)
    , Ev(ev)
  {
  }
  const NewtonEvaluation& current() const override { return this->Ev; }
  bool certainlyHidesADirac(const std::vector<Height>&, NewtonReport&) override { return false; }
  const NewtonEvaluation& evaluateTrial(
    const std::vector<Height>& trial, NewtonReport& timing) override
  {
    evaluate(this->Diracs, trial, this->TrialDiagram, this->TrialEv, timing, &this->Diagram);
    return this->TrialEv;
  }
  void acceptTrial() override
  {
    std::swap(this->Ev, this->TrialEv);
    std::swap(this->Diagram, this->TrialDiagram);
  }

private:
  const std::vector<Vec3>& Diracs;
  SphericalPowerDiagram& Diagram;
  Evaluation& Ev;
  SphericalPowerDiagram TrialDiagram;
  Evaluation TrialEv;
};

std::string listIds(const char* what, const std::vector<size_t>& ids)
{
  std::ostringstream msg;
  msg << ids.size() << " Dirac(s) " << what << " (point ids";
  for (size_t k = 0; k < std::min<size_t>(ids.size(), 10); ++k)
  {
    msg << ' ' << ids[k];
  }
  msg << (ids.size() > 10 ? " ...)" : ")");
  return msg.str();
}

// Log-heights from the coarse-to-fine start (MultiscaleStart.h), evaluated; false (and nothing
// changed but the timings) when there is none or it hides a Dirac.
bool startFromCoarseLevel(const std::vector<Vec3>& diracs, const std::vector<double>& nu,
  std::vector<Height>& psi, SphericalPowerDiagram& diagram, Evaluation& ev, NewtonReport& timing)
{
  std::vector<Height> start;
  if (!sphericalCoarseToFineLogHeights(diracs, nu, start))
  {
    return false;
  }
  evaluate(diracs, start, diagram, ev, timing);
  if (ev.minMass <= 0.0)
  {
    return false;
  }
  psi.swap(start);
  return true;
}

void solveByNewton(const std::vector<Vec3>& diracs, const std::vector<double>& nu,
  std::vector<Height>& psi, SphericalPowerDiagram& diagram, Evaluation& ev,
  const OTOptions& options, NewtonReport& report)
{
  SphericalNewtonProblem problem(diracs, diagram, ev);
  NewtonOptions newton = newtonOptionsOf(options);
  newton.fullStepFirst = false;
  dampedNewton(problem, nu, psi, newton, report);
}

std::vector<Height> toHeights(const std::vector<double>& psi)
{
  return std::vector<Height>(psi.begin(), psi.end());
}
} // namespace

std::string validateSphericalDiracs(std::vector<Vec3>& diracs, const std::vector<double>& masses)
{
  if (diracs.size() < 4)
  {
    std::ostringstream msg;
    msg << "there are " << diracs.size()
        << " Diracs; the sphere needs at least 4 (not all in one hemisphere)";
    return msg.str();
  }
  if (masses.size() != diracs.size())
  {
    std::ostringstream msg;
    msg << "there are " << diracs.size() << " Diracs but " << masses.size() << " masses";
    return msg.str();
  }
  std::vector<size_t> bad;
  for (size_t i = 0; i < diracs.size(); ++i)
  {
    const double r = norm(diracs[i]);
    if (!(std::abs(r - 1.0) <= 1e-6))
    {
      bad.push_back(i);
    }
  }
  if (!bad.empty())
  {
    std::ostringstream msg;
    msg << listIds("are not on the unit sphere", bad) << "; the first is at distance "
        << norm(diracs[bad.front()]) << " from the origin (the sphere's Diracs need |y| = 1)";
    return msg.str();
  }
  for (size_t i = 0; i < masses.size(); ++i)
  {
    if (!(std::isfinite(masses[i]) && masses[i] > 0.0))
    {
      bad.push_back(i);
    }
  }
  if (!bad.empty())
  {
    std::ostringstream msg;
    msg << listIds("have a Mass that is not finite and positive", bad) << "; the first is "
        << masses[bad.front()];
    return msg.str();
  }
  for (Vec3& y : diracs)
  {
    y = normalized(y);
  }
  std::vector<size_t> order(diracs.size());
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](size_t a, size_t b)
  {
    const Vec3 p = diracs[a], q = diracs[b];
    return p.x < q.x || (p.x == q.x && (p.y < q.y || (p.y == q.y && p.z < q.z)));
  };
  std::sort(order.begin(), order.end(), less);
  for (size_t k = 1; k < order.size(); ++k)
  {
    if (!less(order[k - 1], order[k]))
    {
      bad.push_back(std::min(order[k - 1], order[k]));
      bad.push_back(std::max(order[k - 1], order[k]));
    }
  }
  if (!bad.empty())
  {
    return listIds("share their position with another Dirac", bad);
  }
  SphericalPowerDiagram voronoi;
  if (!voronoi.build(diracs, std::vector<Height>(diracs.size())))
  {
    return "the Diracs lie in one closed hemisphere: no transport of the uniform sphere onto "
           "them exists (Alexandrov's condition fails; cells would have to reach beyond 90 "
           "degrees)";
  }
  return std::string();
}

SphericalOTResult solveSphericalOT(
  const std::vector<Vec3>& diracs, const std::vector<double>& masses, const OTOptions& options)
{
  SphericalOTResult result;
  const int n = static_cast<int>(diracs.size());
  result.mass = massesScaledTo(masses, 4.0 * M_PI);
  std::vector<Height> psi;
  SphericalPowerDiagram diagram;
  Evaluation ev;
  const bool multiscale = options.coarseToFineStart &&
    startFromCoarseLevel(diracs, result.mass, psi, diagram, ev, result);
  if (!multiscale)
  {
    psi.assign(n, Height(0.0L));
    evaluate(diracs, psi, diagram, ev, result);
  }
  if (ev.minMass <= 0.0)
  {
    result.message = ev.covers
      ? "a Dirac has no Voronoi cell (Diracs too close for double precision?)"
      : "the Diracs lie in one closed hemisphere (Alexandrov's condition fails)";
  }
  else
  {
    solveByNewton(diracs, result.mass, psi, diagram, ev, options, result);
    // As on the plane (SemiDiscreteOT.cxx): a start that stalls far from the solution is
    // dropped for the Voronoi start.
    if (multiscale && !result.converged && !result.aborted &&
      result.iterations < options.maximumNumberOfIterations && result.relativeError > 1e-3)
    {
      const std::string stalled = result.message;
      result.gradientNormHistory.clear();
      result.stepLengthHistory.clear();
      psi.assign(n, Height(0.0L));
      evaluate(diracs, psi, diagram, ev, result);
      solveByNewton(diracs, result.mass, psi, diagram, ev, options, result);
      result.message = "the coarse-to-fine start stalled (" + stalled +
        "); restarted from the Voronoi start: " + result.message;
    }
  }
  long double mean = 0.0L;
  for (const Height& h : psi)
  {
    mean += h.value();
  }
  mean /= std::max(n, 1);
  result.heights.resize(n);
  result.centroids.resize(n);
  result.cellMass = ev.cellMass;
  for (int i = 0; i < n; ++i)
  {
    result.heights[i] = static_cast<double>(psi[i].value() - mean);
    const double m = norm(ev.moment[i]);
    result.centroids[i] = m > 0.0 ? (1.0 / m) * ev.moment[i] : diracs[i];
  }
  for (int i = 0; i < n && ev.minMass > 0.0; ++i)
  {
    for (const Vec3& v : diagram.cell(i))
    {
      result.largestTransportDegrees =
        std::max(result.largestTransportDegrees, sphericalDistance(v, diracs[i]) * 180.0 / M_PI);
    }
  }
  if (!result.converged && !result.aborted && result.largestTransportDegrees > 80.0)
  {
    std::ostringstream msg;
    msg << result.message << "; cells reach " << result.largestTransportDegrees
        << " degrees from their Diracs: the masses nearly fail Alexandrov's condition (too much "
           "mass gathered in one hemisphere)";
    result.message = msg.str();
  }
  return result;
}

SphericalCellMeasures computeSphericalCellMeasures(
  const std::vector<Vec3>& diracs, const std::vector<double>& psi, bool denseCouplings)
{
  const int n = static_cast<int>(diracs.size());
  SphericalPowerDiagram diagram;
  Evaluation ev;
  NewtonReport timing;
  evaluate(diracs, toHeights(psi), diagram, ev, timing);
  SphericalCellMeasures out;
  out.area = ev.cellMass;
  out.centroid.resize(n);
  for (int i = 0; i < n; ++i)
  {
    const double m = norm(ev.moment[i]);
    out.centroid[i] = m > 0.0 ? (1.0 / m) * ev.moment[i] : diracs[i];
  }
  if (denseCouplings)
  {
    out.coupling.assign(static_cast<size_t>(n) * n, 0.0);
    for (const auto& c : ev.coupling)
    {
      out.coupling[static_cast<size_t>(c.row()) * n + c.col()] = c.value();
      out.coupling[static_cast<size_t>(c.col()) * n + c.row()] = c.value();
    }
  }
  return out;
}

SphericalPowerDiagramGeometry computeSphericalPowerDiagramGeometry(
  const std::vector<Vec3>& diracs, const std::vector<double>& psi, double maxArcAngle)
{
  const int n = static_cast<int>(diracs.size());
  SphericalPowerDiagram diagram;
  const std::vector<Height> heights = toHeights(psi);
  diagram.build(diracs, heights);
  SphericalPowerDiagramGeometry g;
  g.triangles = diagram.triangles();
  for (size_t f = 0; f < g.triangles.size(); ++f)
  {
    g.polytopeVertices.push_back(diagram.polytopeVertex(static_cast<int>(f)));
  }
  for (int i = 0; i < n; ++i)
  {
    g.hullPoints.push_back(static_cast<double>(std::exp(-heights[i].value())) * diracs[i]);
    if (diagram.hidden(i))
    {
      continue;
    }
    std::vector<Vec3> boundary;
    const std::vector<Vec3> corners = diagram.cell(i);
    for (size_t k = 0; k < corners.size(); ++k)
    {
      const Vec3 p = corners[k], q = corners[(k + 1) % corners.size()];
      const int pieces =
        std::max(1, static_cast<int>(std::ceil(sphericalDistance(p, q) / maxArcAngle)));
      for (int s = 0; s < pieces; ++s)
      {
        const double t = static_cast<double>(s) / pieces;
        boundary.push_back(normalized((1.0 - t) * p + t * q));
      }
    }
    g.cells.push_back(boundary);
    g.cellDirac.push_back(i);
    g.polytopeFaces.emplace_back(diagram.ringBegin(i), diagram.ringEnd(i));
    g.polytopeFaceDirac.push_back(i);
  }
  return g;
}

} // namespace otparam
