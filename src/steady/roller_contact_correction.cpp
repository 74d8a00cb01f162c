#include "roller_contact_correction.hpp"

#include "roller/steady/elastic_press.hpp"
#include "roller/steady/steady_load.hpp"

namespace roller {

namespace {

// The roller's contact solved with the elastic stiffness: an elastic twin of the strip (an
// ElasticPress: the scene made linear elastic and frictionless, the roller over the contact's centre
// under the travel force), restored at every iteration to the iterate u without stress and with
// the residual r as a dead load, so that its incremental energy is 1/2 du K_e du - r.du; one
// force-controlled increment gives du and the contact forces. The twin's tangent is constant, so
// the condensed interior-point backend keeps its factors from one iteration to the next. A traction
// (q = mu p when the travel slides, Carter's under fx) rides on the contact's normal forces of the
// iteration before as a dead load beside r: the twin stays frictionless, and at the fixed point the
// traction is the converged contact's.
class RollerContactCorrection final : public RollerCorrection {
 public:
  RollerContactCorrection(const Scene& scene, const Mesh& mesh, const SteadyLoad& steady, Real centre_x, Real force)
      : steady_(steady),
        hertz_(hertz_line_contact(force, scene.roller->radius, scene.contact_modulus())),
        centre_x_(centre_x) {
    Scene twin = elastic_frictionless_scene(scene);
    twin.steps.n_steps = 1;
    twin.roller->start_centre = Vec2(centre_x, scene.mesh.height + scene.roller->radius);
    PathSegment press;
    press.first_step = press.last_step = 1;
    press.fy = force;
    press.friction = 0.0;
    twin.roller->path = {press};
    twin_ = std::make_unique<ElasticPress>(std::move(twin), mesh);
  }
  Result correct(const VecX& u, const std::vector<MaterialState>& states, const VecX& r) override {
    StripModel& strip = twin_->strip();
    strip.restore(strip.mesh().nodes, u, std::vector<MaterialState>(states.size()));
    if (traction_.size() != u.size()) traction_ = VecX::Zero(u.size());
    VecX load = VecX::Zero(u.size());
    strip.dof_map().scatter_free(r + strip.dof_map().gather_free(traction_), load);
    strip.set_dead_load(std::move(load));
    const IncrementReport inc = twin_->press(0.0, 1.0);
    if (!inc.converged()) return {VecX(), VecX(), inc.message};
    Result out;
    out.du = strip.dof_map().restrict_to_free(strip.total_displacement() - u);
    out.load = traction_;
    const std::vector<NodeContactRecord>& contact = twin_->contact();
    for (const NodeContactRecord& c : contact) out.load.segment<2>(2 * c.node) += c.force;
    contact_ = contact;
    if (steady_.traction != 0.0) {  // the next iteration's traction, from this contact
      traction_.setZero();
      const std::vector<Real> fx = traction_forces(steady_, contact, hertz_, centre_x_);
      for (std::size_t i = 0; i < contact.size(); ++i) {
        traction_[2 * contact[i].node] += fx[i];
        contact_[i].force.x() += fx[i];
        contact_[i].contact.tangential_force = steady_.travel_sign * fx[i];
      }
    }
    return out;
  }
  // With the traction on its normal forces.
  const std::vector<NodeContactRecord>& contact() const override { return contact_; }
  RollerPose pose() const override { return twin_->pose(); }

 private:
  SteadyLoad steady_;
  HertzSolution hertz_;
  Real centre_x_ = 0.0;
  VecX traction_;                           // all dofs: the traction of the last contact
  std::vector<NodeContactRecord> contact_;  // the last contact, its traction added
  std::unique_ptr<ElasticPress> twin_;
};

}  // namespace

std::unique_ptr<RollerCorrection> make_roller_contact_correction(const Scene& scene, const Mesh& mesh,
                                                                 const SteadyLoad& steady, Real centre_x, Real force) {
  return std::make_unique<RollerContactCorrection>(scene, mesh, steady, centre_x, force);
}

}  // namespace roller
