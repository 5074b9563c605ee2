// Sparse Cholesky factorization of symmetric positive-definite matrices (graph Laplacians with
// a pinned or Dirichlet part), shared by the OT solver and the conformal map.
#ifndef OTPARAM_COMMON_SPARSECHOLESKY_H
#define OTPARAM_COMMON_SPARSECHOLESKY_H

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <functional>
#include <memory>
#include <vector>

namespace otparam
{

// Eigen's simplicial LDL^T, or CHOLMOD's supernodal LL^T from CholmodThreshold unknowns up
// (measured on planar Laplacians: simplicial wins below ~2e5, supernodal above).
// Reads the lower triangle only.
//
// At CHOLMOD's sizes the unknowns are split in two halves that a small separator S keeps apart
// (GraphSeparator.h), whenever the graph has one: each half is factored with S (and the caller's
// trailing block) last, the two side by side on the two cores, and the Schur complement on S
// (and that block) is summed from the two factors' trailing blocks and factored dense. A
// planar graph's half costs ~0.35 of the whole, so the factorization's wall time falls by more
// than half, and the halves are the same whatever the thread count (the same bits on one core,
// only later). Side by side only while OpenBLAS runs on one thread: two factorizations on its
// default threads oversubscribed the cores (docs/design.md).
class SparseCholesky
{
public:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  static constexpr int CholmodThreshold = 200000;

  SparseCholesky();
  // CHOLMOD from `cholmodFrom` unknowns up, for matrices whose crossover was measured apart.
  explicit SparseCholesky(int cholmodFrom);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Returns false when the matrix is not numerically positive definite, or when `keepGoing`
  // (asked between the ordering and the numeric factorization, the two long steps that cannot
  // be interrupted inside) says stop.
  bool compute(const SparseMatrix& lower, const std::function<bool()>& keepGoing = {});
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;

  // Like compute, for A = [A11 A12; A21 A22] whose leading block A11 (the first `leading` rows
  // and columns) is also to be solved: the factorization eliminates all of A11 first (in a
  // fill-reducing order of its own), so that its first `leading` columns are a factor of A11
  // and solveLeading uses them. One factorization instead of two (the conformal map's Neumann
  // and Dirichlet Laplacians). A22's Schur complement is dense: for a short trailing block.
  bool computeWithLeadingBlock(
    const SparseMatrix& lower, int leading, const std::function<bool()>& keepGoing = {});
  // x with A11 x = b (b: `leading` rows), after computeWithLeadingBlock.
  Eigen::MatrixXd solveLeading(const Eigen::MatrixXd& b) const;
  // The Schur complement A22 - A21 A11^-1 A12 = F diag(d) F^T (F dense lower triangular), read
  // off the factor's last block after computeWithLeadingBlock: products and solves with it
  // cost O(m^2) for m trailing rows. The conformal map's boundary Dirichlet-to-Neumann map.
  struct SchurFactor
  {
    Eigen::MatrixXd lower;   // F
    Eigen::VectorXd diagonal; // d
    Eigen::MatrixXd apply(const Eigen::MatrixXd& y) const;
    Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const;
  };
  SchurFactor trailingSchurFactor() const;
  int size() const { return Size; }
  // Eigen's solve keeps no state between calls; CHOLMOD's shares a workspace.
  bool concurrentSolvesAreSafe() const { return !Supernodal && !Halves; }
  // Whether CHOLMOD-sized factorizations may be split in two halves (see above). Off by
  // default: the halves' factors hold more entries than one factor of the whole (the face at
  // 1.09M points: 1.34e8 against 9.7e7; 1e6 Diracs: peak 1180 -> 1501 MiB, over the OT
  // solver's memory target); the conformal maps turn it on.
  void allowHalves(bool allow) { AllowHalves = allow; }
  // True when the last factorization was done in two halves.
  bool factoredInHalves() const { return static_cast<bool>(Halves); }

private:
  struct Cholmod; // CHOLMOD stays inside SparseCholesky.cxx (see there)
  struct TwoHalves;
  // The factorization in two halves of `lower` whose first `leading` unknowns are split;
  // false when they have no balanced small separator or the matrix is not positive definite.
  bool computeInHalves(
    const SparseMatrix& lower, int leading, const std::function<bool()>& keepGoing);
  bool factorPermuted(const SparseMatrix& lower, const std::function<bool()>& keepGoing);
  Eigen::MatrixXd permuted(const Eigen::MatrixXd& b) const;
  int Size = -1;
  int CholmodFrom = CholmodThreshold;
  bool AllowHalves = false;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> Ldlt;
  // computeWithLeadingBlock: the factor of P A P^T in its own order; Position[i] = row of
  // unknown i in it.
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> OrderedLdlt;
  std::vector<int> Position;
  int Leading = -1;
  std::unique_ptr<Cholmod> Supernodal;
  std::unique_ptr<TwoHalves> Halves;
};

} // namespace otparam

#endif
