// Sparse Cholesky factorization of symmetric positive-definite matrices (graph Laplacians with
// a pinned or Dirichlet part), shared by the OT solver and the conformal map.
#ifndef OTPARAM_COMMON_SPARSECHOLESKY_H
#define OTPARAM_COMMON_SPARSECHOLESKY_H

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#ifdef OTPARAM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <memory>

namespace otparam
{

// Eigen's simplicial LDL^T, or CHOLMOD's supernodal LL^T from CholmodThreshold unknowns up
// (measured on planar Laplacians: simplicial wins below ~2e5, supernodal above).
// Reads the lower triangle only.
class SparseCholesky
{
public:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  static constexpr int CholmodThreshold = 200000;

  // Returns false when the matrix is not numerically positive definite.
  bool compute(const SparseMatrix& lower)
  {
    Size = static_cast<int>(lower.rows());
#ifdef OTPARAM_HAVE_CHOLMOD
    if (Size >= CholmodThreshold)
    {
      Cholmod = std::make_unique<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>();
      // AMD only: by default CHOLMOD also tries METIS when AMD's fill looks high, which on
      // planar graphs costs more time than it saves.
      Cholmod->cholmod().nmethods = 1;
      Cholmod->cholmod().method[0].ordering = CHOLMOD_AMD;
      Cholmod->compute(lower);
      return Cholmod->info() == Eigen::Success;
    }
    Cholmod.reset();
#endif
    Ldlt.compute(lower);
    return Ldlt.info() == Eigen::Success;
  }

  template <typename Rhs>
  Eigen::MatrixXd solve(const Rhs& b) const
  {
#ifdef OTPARAM_HAVE_CHOLMOD
    if (Cholmod)
    {
      return Cholmod->solve(b);
    }
#endif
    return Ldlt.solve(b);
  }

  int size() const
  {
    return Size;
  }

  // Eigen's solve keeps no state between calls; CHOLMOD's shares a workspace.
  bool concurrentSolvesAreSafe() const
  {
#ifdef OTPARAM_HAVE_CHOLMOD
    return !Cholmod;
#else
    return true;
#endif
  }

private:
  int Size = -1;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> Ldlt;
#ifdef OTPARAM_HAVE_CHOLMOD
  std::unique_ptr<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>> Cholmod;
#endif
};

} // namespace otparam

#endif
