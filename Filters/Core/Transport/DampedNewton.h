// The damped Newton iteration of semi-discrete optimal transport (method.md, Algorithm 1, with
// the Kitagawa-Merigot-Thibert step rule), written once for every pair of a power diagram and a
// source measure: the plane (SemiDiscreteOT.cxx) and the sphere plug into it through
// NewtonProblem, which evaluates cell masses and Hessian couplings at trial heights. Private to
// the transport stage (Eigen in its interface).
#ifndef OTPARAM_TRANSPORT_DAMPEDNEWTON_H
#define OTPARAM_TRANSPORT_DAMPEDNEWTON_H

#include "Transport/Height.h"
#include "Transport/SemiDiscreteOT.h"

#include <Eigen/SparseCore>

#include <functional>
#include <string>
#include <vector>

namespace otparam
{

// Cell masses and Hessian couplings mu(W_i ∩ W_j) / |y_i - y_j| (i < j, neighbouring cells,
// in row order) at some heights.
struct NewtonEvaluation
{
  std::vector<double> cellMass;
  std::vector<Eigen::Triplet<double>> coupling;
  double minMass = 0.0;
  int emptyCells = 0;
};

// One transport problem as the Newton iteration sees it: a current state (heights and their
// evaluation, owned by the problem's caller) and trials.
class NewtonProblem
{
public:
  virtual ~NewtonProblem() = default;
  virtual const NewtonEvaluation& current() const = 0;
  // True only when the trial heights certainly hide a Dirac (empty its cell): the trial is then
  // rejected without an evaluation. May always answer false.
  virtual bool certainlyHidesADirac(const std::vector<Height>& trial, NewtonReport& timing) = 0;
  // Evaluates trial heights (a hidden Dirac may end the evaluation early with all masses 0).
  virtual const NewtonEvaluation& evaluateTrial(
    const std::vector<Height>& trial, NewtonReport& timing) = 0;
  // The last trial becomes the current state.
  virtual void acceptTrial() = 0;
  // Memory the iteration gives back (the plane, 1e6 Diracs: peak 1666 MiB, the median of three
  // seeds, -> 1207 MiB, the largest, with the allocator trimmed around each solve as
  // DampedNewton.cxx does; the sphere's
  // problems are ten times smaller and keep the defaults, which do nothing):
  // - before each Newton solve, what the last trial left behind and the current state's cell
  //   geometry, which neither the solve nor the step search reads, so that a factorization's
  //   memory does not add to them;
  virtual void releaseBeforeSolve() {}
  // - after it, the current Hessian couplings: an accepted trial brings its own, and a failed
  //   search ends the iteration.
  virtual void releaseCouplings() {}
};

struct NewtonOptions
{
  double tolerance = 1e-10;
  int maximumNumberOfIterations = 200;
  // After a damped step, try the full step first (true), or twice the last step (false): each
  // rejected trial costs a whole evaluation (the sphere, 1e5 Diracs of contrast 1e4, seed 1:
  // the same 19 iterations in 25.5 s with the full step first (43 evaluations) under load;
  // seeds 1 / 2 paired on a quiet machine: 14.1 / 15.7 s with 4x the last step, 11.3 / 12.4 s
  // with twice it).
  bool fullStepFirst = true;
  // Newton on sqrt(cell mass) for cells below half their masses (DampedNewton.cxx).
  bool squareRootGrowth = true;
  // Called once per iteration with (iteration, relative error); return false to abort.
  std::function<bool(int, double)> progress;
};

// The transport options' share of the Newton iteration, the same for the plane and the sphere
// (each domain then sets its own step rule, fullStepFirst).
NewtonOptions newtonOptionsOf(const OTOptions& options);

// Damped Newton from heights h whose cells are all non-empty (problem.current() evaluated at h)
// to cell masses nu; h ends at the last accepted heights. Records histories and stops as
// documented in NewtonReport.
void dampedNewton(NewtonProblem& problem, const std::vector<double>& nu, std::vector<Height>& h,
  const NewtonOptions& options, NewtonReport& report);

// Diagonal of the Newton Hessian: the sum of each Dirac's couplings.
std::vector<double> hessianDiagonal(int n, const std::vector<Eigen::Triplet<double>>& coupling);

// max_i |cellMass_i - mass_i| / mass_i
double relativeError(const std::vector<double>& cellMass, const std::vector<double>& mass);

} // namespace otparam

#endif
