#include "Common/SparseCholesky.h"

#include "Common/GraphSeparator.h"

#include <Eigen/Cholesky>

#include <array>
#include <cmath>
#include <exception>

#ifdef OTPARAM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#include <dlfcn.h>
// The BLAS and LAPACK under CHOLMOD (Fortran interface).
extern "C" void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k,
  const double* alpha, const double* a, const int* lda, const double* beta, double* c,
  const int* ldc);
extern "C" void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

namespace otparam
{

// CHOLMOD stays in this file, so that every user of the header sees one class whether or not
// CHOLMOD was found.
#ifdef OTPARAM_HAVE_CHOLMOD
struct SparseCholesky::Cholmod
{
  // Eigen's wrapper with its factor in reach, for the half solves of solveLeading.
  struct Factor : Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>
  {
    cholmod_factor* factor() const { return this->m_cholmodFactor; }
  };
  Factor factor;
  // givenOrder: the matrix comes in elimination order (computeWithLeadingBlock).
  explicit Cholmod(bool givenOrder)
  {
    // AMD only: by default CHOLMOD also tries METIS when AMD's fill looks high, which on planar
    // graphs costs more time than it saves.
    this->factor.cholmod().nmethods = 1;
    this->factor.cholmod().method[0].ordering = givenOrder ? CHOLMOD_NATURAL : CHOLMOD_AMD;
    // A postorder of the elimination tree could move a subtree of A11 behind rows of A22.
    this->factor.cholmod().postorder = !givenOrder;
  }

  // The factor's columns from `first` on, rows from `first` on (dense): with the matrix in
  // elimination order (natural ordering, no postorder) CHOLMOD keeps it in that order.
  Eigen::MatrixXd trailingBlock(int first) const
  {
    const cholmod_factor* f = this->factor.factor();
    const int n = static_cast<int>(f->n), m = n - first;
    Eigen::MatrixXd block = Eigen::MatrixXd::Zero(m, m);
    const int* super = static_cast<const int*>(f->super);
    const int* pi = static_cast<const int*>(f->pi);
    const int* px = static_cast<const int*>(f->px);
    const int* rows = static_cast<const int*>(f->s);
    const double* x = static_cast<const double*>(f->x);
    for (std::size_t k = 0; k < f->nsuper; ++k)
    {
      const int rowCount = pi[k + 1] - pi[k];
      for (int col = std::max(super[k], first); col < super[k + 1]; ++col)
      {
        for (int r = 0; r < rowCount; ++r)
        {
          const int row = rows[pi[k] + r];
          if (row >= first)
          {
            block(row - first, col - first) = x[px[k] + r + (col - super[k]) * rowCount];
          }
        }
      }
    }
    return block;
  }

