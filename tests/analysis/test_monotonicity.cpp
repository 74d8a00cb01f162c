// Operator A = C + T (thesis ch. 3; docs/model.md, Monotonicity): the thesis's eigenvalue facts,
// the closed forms derived in docs/monotonicity.md, the three positive-definiteness tests, the
// dynamic term and its Courant-type bound (3.18), the strip-wide check and the sparse LDL^T test.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "../support/impose_field.hpp"
#include "../support/strip_spec.hpp"
#include "roller/analysis/monotonicity.hpp"
#include "roller/analysis/monotonicity_map.hpp"
#include "roller/assembly/increment_energy.hpp"
#include "roller/core/eigenvalues.hpp"
#include "roller/fem/element_kernel.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

MaterialParams steel(Real tangent_ratio = 1.0 / 3.0) {
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = 0.3;
  p.plastic = true;
  p.yield_stress = 40.0;
  p.tangent_modulus = tangent_ratio * p.youngs_modulus;
  p.density = 7.8e-9;
  return p;
}

MaterialParams elastic_steel() {
  MaterialParams p = steel();
  p.plastic = false;
  return p;
}

Vec4 deviator(const Vec4& t) {
  const Real m = (t(0) + t(1) + t(2)) / 3.0;
  return Vec4(t(0) - m, t(1) - m, t(2) - m, t(3));
}

// A stress with the given mean stress and deviator direction, scaled onto the yield surface.
Vec4 on_yield_surface(Real mean, const Vec4& direction, Real sigma_pl) {
  const Vec4 s = deviator(direction);
  const Real q = std::sqrt(1.5 * (s(0) * s(0) + s(1) * s(1) + s(2) * s(2) + 2 * s(3) * s(3)));
  return Vec4(mean, mean, mean, 0.0) + s * (sigma_pl / q);
}

OperatorOptions layout_only(GradientLayout layout, TangentKind tangent, bool with_t = true) {
  OperatorOptions o;
  o.layout = layout;
  o.tangent = tangent;
  o.initial_stress = with_t;
  return o;
}

using test::impose_field;

}  // namespace

TEST_CASE("the thesis's split: S_nu has eigenvalues 1, 1/(1-2nu), 1/2, 1/2 and S* 20/9, 0, 0, 0", "[monotonicity]") {
  for (Real nu : {0.0, 0.2, 0.3, 0.45}) {
    const Vec4 ev = symmetric_eigenvalues(thesis_elastic_split(nu));
    CHECK(ev(0) == Approx(0.5));
    CHECK(ev(1) == Approx(0.5));
    CHECK(ev(2) == Approx(1.0));
    CHECK(ev(3) == Approx(1.0 / (1.0 - 2.0 * nu)));
  }
  const Vec4 ev = symmetric_eigenvalues(thesis_plastic_pattern());
  CHECK(ev(3) == Approx(20.0 / 9.0));
  CHECK(ev.head<3>().cwiseAbs().maxCoeff() < 1e-14);
}

TEST_CASE("C in the thesis layout is E/(1+nu) [S_nu - beta D S* D], D = diag(a, b, c, c)", "[monotonicity]") {
  const MaterialParams p = steel();
  const Real g = p.shear_modulus();
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> ab(-150, 150), cc(-50, 50), sig(5, 105);
  for (int k = 0; k < 50; ++k) {
    const ThesisParameters t{ab(rng), ab(rng), cc(rng)};
    const Real sigma = sig(rng);
    const Vec4 stress = stress_from_parameters(t, OutOfPlaneStress::Zero, p.poisson_ratio);
    // a = 3 s11, b = 3 s22 because t33 = 0.
    CHECK(deviator(stress)(0) == Approx(t.a / 3.0));
    const Real beta = 1.5 / (sigma * sigma) / (1.0 + p.plastic_modulus() / (3.0 * g));
    const Mat4 d = Vec4(t.a, t.b, t.c, t.c).asDiagonal();
    const Mat4 expected = 2.0 * g * (thesis_elastic_split(p.poisson_ratio) - beta * d * thesis_plastic_pattern() * d);
    const Mat4 c = operator_a(p, stress, sigma, layout_only(GradientLayout::Thesis, TangentKind::PlasticBranch, false));
    CHECK((c - expected).norm() < 1e-10 * expected.norm());
  }
}

