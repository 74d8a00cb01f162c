#pragma once
// The main backend (docs/model.md, "Contact"): each increment is a nonlinear program solved by the
// interior-point code Ipopt with MUMPS. Variables: free-dof increments (+ friction
// auxiliaries); objective: the strip's incremental potential plus the friction dissipation;
// constraints: the exact gaps g_i(u) >= 0. Contact forces are the constraint multipliers.
// Ipopt types never appear in this header (the TNLP adapter lives in the .cpp).
#include "roller/contact/backend.hpp"
#include "roller/solver/schur_condenser.hpp"

namespace roller {

class IpoptBackend : public ContactBackend {
 public:
  explicit IpoptBackend(ContactOptions options, LinearSolverOptions linear = {});
  std::string name() const override { return "ipopt"; }
  // The condensed formulation solves for a suspended roller's position; the full one does not.
  bool solves_roller_height() const override { return options_.ipopt.formulation == IpoptFormulation::Condensed; }

 private:
  BackendResult do_solve(IncrementProblem& problem, const VecX& x0) override;
  std::optional<Inertia> do_held_tangent_inertia(const SparseMatrix& k) override { return condenser_.inertia_of(k); }
  ContactOptions options_;
  // The condensed formulation's factorisation of the strip tangent; kept between increments only
  // while the tangent is constant (SchurCondenser reuses it then), freed after each otherwise.
  SchurCondenser condenser_;
};

}  // namespace roller
