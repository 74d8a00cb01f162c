#pragma once
// One increment as both contact backends see it: the strip's
// incremental potential over the free dofs, the contact candidates with their start-of-step
// positions, and the roller's motion over the increment. Backends know nothing about elements
// or time; this class knows nothing about how the increment is solved.
//
// Contact kinematics for candidate i with increment u_i (x_i = x_i^n + u_i, c = c^{n+1}):
//   gap      g_i(u) = |x_i - c| - R            (exact circle; g >= 0 admissible)
//   normal   n_i = (x_i - c) / |x_i - c|       (from the roller centre to the node)
//   tangent  t_i = (-n_y, n_x) of the normal at the predictor, held fixed in the increment
//   slip     s_i(u) = t_i . (u_i - dc) - R dphi   (relative tangential motion of the node against
//            the roller's surface material point; the roller surface moves R dphi along t)
// Forces on the strip node: F_N n_i + F_T t_i with F_N >= 0 (compression) and |F_T| <= mu F_N.
//
// An elastic roller (attach_rim) adds the displacements w of its rim arc as unknowns with the
// energy 1/2 w^T K w (contact/elastic_roller.hpp). Each candidate touches the rim at a point
// sampled, like its tangent, once an increment (RimSample): the gap drops by the rim's radial
// displacement there and the slip by the rim material's tangential displacement increment, both
// affine in w (docs/model.md, Elastic roller).
#include <optional>
#include <vector>

#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/elastic_roller.hpp"
#include "roller/contact/roller.hpp"

namespace roller {

// Where a candidate touches an elastic roller's rim, fixed within the increment: the rim's
// displacements sampled with the node's dual shape function (rim_sample; empty: no rim there, the
// roller rigid), as the coefficients that make
//   gap  += sum_k gap_weight[k] . w_node[k]       (the rim moved radially)
//   slip += sum_k slip_weight[k] . w_node[k] + slip_start
// slip_start: the tangential displacement at the start of the increment of the rim material that
// now lies there (it came from an angle dphi behind as the roller turned).
struct RimSample {
  std::vector<Index> node;
  std::vector<Vec2> gap_weight, slip_weight;
  Real slip_start = 0.0;
  bool on_rim() const { return !node.empty(); }
};

struct ContactCandidate {
  Index node = 0;
  Index free_dof[2] = {-1, -1};    // free index of the x and y dof, -1 when prescribed
  Vec2 position = Vec2::Zero();    // x^n, start of the increment
  Vec2 prescribed = Vec2::Zero();  // increment of prescribed components (0 for free components)
  Vec2 tangent = Vec2::Zero();     // t_i, fixed within the increment
  Real tributary_length = 0.0;     // surface length [mm] that node i represents (for pressures)
  Real element_size = 0.0;         // depth of the surface element under node i [mm] (penalty scale)
  Real tangential_force = 0.0;     // committed F_T^n of the previous increment (penalty history)
  Real normal_force_guess = 0.0;   // F_N of the previous increment / fixed-point pass (friction
                                   // threshold mu F_N for Tresca-type inner problems)
  RimSample rim;                   // where it touches an elastic roller's rim (attach_rim)
};

struct RollerMotion {
  Real radius = 0.0;
  RollerPose start;
  RollerPose end;
  Real friction = 0.0;  // Coulomb coefficient mu
  Vec2 dc() const { return end.centre - start.centre; }
  Real dphi() const { return end.angle - start.angle; }
};

// The force of the roller on a strip node: F_N along the normal plus F_T along the tangent.
inline Vec2 contact_force(Real normal_force, Real tangential_force, const Vec2& normal, const Vec2& tangent) {
  return normal_force * normal + tangential_force * tangent;
}

// A roller free to move vertically, as an unknown of the increment: its centre is the motion's
// end centre plus w e_y, and w carries the potential P(w) = stiffness w^2/2 + load w, so that
// P'(w) = F_y (the strip's force on the roller) at equilibrium: for the suspension's Houbolt
// equation k_eff w + h = F_y stiffness k_eff and load h (docs/model.md, "Roller suspension"), for a
// prescribed vertical force F stiffness 0 and load F. A backend that solves for w (IpoptBackend's
// condensed formulation) finds the strip and the roller in equilibrium together; the others are
// given the roller's position.
struct RollerPotential {
  Real stiffness = 0.0;
  Real load = 0.0;
  Real energy(Real w) const { return 0.5 * stiffness * w * w + load * w; }
  Real derivative(Real w) const { return stiffness * w + load; }
};

class IncrementProblem {
 public:
  IncrementProblem(IncrementEnergy& strip, std::vector<ContactCandidate> candidates, RollerMotion roller,
                   Real youngs_modulus, Real poisson_ratio);