TEST_CASE("elastic states: the plane-strain 4x4 forms have their analytic eigenvalues", "[monotonicity]") {
  const MaterialParams p = elastic_steel();
  const Real g = p.shear_modulus(), lambda = p.lame_lambda(), nu = p.poisson_ratio;
  const auto eig = [&](GradientLayout layout, const Vec4& stress) {
    return symmetric_eigenvalues(operator_a(p, stress, 0.0, layout_only(layout, TangentKind::Continuum)));
  };
  const Vec4 zero = Vec4::Zero();
  SECTION("thesis (3.10): 2G {1/2, 1/2, 1, 1/(1-2nu)}, positive definite") {
    const Vec4 ev = eig(GradientLayout::Thesis, zero);
    CHECK(ev(0) == Approx(g));
    CHECK(ev(1) == Approx(g));
    CHECK(ev(2) == Approx(2 * g));
    CHECK(ev(3) == Approx(2 * g / (1 - 2 * nu)));
  }
  SECTION("navier: G |grad u|^2 + (lambda + G)(div u)^2 -> {G, G, G, 2 lambda + 3G}") {
    const Vec4 ev = eig(GradientLayout::Navier, zero);
    CHECK(ev(0) == Approx(g));
    CHECK(ev(1) == Approx(g));
    CHECK(ev(2) == Approx(g));
    CHECK(ev(3) == Approx(2 * lambda + 3 * g));
  }
  SECTION("gradient (the integrand of K_L): {0, 2G, 2G, 2G/(1-2nu)}, the rotation costs nothing") {
    const Vec4 ev = eig(GradientLayout::Gradient, zero);
    CHECK(std::abs(ev(0)) < 1e-10 * g);
    CHECK(ev(1) == Approx(2 * g));
    CHECK(ev(2) == Approx(2 * g));
    CHECK(ev(3) == Approx(2 * g / (1 - 2 * nu)));
    const Mat4 c = operator_a(p, zero, 0.0, layout_only(GradientLayout::Gradient, TangentKind::Elastic));
    CHECK((c * Vec4(0, 0, 1, -1)).norm() < 1e-10 * g);
    CHECK_FALSE(definiteness(c).positive_definite());
  }
  SECTION("an in-plane hydrostatic stress p shifts every eigenvalue by p (T = p I)") {
    for (Real pr : {-500.0, 300.0}) {
      const Vec4 stress(pr, pr, 0.6 * pr, 0.0);
      CHECK(eig(GradientLayout::Thesis, stress)(0) == Approx(g + pr));
      CHECK(definiteness(operator_a(p, stress, 0.0, layout_only(GradientLayout::Thesis, TangentKind::Elastic)))
                .positive_definite());
    }
  }
}

TEST_CASE("lambda_min(T) = (a+b)/2 - sqrt((a-b)^2/9 + 4c^2)/2, the smaller principal stress", "[monotonicity]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> u(-300, 300);
  for (int k = 0; k < 200; ++k) {
    const Vec4 stress(u(rng), u(rng), u(rng), u(rng) / 3);
    const Vec4 ev = symmetric_eigenvalues(initial_stress_matrix(stress));
    // The eigenvalues are the in-plane principal stresses, each twice.
    Mat2 s;
    s << stress(0), stress(3), stress(3), stress(1);
    const VecX principal = symmetric_eigenvalues(MatX(s));
    CHECK(ev(0) == Approx(principal(0)).margin(1e-9));
    CHECK(ev(1) == Approx(principal(0)).margin(1e-9));
    CHECK(ev(2) == Approx(principal(1)).margin(1e-9));
    CHECK(ev(3) == Approx(principal(1)).margin(1e-9));
    CHECK(initial_stress_min_eigenvalue(stress) == Approx(ev(0)).margin(1e-9));
    CHECK(initial_stress_min_eigenvalue(thesis_parameters(stress)) == Approx(ev(0)).margin(1e-9));
  }
}

TEST_CASE("the gradient layout of A is the integrand of the element stiffness K_L + K_NL", "[monotonicity]") {
  // One T3 (constant gradients, one point), finite kinematics, pre-stressed, zero increment:
  // K = area * Bg^T (C + T) Bg with Bg mapping element dofs to [u1,1 u2,2 u1,2 u2,1].
  const MaterialParams p = elastic_steel();
  const std::vector<Vec2> x{Vec2(0.1, 0.0), Vec2(2.0, 0.3), Vec2(0.7, 1.6)};
  const auto geometry = element_geometry(ElementType::T3, x, 0);
  MaterialState state = initial_state(p);
  state.stress = Vec4(-120.0, 45.0, -20.0, 33.0);
  ElementInput in;
  in.type = ElementType::T3;
  in.geometry = &geometry;
  in.committed = &state;
  in.displacement = ElementVector::Zero(6);
  ElementOutput out;
  evaluate_element(ElementOptions{Kinematics::Finite, Q4Formulation::Standard}, p, in, false, true, out);
  Eigen::Matrix<Real, 4, 6> bg = Eigen::Matrix<Real, 4, 6>::Zero();
  const auto& dn = geometry[0].gradients;
  for (int a = 0; a < 3; ++a) {
    bg(0, 2 * a) = dn(a, 0);      // u1,1
    bg(1, 2 * a + 1) = dn(a, 1);  // u2,2
    bg(2, 2 * a) = dn(a, 1);      // u1,2
    bg(3, 2 * a + 1) = dn(a, 0);  // u2,1
  }
  const Mat4 a = operator_a(p, state.stress, 0.0, layout_only(GradientLayout::Gradient, TangentKind::Elastic));
  const Eigen::Matrix<Real, 6, 6> expected = geometry[0].weight * bg.transpose() * a * bg;
  CHECK((out.tangent - expected).norm() < 1e-10 * expected.norm());
  // The thesis layout is not: it differs in the shear block.
  const Mat4 a_thesis = operator_a(p, state.stress, 0.0, layout_only(GradientLayout::Thesis, TangentKind::Elastic));
  CHECK((out.tangent - geometry[0].weight * bg.transpose() * a_thesis * bg).norm() > 1e-3 * expected.norm());
}

