#pragma once
// The "condensed" formulation of the interior-point backend (contact.ipopt.formulation; the
// default). See ipopt_condensed.cpp.
#include <optional>
#include <vector>

#include "contact_tnlp.hpp"
#include "roller/contact/backend.hpp"
#include "roller/solver/schur_condenser.hpp"

namespace roller::ipopt_detail {

// One linearisation condensed onto the working candidates' free dofs d_C (ipopt_condensed.cpp,
// header comment): the rows of the contact NLP, the free dof of each entry of d_C, the Schur
// complement S and the condensed gradient gc.
struct Condensation {
  std::vector<RowMap> rows;
  std::vector<Index> dofs;
  MatX schur;
  VecX gradient;
};

// Condenses the strip's gradient g and tangent k at x onto the working candidates; Failed when
// the tangent cannot be factorised on the interior dofs (condenser.message() says why). The
// condenser keeps the factors for the interior solves of the step, and for later increments
// when the strip's tangent is constant: it is then factorised with its Schur complement on every
// candidate's dofs, so that the next working sets are reduced from it (solver/schur_condenser.hpp).
SchurCondenser::Outcome condense(const IncrementProblem& problem, const std::vector<int>& working, const VecX& x,
                                 const VecX& g, const SparseMatrix& k, SchurCondenser& condenser, Condensation* out);

// The condensed model q_C(d_C) = gc.d_C + d_C.S.d_C/2 as the NLP's objective; its dense lower
// triangle, row by row, holds the contact curvature too. With a suspended roller at w the last
// variable is its step dw, and the model adds P(w + dw) - P(w) = P'(w) dw + stiffness dw^2/2
// (exact: P is quadratic).
class QuadraticModel : public NlpObjective {
 public:
  explicit QuadraticModel(const Condensation& c) : c_(c) {}
  QuadraticModel(const Condensation& c, const RollerPotential& roller, Real w)
      : c_(c), roller_(roller), roller_gradient_(roller.derivative(w)) {}
  int n() const override { return static_cast<int>(c_.gradient.size()) + (roller_ ? 1 : 0); }
  int roller_slot() const override { return roller_ ? static_cast<int>(c_.gradient.size()) : -1; }
  bool value(const Real* d, Real& f) override;
  bool gradient(const Real* d, Real* g) override;
  int hessian_nnz() const override { return n() * (n() + 1) / 2; }
  void hessian_structure(int* row, int* col) const override;
  bool hessian_values(const Real* d, Real obj_factor, Real* values) override;
  int hessian_position(int r, int c) const override { return r * (r + 1) / 2 + c; }

 private:
  const Condensation& c_;
  std::optional<RollerPotential> roller_;
  Real roller_gradient_ = 0.0;  // P'(w) at the linearisation
};

// The working set at the start of an increment, and `old` grown by the candidates near the roller
// at x (ipopt_condensed.cpp, header comment); length_scale is the increment's l_step.
std::vector<int> initial_working_set(const IncrementProblem& problem, const VecX& x0, Real length_scale);
std::vector<int> grown_working_set(const IncrementProblem& problem, const VecX& x, Real length_scale,
                                   const std::vector<int>& old);

}  // namespace roller::ipopt_detail
