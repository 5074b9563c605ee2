#include "Transport/DampedNewton.h"

#include "Common/Memory.h"
#include "Common/SparseCholesky.h"

#include <algorithm>
#include <chrono>
#include <cmath>
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

double gradientNorm(const std::vector<double>& cellMass, const std::vector<double>& mass)
{
  double s = 0.0;
  for (size_t i = 0; i < mass.size(); ++i)
  {
    const double g = cellMass[i] - mass[i];
    s += g * g;
  }
  return std::sqrt(s);
}

// Sparse SPD solve of the graph Laplacian L d = g with one height pinned (the gauge). The
// pinned cell absorbs the rounding of sum(cellMass) = total, so it must be the largest one.
class NewtonSystem
{
public:
  explicit NewtonSystem(int pinned)
    : Pinned(pinned)
  {
  }

  // When the conjugate gradients may stop: their residual r = g - H d has |r|_2 <= relative
  // |g|_2, or max_i |r_i| / nu_i <= perMass (0: not used). The second bounds directly what
  // the residual adds to the next relative mass error. (A new factorization, when needed,
  // solves exactly.)
  struct ResidualTarget
  {
    double relative;
    double perMass;
  };

  // Returns false when the factorization fails.
  bool solve(int n, const std::vector<Eigen::Triplet<double>>& coupling,
    const std::vector<double>& g, const std::vector<double>& nu, std::vector<double>& d,
    ResidualTarget target, NewtonReport& timing)
  {
    auto t0 = Clock::now();
    const int m = n - 1;
    Eigen::VectorXd rhs(m), inverseMass(m);
    for (int i = 0; i < n; ++i)
    {
      if (i != Pinned)
      {
        rhs[row(i)] = g[i];
        inverseMass[row(i)] = 1.0 / nu[i];
      }
    }
    const Eigen::SparseMatrix<double> L = this->lowerHessian(n, coupling);
    timing.secondsAssembly += secondsSince(t0);

    t0 = Clock::now();
    // Consecutive Newton Hessians differ little (same Diracs, nearby heights), so the last
    // factorization preconditions conjugate gradients; a new factorization (the most expensive
    // step) is made only when that does not converge quickly, or when it barely did last time:
    // the Hessians drift further from the factorized one with every step, and a long run of
    // iterations is usually followed by a failed one.
    Eigen::VectorXd x;
    bool ok = HaveFactor && Factor.size() == m && LastCGIterations <= StaleFactorCGIterations &&
      preconditionedCG(L, rhs, inverseMass, target, x);
    if (!ok)
    {
      LastCGIterations = 0;
      ok = Factor.compute(L);
      HaveFactor = ok;
      if (ok)
      {
        x = Factor.solve(rhs);
        x += Factor.solve(rhs - L.selfadjointView<Eigen::Lower>() * x); // one refinement step
      }
    }
    timing.secondsSolve += secondsSince(t0);
    if (!ok || !x.allFinite())
    {
      return false;
    }
    d.assign(n, 0.0);
    for (int i = 0; i < n; ++i)
    {
      if (i != Pinned)
      {
        d[i] = x[row(i)];
      }
    }
    return true;
  }

private:
  using SparseMatrix = Eigen::SparseMatrix<double>;

  // The system's row of Dirac i (the pinned one has none).
  int row(int i) const { return i < Pinned ? i : i - 1; }

  // The Hessian's lower triangle (both factorizations read one) without the pinned row and
  // column. Its triplets (64 MiB at 1e6 Diracs) die here, before the factorization.
  SparseMatrix lowerHessian(int n, const std::vector<Eigen::Triplet<double>>& coupling) const
  {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(coupling.size() + n);
    for (const auto& c : coupling)
    {
      if (c.row() != Pinned && c.col() != Pinned)
      {
        const int a = row(c.row()), b = row(c.col());
        entries.emplace_back(std::max(a, b), std::min(a, b), -c.value());
      }
    }
    const std::vector<double> diagonal = hessianDiagonal(n, coupling);
    for (int i = 0; i < n; ++i)
    {
      if (i != Pinned)
      {
        entries.emplace_back(row(i), row(i), diagonal[i]);
      }
    }
    SparseMatrix lower(n - 1, n - 1);
    lower.setFromTriplets(entries.begin(), entries.end());
    return lower;
  }

