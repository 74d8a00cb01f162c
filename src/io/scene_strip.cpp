#include "roller/io/scene_strip.hpp"

#include <utility>

#include "roller/io/scene_loader.hpp"
#include "roller/io/scene_warnings.hpp"
#include "roller/solver/blas_buffers.hpp"
#include "roller/solver/memory_estimate.hpp"

namespace roller {

namespace {

// The mesh, once the machine is known to hold the run it starts (else a SystemError with advice).
Mesh make_mesh_that_fits(const Scene& scene) {
  // The condensed ipopt solve keeps a constant tangent's factors for the run.
  const bool held = scene.roller && scene.contact.backend == ContactBackendKind::Ipopt &&
                    scene.contact.ipopt.formulation == IpoptFormulation::Condensed &&
                    tangent_is_constant(scene.element.kinematics, scene.strip_material().any_plastic());
  if (const auto available = available_memory()) {
    const HeldFactors factors = scene.passes.method == PassMethod::Stationary ? HeldFactors::SteadyJacobian
                                : held                                        ? HeldFactors::WholeRun
                                                                              : HeldFactors::PerIncrement;
    check_run_memory(scene.strip_mesh_spec(), scene.newton.linear, *available, factors);
    if (available->address_space_limit) map_blas_buffers();
  }
  return make_strip_mesh(scene.strip_mesh_spec());
}

}  // namespace

std::unique_ptr<StripModel> make_scene_strip(const Scene& scene) {
  check_load_fits_strip(scene);
  check_traction_below_friction(scene);
  Mesh mesh = make_mesh_that_fits(scene);
  ElementMaterials materials = assign_materials(mesh, scene.strip_material());
  return std::make_unique<StripModel>(std::move(mesh), std::move(materials), scene.element);
}

std::vector<Index> contact_candidate_nodes(const Scene& scene, const Mesh& mesh) {
  if (!scene.roller) return {};
  NodeSelector sel;
  sel.set_name = scene.contact.candidates;
  return resolve_nodes(sel, mesh, "contact.candidates");
}

}  // namespace roller
