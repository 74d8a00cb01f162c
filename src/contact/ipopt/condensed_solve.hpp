#pragma once
// The outer loop of the condensed formulation (ipopt_condensed.cpp, header comment: "Outer loop",
// "Step and convergence", "Working set"): one increment, one object, one method per step of a
// linearisation. The solve works on a copy of the problem it is given, whose roller it moves with
// a suspended roller's step; the caller's problem is left as it was.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <IpIpoptApplication.hpp>

#include "friction_passes.hpp"
#include "ipopt_common.hpp"
#include "ipopt_condensed.hpp"

namespace roller::ipopt_detail {

struct CondensedOutcome {
  BackendResult result;
  // The formulation itself failed (singular strip tangent, no descent, linearisations ran out):
  // the caller may solve the increment with the full formulation instead.
  bool formulation_failed = false;
};

class CondensedSolve {
 public:
  CondensedSolve(const IncrementProblem& problem, const ContactOptions& options, SchurCondenser& condenser);
  CondensedOutcome run(const VecX& x0);

 private:
  // What a step computed, or the outcome that ends the solve.
  template <class T>
  using OrEnd = std::variant<T, CondensedOutcome>;
  using End = std::optional<CondensedOutcome>;
  // The NLP's answer on one linearisation: the contact dofs' step, the roller's, an elastic
  // roller's rim displacements (empty for a rigid roller), the friction terms.
  struct ModelStep {
    VecX d_c;
    Real dw = 0.0;
    VecX rim;
    FrictionTerms friction;
  };
  // The whole step d = (d_I, d_C), K d, the roller's and the rim's steps, and the model's change
  // of the energy along it.
  struct Step {
    VecX d, kd;
    Real dw = 0.0;
    VecX d_rim;
    Real model_change = 0.0;
  };
  // The point the line search accepted.
  struct Trial {
    Real alpha = 1.0;
    VecX x, g;
    Real energy = 0.0;
    SparseMatrix k;  // the tangent at the full step (a tangent that changes), else empty
  };

  End start(const VecX& x0);
  End condense_working_set();
  OrEnd<ModelStep> solve_model(int outer);
  Step whole_step(const ModelStep& model);
  OrEnd<Trial> line_search(int outer, const Step& step, const FrictionTerms& friction);
  bool grow_working_set();
  End relinearise(Trial&& trial);
  CondensedOutcome finish();
  IpoptDetails& details() { return result_.details.fill<IpoptDetails>(); }

  IncrementProblem problem_;  // the caller's, copied: the line search moves its roller
  const IpoptOptions& o_;
  SchurCondenser& condenser_;
  const std::optional<RollerPotential> spring_;  // a free roller height (ipopt_condensed.cpp)
  // The free roller's potential at offset w (0 for a placed roller).
  Real roller_energy(Real w) const { return spring_ ? spring_->energy(w) : 0.0; }
  // An elastic roller's strain energy at rim displacements w, 1/2 w^T K w (0 for a rigid roller).
  Real rim_energy(const VecX& w) const;
  // Moves the problem's rim to w0 + alpha dw (nothing for a rigid roller).
  void move_rim(const VecX& w0, Real alpha, const VecX& dw);
  const bool tangent_changes_;  // a constant tangent needs no new one at the full step
  BackendResult result_;
  Scales scales_;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app_;
  std::optional<NormalForceFixedPoint> fixed_point_;
  // The iterate: x, Pi(x), its gradient and tangent.
  VecX x_, g_;
  SparseMatrix k_eff_;
  Real energy_ = 0.0;
  std::vector<int> working_;
  Condensation cond_;
  // Per candidate, from the last solved pass.
  std::vector<Real> normal_, tangential_, fbar_used_;
  std::vector<bool> has_friction_;
  int linearisations_ = 0, passes_last_ = 0;
  bool converged_ = false, fixed_point_converged_ = false;
  Real model_error_ = 0.0;
};

}  // namespace roller::ipopt_detail
