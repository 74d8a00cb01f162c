#include "layer_keys.hpp"

#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

namespace roller {

namespace {

SceneKey make_key(const std::string& table, const std::string& name, const std::string& type,
                  const std::string& default_text, const std::string& range, const std::string& doc) {
  SceneKey k;
  k.table = table;
  k.name = name;
  k.type = type;
  k.default_text = default_text;
  k.range = range;
  k.doc = doc;
  return k;
}

// [[depth, sigma_y], ...]: depth from the top surface [mm], the initial yield stress there [MPa].
void read_yield_profile(TomlSection& s, Scene& scene, std::size_t) {
  const char* key = "yield_profile";
  const toml::node* n = s.node(key);
  if (!n) return;
  const std::string shape = "expected [[depth, yield_stress], ...]: depths [mm] from the top surface, increasing";
  const toml::array* rows = n->as_array();
  if (!rows || rows->empty()) s.fail(key, shape);
  YieldProfile profile;
  for (const toml::node& row : *rows) {
    const toml::array* pair = row.as_array();
    if (!pair || pair->size() != 2) s.fail(key, shape);
    Real v[2];
    for (std::size_t j = 0; j < 2; ++j) {
      const toml::node& x = *pair->get(j);
      if (const auto d = x.value_exact<double>())
        v[j] = *d;
      else if (const auto i = x.value_exact<int64_t>())
        v[j] = static_cast<Real>(*i);
      else
        s.fail(key, shape);
    }
    profile.points.emplace_back(v[0], v[1]);
  }
  std::string why;
  if (!profile.is_valid(&why)) s.fail(key, why);
  if (!scene.material.plastic)
    s.fail(key,
           "a yield profile needs a plastic material: give material.yield_stress too (the nominal yield stress of "
           "p0_over_k; the profile sets each element's initial yield stress by depth)");
  scene.yield_profile = std::move(profile);
}

void write_yield_profile(toml::table& t, const Scene& scene, std::size_t) {
  if (scene.yield_profile.empty()) return;
  toml::array rows;
  for (const auto& [depth, sigma] : scene.yield_profile.points) rows.push_back(toml::array{depth, sigma});
  t.insert("yield_profile", std::move(rows));
}

// Puts layer i's material where the [material] keys read and write it, for the guard's life.
class LayerAsMaterial {
 public:
  LayerAsMaterial(Scene& scene, std::size_t i) : scene_(scene), i_(i) { swap(); }
  ~LayerAsMaterial() { swap(); }
  LayerAsMaterial(const LayerAsMaterial&) = delete;
  LayerAsMaterial& operator=(const LayerAsMaterial&) = delete;