  // L y = b (lower = true) or L^T y = b.
  Eigen::MatrixXd halfSolve(const Eigen::MatrixXd& b, bool lower) const
  {
    Eigen::MatrixXd in = b;
    cholmod_dense view = Eigen::viewAsCholmod(in);
    cholmod_common& common = const_cast<Factor&>(this->factor).cholmod();
    cholmod_dense* out =
      cholmod_solve(lower ? CHOLMOD_L : CHOLMOD_Lt, this->factor.factor(), &view, &common);
    Eigen::MatrixXd y = Eigen::Map<Eigen::MatrixXd>(
      static_cast<double*>(out->x), static_cast<Eigen::Index>(out->nrow), b.cols());
    cholmod_free_dense(&out, &common);
    return y;
  }
};
#else
struct SparseCholesky::Cholmod
{
};
#endif

namespace
{
template <typename Factorization>
bool analyzeThenFactor(Factorization& factorization, const SparseCholesky::SparseMatrix& lower,
  const std::function<bool()>& keepGoing)
{
  factorization.analyzePattern(lower);
  if (factorization.info() != Eigen::Success || (keepGoing && !keepGoing()))
  {
    return false;
  }
  factorization.factorize(lower);
  return factorization.info() == Eigen::Success;
}

// Both tasks on the two cores when there are two and the BLAS under CHOLMOD runs on one thread
// (OpenBLAS's own threads otherwise: side by side they oversubscribed the cores); in turn else.
// The result is the same either way.
template <typename Task>
void onBothCores(const Task& task)
{
  bool together = false;
#if defined(_OPENMP) && defined(OTPARAM_HAVE_CHOLMOD)
  using ThreadCount = int (*)();
  static const auto blasThreads =
    reinterpret_cast<ThreadCount>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  together =
    omp_get_max_threads() > 1 && !omp_in_parallel() && (!blasThreads || blasThreads() == 1);
#endif
  // An exception must not leave an OpenMP region (std::terminate): it is carried out of it.
  std::array<std::exception_ptr, 2> failure;
#pragma omp parallel for num_threads(2) schedule(static, 1) if (together)
  for (int i = 0; i < 2; ++i)
  {
    try
    {
      task(i);
    }
    catch (...)
    {
      failure[i] = std::current_exception();
    }
  }
  for (const std::exception_ptr& f : failure)
  {
    if (f)
    {
      std::rethrow_exception(f);
    }
  }
}
// The lower triangle of A[rows, rows] for the unknowns with local[v] >= 0, renumbered to
// local[v] (a permutation when every local[v] >= 0).
SparseCholesky::SparseMatrix restricted(
  const SparseCholesky::SparseMatrix& lower, const std::vector<int>& local, int size)
{
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(lower.nonZeros());
  for (int col = 0; col < lower.outerSize(); ++col)
  {
    for (SparseCholesky::SparseMatrix::InnerIterator it(lower, col); it; ++it)
    {
      const int r = local[it.row()], c = local[col];
      if (r >= 0 && c >= 0 && it.row() >= col)
      {
        entries.emplace_back(std::max(r, c), std::min(r, c), it.value());
      }
    }
  }
  SparseCholesky::SparseMatrix a(size, size);
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

#ifdef OTPARAM_HAVE_CHOLMOD
// The graph of the leading `leading` unknowns of a lower triangle: an edge per entry below
// the diagonal.
Adjacency leadingGraph(const SparseCholesky::SparseMatrix& lower, int leading)
{
  Adjacency graph;
  graph.offsets.assign(leading + 1, 0);
  auto forEdge = [&](const auto& visit)
  {
    for (int col = 0; col < leading; ++col)
    {
      for (SparseCholesky::SparseMatrix::InnerIterator it(lower, col); it; ++it)
      {
        const int row = static_cast<int>(it.row());
        if (row > col && row < leading)
        {
          visit(row, col);
        }
      }
    }
  };
  forEdge(
    [&](int row, int col)
    {
      ++graph.offsets[row + 1];
      ++graph.offsets[col + 1];
    });
  for (int v = 0; v < leading; ++v)
  {
    graph.offsets[v + 1] += graph.offsets[v];
  }
  graph.targets.resize(graph.offsets.back());
  std::vector<int> fill(graph.offsets.begin(), graph.offsets.end() - 1);
  forEdge(
    [&](int row, int col)
    {
      graph.targets[fill[row]++] = col;
      graph.targets[fill[col]++] = row;
    });
  return graph;
}
#endif
} // namespace

#ifdef OTPARAM_HAVE_CHOLMOD
// The factorization in two halves (SparseCholesky.h). With the unknowns ordered [P0, P1, T]
// (the two sides, then the trailing ones: the separator S, then the caller's trailing block),
// the whole factor is [L0 0 0; 0 L1 0; G0 G1 LC]. Each side's matrix A[Pi T, Pi T] factors as
// [Li 0; Gi Ti], so LC LC^T = A_TT - G0 G0^T - G1 G1^T = T0 T0^T + T1 T1^T - A_TT. The
// solves use each side's half solves: the forward one with the trailing rows at zero leaves
// -Ti^-1 Gi zi there, the backward one with Ti^T xT there gives xi.
struct SparseCholesky::TwoHalves
{
  std::array<std::vector<int>, 2> side; // each side's unknowns in elimination (AMD) order
  std::vector<int> trailing;            // S by index, then the caller's trailing block
  int separator = 0;                    // |S|
  std::array<std::unique_ptr<Cholmod>, 2> factor;
  std::array<Eigen::MatrixXd, 2> border; // Ti
  Eigen::MatrixXd schurLower;            // LC

