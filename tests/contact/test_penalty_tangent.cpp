// The penalty backend's consistent linearisation (normal penalty on the curved gap, stick, and the
// unsymmetric slip term) against central finite differences of its residual.
#include <catch2/catch.hpp>

#include <random>

#include "roller/contact/contact_set.hpp"
#include "roller/contact/penalty_backend.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

TEST_CASE("penalty residual Jacobian matches finite differences (open, stick, slip nodes)", "[contact][tangent]") {
  StripMeshSpec spec;
  spec.length = 20.0;
  spec.height = 5.0;
  spec.nx = 10;
  spec.ny = 3;
  MaterialParams mat;
  mat.plastic = true;
  mat.yield_stress = 50.0;
  mat.tangent_modulus = 0.07 * mat.youngs_modulus;
  StripModel model(make_strip_mesh(spec), mat, ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
  std::vector<bool> fixed(model.n_dofs(), false);
  for (Index a : model.mesh().node_set("bottom")) fixed[2 * a + 1] = true;
  fixed[2 * model.mesh().node_set("bottom_left").front()] = true;
  model.set_dof_map(DofMap(fixed));
  const VecX zero = VecX::Zero(model.n_dofs());
  IncrementEnergy energy(model, zero, zero);

  RollerMotion motion;
  motion.radius = 30.0;
  motion.start.centre = Vec2(10.0, 35.0);
  motion.end.centre = Vec2(10.05, 34.985);  // pressed 15 um and moved sideways
  motion.end.angle = -0.0005;
  motion.friction = 0.3;
  auto candidates =
      make_contact_candidates(model, model.mesh().node_set("top"), zero, zero, motion.end.centre, motion.radius, 1e9);
  // History: some nodes carry a tangential force from before, so stick and slip both occur.
  for (std::size_t i = 0; i < candidates.size(); ++i) candidates[i].tangential_force = (i % 3 == 0) ? 3.0 : -1.0;
  IncrementProblem problem(energy, candidates, motion, mat.youngs_modulus, mat.poisson_ratio);
  ContactOptions opt;
  opt.friction = motion.friction;
  opt.penalty.factor = 10.0;
  opt.penalty.tangential_factor = 0.5;
  PenaltyBackend backend(opt, NewtonOptions{});

  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> uni(-1.0, 1.0);
  VecX x(problem.n_free());
  for (Index i = 0; i < x.size(); ++i) x(i) = 2e-4 * uni(rng);
  VecX r;
  SparseMatrix j;
  backend.residual(problem, x, r, &j);
  const MatX jd = MatX(j);
  MatX fd(x.size(), x.size());
  const Real h = 1e-9;
  for (Index i = 0; i < x.size(); ++i) {
    VecX xp = x, xm = x, rp, rm;
    xp(i) += h;
    xm(i) -= h;
    backend.residual(problem, xp, rp, nullptr);
    backend.residual(problem, xm, rm, nullptr);
    fd.col(i) = (rp - rm) / (2 * h);
  }
  CHECK((jd - fd).norm() <= 1e-5 * jd.norm());
  // The friction term makes the Jacobian unsymmetric when a node slips.
  CHECK((jd - jd.transpose()).norm() > 1e-8 * jd.norm());
}
