#include "Transport/SemiDiscreteOT.h"

#include "Common/Status.h"
#include "Transport/DampedNewton.h"
#include "Transport/MultiscaleStart.h"
#include "Transport/PlanarPowerDiagram.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hilbert_sort_2.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <sstream>

namespace otparam
{
namespace
{
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The Newton evaluation plus each cell's moment (its centroid times its mass).
struct Evaluation : NewtonEvaluation
{
  std::vector<Vec2> moment;
};

// The source box, a little larger so that its edges never touch the domain.
void sourceBox(const SourceMeasure& source, Vec2& lo, Vec2& hi)
{
  source.bounds(lo, hi);
  const double margin = 0.01 * std::max(hi.x - lo.x, hi.y - lo.y) + 1e-12;
  lo = lo - Vec2{ margin, margin };
  hi = hi + Vec2{ margin, margin };
}

// Cell masses, moments and (withCouplings) Hessian couplings at the given heights. Unless
// whenHidden is FindAll, a hidden Dirac (empty cell) ends the evaluation early with all masses
// 0: a Newton trial is then rejected anyway, without paying for the integration.
void evaluate(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<Height>& heights, PowerDiagram& diagram, Evaluation& ev, NewtonReport& timing,
  PowerDiagram::WhenHidden whenHidden = PowerDiagram::WhenHidden::StopAtFirst,
  bool withCouplings = true)
{
  const int n = static_cast<int>(diracs.size());
  auto t0 = Clock::now();
  diagram.build(diracs, heights, whenHidden);
  timing.secondsTriangulation += secondsSince(t0);
  if (whenHidden != PowerDiagram::WhenHidden::FindAll && diagram.hiddenCount() > 0)
  {
    ev.cellMass.assign(n, 0.0);
    ev.moment.assign(n, Vec2{});
    ev.coupling.clear();
    ev.minMass = 0.0;
    ev.emptyCells = diagram.hiddenCount();
    return;
  }

  t0 = Clock::now();
  Vec2 lo, hi;
  sourceBox(source, lo, hi);
  ev.cellMass.assign(n, 0.0);
  ev.moment.assign(n, Vec2{});
  // Couplings in row order, each row in the order of its cell's edges, so that the Newton
  // system (and the whole run) is the same every time whatever thread integrates which cell
  // (without a fixed order the Hessian's rounding varied from run to run, and a run could end
  // near the tolerance one time and not the next). Each row gets a slot per neighbour above it
  // (a convex cell has at most one edge per neighbour) and the unused slots are squeezed out
  // afterwards: no per-thread copies and no reordering copy (1e6 Diracs: 46 MiB less at the
  // solver's peak).
  std::vector<int> rowStart(n + 1, 0), rowCount(n, 0);
  if (withCouplings)
  {
    for (int i = 0; i < n; ++i)
    {
      rowStart[i + 1] = rowStart[i] +
        static_cast<int>(std::count_if(diagram.neighborsBegin(i), diagram.neighborsEnd(i),
          [i](int j) { return j > i; }));
    }
  }
  ev.coupling.resize(rowStart[n]);
#pragma omp parallel
  {
    PowerCell cell;
    CellIntegrals integrals;
    integrals.wantEdgeMass = withCouplings;
#pragma omp for schedule(dynamic, 512)
    for (int i = 0; i < n; ++i)
    {
      diagram.cell(i, lo, hi, cell);
      if (cell.vertices.empty())
      {
        continue;
      }
      source.integrate(cell, integrals);
      ev.cellMass[i] = integrals.mass;
      ev.moment[i] = integrals.moment;
      for (const auto& em : integrals.edgeMass)
      {
        const int j = em.first;
        if (j > i && em.second > 0.0 && rowStart[i] + rowCount[i] < rowStart[i + 1])
        {
          ev.coupling[rowStart[i] + rowCount[i]++] =
            Eigen::Triplet<double>(i, j, em.second / norm(diracs[i] - diracs[j]));
        }
      }
    }
  }
  std::size_t kept = 0;
  for (int i = 0; i < n; ++i)
  {
    for (int k = rowStart[i]; k < rowStart[i] + rowCount[i]; ++k)
    {
      ev.coupling[kept++] = ev.coupling[k];
    }
  }
  ev.coupling.resize(kept);
  ev.minMass = n ? *std::min_element(ev.cellMass.begin(), ev.cellMass.end()) : 0.0;
  ev.emptyCells = static_cast<int>(std::count(ev.cellMass.begin(), ev.cellMass.end(), 0.0));
  timing.secondsIntegration += secondsSince(t0);
}

// True when the trial heights certainly hide a Dirac, found without a triangulation: Dirac i is
// hidden when its lifted point (y_i, h_i) lies above the plane through the lifted points of
// three others whose triangle contains y_i (it is then not a vertex of the lower hull). The
// triangles tried are a fan of i's neighbours in the current diagram, where a trial step that
// empties a cell nearly always does so. Inexact arithmetic: a margin far above the rounding of
// the test keeps every certificate true; a missed one only costs the triangulation.
bool certainlyHidesADirac(
  const PowerDiagram& current, const std::vector<Vec2>& diracs, const std::vector<Height>& trial)
{
  const int n = current.size();
  int found = 0;
#pragma omp parallel for schedule(static) reduction(+ : found)
  for (int i = 0; i < n; ++i)
  {
    if (found > 0 || current.hidden(i))
    {
      continue;
    }
    const int* begin = current.neighborsBegin(i);
    const int* end = current.neighborsEnd(i);
    const int degree = static_cast<int>(end - begin);
    if (degree < 3 || std::find(begin, end, -1) != end)
    {
      continue; // hull Diracs: their cells reach infinity
    }
    const Vec2 yi = diracs[i];
    // One fan, from the first neighbour: it finds most of what all fans find, at a third of
    // the cost (docs/design.md, "Measured decisions").
    const int a = begin[0];
    const Vec2 pa = diracs[a];
    for (int m = 1; m + 1 < degree; ++m)
    {
      const int b = begin[m], c = begin[m + 1];
      const Vec2 pb = diracs[b], pc = diracs[c];
      const double area = cross(pb - pa, pc - pa);
      // Thin triangles are skipped: their barycentric coordinates lose too many digits.
      if (!(area > 1e-6 * (dot(pb - pa, pb - pa) + dot(pc - pa, pc - pa))))
      {
        continue;
      }
      const double la = cross(pb - yi, pc - yi) / area;
      const double lb = cross(pc - yi, pa - yi) / area;
      const double lc = 1.0 - la - lb;
      if (la < 0.0 || lb < 0.0 || lc < 0.0)
      {
        continue;
      }
      // Height of i above the plane, from differences (neighbours' heights are close).
      const long double above =
        -(la * (trial[a] - trial[i]) + lb * (trial[b] - trial[i]) + lc * (trial[c] - trial[i]));
      const long double scale = std::abs(trial[a].value()) + std::abs(trial[b].value()) +
        std::abs(trial[c].value()) + std::abs(trial[i].value()) + 1.0L;
      if (above > 1e-9L * scale)
      {
        ++found;
        break;
      }
    }
  }
  return found > 0;
}

// The plane's transport problem for the damped Newton driver: trials flip the current
// diagram's kept regular triangulation.
class PlanarNewtonProblem final : public NewtonProblem
{
public:
  PlanarNewtonProblem(const SourceMeasure& source, const std::vector<Vec2>& diracs,
    PowerDiagram& diagram, Evaluation& ev)
    : Source(source)
    , Diracs(diracs)
    , Diagram(diagram)
    , Ev(ev)
  {
  }

