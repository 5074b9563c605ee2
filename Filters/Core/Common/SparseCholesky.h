// Sparse Cholesky factorization of symmetric positive-definite matrices (graph Laplacians with
// a pinned or Dirichlet part), shared by the OT solver and the conformal map.
#ifndef OTPARAM_COMMON_SPARSECHOLESKY_H
#define OTPARAM_COMMON_SPARSECHOLESKY_H

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <functional>
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

  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Returns false when the matrix is not numerically positive definite, or when `keepGoing`
  // (asked between the ordering and the numeric factorization, the two long steps that cannot
  // be interrupted inside) says stop.
  bool compute(const SparseMatrix& lower, const std::function<bool()>& keepGoing = {});
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;
  int size() const { return Size; }
  // Eigen's solve keeps no state between calls; CHOLMOD's shares a workspace.
  bool concurrentSolvesAreSafe() const { return !Supernodal; }

private:
  struct Cholmod; // CHOLMOD stays inside SparseCholesky.cxx (see there)
  int Size = -1;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> Ldlt;
  std::unique_ptr<Cholmod> Supernodal;
};

} // namespace otparam

#endif
