// Element kernel: the residual is the gradient of the energy and the tangent the gradient of the
// residual (finite differences), for every element type and formulation; mass integrals.
#include <catch2/catch.hpp>

#include <random>

#include "roller/fem/element_kernel.hpp"

using namespace roller;

namespace {

MaterialParams steel_plastic() {
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = 0.3;
  p.plastic = true;
  p.yield_stress = 50.0;
  p.tangent_modulus = 0.07 * 2.1e5;
  p.density = 7.8e-9;
  return p;
}

std::vector<Vec2> distorted_nodes(ElementType t) {
  if (t == ElementType::T3) return {Vec2(0.1, 0.0), Vec2(2.0, 0.3), Vec2(0.4, 1.7)};
  return {Vec2(0.0, 0.0), Vec2(2.1, 0.2), Vec2(1.8, 1.9), Vec2(-0.2, 1.5)};
}

struct Case {
  ElementType type;
  Kinematics kinematics;
  Q4Formulation q4;
  const char* name;
};

const Case kCases[] = {
    {ElementType::T3, Kinematics::Small, Q4Formulation::Standard, "T3 small"},
    {ElementType::T3, Kinematics::Finite, Q4Formulation::Standard, "T3 finite"},
    {ElementType::Q4, Kinematics::Small, Q4Formulation::Standard, "Q4 small"},
    {ElementType::Q4, Kinematics::Finite, Q4Formulation::Standard, "Q4 finite"},
    {ElementType::Q4, Kinematics::Small, Q4Formulation::BBar, "Q4 B-bar small"},
    {ElementType::Q4, Kinematics::Finite, Q4Formulation::BBar, "Q4 B-bar finite"},
};

}  // namespace

TEST_CASE("element residual and tangent match finite differences of energy and residual", "[fem][tangent]") {
  const MaterialParams mat = steel_plastic();
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> uni(-1.0, 1.0);
  for (const Case& c : kCases) {
    for (const Real amplitude : {1e-4, 3e-3, 5e-2}) {  // elastic, plastic, large rotation/strain
      SECTION(std::string(c.name) + " amplitude " + std::to_string(amplitude)) {
        ElementOptions opt{c.kinematics, c.q4};
        const auto nodes = distorted_nodes(c.type);
        const auto geometry = element_geometry(c.type, nodes, 0);
        std::vector<MaterialState> committed(geometry.size(), initial_state(mat));
        for (auto& s : committed) s.stress = Vec4(20.0, -35.0, 4.0, 12.0);  // pre-stress inside yield
        ElementInput in;
        in.type = c.type;
        in.geometry = &geometry;
        in.committed = committed.data();
        const Index n = 2 * static_cast<Index>(nodes.size());
        in.displacement.resize(n);
        for (Index i = 0; i < n; ++i) in.displacement(i) = amplitude * uni(rng);

        ElementOutput out;
        evaluate_element(opt, mat, in, true, true, out);
        const Real h = 1e-7 * std::max(amplitude, 1e-3);
        ElementVector fd_residual(n);
        ElementMatrix fd_tangent(n, n);
        for (Index i = 0; i < n; ++i) {
          ElementInput plus = in, minus = in;
          plus.displacement(i) += h;
          minus.displacement(i) -= h;
          ElementOutput op, om;
          evaluate_element(opt, mat, plus, true, false, op);
          evaluate_element(opt, mat, minus, true, false, om);
          fd_residual(i) = (op.energy - om.energy) / (2 * h);
          fd_tangent.col(i) = (op.residual - om.residual) / (2 * h);
        }
        INFO("residual " << out.residual.transpose() << "\nfd " << fd_residual.transpose());
        CHECK((out.residual - fd_residual).norm() <= 1e-6 * out.residual.norm() + 1e-6);
        const Real scale = out.tangent.norm();
        CHECK((out.tangent - fd_tangent).norm() <= 1e-5 * scale);
        CHECK((out.tangent - out.tangent.transpose()).norm() <= 1e-10 * scale);
      }
    }
  }
}

TEST_CASE("element mass integrates to rho times area, consistent and lumped", "[fem][mass]") {
  for (ElementType t : {ElementType::T3, ElementType::Q4}) {
    const auto nodes = distorted_nodes(t);
    const auto geometry = element_geometry(t, nodes, 0);
    Real area = 0.0;
    for (const auto& g : geometry) area += g.weight;
    const Real rho = 7.8e-9;
    for (bool lumped : {false, true}) {
      const ElementMatrix m = element_mass(t, geometry, rho, lumped);
      // Rigid translation in x: u^T M u = rho * area.
      ElementVector ux = ElementVector::Zero(m.rows());
      for (Index a = 0; a < m.rows() / 2; ++a) ux(2 * a) = 1.0;
      CHECK(ux.dot(m * ux) == Approx(rho * area).epsilon(1e-12));
      CHECK((m - m.transpose()).norm() == Approx(0.0).margin(1e-20));
      if (lumped) CHECK((m - ElementMatrix(m.diagonal().asDiagonal())).norm() == 0.0);
    }
    if (t == ElementType::T3) {  // exact consistent T3 mass: rho A / 12 [2 1 1; 1 2 1; 1 1 2]
      const ElementMatrix m = element_mass(t, geometry, rho, false);
      CHECK(m(0, 0) == Approx(rho * area / 6.0));
      CHECK(m(0, 2) == Approx(rho * area / 12.0));
      CHECK(m(0, 1) == 0.0);
    }
  }
}

TEST_CASE("push-forward of a rigid rotation rotates the stress", "[fem][objectivity]") {
  const Real angle = 0.7;
  Mat2 r;
  r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  const Vec4 s(100.0, -40.0, 18.0, 25.0);
  const Vec4 rotated = push_forward(r, s);
  Mat2 sm;
  sm << s(0), s(3), s(3), s(1);
  const Mat2 expected = r * sm * r.transpose();
  CHECK(rotated(0) == Approx(expected(0, 0)));
  CHECK(rotated(1) == Approx(expected(1, 1)));
  CHECK(rotated(3) == Approx(expected(0, 1)));
  CHECK(rotated(2) == Approx(s(2)));
}
