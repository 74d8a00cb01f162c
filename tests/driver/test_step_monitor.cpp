// The run-time monitor (driver/step_monitor): its verdict on the assembled tangent, and the reuse
// of that verdict only where the tangent cannot change (linear elastic, small kinematics, the
// same free dofs).
#include <catch2/catch.hpp>

#include <vector>

#include "../support/strip_spec.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/driver/step_monitor.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

MaterialParams steel(bool plastic) {
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = 0.3;
  p.plastic = plastic;
  p.yield_stress = plastic ? 40.0 : 0.0;
  p.tangent_modulus = plastic ? 7.0e4 : 0.0;
  return p;
}

// Bottom clamped (`x_too` = false: only its y held, so the strip can slide sideways freely).
DofMap bottom_held(const StripModel& model, bool x_too) {
  std::vector<bool> fixed(model.n_dofs(), false);
  for (Index a : model.mesh().node_set("bottom")) {
    fixed[2 * a + 1] = true;
    fixed[2 * a] = x_too;
  }
  return DofMap(fixed);
}

}  // namespace

TEST_CASE("step monitor: a constant tangent's verdict is reused only while the free dofs stay", "[monitor]") {
  StripModel model(make_strip_mesh(test::strip_spec(ElementType::Q4, 4.0, 2.0, 4, 2)), steel(false),
                   ElementOptions{Kinematics::Small, Q4Formulation::BBar});
  model.set_dof_map(bottom_held(model, true));
  StepMonitor monitor(true, 1.0, nullptr, nullptr, nullptr);
  const MonitorReport first = monitor.check(1, model);
  CHECK(first.checked);
  CHECK_FALSE(first.reused);
  CHECK(first.assembled.positive_definite());
  const MonitorReport second = monitor.check(2, model);
  CHECK(second.reused);
  CHECK(second.assembled.positive_definite());
  CHECK(second.pointwise.lambda_min == first.pointwise.lambda_min);

  // Other supports: a rigid-body slide is free, K is singular, and the monitor must see it.
  model.set_dof_map(bottom_held(model, false));
  const MonitorReport loose = monitor.check(3, model);
  CHECK_FALSE(loose.reused);
  CHECK_FALSE(loose.assembled.positive_definite());
}

TEST_CASE("step monitor: a tangent that depends on the state is checked at every step", "[monitor]") {
  for (const bool plastic : {true, false}) {
    const Kinematics kinematics = plastic ? Kinematics::Small : Kinematics::Finite;
    StripModel model(make_strip_mesh(test::strip_spec(ElementType::Q4, 4.0, 2.0, 4, 2)), steel(plastic),
                     ElementOptions{kinematics, Q4Formulation::BBar});
    model.set_dof_map(bottom_held(model, true));
    StepMonitor monitor(true, 1.0, nullptr, nullptr, nullptr);
    CHECK_FALSE(monitor.check(1, model).reused);
    const MonitorReport again = monitor.check(2, model);
    CHECK_FALSE(again.reused);
    CHECK(again.assembled.positive_definite());
  }
}
