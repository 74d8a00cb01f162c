// Whole-strip checks: patch tests (a linear displacement field is reproduced exactly on a
// distorted mesh), objectivity of the updated-Lagrangian update under a rigid rotation of a
// pre-stressed strip, and quadratic convergence of Newton on an elastoplastic problem.
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/impose_field.hpp"
#include "../support/strip_spec.hpp"
#include "roller/assembly/increment_energy.hpp"
#include "roller/core/error.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

MaterialParams elastic(Real nu = 0.3) {
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = nu;
  return p;
}

MaterialParams plastic() {
  MaterialParams p = elastic();
  p.plastic = true;
  p.yield_stress = 50.0;
  p.tangent_modulus = 0.07 * p.youngs_modulus;
  return p;
}

// A 4x4 strip on [0,4]x[0,4] with its interior nodes moved off the grid.
Mesh distorted_patch(ElementType t) {
  StripMeshSpec spec;
  spec.element = t;
  spec.length = 4.0;
  spec.height = 4.0;
  spec.nx = 4;
  spec.ny = 4;
  spec.diagonal = Diagonal::Alternating;
  Mesh mesh = make_strip_mesh(spec);
  for (Index a = 0; a < mesh.n_nodes(); ++a) {
    Vec2& x = mesh.nodes[a];
    const bool boundary = x.x() < 1e-12 || x.x() > 4 - 1e-12 || x.y() < 1e-12 || x.y() > 4 - 1e-12;
    if (!boundary) x += Vec2(0.23 * std::sin(3.0 * a), 0.19 * std::cos(5.0 * a));
  }
  return mesh;
}

std::vector<bool> boundary_dofs(const Mesh& mesh) {
  std::vector<bool> fixed(mesh.n_dofs(), false);
  for (const char* set : {"top", "bottom", "left", "right"})
    for (Index a : mesh.node_set(set)) fixed[2 * a] = fixed[2 * a + 1] = true;
  return fixed;
}

// Solves one increment with the boundary dofs prescribed to `field(X)`, commits it, returns
// the Newton report.
using test::impose_field;

}  // namespace

TEST_CASE("patch test: a linear displacement field is reproduced exactly", "[assembly][patch]") {
  struct Variant {
    ElementType type;
    Q4Formulation q4;
    Kinematics kin;
    const char* name;
  };
  const Variant variants[] = {
      {ElementType::T3, Q4Formulation::Standard, Kinematics::Small, "T3 small"},
      {ElementType::Q4, Q4Formulation::Standard, Kinematics::Small, "Q4 small"},
      {ElementType::Q4, Q4Formulation::BBar, Kinematics::Small, "Q4 B-bar small"},
      {ElementType::T3, Q4Formulation::Standard, Kinematics::Finite, "T3 finite"},
      {ElementType::Q4, Q4Formulation::Standard, Kinematics::Finite, "Q4 finite"},
      {ElementType::Q4, Q4Formulation::BBar, Kinematics::Finite, "Q4 B-bar finite"},
  };
  // A general affine field: stretch, shear and rotation, large enough to be finite.
  Mat2 grad;
  grad << 0.02, 0.015, -0.01, -0.012;
  const Vec2 shift(0.3, -0.1);
  for (const auto& v : variants) {
    SECTION(v.name) {
      StripModel model(distorted_patch(v.type), elastic(), ElementOptions{v.kin, v.q4});
      model.set_dof_map(DofMap(boundary_dofs(model.mesh())));
      const auto report = impose_field(model, [&](const Vec2& x) -> Vec2 { return shift + grad * x; });
      REQUIRE(report.converged());
      Real err = 0.0;
      for (Index a = 0; a < model.mesh().n_nodes(); ++a) {
        const Vec2 exact = shift + grad * model.mesh().nodes[a];
        err = std::max(err,
                       (Vec2(model.total_displacement()(2 * a), model.total_displacement()(2 * a + 1)) - exact).norm());
      }
      CHECK(err < 1e-10);
      // Constant stress everywhere.
      const Vec4 s0 = model.state(0, 0).stress;
      for (const auto& s : model.states()) CHECK((s.stress - s0).norm() < 1e-7 * s0.norm());
    }
  }
}