  // Unknowns 0..leading-1 split by `part`; `leading`..n-1 trail.
  void order(const std::vector<SeparatorPart>& part, int leading, int n)
  {
    for (int v = 0; v < leading; ++v)
    {
      if (part[v] == SeparatorPart::Separator)
      {
        this->trailing.push_back(v);
      }
      else
      {
        this->side[part[v] == SeparatorPart::First ? 0 : 1].push_back(v);
      }
    }
    this->separator = static_cast<int>(this->trailing.size());
    for (int v = leading; v < n; ++v)
    {
      this->trailing.push_back(v);
    }
  }

  // Side i in AMD order (of the side alone), then its matrix [Pi T] factored, and Ti read
  // off. Measured at 1.09M points and not kept: CAMD on [Pi T] with T constrained last (its
  // vertices next to S then count their edges into S): factors 10% smaller, but the sides
  // took 5.6 s against 4.6 s.
  bool factorSide(int i, const SparseMatrix& lower)
  {
    std::vector<int>& unknowns = this->side[i];
    const int ni = static_cast<int>(unknowns.size());
    const int m = static_cast<int>(this->trailing.size());
    std::vector<int> local(lower.rows(), -1);
    for (int k = 0; k < ni; ++k)
    {
      local[unknowns[k]] = k;
    }
    {
      const SparseMatrix own = restricted(lower, local, ni);
      Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
      Eigen::AMDOrdering<int>()(own.selfadjointView<Eigen::Lower>(), amd);
      std::vector<int> ordered(ni);
      for (int k = 0; k < ni; ++k)
      {
        ordered[k] = unknowns[amd.indices()[k]]; // AMD's indices: each new place's old one
      }
      unknowns = ordered;
    }
    for (int k = 0; k < ni; ++k)
    {
      local[unknowns[k]] = k;
    }
    for (int k = 0; k < m; ++k)
    {
      local[this->trailing[k]] = ni + k;
    }
    this->factor[i] = std::make_unique<Cholmod>(true);
    if (!analyzeThenFactor(this->factor[i]->factor, restricted(lower, local, ni + m), {}))
    {
      return false;
    }
    this->border[i] = this->factor[i]->trailingBlock(ni);
    return true;
  }

  // LC from T0, T1 and A_TT, by the BLAS and LAPACK (the products one per core, then the dense
  // factor in place). Eigen's own dense kernels, built for the baseline x86-64, took 2.5 s for
  // this at 1.09M points (m = 2637); a CHOLMOD factorization of C as a sparse matrix 0.8 s.
  bool factorSchurComplement(const SparseMatrix& lower)
  {
    const int m = static_cast<int>(this->trailing.size());
    std::array<Eigen::MatrixXd, 2> products;
    onBothCores(
      [&](int i)
      {
        products[i].resize(m, m);
        const char uplo = 'L', trans = 'N';
        const double one = 1.0, zero = 0.0;
        dsyrk_(
          &uplo, &trans, &m, &m, &one, this->border[i].data(), &m, &zero, products[i].data(), &m);
      });
    Eigen::MatrixXd& c = products[0];
    c.triangularView<Eigen::Lower>() += products[1];
    products[1] = Eigen::MatrixXd();
    std::vector<int> local(lower.rows(), -1);
    for (int k = 0; k < m; ++k)
    {
      local[this->trailing[k]] = k;
    }
    const SparseMatrix a = restricted(lower, local, m);
    for (int col = 0; col < m; ++col)
    {
      for (SparseMatrix::InnerIterator it(a, col); it; ++it)
      {
        c(it.row(), col) -= it.value();
      }
    }
    const char uplo = 'L';
    int info = 0;
    dpotrf_(&uplo, &m, c.data(), &m, &info);
    if (info != 0)
    {
      return false;
    }
    c.triangularView<Eigen::StrictlyUpper>().setZero();
    this->schurLower = std::move(c);
    return true;
  }