  bool preconditionedCG(const SparseMatrix& L, const Eigen::VectorXd& b,
    const Eigen::VectorXd& inverseMass, ResidualTarget target, Eigen::VectorXd& x)
  {
    const double bnorm = b.norm();
    if (bnorm == 0.0)
    {
      x.setZero(b.size());
      return true;
    }
    // How far the residual is from its target (done at <= 1).
    auto distance = [&](const Eigen::VectorXd& r)
    {
      double ratio = r.norm() / (target.relative * bnorm);
      if (target.perMass > 0.0)
      {
        ratio =
          std::min(ratio, r.cwiseProduct(inverseMass).lpNorm<Eigen::Infinity>() / target.perMass);
      }
      return ratio;
    };
    const auto A = L.selfadjointView<Eigen::Lower>();
    x = Factor.solve(b);
    Eigen::VectorXd r = b - A * x;
    Eigen::VectorXd z = Factor.solve(r);
    Eigen::VectorXd p = z;
    double rz = r.dot(z);
    const double firstDistance = distance(r);
    for (int k = 0; k < MaximumCGIterations; ++k)
    {
      const double current = distance(r);
      if (current <= 1.0)
      {
        LastCGIterations = k;
        return x.allFinite();
      }
      // The residual falls about geometrically: once its rate so far puts the target well
      // beyond MaximumCGIterations, factorizing at once saves the remaining iterations.
      if (k >= 4 && current < firstDistance &&
        k + std::log(1.0 / current) / (std::log(current / firstDistance) / k) >
          1.5 * MaximumCGIterations)
      {
        return false;
      }
      const Eigen::VectorXd Ap = A * p;
      const double alpha = rz / p.dot(Ap);
      x += alpha * p;
      r -= alpha * Ap;
      z = Factor.solve(r);
      const double rzNext = r.dot(z);
      p = z + (rzNext / rz) * p;
      rz = rzNext;
    }
    LastCGIterations = MaximumCGIterations;
    return distance(r) <= 1.0 && x.allFinite();
  }

  static constexpr int MaximumCGIterations = 15;
  static constexpr int StaleFactorCGIterations = 10;
  int LastCGIterations = 0;
  int Pinned;
  bool HaveFactor = false;
  SparseCholesky Factor;
};

// Relative residuals of the Newton solves: near the solution (full steps) the direction must
// be exact for quadratic convergence to 1e-10; while steps are damped 1e-6 suffices (measured,
// 1e4 Diracs of contrast 1e4: 1e-4 .. 1e-8 take the same 27 iterations; 1e-2 never converged;
// 1e-4 stalled the 6.3e4 Diracs of the coarsest level for 1e6 at relative error ~1).
constexpr double MassFloorFactor = 0.05;
constexpr double ExactResidual = 1e-11;
constexpr double DampedResidual = 1e-6;
// With full steps (quadratic regime, next error ~0.1 err^2 measured at 1e6 Diracs), the
// conjugate gradients also stop once no cell's residual exceeds QuadraticShare err^2 of its
// mass, or ToleranceShare of the tolerance: the direction is then as good as an exact one for
// the next error, and the 1e-11 residual in the 2-norm (which must cover cells of contrast
// 1e4 among 1e6) is not needed while the error is still large.
constexpr double QuadraticShare = 1e-2;
constexpr double ToleranceShare = 0.1;
// An accepted step shorter than the first iteration's search could ever try (40 halvings from
// 1/2): the steps have collapsed, and KMT's test, (1 - lambda / 2) |g| rounding to |g|, accepts
// steps that change nothing. A fuzzed disk of 271 points (otparam_fuzz --entry pipeline-disk
// --seed 13 --case 258) ran 2 x 200 such iterations of 5453 Diracs, steps down to 1e-40 at a
// relative error of 1e5, for 14 s (60 s beside other work) before its stage failed.
constexpr double UselessStep = 1e-12;

