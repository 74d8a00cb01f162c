// The assembled Hessian over the free dofs is the derivative of the assembled gradient, with
// dofs constrained one component at a time (the block slots of StripModel::set_dof_map assume
// rows 2a, 2a+1 adjacent; a node with only x or only y free breaks that unless handled), for
// T3 and Q4, elastic-plastic, finite strain. Also: the sparsity is symmetric and a second
// evaluation into the same matrix gives the same values (the pattern is reused, not summed).
#include <catch2/catch.hpp>

#include <cmath>

#include "roller/assembly/strip_model.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

StripModel plastic_strip(ElementType t) {
  StripMeshSpec spec;  // 100 x 20 mm, 3 x 2 elements
  spec.element = t;
  spec.nx = 3;
  spec.ny = 2;
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = 0.3;
  p.plastic = true;
  p.yield_stress = 50.0;
  p.tangent_modulus = 0.07 * p.youngs_modulus;
  ElementOptions options;
  options.kinematics = Kinematics::Finite;
  return StripModel(make_strip_mesh(spec), p, options);
}

}  // namespace

TEST_CASE("assembled Hessian over free dofs equals central differences of the gradient", "[assembly][tangent]") {
  for (const ElementType t : {ElementType::Q4, ElementType::T3}) {
    StripModel model = plastic_strip(t);
    const Index n = model.n_dofs();
    // Node 0 fully fixed, node 1 only x, node 2 only y, the last node only y.
    std::vector<bool> fixed(n, false);
    fixed[0] = fixed[1] = true;
    fixed[2] = true;
    fixed[5] = true;
    fixed[n - 1] = true;
    model.set_dof_map(DofMap(fixed));
    const DofMap& dofs = model.dof_map();

    // A displacement large enough to yield some points (strain ~ 1e-2 >> 50 / 2.1e5).
    VecX u(n);
    for (Index i = 0; i < n; ++i) u(i) = 0.2 * std::sin(1.7 * i + 0.3) + 0.1 * (i % 2 == 0 ? 1.0 : -0.5);
    VecX g;
    SparseMatrix h;
    REQUIRE(model.evaluate(u, &g, &h).n_yielded > 0);
    REQUIRE(h.rows() == dofs.n_free());

    const MatX dense = MatX(h);
    CHECK((dense - dense.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * dense.cwiseAbs().maxCoeff());

    const Real step = 1e-6;
    Real worst = 0.0;
    for (Index k = 0; k < dofs.n_free(); ++k) {
      VecX up = u, um = u;
      up(dofs.free_dofs()[k]) += step;
      um(dofs.free_dofs()[k]) -= step;
      VecX gp, gm;
      model.evaluate(up, &gp, nullptr);
      model.evaluate(um, &gm, nullptr);
      const VecX column = dofs.restrict_to_free((gp - gm) / (2.0 * step));
      worst = std::max(worst, (column - dense.col(k)).cwiseAbs().maxCoeff());
    }
    INFO("element type " << (t == ElementType::Q4 ? "Q4" : "T3"));
    CHECK(worst <= 1e-5 * dense.cwiseAbs().maxCoeff());

    // Same matrix again: the values are recomputed, not accumulated onto the old ones.
    model.evaluate(u, &g, &h);
    CHECK((MatX(h) - dense).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("a dead load adds -f.u to the increment's energy and -f to its gradient, nothing to its Hessian",
          "[assembly]") {
  StripModel model = plastic_strip(ElementType::Q4);
  const Index n = model.n_dofs();
  model.set_dof_map(DofMap(std::vector<bool>(n, false)));
  VecX u(n), f(n);
  for (Index i = 0; i < n; ++i) u(i) = 0.2 * std::sin(1.7 * i + 0.3), f(i) = 30.0 * std::cos(0.9 * i);
  VecX g0, g1;
  SparseMatrix h0, h1;
  const Real e0 = model.evaluate(u, &g0, &h0).energy;
  model.set_dead_load(f);
  const Real e1 = model.evaluate(u, &g1, &h1).energy;
  CHECK(e1 - e0 == Approx(-f.dot(u)).epsilon(0.0).margin(1e-12 * std::abs(e0)));  // e0 ~ 1e4: roundoff
  CHECK((g1 - g0 + f).cwiseAbs().maxCoeff() <= 1e-12 * f.cwiseAbs().maxCoeff());
  CHECK(MatX(h1) == MatX(h0));
}