  // x with A x = b, or with A's leading block when `leading` (b: that block's rows).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b, bool leading) const
  {
    const int t = leading ? this->separator : static_cast<int>(this->trailing.size());
    const int m = static_cast<int>(this->trailing.size());
    const Eigen::Index columns = b.cols();
    Eigen::MatrixXd trailingRhs(t, columns);
    for (int k = 0; k < t; ++k)
    {
      trailingRhs.row(k) = b.row(this->trailing[k]);
    }
    std::array<Eigen::MatrixXd, 2> forward, coupling;
    onBothCores(
      [&](int i)
      {
        const std::vector<int>& unknowns = this->side[i];
        const int ni = static_cast<int>(unknowns.size());
        Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(ni + m, columns);
        for (int k = 0; k < ni; ++k)
        {
          rhs.row(k) = b.row(unknowns[k]);
        }
        forward[i] = this->factor[i]->halfSolve(rhs, true);
        coupling[i] =
          (this->border[i].triangularView<Eigen::Lower>() * forward[i].bottomRows(m)).topRows(t);
      });
    trailingRhs += coupling[0] + coupling[1]; // b_T - G0 z0 - G1 z1
    const auto lc = this->schurLower.topLeftCorner(t, t).triangularView<Eigen::Lower>();
    lc.solveInPlace(trailingRhs);
    lc.transpose().solveInPlace(trailingRhs);
    Eigen::MatrixXd x(b.rows(), columns);
    onBothCores(
      [&](int i)
      {
        const std::vector<int>& unknowns = this->side[i];
        const int ni = static_cast<int>(unknowns.size());
        Eigen::MatrixXd rhs(ni + m, columns);
        rhs.topRows(ni) = forward[i].topRows(ni);
        Eigen::MatrixXd xT = Eigen::MatrixXd::Zero(m, columns);
        xT.topRows(t) = trailingRhs;
        rhs.bottomRows(m) = this->border[i].triangularView<Eigen::Lower>().transpose() * xT;
        const Eigen::MatrixXd y = this->factor[i]->halfSolve(rhs, false);
        for (int k = 0; k < ni; ++k)
        {
          x.row(unknowns[k]) = y.row(k);
        }
      });
    for (int k = 0; k < t; ++k)
    {
      x.row(this->trailing[k]) = trailingRhs.row(k);
    }
    return x;
  }
};
#else
struct SparseCholesky::TwoHalves
{
};
#endif

SparseCholesky::SparseCholesky() = default;
SparseCholesky::SparseCholesky(int cholmodFrom)
  : CholmodFrom(cholmodFrom)
{
}
SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::compute(const SparseMatrix& lower, const std::function<bool()>& keepGoing)
{
  this->Size = static_cast<int>(lower.rows());
  this->Leading = -1;
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Size >= this->CholmodFrom)
  {
    if (this->computeInHalves(lower, this->Size, keepGoing))
    {
      return true;
    }
    if (keepGoing && !keepGoing())
    {
      return false;
    }
    this->Supernodal = std::make_unique<Cholmod>(false);
    return analyzeThenFactor(this->Supernodal->factor, lower, keepGoing);
  }
  this->Supernodal.reset();
#endif
  return analyzeThenFactor(this->Ldlt, lower, keepGoing);
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& b) const
{
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Halves)
  {
    return this->Halves->solve(b, false);
  }
#endif
  if (this->Leading >= 0)
  {
    Eigen::MatrixXd x;
#ifdef OTPARAM_HAVE_CHOLMOD
    if (this->Supernodal)
    {
      x = this->Supernodal->factor.solve(this->permuted(b));
    }
    else
#endif
    {
      x = this->OrderedLdlt.solve(this->permuted(b));
    }
    Eigen::MatrixXd result(b.rows(), b.cols());
    for (int i = 0; i < this->Size; ++i)
    {
      result.row(i) = x.row(this->Position[i]);
    }
    return result;
  }
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Supernodal)
  {
    return this->Supernodal->factor.solve(b);
  }