TEST_CASE(
    "the navier layout integrates to the gradient layout for displacements vanishing on "
    "the boundary (a null Lagrangian)",
    "[monotonicity]") {
  StripMeshSpec spec = test::strip_spec(ElementType::T3, 3.0, 2.0, 6, 4, Diagonal::Alternating);
  const Mesh mesh = make_strip_mesh(spec);
  std::vector<bool> boundary(mesh.n_nodes(), false);
  for (const char* set : {"top", "bottom", "left", "right"})
    for (Index n : mesh.node_set(set)) boundary[n] = true;
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> u(-1, 1);
  VecX disp = VecX::Zero(mesh.n_dofs());
  for (Index n = 0; n < mesh.n_nodes(); ++n)
    if (!boundary[n]) disp.segment<2>(2 * n) << u(rng), u(rng);
  const MaterialParams p = steel();
  const Vec4 stress = on_yield_surface(-60.0, Vec4(1.0, -0.3, 0.2, 0.5), 40.0);
  const auto form = [&](GradientLayout layout) {
    const Mat4 a = operator_a(p, stress, 40.0, layout_only(layout, TangentKind::Continuum));
    Real sum = 0.0;
    for (Index e = 0; e < mesh.n_elements(); ++e) {
      std::vector<Vec2> x;
      for (Index n : mesh.elements[e]) x.push_back(mesh.nodes[n]);
      const PointGeometry g = element_geometry(ElementType::T3, x, e)[0];
      Vec4 grad = Vec4::Zero();
      for (int k = 0; k < 3; ++k) {
        const Index n = mesh.elements[e][k];
        grad += Vec4(disp(2 * n) * g.gradients(k, 0), disp(2 * n + 1) * g.gradients(k, 1),
                     disp(2 * n) * g.gradients(k, 1), disp(2 * n + 1) * g.gradients(k, 0));
      }
      sum += g.weight * grad.dot(a * grad);
    }
    return sum;
  };
  const Real gradient = form(GradientLayout::Gradient);
  CHECK(form(GradientLayout::Navier) == Approx(gradient).epsilon(1e-12));
  CHECK(std::abs(form(GradientLayout::Thesis) - gradient) > 1e-3 * std::abs(gradient));
}

