#pragma once
// The thesis's method (docs/model.md, Penalty backend): quadratic penalty on penetration and on
// tangential stick slip, Coulomb return map on the tangential penalty force, Newton–Raphson with
// the consistent (unsymmetric in slip) tangent and a residual line search (solver/newton.hpp).
//
// Per candidate i with penalty stiffnesses kN = factor E* l_i / h_i, kT = tangential_factor kN:
//   F_N = kN <-g>                                   (zero when the node is off the roller)
//   F_T^trial = F_T^n - kT s_i                      (s_i: slip increment, F_T^n committed)
//   stick if |F_T^trial| <= mu F_N: F_T = F_T^trial; else slip: F_T = mu F_N sign(F_T^trial)
// so a node in contact penetrates by exactly F_N / kN = p_N h_i / (factor E*): with the default
// factor 1e3 the penetration is 1e-3 of the elastic compression p_N h / E* of the element.
// Solution strategy: (1) active-set passes — Newton with every node's status frozen (smooth),
// statuses updated between passes until none changes; (2) if that fails, Newton on the full
// law; (3) if that fails too, the penalty is raised in stages (factor 10, 1e3, 1e5, ... up to the
// target, each stage started from the previous solution).
#include "roller/contact/backend.hpp"
#include "roller/solver/newton.hpp"

namespace roller {

class PenaltyBackend : public ContactBackend {
 public:
  PenaltyBackend(ContactOptions options, NewtonOptions newton);
  std::string name() const override { return "penalty"; }
  bool minimises_energy() const override { return false; }

  struct Stiffness {
    Real normal, tangential;  // kN, kT of one candidate [N/mm per mm width]
  };
  static constexpr Real kFirstStageFactor = 10.0;  // softest penalty factor of the staging

  // The residual (strip forces minus contact forces, free dofs) at the target penalty and its
  // consistent Jacobian; exposed for finite-difference tests of the linearisation.
  void residual(IncrementProblem& problem, const VecX& x, VecX& r, SparseMatrix* jacobian) const;

 private:
  // Newton at fixed penalties from x (updated in place); with `frozen`, every node keeps the
  // given status (see contact_state in the .cpp).
  BackendResult newton_stage(IncrementProblem& problem, const std::vector<Stiffness>& k, VecX& x, Real tolerance,
                             const std::vector<NodeContact>* frozen = nullptr);
  static constexpr int kMaxActiveSetPasses = 20;
  BackendResult do_solve(IncrementProblem& problem, const VecX& x0) override;
  // The solve over all unknowns z = [x, w] (w: an elastic roller's rim, when there is one).
  BackendResult solve_unknowns(IncrementProblem& problem, const VecX& z0);
  ContactOptions options_;
  NewtonOptions newton_;
  // Kept between solves, with its linear solvers: MUMPS's analysis is redone only for a new pattern.
  NewtonMinimiser newton_solver_;
};

}  // namespace roller