// Far from the solution, a cell much smaller than its mass grows like the square of its height's
// change (its edges all move out linearly), so Newton's linear model asks it for a step about
// sqrt(mass / cell) times too long, and the whole step is damped for it. Where cells span many
// scales (a conformal image crowds a surface's fingers by 1e-8 and less), one damping cannot
// suit them all, and the steps ramp up 4x per iteration (hand_choi_53k: 13 of 17 iterations).
// The rows of cells below GrowthRowsBelow of their masses are therefore Newton's for
// sqrt(cell) = sqrt(mass), exact for such a cell: the right-hand side 2 (cell - sqrt(cell mass))
// instead of cell - mass. The rows must still sum to zero (the cells share the domain), so the
// cells above their masses give up what the growing ones no longer ask: their rows are scaled
// down to balance. (Cells between a half and one of their masses keep their rows: with every
// growing cell transformed, the balance near the solution is rounding noise and 1e4 Diracs of
// contrast 1e6 stalled at 1e-8.) Returns the slope of |g|_2 along the new direction relative to
// the Newton direction's, g . g' / |g|^2 in (0, 1], for the line search's decrease test: below 1
// exactly when some row was transformed.
constexpr double GrowthRowsBelow = 0.5;

double squareRootGrowthRows(
  const std::vector<double>& cellMass, const std::vector<double>& nu, std::vector<double>& g)
{
  // In place: a copy of g is 8 MB at 1e6 Diracs, beside the peak of the first evaluation.
  const size_t n = nu.size();
  bool transformed = false;
  for (size_t i = 0; i < n; ++i)
  {
    if (cellMass[i] > 0.0 && cellMass[i] < GrowthRowsBelow * nu[i])
    {
      g[i] = 2.0 * (cellMass[i] - std::sqrt(cellMass[i] * nu[i]));
      transformed = true;
    }
  }
  if (!transformed)
  {
    return 1.0;
  }
  double growth = 0.0, shrinkage = 0.0;
  for (double r : g)
  {
    (r < 0.0 ? growth : shrinkage) += std::abs(r);
  }
  double along = 0.0, squared = 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    if (g[i] > 0.0)
    {
      g[i] *= growth / shrinkage;
    }
    const double newtonRow = cellMass[i] - nu[i];
    along += g[i] * newtonRow;
    squared += newtonRow * newtonRow;
  }
  return along / squared;
}

// The iteration's state: the problem, the targets and the last accepted step.
class NewtonIteration
{
public:
  NewtonIteration(NewtonProblem& problem, const std::vector<double>& nu,
    const NewtonOptions& options, NewtonReport& report)
    : Problem(problem)
    , Nu(nu)
    , Options(options)
    , Report(report)
    , System(static_cast<int>(std::max_element(nu.begin(), nu.end()) - nu.begin()))
  {
    // KMT: every accepted step keeps each cell's mass above eps0. Their convergence proof holds
    // for any eps0 in (0, min(smallest target mass, smallest start mass)]; KMT take half of
    // it. A tenth of that (0.05) accepts the step 1/2 where half rejected it only for the
    // smallest cell dipping below eps0 while |g| fell by half (contrast 1e4: 1e4 Diracs 27 ->
    // 25 iterations, 1e5 36 -> 32; contrast 1e6, 1e4 Diracs: 45 -> 38). 0.005 gained nothing.
    this->Eps0 = MassFloorFactor *
      std::min(problem.current().minMass, *std::min_element(nu.begin(), nu.end()));
  }

