#include "roller/io/scene.hpp"

namespace roller {

int Scene::total_steps() const {
  return passes.method == PassMethod::Stationary ? passes.count : steps.n_steps * passes.count;
}

Real Scene::contact_modulus() const {
  const Real strip = strip_material().surface().plane_strain_modulus();
  if (!roller || !roller->elastic()) return strip;
  return 1.0 / (1.0 / strip + 1.0 / roller->plane_strain_modulus());
}

StripMeshSpec Scene::strip_mesh_spec() const {
  StripMeshSpec spec = mesh;
  if (mesh_follows_layers)
    for (const Real depth : strip_material().boundaries()) spec.pinned_y.push_back(mesh.height - depth);
  return spec;
}

}  // namespace roller
