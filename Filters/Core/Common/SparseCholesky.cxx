#include "Common/SparseCholesky.h"

#ifdef OTPARAM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <dlfcn.h>

namespace otparam
{
namespace
{
// Looked up at run time: the BLAS behind CHOLMOD is whichever libblas.so.3 the system chose
// (Debian's alternatives), OpenBLAS or not, and the core does not link it itself.
using SetThreads = void (*)(int);
using GetThreads = int (*)();
SetThreads openblasSetThreads()
{
  return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
}
GetThreads openblasGetThreads()
{
  return reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
}
} // namespace

ScopedBlasThreads::ScopedBlasThreads(int threads)
{
  const SetThreads set = openblasSetThreads();
  const GetThreads get = openblasGetThreads();
  if (set && get)
  {
    this->Previous = get();
    set(threads);
  }
}

ScopedBlasThreads::~ScopedBlasThreads()
{
  if (this->Previous > 0)
  {
    openblasSetThreads()(this->Previous);
  }
}

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

bool SparseCholesky::compute(const SparseMatrix& lower)
{
  this->Size = static_cast<int>(lower.rows());
#ifdef OTPARAM_HAVE_CHOLMOD
  if (this->Size >= CholmodThreshold)
  {
    this->Supernodal = std::make_unique<Cholmod>();
    this->Supernodal->factor.compute(lower);
    return this->Supernodal->factor.info() == Eigen::Success;
  }
  this->Supernodal.reset();
#endif
  this->Ldlt.compute(lower);
  return this->Ldlt.info() == Eigen::Success;
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