  void run(std::vector<Height>& h)
  {
    const int n = static_cast<int>(this->Nu.size());
    std::vector<double> g(n), d;
    // Freed memory goes back to the system before and after each solve, or the allocator keeps
    // it beside the factor and the trials' new diagrams (1e6 Diracs, largest peak of three
    // seeds: 1255-1336 MiB with one of the two or neither, 1207 with both, for ~1.5 s of page
    // faults in a 42 s solve); below CHOLMOD's sizes it is not worth the faults.
    const bool large = n >= SparseCholesky::CholmodThreshold;
    auto trim = [large]
    {
      if (large)
      {
        returnFreedMemory();
      }
    };
    for (int it = 0; !this->stopsAt(it); ++it)
    {
      const NewtonEvaluation& ev = this->Problem.current();
      for (int i = 0; i < n; ++i)
      {
        g[i] = ev.cellMass[i] - this->Nu[i];
      }
      const double slope =
        this->SquareRootGrowth ? squareRootGrowthRows(ev.cellMass, this->Nu, g) : 1.0;
      const bool rowsTransformed = slope < 1.0;
      this->Problem.releaseBeforeSolve();
      trim();
      if (!this->System.solve(n, ev.coupling, g, this->Nu, d, this->residualTarget(), this->Report))
      {
        this->Report.message = "the Newton system could not be factorized (disconnected cells?)";
        return;
      }
      const double gnorm = gradientNorm(ev.cellMass, this->Nu);
      this->Problem.releaseCouplings();
      trim();
      const double lambda = this->searchStep(h, d, gnorm, slope);
      if (rowsTransformed && lambda < UselessStep) // no step at all, or a useless one
      {
        // The transformed rows' direction found no step: Newton's own rows from here on (their
        // couplings, released above, come back with the current heights' evaluation).
        this->SquareRootGrowth = false;
        this->Problem.evaluateTrial(h, this->Report);
        this->Problem.acceptTrial();
        --it;
        continue;
      }
      if (lambda <= 0.0)
      {
        std::ostringstream msg;
        msg << "Newton step rejected at every damping down to about " << -2.0 * lambda << " after "
            << it << " iterations (relative error " << this->Report.relativeError
            << "; the tolerance may be below what double precision allows here)";
        this->Report.message = msg.str();
        return;
      }
      if (lambda < UselessStep)
      {
        std::ostringstream msg;
        msg << "Newton steps fell to " << lambda << " after " << it
            << " iterations without lowering the error (relative error "
            << this->Report.relativeError << "): stalled";
        this->Report.message = msg.str();
        return;
      }
      if (rowsTransformed && it > 0 && lambda < this->LastStep)
      {
        // Shorter steps than the last: the transformed rows no longer pay (a staged
        // transport's stage on the sphere crawled from 0.5 to 1e-9 with them and stalled).
        this->SquareRootGrowth = false;
      }
      this->Report.gradientNormHistory.push_back(gnorm);
      this->Report.stepLengthHistory.push_back(lambda);
      this->LastStep = lambda;
      h.swap(this->Trial);
      this->Problem.acceptTrial();
    }
  }

private:
  // Records iteration `it` and tells whether the iteration ends there (converged, aborted, a
  // single Dirac, or out of iterations), with the report's message.
  bool stopsAt(int it)
  {
    NewtonReport& report = this->Report;
    report.iterations = it;
    report.relativeError = relativeError(this->Problem.current().cellMass, this->Nu);
    std::ostringstream msg;
    if (this->Options.progress && !this->Options.progress(it, report.relativeError))
    {
      report.aborted = true;
      msg << "aborted";
    }
    else if (report.relativeError <= this->Options.tolerance)
    {
      report.converged = true;
      msg << "converged in " << it << " Newton iterations, relative error " << report.relativeError;
    }
    else if (this->Nu.size() == 1)
    {
      msg << "a single Dirac: its cell is the whole domain";
    }
    else if (it >= this->Options.maximumNumberOfIterations)
    {
      msg << "not converged after " << it << " Newton iterations: relative error "
          << report.relativeError << " > tolerance " << this->Options.tolerance;
    }
    report.message = msg.str();
    return !report.message.empty();
  }

  // Far from the solution (damped steps, or cells off by more than their masses) an inexact
  // Newton direction does as well: the last factorization preconditions conjugate gradients
  // down to DampedResidual, and a new one is needed far less often (same iterations).
  NewtonSystem::ResidualTarget residualTarget() const
  {
    const double error = this->Report.relativeError;
    return this->LastStep < 1.0 || error >= 1.0
      ? NewtonSystem::ResidualTarget{ DampedResidual, 0.0 }
      : NewtonSystem::ResidualTarget{ ExactResidual,
          std::max(ToleranceShare * this->Options.tolerance, QuadraticShare * error * error) };
  }

