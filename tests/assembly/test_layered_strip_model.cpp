// A strip of several materials (assembly/strip_model.hpp with element_materials.hpp): every user
// of an element's material reads its own: the mass matrix's density, whether the tangent is
// constant, and the run-time monitor's operator A (analysis/monotonicity.hpp, check_strip).
#include <catch2/catch.hpp>

#include <algorithm>
#include <utility>

#include "roller/analysis/monotonicity.hpp"
#include "roller/assembly/element_materials.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

// A 4 x 2 mm strip, rows of 0.25 mm; the top 0.5 mm of `top` over `core`.
StripModel strip(const MaterialParams& top, const MaterialParams& core, Kinematics kinematics = Kinematics::Small) {
  StripMeshSpec spec;
  spec.length = 4.0;
  spec.height = 2.0;
  spec.nx = 8;
  spec.ny = 8;
  const Mesh mesh = make_strip_mesh(spec);
  LayeredMaterial layered = LayeredMaterial::uniform(core);
  layered.layers = {MaterialLayer{0.5, top, false}};
  ElementOptions options;
  options.kinematics = kinematics;
  return StripModel(mesh, assign_materials(mesh, layered), options);
}

MaterialParams steel(Real e, Real density) {
  MaterialParams m;
  m.youngs_modulus = e;
  m.density = density;
  return m;
}

}  // namespace

TEST_CASE("layered strip model: the mass is each layer's density times its area", "[assembly][layers]") {
  const StripModel model = strip(steel(2.1e5, 2e-9), steel(2.1e5, 8e-9));
  const SparseMatrix m = model.mass_matrix(false);
  // Ones in x: u^T M u is the total mass.
  VecX ones_x = VecX::Zero(model.n_dofs());
  for (Index a = 0; a < model.mesh().n_nodes(); ++a) ones_x(2 * a) = 1.0;
  const Real mass = ones_x.dot(m * ones_x);
  CHECK(mass == Approx(4.0 * 0.5 * 2e-9 + 4.0 * 1.5 * 8e-9).epsilon(1e-12));
}

TEST_CASE("layered strip model: the tangent is constant only when no layer is plastic", "[assembly][layers]") {
  MaterialParams hard = steel(2.1e5, 0.0);
  CHECK(strip(hard, steel(2.1e5, 0.0)).tangent_is_constant());
  hard.plastic = true;
  hard.yield_stress = 1500.0;
  CHECK_FALSE(strip(hard, steel(2.1e5, 0.0)).tangent_is_constant());  // a plastic case
  CHECK_FALSE(strip(steel(2.1e5, 0.0), hard).tangent_is_constant());  // a plastic core
  CHECK_FALSE(strip(steel(2.1e5, 0.0), steel(2.1e5, 0.0), Kinematics::Finite).tangent_is_constant());
}

TEST_CASE("layered strip model: the monitor's operator A is each element's", "[assembly][layers][monotonicity]") {
  // Elastic and without initial stress A is the elasticity of each element: the layered strip's
  // smallest eigenvalue is the softer material's, wherever it lies.
  const MaterialParams soft = steel(1.0e5, 0.0), stiff = steel(3.0e5, 0.0);
  const Real lambda_soft = check_strip(strip(soft, soft), 0.0).lambda_min;
  const Real lambda_stiff = check_strip(strip(stiff, stiff), 0.0).lambda_min;
  REQUIRE(lambda_soft < lambda_stiff);
  for (const auto& [top, core] : {std::make_pair(soft, stiff), std::make_pair(stiff, soft)}) {
    const StripModel model = strip(top, core);
    const StripMonotonicity mono = check_strip(model, 0.0);
    CHECK(mono.lambda_min == Approx(lambda_soft).epsilon(1e-12));
    CHECK(model.material(mono.worst.element).youngs_modulus == 1.0e5);
  }
}