TEST_CASE("states on the yield surface with E_T > 0", "[monotonicity]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> u(-1, 1), mean(-300, 300), sig(5, 105);
  const MaterialParams p = steel();  // E_T = E/3: H'/(3G) = (1+nu)/3, alpha = 1.433 < 2
  const Real g = p.shear_modulus();
  const Real alpha = 1.0 + p.plastic_modulus() / (3.0 * g);
  SECTION("C^EP is positive definite on symmetric gradients: only the rotation is free") {
    const Vec4 rotation = Vec4(0, 0, 1, -1) / std::sqrt(2.0);
    for (int k = 0; k < 200; ++k) {
      const Real sigma = sig(rng);
      const Vec4 stress = on_yield_surface(mean(rng), Vec4(u(rng), u(rng), u(rng), u(rng)), sigma);
      const Mat4 c = operator_a(p, stress, sigma, layout_only(GradientLayout::Gradient, TangentKind::Continuum, false));
      CHECK((c * rotation).norm() < 1e-9 * c.norm());
      CHECK(definiteness(c + g * rotation * rotation.transpose()).positive_definite());
    }
  }
  SECTION("the thesis layout: PD iff beta [(1-nu)(s11^2+s22^2) - 2nu s11 s22 + 4 s12^2] < 1") {
    const Real nu = p.poisson_ratio;
    int n_pd = 0, n_not = 0;
    for (int k = 0; k < 400; ++k) {
      const Real sigma = sig(rng);
      const Vec4 stress = on_yield_surface(mean(rng), Vec4(u(rng), u(rng), u(rng), u(rng)), sigma);
      const Vec4 s = deviator(stress);
      const Real beta = 1.5 / (sigma * sigma * alpha);
      const Real q = beta * ((1 - nu) * (s(0) * s(0) + s(1) * s(1)) - 2 * nu * s(0) * s(1) + 4 * s(3) * s(3));
      if (std::abs(q - 1.0) < 1e-6) continue;
      const Mat4 c = operator_a(p, stress, sigma, layout_only(GradientLayout::Thesis, TangentKind::Continuum, false));
      CHECK(definiteness(c).positive_definite() == (q < 1.0));
      (q < 1.0 ? n_pd : n_not)++;
      // With s12 = 0 the thesis layout equals the true tangent: PD on the surface.
      Vec4 normal = stress;
      normal(3) = 0.0;
      normal = on_yield_surface(mean(rng), normal, sigma);
      CHECK(definiteness(operator_a(p, normal, sigma, layout_only(GradientLayout::Thesis, TangentKind::Continuum)))
                .positive_definite());
    }
    CHECK(n_pd > 50);
    CHECK(n_not > 50);
  }
  SECTION("the thesis layout at pure shear on the surface: PD iff H' > 3G (alpha > 2)") {
    const Vec4 shear = on_yield_surface(0.0, Vec4(0, 0, 0, 1), 40.0);
    const auto pd = [&](const MaterialParams& m) {
      return definiteness(operator_a(m, shear, 40.0, layout_only(GradientLayout::Thesis, TangentKind::Continuum)))
          .positive_definite();
    };
    CHECK_FALSE(pd(steel(1.0 / 3.0)));  // H'/3G = 0.43
    CHECK(pd(steel(0.7)));              // H'/3G = 2.02
  }
}

TEST_CASE(
    "E_T = 0: singular in the flow direction, made PD by rho h^2/dt^2 below the (3.18) "
    "time step",
    "[monotonicity]") {
  const MaterialParams perfect = steel(0.0);
  const Real sigma = 50.0;
  // Deviator along [1, -1, 0, 0] (s12 = 0), in-plane mean stress -100 MPa.
  const Vec4 stress = on_yield_surface(-100.0, Vec4(1, -1, 0, 0), sigma);
  const Vec4 flow = Vec4(1, -1, 0, 0) / std::sqrt(2.0);  // [u1,1 u2,2 u1,2 u2,1] along s
  // The thesis and gradient layouts keep the flow direction singular (s12 = 0); the navier
  // layout's null Lagrangian gives it -G (see "frame" below).
  for (GradientLayout layout : {GradientLayout::Thesis, GradientLayout::Gradient}) {
    INFO("layout " << to_string(layout));
    const Mat4 c = operator_a(perfect, stress, sigma, layout_only(layout, TangentKind::Continuum, false));
    CHECK((c * flow).norm() < 1e-9 * c.norm());
    const Mat4 a = operator_a(perfect, stress, sigma, layout_only(layout, TangentKind::Continuum));
    const Definiteness d = definiteness(a);
    CHECK_FALSE(d.positive_definite());
    // The flow direction (and the gradient layout's rotation) carries T alone:
    // lambda_min ~ flow.T.flow = (t11 + t22)/2 = -100 MPa.
    CHECK(d.lambda_min == Approx(-100.0).epsilon(1e-3));

    // Dynamic term on a 2 mm square Q4.
    const std::vector<Vec2> square{Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)};
    const Real h = inverse_estimate_length(ElementType::Q4, square, false);
    const Real dt_star = restoring_time_step(perfect.density, h, d.lambda_min);
    CHECK(dt_star == Approx(h * std::sqrt(perfect.density / -d.lambda_min)));
    for (auto [factor, expect_pd] :
         {std::pair{0.99, true}, std::pair{1.01, false}, std::pair{0.5, true}, std::pair{3.0, false}}) {
      OperatorOptions o = layout_only(layout, TangentKind::Continuum);
      o.mass_scale = mass_scale(perfect.density, h, factor * dt_star);
      const Definiteness dd = definiteness(operator_a(perfect, stress, sigma, o));
      CHECK(dd.positive_definite() == expect_pd);
      CHECK(dd.consistent());
    }
  }
  // The same state with hardening is PD (thesis layout).
  CHECK(definiteness(operator_a(steel(), stress, sigma, layout_only(GradientLayout::Thesis, TangentKind::Continuum)))
            .positive_definite());
  CHECK(restoring_time_step(7.8e-9, 1.0, 10.0) == std::numeric_limits<Real>::infinity());
  CHECK(restoring_time_step(0.0, 1.0, -10.0) == 0.0);
  CHECK(mass_scale(7.8e-9, 1.0, 0.0) == 0.0);
}