  const NewtonEvaluation& current() const override { return this->Ev; }

  bool certainlyHidesADirac(const std::vector<Height>& trial, NewtonReport& timing) override
  {
    const auto start = Clock::now();
    const bool hides = otparam::certainlyHidesADirac(this->Diagram, this->Diracs, trial);
    timing.secondsTriangulation += secondsSince(start);
    return hides;
  }

  const NewtonEvaluation& evaluateTrial(
    const std::vector<Height>& trial, NewtonReport& timing) override
  {
    this->TrialDiagram.takeTriangulationFrom(this->Diagram);
    evaluate(this->Source, this->Diracs, trial, this->TrialDiagram, this->TrialEv, timing);
    return this->TrialEv;
  }

  void acceptTrial() override
  {
    std::swap(this->Ev, this->TrialEv);
    std::swap(this->Diagram, this->TrialDiagram);
  }

  // The replaced diagram and evaluation (their triangulation went on with the trial), and the
  // current diagram's cells: the trials read its adjacency and hidden Diracs only
  // (certainlyHidesADirac) and take its triangulation; its masses and moments stay for the
  // result.
  void releaseBeforeSolve() override
  {
    this->TrialDiagram = PowerDiagram();
    this->TrialEv = Evaluation();
    this->Diagram.releaseCellGeometry();
  }

