#include "roller/assembly/increment_energy.hpp"

#include "roller/core/error.hpp"

#include <algorithm>
#include <cmath>

#include "roller/core/error.hpp"

namespace roller {

IncrementEnergy::IncrementEnergy(StripModel& model, VecX prescribed, VecX external_force,
                                 std::optional<InertiaTerm> inertia)
    : model_(model),
      prescribed_(std::move(prescribed)),
      external_(std::move(external_force)),
      inertia_(std::move(inertia)) {
  ROLLER_ASSERT(prescribed_.size() == model.n_dofs() && external_.size() == model.n_dofs(),
                "prescribed increments and external forces over all dofs");
  // Internal forces at the start of the increment balance the previous loads; their size is a
  // force scale that exists even for purely displacement-driven or unloaded steps.
  VecX g;
  model_.evaluate(VecX::Zero(model_.n_dofs()), &g, nullptr);
  start_scale_ = g.norm();
  if (inertia_) start_scale_ = std::max(start_scale_, inertia_->start_force.norm());
}

VecX IncrementEnergy::full_increment(const VecX& x) const {
  VecX u = VecX::Zero(model_.n_dofs());
  const DofMap& dofs = model_.dof_map();
  for (Index d : dofs.constrained_dofs()) u(d) = prescribed_(d);
  dofs.scatter_free(x, u);
  return u;
}

Expected<ObjectiveValue> IncrementEnergy::evaluate(const VecX& x, VecX* gradient, SparseMatrix* hessian) {
  VecX full_gradient;
  try {
    const ObjectiveValue v = evaluate_all(x, full_gradient, hessian);
    if (gradient) *gradient = model_.dof_map().gather_free(full_gradient);
    return v;
  } catch (const NumericalError& error) {
    return Unexpected{error.what()};
  }
}

ObjectiveValue IncrementEnergy::evaluate_full(const VecX& x, VecX& full_gradient) {
  return evaluate_all(x, full_gradient, nullptr);
}

ObjectiveValue IncrementEnergy::evaluate_all(const VecX& x, VecX& full_gradient, SparseMatrix* hessian) {
  const VecX u = full_increment(x);
  Real energy = model_.evaluate(u, &full_gradient, hessian).energy;
  full_gradient -= external_;
  if (inertia_) {
    const VecX mu = *inertia_->mass * u;
    energy += 0.5 * inertia_->coefficient * u.dot(mu) + u.dot(inertia_->start_force);
    full_gradient += inertia_->coefficient * mu + inertia_->start_force;
    if (hessian) {
      // The strip's pattern covers the element connectivity, hence every entry of M.
      const SparseMatrix& m = *inertia_->mass_free;
      for (int k = 0; k < m.outerSize(); ++k)
        for (SparseMatrix::InnerIterator it(m, k); it; ++it)
          hessian->coeffRef(it.row(), it.col()) += inertia_->coefficient * it.value();
    }
  }
  Real reactions = 0.0;
  for (Index d : model_.dof_map().constrained_dofs()) reactions += full_gradient(d) * full_gradient(d);
  return {energy - external_.dot(u), std::max({external_.norm(), std::sqrt(reactions), start_scale_})};
}

}  // namespace roller
