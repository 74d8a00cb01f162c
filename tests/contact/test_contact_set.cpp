// Contact candidates (contact_set.hpp): the penalty scale of a surface node is the depth of its
// element in the initial mesh, whatever the surface has done since.
#include <catch2/catch.hpp>

#include <limits>

#include "../support/impose_field.hpp"
#include "../support/strip_spec.hpp"
#include "roller/contact/contact_set.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

TEST_CASE("contact candidates keep the initial element depth after the surface deforms", "[contact]") {
  StripMeshSpec spec = test::strip_spec(ElementType::T3, 20.0, 6.0, 4, 3, Diagonal::Alternating);
  MaterialParams mat;
  StripModel model(make_strip_mesh(spec), mat, ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
  model.set_dof_map(DofMap(std::vector<bool>(model.n_dofs(), true)));
  // A dent: neighbouring top nodes end at different heights (the updated reference moves).
  REQUIRE(test::impose_field(model, [](const Vec2& p) {
            return Vec2(0.0, -1e-3 * p.x() * (20.0 - p.x()) * p.y() / 6.0);
          }).converged());
  const VecX zero = VecX::Zero(model.n_dofs());
  const auto candidates = make_contact_candidates(model, model.mesh().node_set("top"), zero, zero, Vec2(10.0, 36.0),
                                                  30.0, std::numeric_limits<Real>::infinity());
  REQUIRE(candidates.size() == 5);
  for (const auto& c : candidates) CHECK(c.element_size == Approx(2.0));
}
