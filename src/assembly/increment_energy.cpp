#include "roller/assembly/increment_energy.hpp"

namespace roller {

IncrementEnergy::IncrementEnergy(StripModel& model, VecX prescribed, VecX external_force)
    : model_(model), prescribed_(std::move(prescribed)), external_(std::move(external_force)) {
  // Internal forces at the start of the increment balance the previous loads; their size is a
  // force scale that exists even for purely displacement-driven or unloaded steps.
  VecX g;
  model_.evaluate(VecX::Zero(model_.n_dofs()), &g, nullptr);
  start_scale_ = g.norm();
}

VecX IncrementEnergy::full_increment(const VecX& x) const {
  VecX u = VecX::Zero(model_.n_dofs());
  const DofMap& dofs = model_.dof_map();
  for (Index d : dofs.constrained_dofs()) u(d) = prescribed_(d);
  dofs.scatter_free(x, u);
  return u;
}

Real IncrementEnergy::evaluate(const VecX& x, VecX* gradient, SparseMatrix* hessian) {
  const VecX u = full_increment(x);
  const Real energy = model_.evaluate(u, &full_gradient_, hessian);
  full_gradient_ -= external_;
  if (gradient) *gradient = model_.dof_map().restrict_to_free(full_gradient_);
  return energy - external_.dot(u);
}

Real IncrementEnergy::force_scale(const VecX& /*x*/) {
  Real reactions = 0.0;
  for (Index d : model_.dof_map().constrained_dofs()) reactions += full_gradient_(d) * full_gradient_(d);
  return std::max({external_.norm(), std::sqrt(reactions), start_scale_});
}

}  // namespace roller
