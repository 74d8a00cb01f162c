#pragma once
// An elastic roller's disc for the VTU (docs/scenes.md, Output): the disc of the contact's rim
// stiffness (contact/elastic_roller.hpp: the same mesh, the bore held) loaded by the contact's
// forces, each node's spread over its tributary arc of the rim as the contact's rows spread it.
// Linear elastic, so its displacement and stresses follow from the forces of the step alone, in
// the frame that moves with the centre without turning (the rim stiffness's frame): the same
// fields for the transient and the stationary pass.
#include <memory>
#include <vector>

#include "roller/assembly/strip_model.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/contact/elastic_roller.hpp"
#include "roller/driver/output_sink.hpp"
#include "roller/io/scene.hpp"
#include "roller/solver/sparse_solver.hpp"

namespace roller {

class RollerDiscFields {
 public:
  // `scene` has an elastic roller; `strip_mesh`: the strip's (the rim arc follows its top spacing).
  RollerDiscFields(const Scene& scene, const Mesh& strip_mesh);
  // The disc under the contact's forces (`contact`: a solved contact, the roller centred at `centre`).
  std::shared_ptr<const RollerBody> at(const std::vector<NodeContactRecord>& contact, const Vec2& centre);

 private:
  RollerDiscFields(const RollerDiscMesh& disc, const Scene& scene);

  std::shared_ptr<const Mesh> mesh_;
  std::vector<Index> arc_;           // the rim arc's nodes
  std::vector<Vec2> arc_positions_;  // about the centre
  Real radius_ = 0.0;
  std::unique_ptr<StripModel> model_;  // the disc, committed to the last fields' displacement (linear: exact)
  SparseSolver solver_;                // its stiffness on the free dofs, factorised once
};

}  // namespace roller