 private:
  void swap() { std::swap(scene_.material, scene_.layers[i_].material); }
  Scene& scene_;
  std::size_t i_;
};

// A [material] key as a key of [[layer]]: read into the layer's copy of [material] only when the
// block gives it (absent keys keep [material]'s value); written from the layer's material.
SceneKey layer_twin(const SceneKey& m) {
  SceneKey k = m;
  k.table = "layer";
  k.default_text = "[material]'s";
  k.read = [read = m.read, name = m.name](TomlSection& s, Scene& scene, std::size_t i) {
    if (!s.has(name)) return;
    LayerAsMaterial as_material(scene, i);
    read(s, scene, 0);
  };
  k.write = [write = m.write, name = m.name](toml::table& t, const Scene& scene, std::size_t i) {
    const MaterialLayer& layer = scene.layers[i];
    // A layer that follows the profile took [material]'s yield_stress, which it must not repeat.
    if (name == "yield_stress" && layer.follows_profile && !scene.yield_profile.empty()) return;
    Scene copy = scene;
    copy.material = layer.material;
    write(t, copy, 0);
  };
  return k;
}

}  // namespace

void add_layer_keys(std::vector<SceneKey>& keys) {
  std::vector<SceneKey> twins;
  for (const SceneKey& k : keys)
    if (k.table == "material") twins.push_back(layer_twin(k));

  SceneKey profile = make_key("material", "yield_profile", "array of [depth, sigma_y]", "absent", "depths increasing",
                              "initial yield stress by depth from the top surface [mm, MPa]: linear in between, "
                              "constant beyond the ends; needs yield_stress");
  profile.read = read_yield_profile;
  profile.write = write_yield_profile;
  keys.push_back(std::move(profile));

  SceneKey follow = make_key("mesh", "follow_layers", "bool", "false", "",
                             "put horizontal grid lines on the layers' boundaries (moving the nearest line, or adding "
                             "one); otherwise an element takes its centroid's layer");
  follow.read = [](TomlSection& s, Scene& scene, std::size_t) {
    if (const auto v = s.boolean("follow_layers")) scene.mesh_follows_layers = *v;
  };
  follow.write = [](toml::table& t, const Scene& scene, std::size_t) {
    t.insert("follow_layers", scene.mesh_follows_layers);
  };
  keys.push_back(std::move(follow));

  SceneKey thickness = make_key("layer", "thickness", "number", "required", "1e-06 <= thickness <= 1e+09",
                                "thickness of the band [mm]; the bands lie from the top surface down, in order");
  thickness.read = [](TomlSection& s, Scene& scene, std::size_t i) {
    const auto t = s.real("thickness");
    if (!t) s.fail("thickness", "each [[layer]] needs its thickness [mm] > 0 (the bands lie from the top down)");
    // The bounds of every length of a scene (io/scene_keys.cpp): a thinner band is below round-off
    // of the strip's coordinates.
    if (!(*t >= 1e-6 && *t <= 1e9)) s.fail("thickness", "expected a thickness of 1e-6 to 1e9 mm");
    scene.layers[i].thickness = *t;
  };
  thickness.write = [](toml::table& t, const Scene& scene, std::size_t i) {
    t.insert("thickness", scene.layers[i].thickness);
  };
  keys.push_back(std::move(thickness));
  for (SceneKey& k : twins) keys.push_back(std::move(k));
}

void declare_layer_table(SceneTable& table) {
  table.enter = [](TomlSection& s, Scene& scene) {
    if (s.has("yield_profile"))
      s.fail("yield_profile",
             "a yield profile is given once, in [material] (depths from the top surface); a layer follows it unless "
             "it gives its own yield_stress");
    MaterialLayer layer;
    layer.material = scene.material;  // a copy of [material], the block's keys over it
    scene.layers.push_back(layer);
  };
  table.check = [](TomlSection& s, Scene& scene, std::size_t i) {
    MaterialLayer& layer = scene.layers[i];
    layer.follows_profile = !s.has("yield_stress");
    std::string why;
    if (!layer.material.is_valid(&why))
      s.fail_invalid(why, {{"youngs_modulus", "E"},
                           {"poisson_ratio", "nu"},
                           {"tangent_modulus", s.has("kappa") ? "kappa" : "tangent_modulus"},
                           {"n_substeps", "substeps"}});
  };
  table.count = [](const Scene& s) { return s.layers.size(); };
}

void check_layers_fit(TomlSection& mesh_section, const Scene& scene) {
  Real sum = 0.0;
  std::string parts;
  for (std::size_t i = 0; i < scene.layers.size(); ++i) {
    sum += scene.layers[i].thickness;
    parts += fmt::format("{}layer[{}].thickness = {:g}", i ? ", " : "", i, scene.layers[i].thickness);
  }
  if (sum > scene.mesh.height * (1.0 + 1e-12))
    mesh_section.fail("height",
                      fmt::format("the [[layer]] blocks are {:g} mm thick together ({}): expected a strip at least as "
                                  "high as its layers (mesh.height >= {:g} mm, or thinner layers)",
                                  sum, parts, sum));
}

void check_layers_have_density(TomlSection& dynamics_section, const Scene& scene) {
  if (!scene.dynamics.strip_inertia) return;
  for (std::size_t i = 0; i < scene.layers.size(); ++i)
    if (!(scene.layers[i].material.density > 0.0))
      dynamics_section.fail("strip_inertia", fmt::format("strip inertia needs every layer's density > 0 [t/mm^3]: "
                                                         "layer[{}].density = {}; steel: 7.8e-9",
                                                         i, scene.layers[i].material.density));
}

}  // namespace roller
