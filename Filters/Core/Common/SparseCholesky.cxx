#include "Common/SparseCholesky.h"

#ifdef OTPARAM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
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

SparseCholesky::SparseCholesky() = default;
SparseCholesky::SparseCholesky(int cholmodFrom)
  : CholmodFrom(cholmodFrom)
{
}
SparseCholesky::~SparseCholesky() = default;

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
} // namespace

bool SparseCholesky::compute(const SparseMatrix& lower, const std::function<bool()>& keepGoing)
{
  this->Size = static_cast<int>(lower.rows());
  this->Leading = -1;
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Size >= this->CholmodFrom)
  {
    this->Supernodal = std::make_unique<Cholmod>(false);
    return analyzeThenFactor(this->Supernodal->factor, lower, keepGoing);
  }
  this->Supernodal.reset();
#endif
  return analyzeThenFactor(this->Ldlt, lower, keepGoing);
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& b) const
{
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
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(lower.nonZeros());
  for (int col = 0; col < n; ++col)
  {
    for (SparseMatrix::InnerIterator it(lower, col); it; ++it)
    {
      const int r = this->Position[it.row()], c = this->Position[col];
      if (it.row() >= col)
      {
        entries.emplace_back(std::max(r, c), std::min(r, c), it.value());
      }
    }
  }
  SparseMatrix ordered(n, n);
  ordered.setFromTriplets(entries.begin(), entries.end());
  return this->factorPermuted(ordered, keepGoing);
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

} // namespace otparam