  // Strip part: Pi(x) over the free dofs and the force scale at x, its gradient and Hessian
  // (full symmetric storage), or why the strip cannot take x.
  Index n_free() const { return n_free_; }
  Expected<ObjectiveValue> strip_energy(const VecX& x, VecX* gradient, SparseMatrix* hessian) {
    return strip_.evaluate(x, gradient, hessian);
  }
  // The strip's potential itself, as Newton's objective (the problem without contact candidates).
  IncrementEnergy& strip() { return strip_; }
  VecX full_increment(const VecX& x) const { return strip_.full_increment(x); }
  StripModel& strip_model() { return strip_.model(); }
  // The strip's tangent is the same matrix at every x (StripModel::tangent_is_constant).
  bool strip_tangent_is_constant() const { return strip_.model().tangent_is_constant(); }

  const std::vector<ContactCandidate>& candidates() const { return candidates_; }
  std::vector<ContactCandidate>& candidates() { return candidates_; }
  const RollerMotion& roller() const { return roller_; }

  // The roller's vertical position as an unknown (RollerPotential): w0 is where the motion's end
  // centre puts it now. move_roller sets w, and with it the centre every kinematic function uses.
  void free_roller(const RollerPotential& spring, Real w0) {
    potential_ = spring;
    w_ = w0;
  }
  const std::optional<RollerPotential>& roller_potential() const { return potential_; }
  Real roller_offset() const { return w_; }
  void move_roller(Real w) {
    roller_.end.centre.y() += w - w_;
    w_ = w;
  }
  // An elastic roller: its rim's condensed stiffness (kept by the caller) and the rim displacements
  // the increment starts from; samples every candidate's point on the rim (RimSample) from its
  // start position relative to the end centre. Candidates beyond the arc keep no sample.
  // `start` null: the rim at rest.
  void attach_rim(const RimStiffness& rim, const VecX* start);
  const RimStiffness* rim() const { return rim_; }
  Index n_rim() const { return rim_ ? 2 * static_cast<Index>(rim_->positions.size()) : 0; }
  // The rim displacements every kinematic function below uses (a backend sets its iterate's).
  const VecX& rim_displacement() const { return rim_w_; }
  const VecX& rim_start() const { return rim_start_; }  // where the increment's rim starts
  void set_rim_displacement(const VecX& w) { rim_w_ = w; }
  // The rim's shares of a candidate's gap and slip at rim displacements w (2 n_rim values).
  Real rim_gap_shift(const ContactCandidate& c, const Real* w) const;
  Real rim_slip_shift(const ContactCandidate& c, const Real* w) const;

  Real youngs_modulus() const { return youngs_modulus_; }
  Real plane_strain_modulus() const;  // E* = E / (1 - nu^2)

  // Kinematics of candidate c for a node increment u (see the header comment): the one place
  // where gap, normal, slip and the gap's curvature are computed, and so the one place that knows
  // the roller is a rigid circle (docs/architecture.md); the NLP formulations map their variables to u.
  Vec2 from_centre(const ContactCandidate& c, const Vec2& u) const { return (c.position + u) - roller_.end.centre; }
  // With an elastic roller: at the rim displacements w (gap_at, slip_at) or at those set
  // (set_rim_displacement).
  Real gap_at(const ContactCandidate& c, const Vec2& u, const Real* w) const {
    return from_centre(c, u).norm() - roller_.radius + rim_gap_shift(c, w);
  }
  Real slip_at(const ContactCandidate& c, const Vec2& u, const Real* w) const {
    return c.tangent.dot(u - roller_.dc()) - roller_.radius * roller_.dphi() + rim_slip_shift(c, w);
  }
  Real gap_for(const ContactCandidate& c, const Vec2& u) const { return gap_at(c, u, rim_w_.data()); }
  Vec2 normal_for(const ContactCandidate& c, const Vec2& u) const { return from_centre(c, u).normalized(); }
  Real slip_for(const ContactCandidate& c, const Vec2& u) const { return slip_at(c, u, rim_w_.data()); }
  // `weight` times the gap's curvature d2g/du2, (I - n n^T) / |x - c| for the circle: the Hessian
  // a contact force of that size adds (penalty, the NLP's contact rows).
  Mat2 gap_curvature(const ContactCandidate& c, const Vec2& u, Real weight) const {
    const Vec2 d = from_centre(c, u);
    const Real rho = d.norm();
    const Vec2 n = d / rho;
    return weight * (Mat2::Identity() - n * n.transpose()) / rho;
  }

  // The same at free values x.
  Vec2 increment(const ContactCandidate& c, const VecX& x) const;
  Vec2 position(const ContactCandidate& c, const VecX& x) const { return c.position + increment(c, x); }
  Real gap(const ContactCandidate& c, const VecX& x) const { return gap_for(c, increment(c, x)); }
  Vec2 normal(const ContactCandidate& c, const VecX& x) const { return normal_for(c, increment(c, x)); }
  Real slip(const ContactCandidate& c, const VecX& x) const { return slip_for(c, increment(c, x)); }

 private:
  IncrementEnergy& strip_;
  std::vector<ContactCandidate> candidates_;
  RollerMotion roller_;
  std::optional<RollerPotential> potential_;
  Real w_ = 0.0;  // the suspended roller's offset w (its centre: roller_.end.centre)
  const RimStiffness* rim_ = nullptr;
  VecX rim_w_, rim_start_;
  Real youngs_modulus_;
  Real poisson_ratio_;
  Index n_free_;
};

}  // namespace roller