TEST_CASE("inverse-estimate length: d/sqrt(24) for a square Q4, d/6 for a right T3", "[monotonicity]") {
  const Real d = 3.0;
  const std::vector<Vec2> square{Vec2(1, 1), Vec2(1 + d, 1), Vec2(1 + d, 1 + d), Vec2(1, 1 + d)};
  const std::vector<Vec2> triangle{Vec2(0, 0), Vec2(d, 0), Vec2(0, d)};
  CHECK(inverse_estimate_length(ElementType::Q4, square, false) == Approx(d / std::sqrt(24.0)));
  CHECK(inverse_estimate_length(ElementType::T3, triangle, false) == Approx(d / 6.0));
  CHECK(inverse_estimate_length(ElementType::Q4, square, true) == Approx(d / 2.0));
  CHECK(inverse_estimate_length(ElementType::T3, triangle, true) == Approx(d / 3.0));
  // It scales with the element and is an upper bound of the Rayleigh quotient.
  const std::vector<Vec2> skew{Vec2(0, 0), Vec2(2, 0.3), Vec2(2.4, 1.9), Vec2(-0.2, 1.5)};
  const Real h = inverse_estimate_length(ElementType::Q4, skew, false);
  const auto geometry = element_geometry(ElementType::Q4, skew, 0);
  const ElementMatrix m = element_mass(ElementType::Q4, geometry, 1.0, false);
  std::mt19937 rng(2);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (int k = 0; k < 20; ++k) {
    Eigen::Vector4d v(u(rng), u(rng), u(rng), u(rng));
    Real grad2 = 0.0, val2 = 0.0;
    for (const auto& g : geometry) grad2 += g.weight * (g.gradients.transpose() * v).squaredNorm();
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) val2 += v(a) * m(2 * a, 2 * b) * v(b);
    CHECK(grad2 <= val2 / (h * h) * (1 + 1e-12));
  }
}

TEST_CASE(
    "frame: the navier and gradient layouts are invariant under a rotation of the axes, "
    "the thesis layout is not",
    "[monotonicity]") {
  const MaterialParams p = steel();
  std::mt19937 rng(17);
  std::uniform_real_distribution<Real> u(-1, 1), angle(0.1, 3.0);
  const auto rotate = [](const Vec4& t, Real phi) {
    Mat2 r, s;
    r << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
    s << t(0), t(3), t(3), t(1);
    const Mat2 rs = r * s * r.transpose();
    return Vec4(rs(0, 0), rs(1, 1), t(2), rs(0, 1));
  };
  Real thesis_spread = 0.0;
  for (int k = 0; k < 50; ++k) {
    const Vec4 stress = on_yield_surface(100 * u(rng), Vec4(u(rng), u(rng), u(rng), u(rng)), 40.0);
    const Vec4 rotated = rotate(stress, angle(rng));
    for (GradientLayout layout : {GradientLayout::Navier, GradientLayout::Gradient, GradientLayout::Thesis}) {
      const OperatorOptions o = layout_only(layout, TangentKind::Continuum);
      const Vec4 ev = symmetric_eigenvalues(operator_a(p, stress, 40.0, o));
      const Vec4 ev_rot = symmetric_eigenvalues(operator_a(p, rotated, 40.0, o));
      if (layout == GradientLayout::Thesis) {
        thesis_spread = std::max(thesis_spread, (ev - ev_rot).norm() / ev.norm());
      } else {
        CHECK((ev - ev_rot).norm() < 1e-10 * ev.norm());
      }
    }
  }
  CHECK(thesis_spread > 1e-2);
  // Pure shear t12 = k is not PD in the thesis layout (alpha < 2); the same state in axes
  // turned by 45 degrees (t11 = -t22 = k) is.
  const Vec4 shear = on_yield_surface(0.0, Vec4(0, 0, 0, 1), 40.0);
  const OperatorOptions thesis = layout_only(GradientLayout::Thesis, TangentKind::Continuum);
  CHECK_FALSE(definiteness(operator_a(p, shear, 40.0, thesis)).positive_definite());
  CHECK(definiteness(operator_a(p, rotate(shear, M_PI / 4), 40.0, thesis)).positive_definite());
}

TEST_CASE("the three positive-definiteness tests agree on random states away from the boundary", "[monotonicity]") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<Real> ab(-150, 150), cc(-50, 50), sig(5, 105), big(-2e5, 2e5);
  int n_pd = 0, n_not = 0, n_checked = 0;
  for (GradientLayout layout : {GradientLayout::Thesis, GradientLayout::Navier, GradientLayout::Gradient}) {
    MonotonicityMapOptions o;
    o.layout = layout;
    for (int k = 0; k < 3000; ++k) {
      const ThesisParameters t =
          k % 3 == 0 ? ThesisParameters{big(rng), big(rng), big(rng) / 3} : ThesisParameters{ab(rng), ab(rng), cc(rng)};
      const Mat4 a = map_operator(o, sig(rng), t);
      const Definiteness d = definiteness(a);
      if (std::abs(d.lambda_min) < 1e-9 * a.norm()) continue;
      ++n_checked;
      INFO("a " << t.a << " b " << t.b << " c " << t.c << " lambda_min " << d.lambda_min);
      CHECK(d.consistent());
      (d.positive_definite() ? n_pd : n_not)++;
    }
  }
  CHECK(n_checked > 8000);
  CHECK(n_pd > 1000);
  CHECK(n_not > 1000);
}

