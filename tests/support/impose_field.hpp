#pragma once
// Drives a strip model through one increment in which every prescribed dof follows a
// displacement field u(X) of the start-of-increment coordinates; commits on convergence.
#include "roller/assembly/increment_energy.hpp"

namespace roller::test {

template <class Field>
NewtonReport impose_field(StripModel& model, const Field& field) {
  VecX prescribed = VecX::Zero(model.n_dofs());
  const auto& x = model.reference_coordinates();
  for (Index a = 0; a < model.mesh().n_nodes(); ++a) {
    const Vec2 u = field(x[a]);
    prescribed(2 * a) = u.x();
    prescribed(2 * a + 1) = u.y();
  }
  IncrementEnergy energy(model, prescribed, VecX::Zero(model.n_dofs()));
  VecX free = VecX::Zero(model.dof_map().n_free());
  NewtonOptions opt;
  opt.residual_tolerance = 1e-12;
  const NewtonReport report = minimise_newton(energy, free, opt);
  if (report.converged()) model.commit(energy.full_increment(free));
  return report;
}

}  // namespace roller::test
