// The keys of layered strips (docs/scenes.md, `[[layer]]`, material.yield_profile,
// mesh.follow_layers): a layer is a copy of [material] with its own keys over it, bad values are
// refused naming the file, key and value, and the resolved scene shows and re-reads them.
#include <catch2/catch.hpp>

#include <string>

#include "../support/scene_errors.hpp"
#include "roller/io/scene_keys.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;
using Catch::Contains;
using test::error_of;

namespace {

const std::string kBase = R"(
[mesh]
length = 10.0
height = 3.0
[material]
E = 2.1e5
nu = 0.3
yield_stress = 800.0
tangent_modulus = 2100.0
density = 7.8e-9
)";

}  // namespace

TEST_CASE("layers: a copy of [material] with the block's keys over it", "[io][scene][layers]") {
  const Scene s = parse_scene(kBase +
                                  "[[layer]]\nthickness = 0.2\nE = 3.0e5\nyield_stress = 2000.0\n"
                                  "[[layer]]\nthickness = 0.8\nkappa = 0.02\n",
                              "layers.toml");
  REQUIRE(s.layers.size() == 2);
  CHECK(s.layers[0].thickness == 0.2);
  CHECK(s.layers[0].material.youngs_modulus == 3.0e5);
  CHECK(s.layers[0].material.yield_stress == 2000.0);
  CHECK(s.layers[0].material.poisson_ratio == 0.3);       // [material]'s
  CHECK(s.layers[0].material.density == 7.8e-9);          // [material]'s
  CHECK(s.layers[0].material.tangent_modulus == 2100.0);  // [material]'s E_T, not kappa E
  CHECK_FALSE(s.layers[0].follows_profile);
  CHECK(s.layers[1].material.tangent_modulus == Approx(0.02 * 2.1e5));
  CHECK(s.layers[1].material.yield_stress == 800.0);
  CHECK(s.layers[1].follows_profile);
  CHECK(s.material.youngs_modulus == 2.1e5);  // [material] itself unchanged
  // Every [material] key has its [[layer]] twin (also those [material] gains later).
  for (const SceneKey* k : keys_of("material")) {
    if (k->name == "yield_profile") continue;  // given once, in [material]
    INFO(k->name);
    bool twin = false;
    for (const SceneKey* l : keys_of("layer")) twin = twin || l->name == k->name;
    CHECK(twin);
  }
}

TEST_CASE("layers and yield profile: the resolved scene shows them and reads back the same", "[io][scene][layers]") {
  const Scene s = parse_scene(kBase +
                                  "yield_profile = [[0.0, 1600.0], [1.0, 1200], [1.5, 800.0]]\n"
                                  "[[layer]]\nthickness = 0.1\nyield_stress = 2000.0\n"
                                  "[[layer]]\nthickness = 0.4\nnu = 0.29\n",
                              "layers.toml");
  REQUIRE(s.yield_profile.points.size() == 3);
  CHECK(s.yield_profile.points[1] == std::make_pair(1.0, 1200.0));
  const std::string resolved = scene_to_toml(s);
  CHECK_THAT(resolved, Contains("yield_profile = [") && Contains("[[layer]]") && Contains("thickness = 0.4"));
  const Scene again = parse_scene(resolved, "resolved.toml");
  CHECK(scene_to_toml(again) == resolved);
  CHECK(again.layers[1].follows_profile);  // its copied yield_stress is not written back
  CHECK_FALSE(again.layers[0].follows_profile);
  CHECK(again.strip_material().at_depth(0.3).material.yield_stress == Approx(1600.0 - 400.0 * 0.3));
  CHECK(again.strip_material().at_depth(0.3).material.poisson_ratio == 0.29);
}

TEST_CASE("layers and yield profile: bad values name the file, the key and what was expected",
          "[io][scene][layers][errors]") {
  CHECK_THAT(error_of(kBase + "[[layer]]\nE = 3e5\n"),
             Contains("bad.toml") && Contains("layer[0].thickness") && Contains("needs its thickness"));
  CHECK_THAT(error_of(kBase + "[[layer]]\nthickness = -0.5\n"),
             Contains("layer[0].thickness = -0.5") && Contains("expected a thickness of 1e-6 to 1e9 mm"));
  CHECK_THAT(error_of(kBase + "[[layer]]\nthickness = 0.5\nyeld_stress = 900.0\n"),
             Contains("layer[0].yeld_stress") && Contains("did you mean 'layer[0].yield_stress'"));
  CHECK_THAT(error_of(kBase + "[[layer]]\nthickness = 0.5\nnu = 0.5\n"),
             Contains("layer[0].nu = 0.5") && Contains("0 <= nu < 0.5"));
  CHECK_THAT(error_of(kBase + "[[layer]]\nthickness = 0.5\ntangent_modulus = 3e5\n"),
             Contains("layer[0].tangent_modulus = 300000") && Contains("E_T < E"));
  CHECK_THAT(error_of(kBase + "[[layer]]\nthickness = 2.0\n[[layer]]\nthickness = 1.5\n"),
             Contains("mesh.height = 3") && Contains("3.5 mm thick together") && Contains("layer[1].thickness = 1.5") &&
                 Contains("mesh.height >= 3.5"));
  CHECK_THAT(error_of(kBase + "[[layer]]\nthickness = 0.5\nyield_profile = [[0.0, 900.0]]\n"),
             Contains("layer[0].yield_profile") && Contains("given once, in [material]"));
  CHECK_THAT(error_of(kBase + "yield_profile = [[0.0, 1600.0], [1.0, 1200.0], [0.8, 800.0]]\n"),
             Contains("material.yield_profile") && Contains("yield_profile[2]: depth 0.8 mm after depth 1 mm") &&
                 Contains("strictly increasing depths"));
  CHECK_THAT(error_of(kBase + "yield_profile = [[0.0, 1600.0], [1.0]]\n"),
             Contains("material.yield_profile") && Contains("expected [[depth, yield_stress], ...]"));
  CHECK_THAT(error_of("[mesh]\n[material]\nE = 2.1e5\nyield_profile = [[0.0, 1600.0]]\n"),
             Contains("material.yield_profile") && Contains("needs a plastic material"));
  CHECK_THAT(error_of(kBase + "[[layer]]\nthickness = 0.5\ndensity = 0.0\n[dynamics]\nstrip_inertia = true\n"),
             Contains("dynamics.strip_inertia = true") && Contains("layer[0].density = 0"));
  CHECK_THAT(error_of("[mesh]\nfollow_layers = 1\n[material]\nE = 2.1e5\n"), Contains("mesh.follow_layers = 1"));
}

TEST_CASE("follow_layers: the layers' boundaries become grid lines of the mesh", "[io][scene][layers]") {
  Scene s = parse_scene(kBase + "[[layer]]\nthickness = 0.35\n", "layers.toml");
  CHECK(s.strip_mesh_spec().pinned_y.empty());
  s.mesh_follows_layers = true;
  CHECK(s.strip_mesh_spec().pinned_y == std::vector<Real>{3.0 - 0.35});
}