TEST_CASE("the algorithmic operator uses the consistent tangent and tends to the continuum one", "[monotonicity]") {
  const MaterialParams p = steel();
  // Load uniaxially in strain past yield, then a further increment along the same path.
  const Vec4 path(-1.0, 0.4, 0.0, 0.6);
  const MaterialUpdate first = update_material(p, 1e-3 * path, initial_state(p));
  REQUIRE(first.yielded);
  const OperatorOptions o = layout_only(GradientLayout::Thesis, TangentKind::Continuum);
  Real previous = std::numeric_limits<Real>::infinity();
  for (Real size : {1e-4, 1e-5, 1e-6, 1e-7}) {
    const MaterialUpdate next = update_material(p, size * path, first.trial);
    REQUIRE(next.yielded);
    const Mat4 alg = operator_a_algorithmic(p, first.trial, size * path, o);
    const Mat4 cont = operator_a(p, next.stress, next.trial.yield_stress, o);
    const Real diff = (alg - cont).norm() / cont.norm();
    CHECK(diff < previous);
    previous = diff;
  }
  CHECK(previous < 1e-3);
}

TEST_CASE("maps: symmetric under c <-> -c and a <-> b, the thesis's c-slices at sigma_pl = 40", "[monotonicity]") {
  MonotonicityMapOptions o;
  o.sigma = {20.0, 60.0, 3};
  o.a = {-150.0, 150.0, 7};
  o.b = {-150.0, 150.0, 7};
  o.c = {-45.0, 45.0, 7};
  for (GradientLayout layout : {GradientLayout::Thesis, GradientLayout::Gradient}) {
    o.layout = layout;
    const auto grid = sweep_grid(o);
    REQUIRE(grid.size() == 3u * 7 * 7 * 7);
    const auto at = [&](int is, int ia, int ib, int ic) -> const MapPoint& {
      return grid[((is * 7 + ia) * 7 + ib) * 7 + ic];
    };
    int n_pd = 0;
    for (int is = 0; is < 3; ++is)
      for (int ia = 0; ia < 7; ++ia)
        for (int ib = 0; ib < 7; ++ib)
          for (int ic = 0; ic < 7; ++ic) {
            const MapPoint& m = at(is, ia, ib, ic);
            const MapPoint& mirror_c = at(is, ia, ib, 6 - ic);
            const MapPoint& swap_ab = at(is, ib, ia, ic);
            CHECK(mirror_c.p.c == Approx(-m.p.c).margin(1e-12));
            CHECK(mirror_c.d.lambda_min == Approx(m.d.lambda_min).epsilon(1e-10).margin(1e-6));
            CHECK(swap_ab.d.lambda_min == Approx(m.d.lambda_min).epsilon(1e-10).margin(1e-6));
            CHECK(mirror_c.d.positive_definite() == m.d.positive_definite());
            n_pd += m.d.positive_definite();
          }
    if (layout == GradientLayout::Thesis) CHECK(n_pd > 0);
  }
  // Fig. 3.1 a-e at s = 40: PD at the yield curve for c = 0 and c = -5, no PD point at c = -20.
  o.layout = GradientLayout::Thesis;
  o.a.n = o.b.n = 21;
  for (Real c : {0.0, -5.0}) {
    for (int k = 0; k < 36; ++k) {  // points of the yield curve f = 0 (t33 = 0)
      // a^2 + ab + b^2 + 9c^2 = 3 sigma^2 in polar form along the ellipse's axes.
      const Real phi = k * M_PI / 18.0;
      const Real r2 = 3.0 * 1600.0 - 9.0 * c * c;
      const Real u = std::cos(phi), v = std::sin(phi);
      const Real scale = std::sqrt(r2 / (u * u + u * v + v * v));
      CHECK(evaluate_map_point(o, 40.0, {scale * u, scale * v, c}).d.positive_definite());
    }
  }
  const auto e = sweep_slice(o, {"e", SlicePlane::AB, -20.0}, 40.0, 21, 21);
  for (const auto& m : e) CHECK_FALSE(m.d.positive_definite());
  std::string why;
  o.sigma.lo = 0.0;
  CHECK_FALSE(o.is_valid(&why));
  CHECK(why.find("sigma_pl") != std::string::npos);
}

