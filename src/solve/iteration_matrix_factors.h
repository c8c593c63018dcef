// The factors of an implicit integrator's iteration matrix S = I - c1 df/dq - c2 df/dqd, and
// solves with them.
//
// Where S allows it, the work is halved: the coordinates split into free ones (qdd = g / m:
// particles and bodies moved by forces alone) and the others (constrained, imposed). Scaled by
// the masses, the free block M_F S_FF = M_F + c1 K + c2 C is symmetric when the forces derive
// from a potential with a symmetric damping (peridynamic bonds, springs), and positive definite
// for the step sizes an implicit run takes. When moreover no constrained row reads a free
// coordinate (S_CF = 0: grips whose motion the drivers determine alone, as on the notched plate),
//   S = [S_FF S_FC; 0 S_CC]:  S_CC x_C = b_C by LU,  (M_F S_FF) x_F = M_F (b_F - S_FC x_C)
// by a supernodal Cholesky (sparse_cholesky.h). Otherwise, or when the free block is not
// symmetric to within kAsymmetry (a finite-difference tangent is symmetric to about 1e-7; a
// friction contact or a follower force is not, by far) or not positive definite, S is
// factorised whole by LU (sparse_lu.h), from then on for this pattern.
//
// On the notched plate's first HHT step (8,006 unknowns): the LU of S 80-110 ms, the Cholesky
// of the free block 35-60 ms (docs/solver.md).
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "solve/sparse_cholesky.h"
#include "solve/sparse_lu.h"

namespace periflex {

class IterationMatrixFactors {
 public:
  // Analyses the pattern of s (square, compressed, column-major). free_mass[i] is the mass of
  // coordinate i where its acceleration is its force over its mass, 0 where it is not (an empty
  // vector: no coordinate is free, S is factorised whole).
  void analyse(const Eigen::SparseMatrix<double>& s, const Eigen::VectorXd& free_mass);
  // True when s has the pattern last analysed.
  bool same_pattern(const Eigen::SparseMatrix<double>& s) const;
  // Factorises s; false when it is singular or its pattern is not the analysed one.
  bool factorize(const Eigen::SparseMatrix<double>& s);
  // x with S x = b, after a successful factorize() (NaN where a solve failed).
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // Whether the last factorisation took the symmetric free block by Cholesky.
  bool split() const { return split_; }

  // Largest |a_ij - a_ji| / sqrt(a_ii a_jj) of the mass-scaled free block taken as symmetric
  // (and then averaged). The finite-difference tangent of the notched plate reaches 2.8e-7; a
  // block averaged within 1e-5 of itself costs Newton about that rate of convergence, nothing
  // a step would see.
  static constexpr double kAsymmetry = 1e-5;

 private:
  bool factorize_whole(const Eigen::SparseMatrix<double>& s);

  // the pattern analysed, and whether it can be split at all
  std::vector<int> outer_, inner_;
  bool splittable_ = false, split_ = false;
  int n_ = 0;
  // free coordinates (F) and the others (C): their places in S, and each coordinate's place in
  // its set
  std::vector<int> free_, other_;
  Eigen::VectorXd mass_;  // of the free coordinates, in F's order
  // the lower triangle of M_F S_FF in compressed columns; entry e is the mean of m_i s_ij at
  // S's value index source_[2e] and m_j s_ji at source_[2e + 1] (-1: not in S), or m_i s_ii
  std::vector<int> lower_start_, lower_rows_, source_;
  std::vector<double> lower_values_;
  std::vector<int> diagonal_;  // entry of each free column's diagonal in the lower triangle
  // S_FC: row in F, column in C and value index in S of each entry
  std::vector<int> coupling_row_, coupling_col_, coupling_source_;
  std::vector<double> coupling_values_;
  // S_CC in compressed columns and the value index in S of each of its entries
  Eigen::SparseMatrix<double> other_block_;
  std::vector<int> other_source_;
  SparseCholesky cholesky_;
  SparseLu other_lu_;
  SparseLu whole_lu_;  // of S, when it cannot be split
  bool whole_analysed_ = false;
};

}  // namespace periflex
