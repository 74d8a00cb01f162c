// The strain of one step's increment (StripModel::increment_strain, the thesis's
// updated-Lagrangian strain written to the VTU files): the difference of the totals for small
// kinematics, exactly zero for a rigid rotation and the Green-Lagrange value of a stretch for
// finite kinematics, measured from the configuration before the step.
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/strip_spec.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

MaterialParams elastic() {
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = 0.3;
  return p;
}

template <class Field>
VecX sample(const StripModel& model, const Field& field) {
  VecX u(model.n_dofs());
  const auto& x = model.reference_coordinates();
  for (Index a = 0; a < model.mesh().n_nodes(); ++a) {
    const Vec2 v = field(x[a]);
    u(2 * a) = v.x();
    u(2 * a + 1) = v.y();
  }
  return u;
}

Vec2 wavy(const Vec2& x) {
  return Vec2(1e-3 * std::sin(0.3 * x.x()) * x.y(), -2e-3 * x.x() * x.x() / 16.0 + 1e-3 * x.y());
}

}  // namespace

TEST_CASE("step strain: small kinematics, the difference of the total strains", "[assembly][strain]") {
  for (const ElementType type : {ElementType::Q4, ElementType::T3}) {
    StripModel model(make_strip_mesh(test::strip_spec(type, 8.0, 2.0, 8, 2)), elastic(),
                     ElementOptions{Kinematics::Small, Q4Formulation::BBar});
    model.commit(sample(model, wavy));
    std::vector<std::vector<Vec4>> before;
    for (Index e = 0; e < model.mesh().n_elements(); ++e) before.push_back(model.total_strain(e));
    const VecX du = sample(model, [](const Vec2& x) { return Vec2(2e-3 * x.y() * x.x() / 8.0, 1e-3 * x.x()); });
    model.commit(du);
    for (Index e = 0; e < model.mesh().n_elements(); ++e) {
      const auto after = model.total_strain(e);
      const auto step = model.increment_strain(e, du);
      for (std::size_t q = 0; q < step.size(); ++q) CHECK((step[q] - (after[q] - before[e][q])).norm() <= 1e-15);
    }
  }
}

TEST_CASE("step strain: finite kinematics, zero for a rigid rotation, Green-Lagrange for a stretch",
          "[assembly][strain]") {
  StripModel model(make_strip_mesh(test::strip_spec(ElementType::Q4, 8.0, 2.0, 8, 2)), elastic(),
                   ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
  model.commit(sample(model, wavy));  // the step starts from a deformed configuration
  const Real angle = 0.3;
  const Mat2 r = Eigen::Rotation2D<Real>(angle).toRotationMatrix();
  const Vec2 centre(4.0, 1.0);
  const VecX rotation = sample(model, [&](const Vec2& x) { return Vec2((r - Mat2::Identity()) * (x - centre)); });
  model.commit(rotation);
  for (Index e = 0; e < model.mesh().n_elements(); ++e)
    for (const Vec4& strain : model.increment_strain(e, rotation)) CHECK(strain.norm() <= 1e-14);

  const Real stretch = 1.02;
  const VecX pull = sample(model, [&](const Vec2& x) { return Vec2((stretch - 1.0) * x.x(), 0.0); });
  model.commit(pull);
  for (Index e = 0; e < model.mesh().n_elements(); ++e)
    for (const Vec4& strain : model.increment_strain(e, pull)) {
      CHECK(strain(0) == Approx(0.5 * (stretch * stretch - 1.0)).epsilon(1e-12));
      CHECK(std::abs(strain(1)) <= 1e-14);
      CHECK(std::abs(strain(3)) <= 1e-14);
    }
}
