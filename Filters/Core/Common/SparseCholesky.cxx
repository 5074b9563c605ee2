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
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> factor;
  Cholmod()
  {
    // AMD only: by default CHOLMOD also tries METIS when AMD's fill looks high, which on planar
    // graphs costs more time than it saves.
    this->factor.cholmod().nmethods = 1;
    this->factor.cholmod().method[0].ordering = CHOLMOD_AMD;
  }
};
#else
struct SparseCholesky::Cholmod
{
};
#endif

SparseCholesky::SparseCholesky() = default;
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
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Size >= CholmodThreshold)
  {
    this->Supernodal = std::make_unique<Cholmod>();
    return analyzeThenFactor(this->Supernodal->factor, lower, keepGoing);
  }
  this->Supernodal.reset();
#endif
  return analyzeThenFactor(this->Ldlt, lower, keepGoing);
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& b) const
{
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Supernodal)
  {
    return this->Supernodal->factor.solve(b);
  }
#endif
  return this->Ldlt.solve(b);
}

} // namespace otparam
