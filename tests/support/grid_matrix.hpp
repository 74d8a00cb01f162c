#pragma once
// A sparse symmetric test matrix with a known structure, for the linear solver tests.
#include <vector>

#include "roller/core/types.hpp"

namespace roller::test {

// Symmetric matrix on the 5-point stencil of a g x g grid: `diagonal(k)` on the diagonal, `off`
// between grid neighbours.
template <class Diagonal>
SparseMatrix grid_matrix(int g, Diagonal diagonal, Real off) {
  std::vector<Triplet> t;
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j) {
      const int k = i * g + j;
      t.emplace_back(k, k, diagonal(k));
      if (i + 1 < g) t.emplace_back(k + g, k, off), t.emplace_back(k, k + g, off);
      if (j + 1 < g) t.emplace_back(k + 1, k, off), t.emplace_back(k, k + 1, off);
    }
  SparseMatrix a(g * g, g * g);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

}  // namespace roller::test