#endif
  return this->Ldlt.solve(b);
}

bool SparseCholesky::computeWithLeadingBlock(
  const SparseMatrix& lower, int leading, const std::function<bool()>& keepGoing)
{
  const int n = static_cast<int>(lower.rows());
  this->Size = n;
  this->Leading = leading;
  if (n >= this->CholmodFrom && this->computeInHalves(lower, leading, keepGoing))
  {
    return true;
  }
  if (keepGoing && !keepGoing())
  {
    return false;
  }
  // Elimination order: A11 in AMD order, then A22's rows as they come.
  const SparseMatrix a11 = lower.topLeftCorner(leading, leading);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(a11.selfadjointView<Eigen::Lower>(), order);
  this->Position.assign(n, 0);
  for (int k = 0; k < leading; ++k)
  {
    this->Position[order.indices()[k]] = k;
  }
  for (int i = leading; i < n; ++i)
  {
    this->Position[i] = i;
  }
  return this->factorPermuted(restricted(lower, this->Position, n), keepGoing);
}

bool SparseCholesky::factorPermuted(
  const SparseMatrix& lower, const std::function<bool()>& keepGoing)
{
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Size >= this->CholmodFrom)
  {
    this->Supernodal = std::make_unique<Cholmod>(true);
    return analyzeThenFactor(this->Supernodal->factor, lower, keepGoing);
  }
#endif
  this->Supernodal.reset();
  return analyzeThenFactor(this->OrderedLdlt, lower, keepGoing);
}

Eigen::MatrixXd SparseCholesky::permuted(const Eigen::MatrixXd& b) const
{
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(this->Size, b.cols());
  for (Eigen::Index i = 0; i < b.rows(); ++i)
  {
    p.row(this->Position[i]) = b.row(i);
  }
  return p;
}

SparseCholesky::SchurFactor SparseCholesky::trailingSchurFactor() const
{
  const int first = this->Leading;
  const int m = this->Size - first;
  SchurFactor schur;
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Halves)
  {
    // LC = [Lss 0; Lbs Lbb] over [S, trailing block]: the block's Schur complement is Lbb Lbb^T.
    schur.lower = this->Halves->schurLower.bottomRightCorner(m, m);
    schur.diagonal = Eigen::VectorXd::Ones(m);
    return schur;
  }
  if (this->Supernodal)
  {
    schur.lower = this->Supernodal->trailingBlock(first);
    schur.diagonal = Eigen::VectorXd::Ones(m);
    return schur;
  }
#endif
  // L D L^T: the trailing block of the unit lower L, and of D.
  schur.lower = Eigen::MatrixXd::Identity(m, m);
  const SparseMatrix& stored = this->OrderedLdlt.matrixL().nestedExpression();
  for (int col = first; col < this->Size; ++col)
  {
    for (SparseMatrix::InnerIterator it(stored, col); it; ++it)
    {
      if (it.row() > col)
      {
        schur.lower(it.row() - first, col - first) = it.value();
      }
    }
  }
  schur.diagonal = this->OrderedLdlt.vectorD().tail(m);
  return schur;
}

