#include "roller_disc_fields.hpp"

#include <set>
#include <string>

#include "roller/contact/elastic_roller.hpp"
#include "roller/core/error.hpp"
#include "roller/io/contact_settings.hpp"

namespace roller {

namespace {

// The scene's disc, meshed as the contact's rim stiffness meshes it.
RollerDiscMesh disc_of(const Scene& scene, const Mesh& strip_mesh) {
  return roller_disc_mesh(elastic_roller_spec(scene), elastic_rim_arc(scene, strip_mesh));
}

}  // namespace

RollerDiscFields::RollerDiscFields(const Scene& scene, const Mesh& strip_mesh)
    : RollerDiscFields(disc_of(scene, strip_mesh), scene) {}

RollerDiscFields::RollerDiscFields(const RollerDiscMesh& disc, const Scene& scene)
    : mesh_(std::make_shared<const Mesh>(disc.mesh)),
      arc_(disc.arc),
      radius_(scene.roller->radius),
      model_(roller_disc_model(elastic_roller_spec(scene), disc)),
      solver_(MumpsSolver::Symmetry::Symmetric) {
  for (Index a : arc_) arc_positions_.push_back(disc.mesh.nodes[a]);
  SparseMatrix k;
  model_->evaluate(VecX::Zero(model_->n_dofs()), nullptr, &k);
  if (!solver_.factorize(k)) throw NumericalError("elastic roller: the disc's stiffness (for its output) is singular");
}

std::shared_ptr<const RollerBody> RollerDiscFields::at(const std::vector<NodeContactRecord>& contact,
                                                       const Vec2& centre) {
  // The strip's forces on the rim, spread with the contact rows' weights (rim_sample).
  const DofMap& dofs = model_->dof_map();
  VecX load = VecX::Zero(dofs.n_free());
  VecX nodal = VecX::Zero(model_->n_dofs());
  for (const NodeContactRecord& c : contact) {
    if (c.force.isZero()) continue;
    const Real angle = rim_angle(c.position - centre);
    for (const RimWeight& w : rim_sample(arc_positions_, angle, c.tributary_length / radius_))
      for (int a = 0; a < 2; ++a) {
        const Index dof = 2 * arc_[w.node] + a;
        nodal(dof) -= w.weight * c.force(a);
        load(dofs.free_index(dof)) -= w.weight * c.force(a);
      }
  }
  VecX u = VecX::Zero(model_->n_dofs());
  dofs.scatter_free(solver_.solve(load), u);
  const VecX step = u - model_->total_displacement();
  model_->commit(step);

  auto body = std::make_shared<RollerBody>();
  body->mesh = mesh_;
  for (const Vec2& p : mesh_->nodes) body->points.push_back(centre + p);
  const StripFields f = strip_fields(*model_, step);
  // The elastic disc's displacement and element stresses: the disc is finer than the strip (its
  // rings run round it), so fewer fields keep its file near the strip's (ParaView's Cell Data to
  // Point Data smooths the stresses).
  static const std::set<std::string> kept{"displacement", "stress", "von_mises"};
  for (const VtuField& v : f.point_data)
    if (kept.count(v.name)) body->point_data.push_back(v);
  for (const VtuField& v : f.cell_data)
    if (kept.count(v.name)) body->cell_data.push_back(v);
  VtuField force;
  force.name = "contact_force";  // the strip's on the rim nodes [N per mm of roller length]
  force.n_components = 3;
  force.values.assign(3 * mesh_->nodes.size(), 0.0);
  for (Index a = 0; a < static_cast<Index>(mesh_->nodes.size()); ++a)
    for (int c = 0; c < 2; ++c) force.values[3 * a + c] = nodal(2 * a + c);
  body->point_data.push_back(std::move(force));
  return body;
}

}  // namespace roller
