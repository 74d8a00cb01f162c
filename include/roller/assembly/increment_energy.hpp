#pragma once
// The incremental potential of the strip over the free dofs (docs/model.md, Increment energy;
// here without contact):
//   Pi(x) = E(u(x)) - f_ext . u(x),  u = prescribed increments on constrained dofs, x elsewhere,
// with f_ext the external nodal forces at the end of the increment. Its gradient is the
// out-of-balance force, its Hessian the tangent stiffness K_L + K_NL.
//
// With strip inertia (Houbolt; docs/model.md, Strip inertia) the potential gains the inertial part
//   1/2 c_a u.M u + u.b,   b = M a_{n+1}(u = 0) = M (c_a u_n + a_offset),
// whose gradient is M a_{n+1} and whose Hessian is c_a M = 2M/dt^2: the effective stiffness
// K + 2M/dt^2 of (4.17). Quasistatic scenes pass no inertia and build no mass matrix.
#include <optional>

#include "roller/assembly/strip_model.hpp"
#include "roller/solver/newton.hpp"

namespace roller {

struct InertiaTerm {
  const SparseMatrix* mass = nullptr;       // M over all dofs
  const SparseMatrix* mass_free = nullptr;  // M over the free dofs (rows/cols in free numbering)
  Real coefficient = 0.0;                   // c_a = 2/dt^2 (Houbolt)
  VecX start_force;                         // b = M a_{n+1}(u = 0), all dofs
};

class IncrementEnergy : public NewtonObjective {
 public:
  // `prescribed` holds the increments of the constrained dofs (other entries ignored).
  IncrementEnergy(StripModel& model, VecX prescribed, VecX external_force,
                  std::optional<InertiaTerm> inertia = std::nullopt);

  // Pi(x), and as force scale max(|f_ext|, |reactions at x|, |internal force at the start of
  // the increment|, |b|); the strip's NumericalError (an inverted element) as the failure.
  Expected<ObjectiveValue> evaluate(const VecX& x, VecX* gradient, SparseMatrix* hessian) override;

  Index n_free() const { return model_.dof_map().n_free(); }
  const StripModel& model() const { return model_; }
  StripModel& model() { return model_; }
  // Full increment vector for free values x.
  VecX full_increment(const VecX& x) const;
  // Pi(x) and its gradient over all dofs: internal minus external forces, whose entries at the
  // constrained dofs are the reactions.
  ObjectiveValue evaluate_full(const VecX& x, VecX& full_gradient);

 private:
  ObjectiveValue evaluate_all(const VecX& x, VecX& full_gradient, SparseMatrix* hessian);

  StripModel& model_;
  VecX prescribed_;
  VecX external_;
  std::optional<InertiaTerm> inertia_;
  Real start_scale_ = 0.0;
};

}  // namespace roller
