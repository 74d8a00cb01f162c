// Each element takes the band of its centroid's depth and the profile there
// (assembly/element_materials.hpp), with one table entry per distinct material; follow_layers
// pins grid lines on the boundaries (mesh/strip_mesher.hpp, pin_lines).
#include <catch2/catch.hpp>

#include <vector>

#include "roller/assembly/element_materials.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

LayeredMaterial two_layers() {
  MaterialParams core;
  core.plastic = true;
  core.yield_stress = 800.0;
  LayeredMaterial m = LayeredMaterial::uniform(core);
  MaterialLayer hard{0.3, core, false};
  hard.material.yield_stress = 1500.0;
  MaterialLayer middle{0.5, core, false};
  middle.material.yield_stress = 1100.0;
  m.layers = {hard, middle};
  return m;
}

StripMeshSpec strip(ElementType type) {
  StripMeshSpec s;
  s.element = type;
  s.length = 2.0;
  s.height = 2.0;
  s.nx = 2;
  s.ny = 10;  // rows of 0.2 mm: centroids at depths 0.1, 0.3, 0.5, ...
  return s;
}

}  // namespace

TEST_CASE("element materials: the centroid's depth picks the layer", "[assembly][layers]") {
  const Mesh mesh = make_strip_mesh(strip(ElementType::Q4));
  const ElementMaterials m = assign_materials(mesh, two_layers());
  CHECK(m.table.size() == 3);
  CHECK(static_cast<Index>(m.index.size()) == mesh.n_elements());
  const Real top = mesh_top(mesh);
  CHECK(top == 2.0);
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const Real z = centroid_depth(mesh, e, top);
    INFO("element " << e << " at depth " << z);
    // Depth 0.1: layer 0. 0.3 (straddles the boundary at 0.3 by round-off either way) is not
    // asserted. 0.5, 0.7: layer 1. From 0.9: [material].
    if (z < 0.2) CHECK(m.layer_of(e) == 0);
    if (z > 0.4 && z < 0.8) CHECK(m.layer_of(e) == 1);
    if (z > 0.8) CHECK(m.layer_of(e) == 2);
    if (z > 0.8) CHECK(m.of(e).yield_stress == 800.0);
  }
}

TEST_CASE("element materials: T3 triangles of one quad may lie in different layers", "[assembly][layers]") {
  // One row of quads 0.6 mm high straddling the boundary at 0.3: each triangle's centroid is a
  // third of the row from its two-node edge, at depths 0.2 and 0.4.
  StripMeshSpec s = strip(ElementType::T3);
  s.ny = 1;
  s.y_lines = {0.0, 1.4, 2.0};
  const Mesh mesh = make_strip_mesh(s);
  const ElementMaterials m = assign_materials(mesh, two_layers());
  int in_hard = 0, in_middle = 0;
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const Real z = centroid_depth(mesh, e, mesh_top(mesh));
    if (z < 0.6) (m.layer_of(e) == 0 ? in_hard : in_middle) += 1;
  }
  CHECK(in_hard == 2);    // the triangles with two nodes on the top
  CHECK(in_middle == 2);  // the others
}

TEST_CASE("element materials: a profile gives one entry per distinct depth, a uniform strip one",
          "[assembly][layers]") {
  const Mesh mesh = make_strip_mesh(strip(ElementType::Q4));
  MaterialParams core;
  core.plastic = true;
  core.yield_stress = 800.0;
  CHECK(assign_materials(mesh, LayeredMaterial::uniform(core)).table.size() == 1);
  LayeredMaterial profiled = LayeredMaterial::uniform(core);
  profiled.yield_profile = YieldProfile{{{0.0, 1600.0}, {1.0, 800.0}}};
  const ElementMaterials m = assign_materials(mesh, profiled);
  CHECK(m.table.size() == 6);  // rows at 0.1, 0.3, 0.5, 0.7, 0.9 and every row below 1.0 alike
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const Real z = centroid_depth(mesh, e, mesh_top(mesh));
    CHECK(m.of(e).yield_stress == Approx(z < 1.0 ? 1600.0 - 800.0 * z : 800.0).epsilon(1e-12));
  }
}

TEST_CASE("follow_layers: pinned lines move the nearest grid line or add one", "[mesh][layers]") {
  const std::vector<Real> lines{0.0, 1.0, 2.0, 3.0, 4.0};
  CHECK(pin_lines(lines, {2.0}) == lines);                                                 // on a line
  CHECK(pin_lines(lines, {2.2}) == std::vector<Real>{0.0, 1.0, 2.2, 3.0, 4.0});            // moved
  CHECK(pin_lines(lines, {2.5}) == std::vector<Real>{0.0, 1.0, 2.0, 2.5, 3.0, 4.0});       // added
  CHECK(pin_lines(lines, {0.1}) == std::vector<Real>{0.0, 0.1, 1.0, 2.0, 3.0, 4.0});       // the end stays
  CHECK(pin_lines(lines, {2.1, 2.2}) == std::vector<Real>{0.0, 1.0, 2.1, 2.2, 3.0, 4.0});  // one line each
  CHECK(pin_lines(lines, {4.0, 5.0, -1.0}) == lines);                                      // not inside: ignored
  // In a mesh: the boundary at depth 0.35 of a 2 mm strip with 0.2 mm rows (y = 1.65) moves the
  // line at 1.6, refinement then splits the moved intervals.
  StripMeshSpec s = strip(ElementType::Q4);
  s.pinned_y = {1.65};
  s.refine = 2;
  const Mesh mesh = make_strip_mesh(s);
  bool found = false;
  for (const Vec2& x : mesh.nodes) found = found || x.y() == 1.65;
  CHECK(found);
  CHECK(mesh.n_elements() == 2 * 2 * 10 * 2);
}
