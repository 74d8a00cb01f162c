#include "roller_contact_correction.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "roller/assembly/element_materials.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/contact/condensed_contact.hpp"
#include "roller/core/error.hpp"
#include "roller/io/contact_settings.hpp"
#include "roller/io/load_program.hpp"
#include "roller/io/scene_strip.hpp"
#include "roller/steady/steady_load.hpp"

namespace roller {

namespace {

// The strip's linear elastic stiffness K_e over the free dofs of `dofs`.
SparseMatrix elastic_stiffness(const Scene& scene, const Mesh& mesh, const DofMap& dofs) {
  StripModel elastic(mesh, linear_elastic(assign_materials(mesh, scene.strip_material())), scene.element);
  elastic.set_dof_map(dofs);
  SparseMatrix k;
  elastic.evaluate(VecX::Zero(mesh.n_dofs()), nullptr, &k);
  return k;
}

// The roller's contact condensed onto the scene's contact candidates within `window` of centre_x,
// with the strip's stiffness `k` (K_e).
std::unique_ptr<CondensedContact> condensed_contact(const Scene& scene, const Mesh& mesh, const DofMap& dofs,
                                                    const SparseMatrix& k, Real centre_x, Real window) {
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
  return std::make_unique<CondensedContact>(k, dofs, std::move(nodes), std::move(positions), centre_x,
                                            scene.roller->radius, scene.newton.linear);
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
    require_rollable(steady);
    load.creep = 0.0;  // the start of the unknown creep
    load.horizontal_force = -steady.travel_sign * steady.traction * force;
  }
  return load;
}

// The roller's contact solved with the elastic stiffness: K_e du = r + f_c with the gaps to the
// roller closed at u + du, Coulomb's law between them on the steady slip, the roller carrying the
// travel force (its height an unknown) and, under a horizontal force, that force (its creep an
// unknown), by the contact condensed onto the top nodes under the roller
// (contact/condensed_contact.hpp). K_e is factorised once a run. With phases, on every copy of
// the strip (assembly/phased_strip.hpp): copy k's block of the iterate under its own roller, k/P
// of an element further along the base strip; K_e is block diagonal, so each copy's contact is
// condensed on its own. Once the steady Jacobian takes over (take_operator), one contact is
// condensed with it over every copy's nodes, since J couples the copies through the lanes. The
// first copy's contact, pose and creep are the pass's.
class RollerContactCorrection final : public RollerCorrection {
 public:
  RollerContactCorrection(const Scene& scene, const Mesh& mesh, const SteadyLoad& steady, const RollerPlaces& places,
                          Real force)
      : load_(condensed_load(steady, force)),
        radius_(scene.roller->radius),
        dofs_(LoadProgram(scene, mesh).dof_map()),
        n_dofs_(mesh.n_dofs()),
        n_free_(dofs_.n_free()),
        rim_(elastic_rim(scene, mesh)) {
    const SparseMatrix k = elastic_stiffness(scene, mesh, dofs_);
    const Real window = 4.0 * hertz_line_contact(force, radius_, scene.contact_modulus()).half_width;
    for (int c = 0; c < places.phases; ++c) {
      copies_.push_back(condensed_contact(scene, mesh, dofs_, k, places.centre_x - c * places.shift, window));
      if (rim_) copies_.back()->set_roller(*rim_);
    }
  }
  Result correct(const VecX& u, const std::vector<MaterialState>& /*states*/, const VecX& r) override {
    const auto n = static_cast<Index>(copies_.size());
    ROLLER_ASSERT(u.size() == n * n_dofs_ && r.size() == n * n_free_, "the iterate of every copy");
    Result out;
    out.load = VecX::Zero(u.size());
    std::vector<NodeContactRecord> first;
    if (on_tangent_) {
      CondensedContact::Press pressed = on_tangent_->solve(u, r, load_);
      if (pressed.du.size() == 0) return {VecX(), VecX(), pressed.message};
      out.du = std::move(pressed.du);
      for (const NodeContactRecord& c : pressed.contact) {
        out.load.segment<2>(2 * c.node) += c.force;
        if (c.node < n_dofs_ / 2) first.push_back(c);  // the first copy's nodes: the strip's own
      }
      pose_ = pressed.pose;
      creep_ = pressed.creep;
    } else {
      out.du.resize(r.size());
      for (Index k = 0; k < n; ++k) {
        CondensedContact::Press pressed = copies_[static_cast<std::size_t>(k)]->solve(
            u.segment(k * n_dofs_, n_dofs_), r.segment(k * n_free_, n_free_), load_);
        if (pressed.du.size() == 0)
          return {VecX(), VecX(),
                  n == 1 ? pressed.message : fmt::format("phase {} of {}: {}", k + 1, n, pressed.message)};
        out.du.segment(k * n_free_, n_free_) = pressed.du;
        for (const NodeContactRecord& c : pressed.contact) out.load.segment<2>(k * n_dofs_ + 2 * c.node) += c.force;
        if (k > 0) continue;
        first = std::move(pressed.contact);
        pose_ = pressed.pose;
        creep_ = pressed.creep;
      }
    }
    records_ = std::move(first);
    return out;
  }
  // The contact condensed with the steady Jacobian: each Newton step finds its own contact.
  bool take_operator(const SparseMatrix* tangent, const LinearSolverOptions& options) override {
    const auto n = static_cast<int>(copies_.size());
    if (!tangent) {
      if (on_tangent_)
        for (int k = 0; k < n; ++k) copies_[static_cast<std::size_t>(k)]->start_from(*on_tangent_, k, 0);
      on_tangent_.reset();
      return false;
    }
    std::vector<CondensedPlace> places;
    for (int k = 0; k < n; ++k) {  // copy k's nodes and free dofs in the k-th blocks
      CondensedPlace p = copies_[static_cast<std::size_t>(k)]->place(0);
      for (Index& a : p.nodes) a += k * (n_dofs_ / 2);
      for (Index& i : p.unknowns) i += k * n_free_;
      places.push_back(std::move(p));
    }
    std::unique_ptr<CondensedContact> next;
    try {
      next = std::make_unique<CondensedContact>(*tangent, n * n_free_, std::move(places), radius_, options,
                                                MumpsSolver::Symmetry::General);
    } catch (const NumericalError&) {  // a singular J: the caller's factorisation says so
      take_operator(nullptr, options);
      return false;
    }
    for (int k = 0; k < n; ++k)
      next->start_from(on_tangent_ ? *on_tangent_ : *copies_[static_cast<std::size_t>(k)], on_tangent_ ? k : 0, k);
    if (rim_) next->set_roller(*rim_);
    on_tangent_ = std::move(next);
    return true;
  }
  const std::vector<NodeContactRecord>& contact() const override { return records_; }
  RollerPose pose() const override { return pose_; }
  Real creep() const override { return creep_; }
  void restart() override {
    on_tangent_.reset();
    for (const auto& c : copies_) c->restart();
    records_.clear();
    pose_ = RollerPose{};
    creep_ = 0.0;
  }

 private:
  CondensedLoad load_;
  Real radius_ = 0.0;
  DofMap dofs_;                                            // the base strip's
  Index n_dofs_, n_free_;                                  // a copy's
  std::shared_ptr<const RimStiffness> rim_;                // an elastic roller's condensed rim; null: rigid
  std::vector<std::unique_ptr<CondensedContact>> copies_;  // with K_e, factorised once a run
  std::unique_ptr<CondensedContact> on_tangent_;           // with the steady Jacobian, while it is the operator
  std::vector<NodeContactRecord> records_;                 // the first copy's last contact
  RollerPose pose_;
  Real creep_ = 0.0;
};

}  // namespace

std::unique_ptr<RollerCorrection> make_roller_contact_correction(const Scene& scene, const Mesh& mesh,
                                                                 const SteadyLoad& steady, const RollerPlaces& places,
                                                                 Real force) {
  return std::make_unique<RollerContactCorrection>(scene, mesh, steady, places, force);
}

}  // namespace roller