Eigen::MatrixXd SparseCholesky::SchurFactor::apply(const Eigen::MatrixXd& y) const
{
  const auto f = this->lower.triangularView<Eigen::Lower>();
  return f * (this->diagonal.asDiagonal() * (f.transpose() * y));
}

Eigen::MatrixXd SparseCholesky::SchurFactor::solve(const Eigen::MatrixXd& r) const
{
  const auto f = this->lower.triangularView<Eigen::Lower>();
  Eigen::MatrixXd x = f.solve(r);
  x = this->diagonal.asDiagonal().inverse() * x;
  f.transpose().solveInPlace(x);
  return x;
}

// The leading block's factor is the first `Leading` columns of the whole one: solve with it,
// the trailing rows held at zero between the two triangular solves.
Eigen::MatrixXd SparseCholesky::solveLeading(const Eigen::MatrixXd& b) const
{
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Halves)
  {
    return this->Halves->solve(b, true);
  }
#endif
  const int trailing = this->Size - this->Leading;
  Eigen::MatrixXd y = this->permuted(b);
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Supernodal)
  {
    y = this->Supernodal->halfSolve(y, true);
    y.bottomRows(trailing).setZero();
    y = this->Supernodal->halfSolve(y, false);
  }
  else
#endif
  {
    this->OrderedLdlt.matrixL().solveInPlace(y);
    y = this->OrderedLdlt.vectorD().asDiagonal().inverse() * y;
    y.bottomRows(trailing).setZero();
    this->OrderedLdlt.matrixU().solveInPlace(y);
  }
  Eigen::MatrixXd x(b.rows(), b.cols());
  for (Eigen::Index i = 0; i < b.rows(); ++i)
  {
    x.row(i) = y.row(this->Position[i]);
  }
  return x;
}

// The separator must be small: its dense Schur complement costs m^3 / 3 flops for m trailing
// unknowns, against ~n^1.5 for the sparse part of a planar graph.
bool SparseCholesky::computeInHalves(
  const SparseMatrix& lower, int leading, const std::function<bool()>& keepGoing)
{
  this->Halves.reset();
#ifdef OTPARAM_HAVE_CHOLMOD
  if (!this->AllowHalves)
  {
    return false;
  }
  const Adjacency graph = leadingGraph(lower, leading);
  // Work models (flops): AMD on a planar graph of n unknowns ~SparseWork n^1.5 (CHOLMOD, the
  // face at 1.09M points: 9.5e10); m dense trailing unknowns ~m^3 in all (their share of both
  // sides' factors, the two products and the dense factor).
  constexpr double SparseWork = 83.0;
  const double trailing = static_cast<double>(lower.rows() - leading);
  const auto work = [&](std::int64_t first, std::int64_t second, std::int64_t separator)
  {
    const double side = static_cast<double>(std::max(first, second));
    const double dense = static_cast<double>(separator) + trailing;
    return SparseWork * side * std::sqrt(side) + dense * dense * dense;
  };
  std::vector<SeparatorPart> part;
  const double split = separateByLevels(graph, work, part);
  const double whole =
    SparseWork * leading * std::sqrt(double(leading)) + trailing * trailing * trailing / 3.0;
  if (!(split < 0.8 * whole)) // halves only where the model saves a fifth or more
  {
    return false;
  }
  auto halves = std::make_unique<TwoHalves>();
  halves->order(part, leading, static_cast<int>(lower.rows()));
  std::array<bool, 2> factored = { false, false };
  onBothCores([&](int i) { factored[i] = halves->factorSide(i, lower); });
  if (!factored[0] || !factored[1] || (keepGoing && !keepGoing()) ||
    !halves->factorSchurComplement(lower))
  {
    return false;
  }
  this->Supernodal.reset();
  this->Halves = std::move(halves);
  return true;
#else
  (void)lower;
  (void)leading;
  (void)keepGoing;
  return false;
#endif
}

} // namespace otparam