TEST_CASE("check_strip flags a large compressive initial stress and a small dt restores PD", "[monotonicity]") {
  StripMeshSpec spec = test::strip_spec(ElementType::Q4, 4.0, 2.0, 4, 2);
  StripModel model(make_strip_mesh(spec), elastic_steel(), ElementOptions{Kinematics::Finite, Q4Formulation::Standard});
  model.set_dof_map(DofMap(std::vector<bool>(model.n_dofs(), true)));  // every node prescribed
  const Real g = model.material(0).shear_modulus();
  const auto squeeze = [](const Vec2& x) -> Vec2 { return -0.2 * x; };  // F = 0.8 I

  REQUIRE(impose_field(model, squeeze).converged());
  const StripMonotonicity first = check_strip(model, 0.0);
  INFO(first.brief_report());
  CHECK(first.monotone());
  CHECK(first.n_points == 8 * 4);

  REQUIRE(impose_field(model, squeeze).converged());
  const Vec4 s = model.state(0, 0).stress;
  REQUIRE(s(0) == Approx(s(1)));
  REQUIRE(s(0) < -g);  // in-plane hydrostatic compression beyond G
  const StripMonotonicity second = check_strip(model, 0.0);
  INFO(second.brief_report());
  CHECK(second.n_not_pd == second.n_points);
  CHECK(second.not_pd.size() == static_cast<std::size_t>(second.n_points));
  // T = t11 I: lambda_min = G + t11 in the thesis layout.
  CHECK(second.lambda_min == Approx(g + s(0)).epsilon(1e-8));
  // (3.18) with Houbolt's 2M/dt^2 on the squeezed unit squares (side 0.8^2 mm, h = side/sqrt(24)).
  CHECK(second.dt_restore_worst ==
        Approx(0.64 / std::sqrt(24.0) * std::sqrt(2.0 * 7.8e-9 / -(g + s(0)))).epsilon(1e-8));
  CHECK(second.dt_restore_all <= second.dt_restore_worst);
  CHECK(second.brief_report().find("not positive definite") != std::string::npos);

  // Small kinematics has no K_NL: by default the check follows the model.
  StripMonotonicityOptions never;
  never.initial_stress = InitialStressTerm::Never;
  CHECK(check_strip(model, 0.0, never).monotone());

  // The Courant-type bound restores every point just below dt_restore_all, not above.
  CHECK(check_strip(model, 0.99 * second.dt_restore_all).monotone());
  const StripMonotonicity slow = check_strip(model, 1.01 * second.dt_restore_worst);
  CHECK_FALSE(slow.monotone());
  CHECK(slow.lambda_min > second.lambda_min);
}

TEST_CASE("check_strip: an elastic strip's one operator gives what the point-by-point check gives", "[monotonicity]") {
  // The elastic shortcut computes A's eigenvalue once; a plastic material whose points are all
  // elastic (a yield stress never reached) takes the point-by-point path and must agree,
  // quasistatic and with the mass term on a graded mesh (h, so the dynamic term, varies: the
  // worst point is the largest element's).
  StripMeshSpec spec = test::strip_spec(ElementType::Q4, 8.0, 2.0, 8, 4);
  spec.grading_x.kind = Grading::Kind::Geometric;
  spec.grading_x.ratio = 5.0;
  spec.grading_x.focus = 0.0;
  MaterialParams never_yields = steel();
  never_yields.yield_stress = 1e9;
  const ElementOptions small{Kinematics::Small, Q4Formulation::Standard};
  StripModel elastic(make_strip_mesh(spec), elastic_steel(), small);
  StripModel plastic(make_strip_mesh(spec), never_yields, small);
  for (const Real dt : {0.0, 1e-6}) {
    INFO("dt " << dt);
    const StripMonotonicity a = check_strip(elastic, dt), b = check_strip(plastic, dt);
    CHECK(a.n_points == b.n_points);
    CHECK(a.n_not_pd == 0);
    CHECK(b.n_not_pd == 0);
    CHECK(a.lambda_min == b.lambda_min);
    CHECK(a.worst.element == b.worst.element);
    CHECK(a.worst.point == b.worst.point);
    if (dt > 0.0) CHECK(a.lambda_min > check_strip(elastic, 0.0).lambda_min);  // the mass term counted
  }
}