TEST_CASE("a pre-stressed strip rotated rigidly by 90 degrees keeps its stress invariants", "[assembly][objectivity]") {
  for (Kinematics kin : {Kinematics::Finite, Kinematics::Small}) {
    StripMeshSpec spec = test::strip_spec(ElementType::Q4, 2.0, 1.0, 2, 1);
    StripModel model(make_strip_mesh(spec), elastic(), ElementOptions{kin, Q4Formulation::BBar});
    model.set_dof_map(DofMap(std::vector<bool>(model.n_dofs(), true)));  // every node prescribed
    // Pre-stress: a homogeneous stretch.
    Mat2 stretch;
    stretch << 1e-3, 4e-4, 4e-4, -5e-4;
    REQUIRE(impose_field(model, [&](const Vec2& x) -> Vec2 { return stretch * x; }).converged());
    const Vec4 s0 = model.state(0, 0).stress;
    // Rigid rotation in 9 steps of 10 degrees about the origin of the current configuration.
    const Real step = M_PI / 18.0;
    Mat2 r;
    r << std::cos(step), -std::sin(step), std::sin(step), std::cos(step);
    for (int i = 0; i < 9; ++i)
      REQUIRE(impose_field(model, [&](const Vec2& x) -> Vec2 { return r * x - x; }).converged());
    const Vec4 s1 = model.state(0, 0).stress;
    // After 90 degrees: sigma_xx <-> sigma_yy, sigma_xy -> -sigma_xy, sigma_zz unchanged.
    const Vec4 expected(s0(1), s0(0), s0(2), -s0(3));
    INFO("kinematics " << to_string(kin) << " s0 " << s0.transpose() << " s1 " << s1.transpose());
    if (kin == Kinematics::Finite) {
      CHECK((s1 - expected).norm() < 1e-9 * s0.norm());
      CHECK(sqrt_j2(s1) == Approx(sqrt_j2(s0)).epsilon(1e-10));
    } else {
      // Small kinematics reads the rotation as strain: the stress is not objective (this is
      // why the finite option exists) — the check above must fail for it.
      CHECK((s1 - expected).norm() > 1e-2 * s0.norm());
    }
  }
}

