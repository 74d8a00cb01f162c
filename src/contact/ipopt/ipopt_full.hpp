#pragma once
// The "full" formulation of the interior-point backend (contact.ipopt.formulation = "full"):
// Ipopt on the whole strip's nonlinear energy, every free dof an NLP variable (docs/model.md,
// "The interior-point backend's NLP in detail"). Also the fallback of the condensed formulation.
#include <string>
#include <vector>

#include "contact_tnlp.hpp"
#include "roller/contact/backend.hpp"

namespace roller::ipopt_detail {

// The strip's incremental potential Pi over the free dofs as the NLP's objective. Energy and
// gradient are cached (Ipopt asks for f and grad f separately); the Hessian's pattern is fixed at
// construction (the Hessian at the start vector) and checked at every evaluation; the contact curvature is appended to
// it as entries of their own (Ipopt sums duplicates).
class StripObjective : public NlpObjective {
 public:
  StripObjective(IncrementProblem& problem, SparseMatrix start_hessian);
  int n() const override { return static_cast<int>(problem_.n_free()); }
  bool value(const Real* d, Real& f) override;
  bool gradient(const Real* d, Real* g) override;
  int hessian_nnz() const override { return static_cast<int>(slot_.size()); }
  void hessian_structure(int* row, int* col) const override;
  bool hessian_values(const Real* d, Real obj_factor, Real* values) override;
  int hessian_position(int /*r*/, int /*c*/) const override { return -1; }
  std::string evaluation_error() const override { return evaluation_error_; }

 private:
  bool update(const Real* d);
  IncrementProblem& problem_;
  // Lower triangle of the strip Hessian's fixed pattern: value slots and (row, col); the full
  // pattern (outer, inner) to check that it does not change between evaluations.
  std::vector<int> slot_, row_, col_, outer_, inner_;
  VecX x_;
  bool cache_valid_ = false, cache_ok_ = false;
  Real energy_ = 0.0;
  VecX gradient_;
  SparseMatrix hessian_;
  std::string evaluation_error_;
};

// Every candidate with a free dof is a row; the primal variables are the free dofs.
std::vector<RowMap> full_rows(const IncrementProblem& problem);
// x0 and the candidates' previous forces.
NlpStart full_start(const IncrementProblem& problem, const std::vector<RowMap>& rows, const VecX& x0);

BackendResult solve_full(IncrementProblem& problem, const VecX& x0, const ContactOptions& options);

}  // namespace roller::ipopt_detail
