#include "roller_contact_correction.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "roller/assembly/element_materials.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/contact/condensed_contact.hpp"
#include "roller/core/error.hpp"
#include "roller/io/load_program.hpp"
#include "roller/io/scene_strip.hpp"
#include "roller/steady/steady_load.hpp"

namespace roller {

namespace {

// The roller's contact condensed onto the scene's contact candidates within `window` of centre_x,
// with the strip's linear elastic stiffness K_e.
CondensedContact condensed_contact(const Scene& scene, const Mesh& mesh, const DofMap& dofs, Real centre_x,
                                   Real window) {
  std::vector<Index> nodes;
  for (const Index a : contact_candidate_nodes(scene, mesh))
    if (std::abs(mesh.nodes[a].x() - centre_x) <= window && !dofs.is_constrained(2 * a) &&
        !dofs.is_constrained(2 * a + 1))
      nodes.push_back(a);
  std::sort(nodes.begin(), nodes.end(), [&](Index a, Index b) { return mesh.nodes[a].x() < mesh.nodes[b].x(); });
  if (nodes.size() < 3)
    throw NumericalError(fmt::format(
        "the roller's contact: {} free surface nodes within {:.4g} mm of x = {:.6g}: the mesh is too coarse there",
        nodes.size(), window, centre_x));
  std::vector<Vec2> positions;
  for (const Index a : nodes) positions.push_back(mesh.nodes[a]);
  StripModel elastic(mesh, linear_elastic(assign_materials(mesh, scene.strip_material())), scene.element);
  elastic.set_dof_map(dofs);
  SparseMatrix k;
  elastic.evaluate(VecX::Zero(mesh.n_dofs()), nullptr, &k);
  return CondensedContact(k, dofs, std::move(nodes), std::move(positions), centre_x, scene.roller->radius,
                          scene.newton.linear);
}

// The roller's contact solved with the elastic stiffness: K_e du = r + f_c with the gaps to the
// roller closed at u + du and the roller carrying the travel force, its height an unknown, by the
// contact condensed onto the top nodes under the roller (contact/condensed_contact.hpp). K_e is
// factorised once a pass. A traction (q = mu p when the travel slides, Carter's under fx) rides on
// the contact's normal forces of the iteration before as a load beside r: the contact stays
// frictionless, and at the fixed point the traction is the converged contact's.
class RollerContactCorrection final : public RollerCorrection {
 public:
  RollerContactCorrection(const Scene& scene, const Mesh& mesh, const SteadyLoad& steady, Real centre_x, Real force)
      : steady_(steady),
        hertz_(hertz_line_contact(force, scene.roller->radius, scene.contact_modulus())),
        centre_x_(centre_x),
        dofs_(LoadProgram(scene, mesh).dof_map()),
        contact_(condensed_contact(scene, mesh, dofs_, centre_x, kWindow * hertz_.half_width)) {}
  Result correct(const VecX& u, const std::vector<MaterialState>& /*states*/, const VecX& r) override {
    if (traction_.size() != u.size()) traction_ = VecX::Zero(u.size());
    CondensedContact::Press pressed = contact_.solve(u, r + dofs_.gather_free(traction_), hertz_.load);
    if (pressed.du.size() == 0) return {VecX(), VecX(), pressed.message};
    Result out;
    out.du = std::move(pressed.du);
    out.load = traction_;
    for (const NodeContactRecord& c : pressed.contact) out.load.segment<2>(2 * c.node) += c.force;
    records_ = std::move(pressed.contact);
    pose_ = pressed.pose;
    if (steady_.traction != 0.0) {  // the next iteration's traction, from this contact
      traction_.setZero();
      const std::vector<Real> fx = traction_forces(steady_, records_, hertz_, centre_x_);
      for (std::size_t i = 0; i < records_.size(); ++i) {
        traction_[2 * records_[i].node] += fx[i];
        records_[i].force.x() += fx[i];
        records_[i].contact.tangential_force = steady_.travel_sign * fx[i];
        if (records_[i].contact.status != ContactStatus::Open)
          records_[i].contact.status =
              traction_slips(steady_, hertz_, steady_.travel_sign * (records_[i].position.x() - centre_x_))
                  ? ContactStatus::Slip
                  : ContactStatus::Stick;
      }
    }
    return out;
  }
  // With the traction on its normal forces.
  const std::vector<NodeContactRecord>& contact() const override { return records_; }
  RollerPose pose() const override { return pose_; }

 private:
  // The nodes condensed reach this many Hertz half-widths either side of the contact's centre:
  // the contact's own half-width stays near a (0.996 a at p0/k = 4.5, docs/benchmarks-log.md), and
  // one that reaches the last node stops the pass with a message.
  static constexpr Real kWindow = 4.0;
  SteadyLoad steady_;
  HertzSolution hertz_;
  Real centre_x_ = 0.0;
  DofMap dofs_;
  CondensedContact contact_;
  VecX traction_;                           // all dofs: the traction of the last contact
  std::vector<NodeContactRecord> records_;  // the last contact, its traction added
  RollerPose pose_;
};

}  // namespace

std::unique_ptr<RollerCorrection> make_roller_contact_correction(const Scene& scene, const Mesh& mesh,
                                                                 const SteadyLoad& steady, Real centre_x, Real force) {
  return std::make_unique<RollerContactCorrection>(scene, mesh, steady, centre_x, force);
}

}  // namespace roller
