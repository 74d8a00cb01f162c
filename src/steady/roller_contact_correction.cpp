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

// The roller's load in the steady pass: its force, and its creep or, rolling under a horizontal
// force, the force that sets the creep; InputError for a force the contact cannot carry rolling.
CondensedLoad condensed_load(const SteadyLoad& steady, Real force) {
  CondensedLoad load;
  load.force = force;
  load.friction = steady.friction;
  load.travel_sign = steady.travel_sign;
  load.creep = steady.creep;
  if (steady.shape == TractionShape::Carter && steady.friction > 0.0) {
    if (std::abs(steady.traction) >= steady.friction)
      throw InputError(fmt::format(
          "{}: |q/p| = |fx|/fy = {:.6g} is mu = {}: on the roller's contact no creep carries it rolling; give the "
          "segment slip = 1 (the roller slides) instead of the force",
          steady.segment, std::abs(steady.traction), steady.friction));
    load.creep = 0.0;  // the start of the unknown creep
    load.horizontal_force = -steady.travel_sign * steady.traction * force;
  }
  return load;
}

// The roller's contact solved with the elastic stiffness: K_e du = r + f_c with the gaps to the
// roller closed at u + du, Coulomb's law between them on the steady slip, the roller carrying the
// travel force (its height an unknown) and, under a horizontal force, that force (its creep an
// unknown), by the contact condensed onto the top nodes under the roller
// (contact/condensed_contact.hpp). K_e is factorised once a pass.
class RollerContactCorrection final : public RollerCorrection {
 public:
  RollerContactCorrection(const Scene& scene, const Mesh& mesh, const SteadyLoad& steady, Real centre_x, Real force)
      : load_(condensed_load(steady, force)),
        centre_x_(centre_x),
        radius_(scene.roller->radius),
        dofs_(LoadProgram(scene, mesh).dof_map()),
        contact_(condensed_contact(scene, mesh, dofs_, centre_x, window(scene, force))) {}
  Result correct(const VecX& u, const std::vector<MaterialState>& /*states*/, const VecX& r) override {
    CondensedContact& contact = on_tangent_ ? *on_tangent_ : contact_;
    CondensedContact::Press pressed = contact.solve(u, r, load_);
    if (pressed.du.size() == 0) return {VecX(), VecX(), pressed.message};
    Result out;
    out.du = std::move(pressed.du);
    out.load = VecX::Zero(u.size());
    for (const NodeContactRecord& c : pressed.contact) out.load.segment<2>(2 * c.node) += c.force;
    records_ = std::move(pressed.contact);
    pose_ = pressed.pose;
    creep_ = pressed.creep;
    return out;
  }
  // The contact condensed with the steady Jacobian: each Newton step finds its own contact.
  bool take_operator(const SparseMatrix* tangent, const LinearSolverOptions& options) override {
    const CondensedContact& last = on_tangent_ ? *on_tangent_ : contact_;
    if (!tangent) {
      contact_.start_from(last);
      on_tangent_.reset();
      return false;
    }
    try {
      auto next = std::make_unique<CondensedContact>(*tangent, dofs_, last.nodes(), last.positions(), centre_x_,
                                                     radius_, options, MumpsSolver::Symmetry::General);
      next->start_from(last);
      on_tangent_ = std::move(next);
      return true;
    } catch (const NumericalError&) {  // a singular J: the caller's factorisation says so
      on_tangent_.reset();
      return false;
    }
  }
  const std::vector<NodeContactRecord>& contact() const override { return records_; }
  RollerPose pose() const override { return pose_; }
  Real creep() const override { return creep_; }

 private:
  // The nodes condensed reach this many Hertz half-widths either side of the contact's centre:
  // the contact's own half-width stays near a (0.996 a at p0/k = 4.5, docs/benchmarks-log.md), and
  // one that reaches the last node stops the pass with a message.
  static Real window(const Scene& scene, Real force) {
    return 4.0 * hertz_line_contact(force, scene.roller->radius, scene.contact_modulus()).half_width;
  }
  CondensedLoad load_;
  Real centre_x_ = 0.0, radius_ = 0.0;
  DofMap dofs_;
  CondensedContact contact_;                      // with K_e, factorised once a pass
  std::unique_ptr<CondensedContact> on_tangent_;  // with the steady Jacobian, while it is the operator
  std::vector<NodeContactRecord> records_;        // the last contact
  RollerPose pose_;
  Real creep_ = 0.0;
};

}  // namespace

std::unique_ptr<RollerCorrection> make_roller_contact_correction(const Scene& scene, const Mesh& mesh,
                                                                 const SteadyLoad& steady, Real centre_x, Real force) {
  return std::make_unique<RollerContactCorrection>(scene, mesh, steady, centre_x, force);
}

}  // namespace roller