  // The damping of direction d: the accepted step (Trial then holds its heights and the
  // problem its evaluation), or minus the last one tried when every damping was rejected.
  // `slope`: |g|_2's predicted decrease along d relative to along Newton's direction.
  double searchStep(
    const std::vector<Height>& h, const std::vector<double>& d, double gnorm, double slope)
  {
    const int n = static_cast<int>(this->Nu.size());
    const double tolerance = this->Options.tolerance;
    const double error = this->Report.relativeError;
    // The full step first (quadratic convergence near the solution); after it fails, the
    // backtracking resumes at 4x the last accepted step rather than at 1/2: every rejected
    // trial costs a whole evaluation, and high-contrast problems need damped steps for many
    // iterations in a row.
    // Near the tolerance after full steps, Newton is in its quadratic regime: a step it must
    // damp below 1/4 there meets the rounding floor of the cell masses, and further halvings
    // only cost evaluations (with long double heights, 1e6 Diracs of contrast 1e4 stalled at
    // 1.9e-10; every trial from 1 down to 2e-12 left the error at 1.9e-10 .. 3.3e-10).
    const bool nearTolerance = this->LastStep == 1.0 && error <= 1e3 * tolerance;
    const double smallestStep = nearTolerance ? 0.25 : 0.0;
    this->Trial.resize(n);
    double lambda = this->Options.fullStepFirst ? 1.0 : std::min(1.0, 2.0 * this->LastStep);
    for (int trialCount = 0; trialCount < 40 && lambda >= smallestStep; ++trialCount)
    {
      for (int i = 0; i < n; ++i)
      {
        this->Trial[i] = h[i] + lambda * d[i];
      }
      if (!this->Problem.certainlyHidesADirac(this->Trial, this->Report))
      {
        const NewtonEvaluation& trialEv = this->Problem.evaluateTrial(this->Trial, this->Report);
        // KMT's rule guarantees global convergence (with the transformed rows: half the
        // decrease |g|_2 is predicted to have along d, the same sufficient-decrease test). Near
        // the solution |g|_2 sits at the rounding level of the largest cells while small cells
        // still have relative errors to remove: a full step that halves the largest relative error
        // is then accepted as well, and so is one that reaches the tolerance (1e5 Diracs, contrast
        // 1e4, seed 3: |g|_2 = 2e-16, the full step took the error from 1.08e-10 to 6.6e-11 and was
        // rejected at every damping).
        const double trialError = relativeError(trialEv.cellMass, this->Nu);
        if (trialEv.minMass >= this->Eps0 &&
          (gradientNorm(trialEv.cellMass, this->Nu) <= (1.0 - 0.5 * lambda * slope) * gnorm ||
            trialError <= tolerance || (lambda == 1.0 && trialError < 0.5 * error)))
        {
          return lambda;
        }
      }
      lambda = lambda == 1.0 && this->Options.fullStepFirst ? std::min(0.5, 4.0 * this->LastStep)
                                                            : 0.5 * lambda;
    }
    return -lambda;
  }

  NewtonProblem& Problem;
  const std::vector<double>& Nu;
  const NewtonOptions& Options;
  NewtonReport& Report;
  NewtonSystem System;
  double Eps0 = 0.0;
  double LastStep = 1.0;
  bool SquareRootGrowth = Options.squareRootGrowth;
  std::vector<Height> Trial;
};

} // namespace

NewtonOptions newtonOptionsOf(const OTOptions& options)
{
  NewtonOptions newton;
  newton.tolerance = options.tolerance;
  newton.maximumNumberOfIterations = options.maximumNumberOfIterations;
  newton.progress = options.progress;
  newton.squareRootGrowth = options.squareRootGrowth;
  return newton;
}

void dampedNewton(NewtonProblem& problem, const std::vector<double>& nu, std::vector<Height>& h,
  const NewtonOptions& options, NewtonReport& report)
{
  NewtonIteration(problem, nu, options, report).run(h);
}

std::vector<double> hessianDiagonal(int n, const std::vector<Eigen::Triplet<double>>& coupling)
{
  std::vector<double> diagonal(n, 0.0);
  for (const auto& c : coupling)
  {
    diagonal[c.row()] += c.value();
    diagonal[c.col()] += c.value();
  }
  return diagonal;
}

double relativeError(const std::vector<double>& cellMass, const std::vector<double>& mass)
{
  double err = 0.0;
  for (size_t i = 0; i < mass.size(); ++i)
  {
    err = std::max(err, std::abs(cellMass[i] - mass[i]) / mass[i]);
  }
  return err;
}

} // namespace otparam
