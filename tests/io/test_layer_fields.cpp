// The VTU's cell fields of a layered strip (io/field_output.hpp): `layer` is each element's band
// (the number of layers for [material]) and `initial_yield_stress` its sigma_y0, the profile's at
// its centroid; a homogeneous strip has layer 0 and its yield stress everywhere.
#include <catch2/catch.hpp>

#include <string>

#include "roller/assembly/element_materials.hpp"
#include "roller/io/field_output.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

const VtuField& cell_field(const StripFields& f, const std::string& name) {
  const VtuField* found = nullptr;
  for (const VtuField& v : f.cell_data)
    if (v.name == name) found = &v;
  INFO("cell field " << name);
  REQUIRE(found);
  return *found;
}

}  // namespace

TEST_CASE("VTU cell fields: each element's layer and initial yield stress", "[io][vtu][layers]") {
  StripMeshSpec spec;
  spec.length = 2.0;
  spec.height = 2.0;
  spec.nx = 2;
  spec.ny = 10;  // centroids at depths 0.1, 0.3, ...
  const Mesh mesh = make_strip_mesh(spec);
  MaterialParams core;
  core.plastic = true;
  core.yield_stress = 800.0;
  LayeredMaterial layered = LayeredMaterial::uniform(core);
  MaterialLayer coat{0.2, core, false};
  coat.material.plastic = true;
  coat.material.yield_stress = 2500.0;
  layered.layers = {coat};
  layered.yield_profile = YieldProfile{{{0.0, 1600.0}, {1.0, 800.0}}};
  const StripModel model(mesh, assign_materials(mesh, layered), ElementOptions{});
  const StripFields f = strip_fields(model, VecX::Zero(model.n_dofs()));
  const VtuField& layer = cell_field(f, "layer");
  const VtuField& yield = cell_field(f, "initial_yield_stress");
  REQUIRE(static_cast<Index>(layer.values.size()) == mesh.n_elements());
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const Real z = centroid_depth(mesh, e, mesh_top(mesh));
    INFO("element " << e << " at depth " << z);
    CHECK(layer.values[e] == (z < 0.2 ? 0.0 : 1.0));
    CHECK(yield.values[e] == Approx(z < 0.2 ? 2500.0 : z < 1.0 ? 1600.0 - 800.0 * z : 800.0).epsilon(1e-12));
  }
  // Homogeneous and elastic: layer 0, yield stress 0.
  const StripModel elastic(mesh, MaterialParams{}, ElementOptions{});
  const StripFields g = strip_fields(elastic, VecX::Zero(elastic.n_dofs()));
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    CHECK(cell_field(g, "layer").values[e] == 0.0);
    CHECK(cell_field(g, "initial_yield_stress").values[e] == 0.0);
  }
}