TEST_CASE("check_strip: the Cholesky screen changes nothing against every point's eigenvalues", "[monotonicity]") {
  // A squeeze that rises and falls along the strip leaves points on both sides of the loss of
  // definiteness, in no order, many close to the running minimum; the brute-force reference
  // takes every point's smallest eigenvalue.
  StripMeshSpec spec = test::strip_spec(ElementType::Q4, 4.0, 2.0, 24, 12);
  StripModel model(make_strip_mesh(spec), elastic_steel(), ElementOptions{Kinematics::Finite, Q4Formulation::Standard});
  model.set_dof_map(DofMap(std::vector<bool>(model.n_dofs(), true)));
  const auto squeeze = [](const Vec2& x) -> Vec2 {
    return -0.1 * (1.0 + 0.3 * std::sin(3.0 * x.x()) + 0.2 * std::sin(2.0 * x.y())) * x;
  };
  REQUIRE(impose_field(model, squeeze).converged());
  REQUIRE(impose_field(model, squeeze).converged());
  const MaterialParams& m = model.material(0);
  OperatorOptions op;
  op.initial_stress = true;
  const Real rho = 2.0 * m.density;
  for (const Real dt : {0.0, 2e-7}) {
    INFO("dt " << dt);
    Index n_not_pd = 0;
    Real lambda_min = std::numeric_limits<Real>::infinity();
    for (Index e = 0; e < model.mesh().n_elements(); ++e) {
      std::vector<Vec2> xe;
      for (Index a : model.mesh().elements[e]) xe.push_back(model.reference_coordinates()[a]);
      const Real kappa = mass_scale(rho, inverse_estimate_length(ElementType::Q4, xe, false), dt);
      for (int q = 0; q < model.points_per_element(); ++q) {
        const MaterialState& s = model.state(e, q);
        const Real lambda = symmetric_eigenvalues(operator_a(m, s.stress, s.yield_stress, op))(0) + kappa;
        lambda_min = std::min(lambda_min, lambda);
        n_not_pd += lambda > 0.0 ? 0 : 1;
      }
    }
    const StripMonotonicity screened = check_strip(model, dt);
    INFO(screened.brief_report());
    CHECK(screened.n_points == model.mesh().n_elements() * model.points_per_element());
    CHECK(screened.n_not_pd == n_not_pd);
    CHECK(screened.lambda_min == lambda_min);
    if (dt == 0.0) {
      CHECK(n_not_pd > 0);  // both sides present
      CHECK(n_not_pd < screened.n_points);
    }
  }
}

TEST_CASE("is_positive_definite: sparse LDL^T, inertia from the pivots", "[monotonicity]") {
  // 1D Laplacian (PD) and shifted copies with a known number of negative eigenvalues.
  const int n = 30;
  std::vector<Triplet> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0);
    if (i > 0) t.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0);
  }
  SparseMatrix k(n, n);
  k.setFromTriplets(t.begin(), t.end());
  CHECK(is_positive_definite(k));
  const VecX ev = symmetric_eigenvalues(MatX(k));
  SparseMatrix identity(n, n);
  identity.setIdentity();
  for (Real shift : {0.5, 1.7}) {
    const SparseMatrix shifted = k - shift * identity;
    const Index expected = (ev.array() < shift).count();
    const SparseDefiniteness d = sparse_definiteness(shifted);
    CHECK_FALSE(is_positive_definite(shifted));
    if (d.factorized) CHECK(d.n_negative == expected);
  }

  // The assembled stiffness of a strip clamped at its bottom: PD unstressed; the mass term
  // 2M/dt^2 keeps K_eff PD.
  StripMeshSpec spec = test::strip_spec(ElementType::Q4, 4.0, 2.0, 4, 2);
  StripModel model(make_strip_mesh(spec), elastic_steel(), ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
  std::vector<bool> fixed(model.n_dofs(), false);
  for (Index a : model.mesh().node_set("bottom")) fixed[2 * a] = fixed[2 * a + 1] = true;
  model.set_dof_map(DofMap(fixed));
  SparseMatrix hessian;
  model.evaluate(VecX::Zero(model.n_dofs()), nullptr, &hessian);
  CHECK(is_positive_definite(hessian));
  CHECK_FALSE(is_positive_definite(SparseMatrix(-1.0 * hessian)));
}

TEST_CASE("roller monotonicity writes the grid, the slices and the summary", "[monotonicity][cli]") {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / "roller_test_monotonicity";
  fs::remove_all(out);
  const std::string command = std::string(ROLLER_ROLLER_EXE) +
                              " monotonicity --grid 5 --slice-grid 7 --no-plot --out " + out.string() + " > /dev/null";
  REQUIRE(std::system(command.c_str()) == 0);
  CHECK(fs::exists(out / "monotonicity_grid.csv"));
  CHECK(fs::exists(out / "monotonicity_slices.csv"));
  CHECK(fs::exists(out / "monotonicity.json"));
  const std::string bad = std::string(ROLLER_ROLLER_EXE) + " monotonicity --sigma-range 0,10 --no-plot --out " +
                          out.string() + " > /dev/null 2>&1";
  CHECK(WEXITSTATUS(std::system(bad.c_str())) == 2);
  fs::remove_all(out);
}