  void releaseCouplings() override
  {
    std::vector<Eigen::Triplet<double>>().swap(this->Ev.coupling);
  }

private:
  const SourceMeasure& Source;
  const std::vector<Vec2>& Diracs;
  PowerDiagram& Diagram;
  Evaluation& Ev;
  PowerDiagram TrialDiagram;
  Evaluation TrialEv;
};

void solveByNewton(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& h, PowerDiagram& diagram, Evaluation& ev,
  const OTOptions& options, OTResult& result)
{
  PlanarNewtonProblem problem(source, diracs, diagram, ev);
  dampedNewton(problem, nu, h, newtonOptionsOf(options), result);
}

} // namespace

std::vector<double> massesScaledTo(const std::vector<double>& masses, double total)
{
  // Compensated, in long double: the largest cell (the gauge) absorbs sum(mass) - total, and a
  // plain sum of 1e5 masses is off by ~1e-14 relative, ~1e-10 of one cell's mass (on the
  // sphere, 1e5 masses of contrast 1e4 missed 4 pi by 2e-13 and the solve stalled at 1.8e-10).
  long double sum = 0.0L, carry = 0.0L;
  for (const double m : masses)
  {
    const long double y = m - carry;
    const long double t = sum + y;
    carry = (t - sum) - y;
    sum = t;
  }
  const long double scale = static_cast<long double>(total) / sum;
  std::vector<double> scaled(masses.size());
  for (size_t i = 0; i < masses.size(); ++i)
  {
    scaled[i] = static_cast<double>(masses[i] * scale);
  }
  return scaled;
}

std::string checkTransportOptions(const OTOptions& options, double maximumArcAngle)
{
  std::string error = checkPositiveFinite("Tolerance", options.tolerance);
  if (error.empty())
  {
    error = checkAtLeast("MaximumNumberOfIterations", options.maximumNumberOfIterations, 1);
  }
  if (error.empty() && !(maximumArcAngle > 0.0 && maximumArcAngle <= 1.0))
  {
    std::ostringstream msg;
    msg << "MaximumArcAngle must be in (0, 1] radians; got " << maximumArcAngle << ".";
    error = msg.str();
  }
  return error;
}

std::string validateDiracs(const std::vector<Vec2>& diracs, const std::vector<double>& masses)
{
  std::ostringstream msg;
  if (diracs.empty())
  {
    return "there are no Diracs (the target has no points)";
  }
  if (masses.size() != diracs.size())
  {
    msg << "there are " << diracs.size() << " Diracs but " << masses.size() << " masses";
    return msg.str();
  }
  auto listIds = [&](const char* what, const std::vector<size_t>& ids)
  {
    msg << ids.size() << " Dirac(s) " << what << " (point ids";
    for (size_t k = 0; k < std::min<size_t>(ids.size(), 10); ++k)
    {
      msg << ' ' << ids[k];
    }
    msg << (ids.size() > 10 ? " ...)" : ")");
  };
  std::vector<size_t> bad;
  for (size_t i = 0; i < diracs.size(); ++i)
  {
    if (!std::isfinite(diracs[i].x) || !std::isfinite(diracs[i].y))
    {
      bad.push_back(i);
    }
  }
  if (!bad.empty())
  {
    listIds("have NaN or infinite coordinates", bad);
    return msg.str();
  }
  for (size_t i = 0; i < diracs.size(); ++i)
  {
    // The power diagram's weights hold |y|^2.
    if (!std::isfinite(dot(diracs[i], diracs[i])))
    {
      bad.push_back(i);
    }
  }
  if (!bad.empty())
  {
    listIds("lie too far from the origin for double precision (|y|^2 overflows)", bad);
    msg << "; the first is at (" << diracs[bad.front()].x << ", " << diracs[bad.front()].y << ")";
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
    listIds("have a Mass that is not finite and positive", bad);
    msg << "; the first is " << masses[bad.front()];
    return msg.str();
  }
  std::vector<size_t> order(diracs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
    [&](size_t a, size_t b) {
      return diracs[a].x < diracs[b].x || (diracs[a].x == diracs[b].x && diracs[a].y < diracs[b].y);
    });
  for (size_t k = 1; k < order.size(); ++k)
  {
    const Vec2 a = diracs[order[k - 1]], b = diracs[order[k]];
    if (a.x == b.x && a.y == b.y)
    {
      bad.push_back(std::min(order[k - 1], order[k]));
      bad.push_back(std::max(order[k - 1], order[k]));
    }
  }
  if (!bad.empty())
  {
    listIds("share their position with another Dirac", bad);
    return msg.str();
  }
  return std::string();
}

namespace
{
// Start heights: the Voronoi diagram of the Diracs when it already solves the problem, or when
// every cell meets the domain and the masses differ by at most MildContrast (unless the radial
// start below is nearer). Otherwise the
// Voronoi diagram of the Diracs mapped by a similarity z = c + s (y - c) that makes them fill
// 90% of a disk inside the domain: its cells are the power cells of y with
// h_i = |z_i|^2 / (2 s), since <x, y_i> - h_i = (<x, z_i> - |z_i|^2 / 2) / s + terms common to
// all i. Besides giving a cell to Diracs outside the domain, this keeps the Diracs next to the
// boundary from starting as thin caps, which full Newton steps push out of the domain when
// their masses must shrink a lot. Measured, Newton iterations from the Voronoi / the shrunk
// start, 1e4 random Diracs in the disk: contrast 10: 6 / 8; 100: 16 / 12; 1e3: 72 / 18;
// 1e4: 84 / 28 (3e4 Diracs: 119 / 30).
// Where Voronoi cells miss the unit disk (Diracs outside it), they first get a small cap at the
// circle (pullEmptyCellsIntoDisk), so that the Voronoi start competes too: the shrunk start
// crushes every other Dirac together when one lies far away.
// Of the two (and of the radial start below, where the Diracs crowd towards the circle), the
// start whose typical cell is nearer its mass is kept (median over the Diracs of
// |log(m_i / nu_i)|): random Diracs of contrasted masses keep the shrunk start (contrast
// 100 / 1e4: 1.47 / 4.20 against 1.60 / 4.37 for the Voronoi diagram), while a conformal
// image's adaptive samples, of near-equal masses crowded where the surface is, keep their
// Voronoi diagram (hand_choi_53k 3.59 against 3.96, face_dense_gpp_5k 0.13 against 0.28) and
// need fewer Newton iterations from it (docs/performance.md).
constexpr double MildContrast = 30.0;

// Median over the Diracs of |log(m_i / nu_i)|.
double medianAbsLogMassRatio(const std::vector<double>& cellMass, const std::vector<double>& nu)
{
  std::vector<double> logRatio(nu.size());
  for (size_t i = 0; i < nu.size(); ++i)
  {
    logRatio[i] = std::abs(std::log(cellMass[i] / nu[i]));
  }
  const auto middle = logRatio.begin() + static_cast<std::ptrdiff_t>(logRatio.size() / 2);
  std::nth_element(logRatio.begin(), middle, logRatio.end());
  return *middle;
}

// Newton's first steps from a start with cells far below their masses are tiny: the mass of a
// small cell grows like the square of how far its height is lowered, so the linear model asks
// for far too much (by sqrt(nu_i / m_i) / 2) and every longer step hides Diracs. Before Newton,
// each such cell is lowered by the step that the square model m(t) = m_i (1 + H_ii t / (2 m_i))^2
// (a cell growing by homothety; H_ii = dm/dt) gives for a share of its mass; a lowering that
// empties or hides another Dirac is halved for the Diracs around it and tried again. Measured,
// 1e5 Diracs of contrast 1e4 from the coarse-to-fine start: 2 cells below a thousandth of their
// mass made the first step 0.0039 (10 iterations); inflated, it is 0.0625 (8 iterations).
void inflateSmallCells(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& h, PowerDiagram& diagram, Evaluation& ev,
  OTResult& result)
{
  const int n = static_cast<int>(diracs.size());
  constexpr double SmallFraction = 1e-3, Share = 0.25;
  constexpr int Rounds = 3, Attempts = 8;
  std::vector<Height> trial;
  Evaluation trialEv;
  PowerDiagram trialDiagram;
  for (int round = 0; round < Rounds; ++round)
  {
    const std::vector<double> diagonal = hessianDiagonal(n, ev.coupling);
    std::vector<double> lowering(n, 0.0);
    int small = 0;
    for (int i = 0; i < n; ++i)
    {
      const double m = ev.cellMass[i];
      if (m < SmallFraction * nu[i] && m > 0.0 && diagonal[i] > 0.0)
      {
        lowering[i] = 2.0 * m / diagonal[i] * (std::sqrt(Share * nu[i] / m) - 1.0);
        ++small;
      }
    }
    if (small == 0)
    {
      return;
    }
    bool accepted = false;
    for (int attempt = 0; attempt < Attempts && !accepted; ++attempt)
    {
      trial = h;
      for (int i = 0; i < n; ++i)
      {
        trial[i] -= lowering[i];
      }
      trialDiagram.takeTriangulationFrom(diagram);
      evaluate(
        source, diracs, trial, trialDiagram, trialEv, result, PowerDiagram::WhenHidden::ReportSome);
      // Broken: the Diracs found hidden, or else those whose cells left the domain.
      const bool hides = trialDiagram.hiddenCount() > 0;
      int broken = 0;
      for (int j = 0; j < n; ++j)
      {
        if (hides ? !trialDiagram.hidden(j) : trialEv.cellMass[j] > 0.0 || ev.cellMass[j] <= 0.0)
        {
          continue;
        }
        ++broken;
        lowering[j] *= 0.5;
        if (trialDiagram.hidden(j) && trialDiagram.hiddenFace(j)[0] >= 0)
        {
          for (const int k : trialDiagram.hiddenFace(j))
          {
            lowering[k] *= 0.5;
          }
        }
        for (const int* k = diagram.neighborsBegin(j); k != diagram.neighborsEnd(j); ++k)
        {
          if (*k >= 0)
          {
            lowering[*k] *= 0.5;
          }
        }
      }
      accepted = broken == 0;
    }
    if (!accepted)
    {
      return;
    }
    h.swap(trial);
    std::swap(ev, trialEv);
    std::swap(diagram, trialDiagram);
  }
}

// Coarse-to-fine start heights (OTOptions::coarseToFineStart) checked and, rarely, repaired:
// the prolongation's heights lie on a convex surface, so that no Dirac should be hidden, but
// rounding can hide one, and a cell can miss the disk. Hidden Diracs are lowered under the lower
// hull, empty cells pulled into the disk. Returns false when cells stay empty after a few rounds.
bool coarseToFineStart(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& h, PowerDiagram& diagram, Evaluation& ev,
  OTResult& result)
{
  std::vector<Height> fine;
  if (!source.isUnitDisk() || !coarseToFineHeights(source, diracs, nu, fine))
  {
    return false;
  }
  for (int round = 0; round < 8; ++round)
  {
    evaluate(source, diracs, fine, diagram, ev, result);
    if (ev.minMass > 0.0)
    {
      h.swap(fine);
      inflateSmallCells(source, diracs, nu, h, diagram, ev, result);
      return true;
    }
    const bool stuck = diagram.hiddenCount() > 0
      ? unhideDiracs(source, diracs, nu, fine, diagram) > 0
      : pullEmptyCellsIntoDisk(diracs, nu, ev.cellMass, diagram, fine) == 0;
    if (stuck)
    {
      return false;
    }
  }
  return false;
}

// The shrunk start's heights (see MildContrast).
void shrunkStart(
  const SourceMeasure& source, const std::vector<Vec2>& diracs, std::vector<Height>& h)
{
  Vec2 center;
  double inner;
  source.innerDisk(center, inner);
  double reach = 0.0;
  for (const Vec2& y : diracs)
  {
    reach = std::max(reach, norm(y - center));
  }
  const double s = reach > 0.0 ? 0.9 * inner / reach : 1.0;
  for (size_t i = 0; i < diracs.size(); ++i)
  {
    const Vec2 z = center + s * (diracs[i] - center);
    h[i] = static_cast<long double>(dot(z, z)) / (2.0L * s);
  }
}

// The radial start (unit disk only): the optimal map between the uniform disk and the
// Diracs' masses spread evenly over circles about its centre, i.e. the monotone rearrangement of
// radii. The Diracs within radius r carry the share F(r) of the mass, which the uniform disk
// holds within R(r) = sqrt(F(r)); the map's dual potential is h(y) = int_0^|y| R(s) ds, sampled
// at each Dirac with R linear between consecutive Diracs' radii (each counts half its own
// mass). R increases, so h is strictly convex and hides no Dirac. A conformal image crowds its
// samples towards the circle (the disk's boundary takes the surface's thin extremities), which
// this start undoes around the whole circle at once; the Voronoi diagram leaves that to
// Newton's damped first steps. Measured Newton iterations, Voronoi -> radial start, adaptive
// samples of the shared disk meshes (docs/performance.md): bunny_holes_35k 22 -> 13,
// hand_choi_53k 20 -> 17, bust_aphrodite_56k 12 -> 9, face_choi_bff_17k 11 -> 9; the others
// the same or one fewer.
std::vector<Height> radialStartHeights(
  const std::vector<Vec2>& diracs, const std::vector<int>& byRadius, const std::vector<double>& nu)
{
  const double total = std::accumulate(nu.begin(), nu.end(), 0.0);
  std::vector<Height> h(diracs.size());
  long double potential = 0.0L;
  double massInside = 0.0, lastR = 0.0, lastRadius = 0.0;
  for (const int i : byRadius)
  {
    const double radius = norm(diracs[i]);
    const double R = std::sqrt(std::min(1.0, (massInside + 0.5 * nu[i]) / total));
    potential += 0.5L * (lastR + R) * (radius - lastRadius);
    h[i] = potential;
    massInside += nu[i];
    lastR = R;
    lastRadius = radius;
  }
  return h;
}

// The Diracs' ids by distance to the disk's centre (ties by id), which both the radial start
// and its share test walk.
std::vector<int> idsByRadius(const std::vector<Vec2>& diracs)
{
  std::vector<double> radius(diracs.size());
  for (size_t i = 0; i < diracs.size(); ++i)
  {
    radius[i] = norm(diracs[i]);
  }
  std::vector<int> ids(diracs.size());
  std::iota(ids.begin(), ids.end(), 0);
  std::sort(ids.begin(), ids.end(),
    [&radius](int a, int b) { return radius[a] < radius[b] || (radius[a] == radius[b] && a < b); });
  return ids;
}

// Share of the variance of log(m_i / nu_i) (cell masses m_i of some start, all positive) that
// the Diracs' distance to the disk's centre explains: the variance between RadialStartRings
// rings of as many Diracs each, over the whole variance (0 when there are too few Diracs for
// the rings). Measured at the Voronoi diagram: adaptive samples of the shared disk meshes
// 0.26-0.997 (0.61-0.997 where the radial start saves iterations), random Diracs of random
// masses 0.08-0.2, from which the radial start, though nearer by the median, needed 111
// Newton iterations against 19 (3e3 Diracs of contrast 1e4) and 198 against 25 (1e4).
constexpr int RadialStartRings = 20;
constexpr double RadialStartShare = 0.5;
double radialShareOfMassErrors(const std::vector<int>& byRadius,
  const std::vector<double>& cellMass, const std::vector<double>& nu)
{
  const size_t n = byRadius.size();
  if (n < 10 * RadialStartRings)
  {
    return 0.0;
  }
  std::vector<double> logRatio(n), ringSum(RadialStartRings, 0.0);
  std::vector<int> ringCount(RadialStartRings, 0);
  double mean = 0.0;
  for (size_t k = 0; k < n; ++k)
  {
    const int i = byRadius[k], ring = static_cast<int>(k * RadialStartRings / n);
    logRatio[k] = std::log(cellMass[i] / nu[i]);
    ringSum[ring] += logRatio[k];
    ++ringCount[ring];
    mean += logRatio[k] / static_cast<double>(n);
  }
  double between = 0.0, total = 0.0;
  for (size_t k = 0; k < n; ++k)
  {
    const int ring = static_cast<int>(k * RadialStartRings / n);
    const double ringMean = ringSum[ring] / ringCount[ring];
    between += (ringMean - mean) * (ringMean - mean);
    total += (logRatio[k] - mean) * (logRatio[k] - mean);
  }
  return total > 0.0 ? between / total : 0.0;
}

// The current start (h, diagram, ev) replaced by the candidate heights when all of the
// candidate's cells meet the domain and its typical cell is nearer its mass (median over the
// Diracs of |log(m_i / nu_i)|), or when the current start has an empty cell.
void keepNearerStart(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, std::vector<Height>& candidate, std::vector<Height>& h,
  PowerDiagram& diagram, Evaluation& ev, OTResult& result)
{
  Evaluation candidateEv;
  PowerDiagram candidateDiagram;
  evaluate(source, diracs, candidate, candidateDiagram, candidateEv, result);
  if (candidateEv.minMass > 0.0 &&
    (ev.minMass <= 0.0 ||
      medianAbsLogMassRatio(candidateEv.cellMass, nu) < medianAbsLogMassRatio(ev.cellMass, nu)))
  {
    h.swap(candidate);
    std::swap(ev, candidateEv);
    std::swap(diagram, candidateDiagram);
  }
}

bool startHeights(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& nu, double tolerance, bool coarseToFine, bool radialStart,
  std::vector<Height>& h, PowerDiagram& diagram, Evaluation& ev, OTResult& result)
{
  const size_t n = diracs.size();
  h.resize(n);
  for (size_t i = 0; i < n; ++i)
  {
    h[i] = 0.5L * dot(diracs[i], diracs[i]);
  }
  const auto [lightest, heaviest] = std::minmax_element(nu.begin(), nu.end());
  const bool mild = *heaviest <= MildContrast * *lightest;
  // Many Diracs of high contrast go straight to the coarse-to-fine start: their Voronoi diagram
  // is not the solution, and evaluating it would cost a whole evaluation.
  const bool multiscale = coarseToFine && !mild && static_cast<int>(n) >= MultiscaleMinimumDiracs;
  if (multiscale && coarseToFineStart(source, diracs, nu, h, diagram, ev, result))
  {
    return true;
  }
  evaluate(source, diracs, h, diagram, ev, result);
  if (ev.minMass > 0.0 && relativeError(ev.cellMass, nu) <= tolerance)
  {
    return false;
  }
  if (!(ev.minMass > 0.0) && source.isUnitDisk() && diagram.hiddenCount() == 0 &&
    pullEmptyCellsIntoDisk(diracs, nu, ev.cellMass, diagram, h) > 0)
  {
    // Diracs outside the disk whose Voronoi cells miss it, each given a small cap at the
    // circle: a candidate beside the shrunk start, which crushes the others together when one
    // Dirac lies far away (one 1e6 from the disk among 300 over it stopped at the start).
    evaluate(source, diracs, h, diagram, ev, result);
  }
  const std::vector<int> byRadius = radialStart && source.isUnitDisk() && ev.minMass > 0.0
    ? idsByRadius(diracs)
    : std::vector<int>();
  const bool radial =
    !byRadius.empty() && radialShareOfMassErrors(byRadius, ev.cellMass, nu) >= RadialStartShare;
  if (!mild || !(ev.minMass > 0.0))
  {
    std::vector<Height> shrunk(n);
    shrunkStart(source, diracs, shrunk);
    keepNearerStart(source, diracs, nu, shrunk, h, diagram, ev, result);
  }
  if (radial)
  {
    std::vector<Height> radialHeights = radialStartHeights(diracs, byRadius, nu);
    keepNearerStart(source, diracs, nu, radialHeights, h, diagram, ev, result);
  }
  return false;
}

} // namespace

namespace
{
// Above this relative error a stalled solve blames its coarse-to-fine start (the coarse levels
// are solved to 1e-3).
constexpr double StalledStartError = 1e-3;

// solveSemiDiscreteOT for valid Diracs.
OTResult solveValid(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& masses, const OTOptions& options)
{
  OTResult result;
  const int n = static_cast<int>(diracs.size());
  result.mass = massesScaledTo(masses, source.totalMass());
  const std::vector<double>& nu = result.mass;

  std::vector<Height> h;
  PowerDiagram diagram;
  Evaluation ev;
  const bool multiscale = startHeights(source, diracs, nu, options.tolerance,
    options.coarseToFineStart, options.radialStart, h, diagram, ev, result);
  if (ev.minMass <= 0.0)
  {
    std::ostringstream msg;
    msg << ev.emptyCells
        << " cell(s) stay empty at the start (Diracs too close for double precision?)";
    result.message = msg.str();
    result.relativeError = relativeError(ev.cellMass, nu);
  }
  else
  {
    solveByNewton(source, diracs, nu, h, diagram, ev, options, result);
    // The coarse-to-fine start only saves time: when Newton stalls from it far from the
    // solution, the solve starts over from the single-level start (seen with 2e4 adaptive
    // samples of a hand, whose spacing varies by 1e3, before such Diracs were kept single-level:
    // every damping of the first step was rejected). A stall near the solution is the rounding
    // limit of the cell masses, which a restart would only reach again, much later.
    if (multiscale && !result.converged && !result.aborted &&
      result.iterations < options.maximumNumberOfIterations &&
      result.relativeError > StalledStartError)
    {
      std::ostringstream note;
      note << "the coarse-to-fine start stalled (" << result.message
           << "); restarted from the single-level start: ";
      result.gradientNormHistory.clear();
      result.stepLengthHistory.clear();
      startHeights(
        source, diracs, nu, options.tolerance, false, options.radialStart, h, diagram, ev, result);
      if (ev.minMass > 0.0)
      {
        solveByNewton(source, diracs, nu, h, diagram, ev, options, result);
      }
      result.message = note.str() + result.message;
    }
  }

  result.heights.resize(n);
  for (int i = 0; i < n; ++i)
  {
    result.heights[i] = static_cast<double>(h[i].value());
  }
  result.cellMass = ev.cellMass;
  result.centroids.resize(n);
  for (int i = 0; i < n; ++i)
  {
    const double w = ev.cellMass[i];
    result.centroids[i] = w > 0.0 ? (1.0 / w) * ev.moment[i] : diracs[i];
  }
  return result;
}

} // namespace

namespace
{
// How far p lies outside the box [lo, hi] (0 inside).
double distanceOutside(Vec2 lo, Vec2 hi, Vec2 p)
{
  return norm(
    Vec2{ std::max({ lo.x - p.x, p.x - hi.x, 0.0 }), std::max({ lo.y - p.y, p.y - hi.y, 0.0 }) });
}

// Moving every Dirac by the same vector v leaves every power cell as it is under the same
// heights (<x, v> is common to all of them), but Diracs far from the source lose digits in
// the power diagram and the shrunk start crushes them together: 3e4 random Diracs in a unit
// disk centred 1e3 away from the unit-disk source (300 of them centred 1e6 away) stopped at
// the start; centred over the source they converge in 10 Newton iterations, as at 0. The
// shift that brings the Diracs' coordinate-wise median to the centre of the source's inner
// disk, when it lies farther from the source's bounding box than the box's size (else none:
// Diracs over or near the source are solved where they are, to the bit as before). The
// median, so that a few outliers do not move the others away.
Vec2 shiftOntoSource(const SourceMeasure& source, const std::vector<Vec2>& diracs)
{
  std::vector<double> xs(diracs.size()), ys(diracs.size());
  for (size_t i = 0; i < diracs.size(); ++i)
  {
    xs[i] = diracs[i].x;
    ys[i] = diracs[i].y;
  }
  const auto middle = static_cast<std::ptrdiff_t>(diracs.size() / 2);
  std::nth_element(xs.begin(), xs.begin() + middle, xs.end());
  std::nth_element(ys.begin(), ys.begin() + middle, ys.end());
  const Vec2 median{ xs[middle], ys[middle] };
  Vec2 lo, hi, center;
  double inner;
  source.bounds(lo, hi);
  source.innerDisk(center, inner);
  return distanceOutside(lo, hi, median) > norm(hi - lo) ? median - center : Vec2{ 0.0, 0.0 };
}

std::vector<Vec2> shiftedOntoSource(const SourceMeasure& source, std::vector<Vec2> diracs)
{
  const Vec2 shift = diracs.empty() ? Vec2{ 0.0, 0.0 } : shiftOntoSource(source, diracs);
  for (Vec2& y : diracs)
  {
    y = y - shift;
  }
  return diracs;
}
} // namespace

OTResult solveSemiDiscreteOT(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& masses, const OTOptions& options)
{
  const std::string invalid = validateDiracs(diracs, masses);
  if (!invalid.empty())
  {
    OTResult result;
    result.message = invalid;
    return result;
  }
  // The solve numbers the Diracs along a Hilbert curve, so that every loop over them (the power
  // diagram's rings and vertices, the integration, the Hessian's rows) walks memory in spatial
  // order; in the caller's order (random, for sampled points) those walks miss the cache
  // (a third of the solve at 1e6 Diracs; docs/design.md).
  const int n = static_cast<int>(diracs.size());
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Point_2> points;
  points.reserve(n);
  for (const Vec2& y : diracs)
  {
    points.emplace_back(y.x, y.y);
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  using Traits =
    CGAL::Spatial_sort_traits_adapter_2<K, CGAL::Pointer_property_map<K::Point_2>::type>;
  CGAL::Hilbert_sort_2<Traits, CGAL::Hilbert_sort_median_policy>(
    Traits(CGAL::make_property_map(points)))(order.begin(), order.end());
  std::vector<Vec2> sortedDiracs(n);
  std::vector<double> sortedMasses(n);
  const Vec2 shift = shiftOntoSource(source, diracs);
  for (int k = 0; k < n; ++k)
  {
    sortedDiracs[k] = diracs[order[k]] - shift;
    sortedMasses[k] = masses[order[k]];
  }
  OTResult sorted = solveValid(source, sortedDiracs, sortedMasses, options);
  OTResult result = sorted;
  auto unsort = [&](const auto& from, auto& to)
  {
    if (static_cast<int>(from.size()) == n)
    {
      for (int k = 0; k < n; ++k)
      {
        to[order[k]] = from[k];
      }
    }
  };
  unsort(sorted.mass, result.mass);
  unsort(sorted.heights, result.heights);
  unsort(sorted.cellMass, result.cellMass);
  unsort(sorted.centroids, result.centroids);
  const bool shifted = shift.x != 0.0 || shift.y != 0.0;
  for (int i = 0; shifted && i < static_cast<int>(result.centroids.size()); ++i)
  {
    if (!(result.cellMass[i] > 0.0))
    {
      result.centroids[i] = diracs[i]; // an empty cell's centroid is its Dirac, unshifted
    }
  }
  return result;
}

CellMeasures computeCellMeasures(
  const SourceMeasure& source, const std::vector<Vec2>& diracs, const std::vector<double>& heights)
{
  PowerDiagram diagram;
  return computeCellMeasures(source, diracs, heights, diagram);
}

CellMeasures computeCellMeasures(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& heights, PowerDiagram& diagram)
{
  OTResult unusedTiming;
  Evaluation ev;
  evaluate(source, shiftedOntoSource(source, diracs),
    std::vector<Height>(heights.begin(), heights.end()), diagram, ev, unusedTiming,
    PowerDiagram::WhenHidden::FindAll, false);
  CellMeasures measures;
  measures.mass = ev.cellMass;
  measures.centroid.resize(diracs.size());
  for (size_t i = 0; i < diracs.size(); ++i)
  {
    const double w = ev.cellMass[i];
    measures.centroid[i] = w > 0.0 ? (1.0 / w) * ev.moment[i] : diracs[i];
  }
  return measures;
}

PowerDiagramGeometry computePowerDiagramGeometry(const SourceMeasure& source,
  const std::vector<Vec2>& diracs, const std::vector<double>& heights, double maxArcAngle)
{
  PowerDiagramGeometry geometry;
  PowerDiagram diagram;
  diagram.build(
    shiftedOntoSource(source, diracs), std::vector<Height>(heights.begin(), heights.end()));
  geometry.triangles = diagram.triangles();
  Vec2 lo, hi;
  sourceBox(source, lo, hi);
  PowerCell cell;
  for (int i = 0; i < diagram.size(); ++i)
  {
    diagram.cell(i, lo, hi, cell);
    if (cell.vertices.empty())
    {
      continue;
    }
    std::vector<Vec2> boundary = source.clippedBoundary(cell, maxArcAngle);
    if (boundary.size() < 3)
    {
      continue;
    }
    // Shared edges inside the domain: clip each labelled edge to the clipped cell.
    const size_t m = cell.vertices.size();
    for (size_t k = 0; k < m; ++k)
    {
      const int j = cell.neighbor[k];
      if (j <= i)
      {
        continue;
      }
      PowerCell edgeCell;
      edgeCell.vertices = { cell.vertices[k], cell.vertices[(k + 1) % m] };
      // Clip the segment by the clipped boundary polygon (convex up to arc sampling).
      Vec2 a = edgeCell.vertices[0], b = edgeCell.vertices[1];
      double t0 = 0.0, t1 = 1.0;
      const size_t bn = boundary.size();
      for (size_t e = 0; e < bn && t0 < t1; ++e)
      {
        const Vec2 p = boundary[e], q = boundary[(e + 1) % bn];
        const double sa = cross(q - p, a - p), sb = cross(q - p, b - p);
        const double tol = 1e-12 * norm(q - p);
        if (sa < -tol && sb < -tol)
        {
          t1 = -1.0;
        }
        else if (sa < -tol)
        {
          t0 = std::max(t0, sa / (sa - sb));
        }
        else if (sb < -tol)
        {
          t1 = std::min(t1, sa / (sa - sb));
        }
      }
      if (t0 < t1)
      {
        geometry.edges.push_back({ a + t0 * (b - a), a + t1 * (b - a), i, j });
      }
    }
    geometry.cells.push_back(std::move(boundary));
    geometry.cellDirac.push_back(i);
  }
  return geometry;
}

} // namespace otparam