TEST_CASE("Newton converges quadratically on an elastoplastic compression", "[assembly][newton]") {
  StripMeshSpec spec = test::strip_spec(ElementType::Q4, 10.0, 5.0, 8, 4);
  StripModel model(make_strip_mesh(spec), plastic(), ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
  // Bottom on the symmetry plane (uy = 0), left edge fixed in x, top pushed down non-uniformly.
  std::vector<bool> fixed(model.n_dofs(), false);
  for (Index a : model.mesh().node_set("bottom")) fixed[2 * a + 1] = true;
  for (Index a : model.mesh().node_set("left")) fixed[2 * a] = true;
  for (Index a : model.mesh().node_set("top")) fixed[2 * a + 1] = true;
  model.set_dof_map(DofMap(fixed));
  VecX prescribed = VecX::Zero(model.n_dofs());
  for (Index a : model.mesh().node_set("top")) prescribed(2 * a + 1) = -0.02 * (1.0 + 0.05 * model.mesh().nodes[a].x());
  IncrementEnergy energy(model, prescribed, VecX::Zero(model.n_dofs()));
  VecX free = VecX::Zero(model.dof_map().n_free());
  NewtonOptions opt;
  opt.residual_tolerance = 1e-13;
  const NewtonReport report = minimise_newton(energy, free, opt);
  REQUIRE(report.converged());
  REQUIRE(model.evaluate(energy.full_increment(free), nullptr, nullptr).n_yielded > 0);
  const auto& r = report.residual_history;
  REQUIRE(r.size() >= 4);
  // In the asymptotic range r_{k+1} ~ C r_k^2: the convergence order
  // log(r_{k+1}/r_k) / log(r_k/r_{k-1}) approaches 2. Take the last three above round-off
  // (1e-13 of the first residual; the floor is ~1e-16 of the internal forces).
  std::size_t last = r.size() - 1;
  while (last > 2 && r[last] < 1e-13 * r[0]) --last;
  REQUIRE(last >= 2);
  const std::size_t k = last - 1;
  const Real order = std::log(r[k + 1] / r[k]) / std::log(r[k] / r[k - 1]);
  INFO("residual history: " << Catch::Detail::stringify(r) << " last " << r.back());
  CHECK(order > 1.7);
}

TEST_CASE("an increment that inverts an element is rejected and changes nothing", "[assembly][robustness]") {
  StripMeshSpec spec;
  spec.length = 2.0;
  spec.height = 1.0;
  spec.nx = 2;
  spec.ny = 1;
  StripModel model(make_strip_mesh(spec), elastic(), ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
  // Push the top-left node through the bottom edge: the first element turns inside out.
  VecX u = VecX::Zero(model.n_dofs());
  const Index corner = model.mesh().node_set("top_left").front();
  u(2 * corner + 1) = -2.0;
  VecX g;
  CHECK_THROWS_AS(model.evaluate(u, &g, nullptr), NumericalError);
  CHECK_THROWS_AS(model.commit(u), NumericalError);
  CHECK(model.total_displacement().norm() == 0.0);
  CHECK((model.reference_coordinates()[corner] - model.mesh().nodes[corner]).norm() == 0.0);
  for (const auto& s : model.states()) CHECK(s.stress.norm() == 0.0);
}

TEST_CASE("a strip with back-stresses rotated rigidly by 90 degrees carries them round with the stress",
          "[assembly][objectivity][hardening]") {
  // Kinematic hardening (docs/model.md, Hardening laws): the back-stresses are pushed forward with
  // the stress, so a rigid rotation turns both, and a rotation does not move a state off its
  // yield surface.
  StripMeshSpec spec = test::strip_spec(ElementType::Q4, 2.0, 1.0, 2, 1);
  MaterialParams m = plastic();
  m.tangent_modulus = 0.0;
  m.hardening = Hardening::Chaboche;
  m.n_chaboche = 2;
  m.chaboche[0] = {2.0e4, 200.0};
  m.chaboche[1] = {3.0e3, 0.0};
  StripModel model(make_strip_mesh(spec), m, ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
  model.set_dof_map(DofMap(std::vector<bool>(model.n_dofs(), true)));
  Mat2 stretch;
  stretch << 1.5e-3, 8e-4, 8e-4, -9e-4;  // past yield (sigma_y = 50 MPa)
  REQUIRE(impose_field(model, [&](const Vec2& x) -> Vec2 { return stretch * x; }).converged());
  // The stretch's push-forward leaves the state off its surface by O(strain x stress); a zero
  // increment returns it there, so that the rotation below starts on the surface.
  REQUIRE(impose_field(model, [&](const Vec2&) -> Vec2 { return Vec2::Zero(); }).converged());
  const MaterialState s0 = model.state(0, 0);
  REQUIRE(s0.back_stress[0].norm() > 1.0);
  const Real step = M_PI / 18.0;
  Mat2 r;
  r << std::cos(step), -std::sin(step), std::sin(step), std::cos(step);
  for (int i = 0; i < 9; ++i)
    REQUIRE(impose_field(model, [&](const Vec2& x) -> Vec2 { return r * x - x; }).converged());
  const MaterialState s1 = model.state(0, 0);
  auto turned = [](const Vec4& t) { return Vec4(t(1), t(0), t(2), -t(3)); };
  CHECK((s1.stress - turned(s0.stress)).norm() < 1e-9 * s0.stress.norm());
  for (int i = 0; i < 2; ++i) {
    INFO("back-stress " << i + 1 << " before " << s0.back_stress[i].transpose() << " after "
                        << s1.back_stress[i].transpose());
    CHECK((s1.back_stress[i] - turned(s0.back_stress[i])).norm() < 1e-9 * s0.back_stress[i].norm());
    CHECK(std::abs(s1.back_stress[i].head<3>().sum()) < 1e-12 * s0.back_stress[i].norm());  // deviatoric
  }
  CHECK(s1.eq_plastic_strain == Approx(s0.eq_plastic_strain).epsilon(1e-12));  // no plastic flow on the way
}
