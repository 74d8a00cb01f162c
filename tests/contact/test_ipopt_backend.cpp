// The Ipopt contact backend: exact derivatives of its NLP (finite differences and Ipopt's own
// derivative checker), a frictionless press (feasibility, complementarity, global and nodal
// equilibrium, the sign of the multipliers), a lifted roller, Coulomb friction through the
// fixed point on the normal force, and the mapping of Ipopt's failures to messages.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>

#include "../support/strip_spec.hpp"
#include "contact/ipopt/ipopt_testing.hpp"
#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/backend.hpp"
#include "roller/contact/backend_factory.hpp"
#include "roller/contact/contact_set.hpp"
#include "roller/contact/friction_history.hpp"
#include "roller/contact/ipopt_backend.hpp"
#include "roller/core/error.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

MaterialParams steel(Real youngs = 2.1e5) {
  MaterialParams p;
  p.youngs_modulus = youngs;
  p.poisson_ratio = 0.3;
  return p;
}

// Strip L x H of nx x ny Q4 (B-bar, finite kinematics). Bottom: u_y = 0 everywhere; u_x = 0 at
// every bottom node (`clamped`) or only at the bottom node under x = L/2.
std::unique_ptr<StripModel> make_strip(Real length, Real height, int nx, int ny, bool clamped, Real youngs = 2.1e5) {
  StripMeshSpec spec = test::strip_spec(ElementType::Q4, length, height, nx, ny);
  auto model = std::make_unique<StripModel>(make_strip_mesh(spec), steel(youngs),
                                            ElementOptions{Kinematics::Finite, Q4Formulation::BBar});
  std::vector<bool> fixed(model->n_dofs(), false);
  for (Index a : model->mesh().node_set("bottom")) {
    fixed[2 * a + 1] = true;
    if (clamped || std::abs(model->mesh().nodes[a].x() - 0.5 * length) < 1e-9) fixed[2 * a] = true;
  }
  model->set_dof_map(DofMap(fixed));
  return model;
}

// One increment of a strip under the roller: energy (no prescribed motion, no loads), candidates
// of the top edge, the problem both backends see.
struct Increment {
  Increment(StripModel& model, const RollerMotion& roller, Real reach = kInf)
      : energy(model, VecX::Zero(model.n_dofs()), VecX::Zero(model.n_dofs())),
        problem(energy,
                make_contact_candidates(model, model.mesh().node_set("top"), VecX::Zero(model.n_dofs()),
                                        VecX::Zero(model.n_dofs()), roller.end.centre, roller.radius, reach),
                roller, model.material(0).youngs_modulus, model.material(0).poisson_ratio) {}
  IncrementEnergy energy;
  IncrementProblem problem;
};

RollerMotion roller_motion(Vec2 start, Vec2 end, Real radius, Real mu, Real dphi = 0.0) {
  RollerMotion r;
  r.radius = radius;
  r.start.centre = start;
  r.end.centre = end;
  r.end.angle = dphi;
  r.friction = mu;
  return r;
}

ContactOptions ipopt_options(const std::string& friction = "split", const std::string& formulation = "condensed") {
  ContactOptions o;
  o.backend = ContactBackendKind::Ipopt;
  o.ipopt.friction = parse_enum<IpoptFriction>(friction).value();
  o.ipopt.formulation = parse_enum<IpoptFormulation>(formulation).value();
  return o;
}

// NLP solves of an increment: the full formulation solves one per fixed-point pass, the condensed
// one per pass and linearisation.
Real nlp_solves(const BackendResult& r) { return r.details.get<IpoptDetails>().nlp_solves; }

// Reactions: internal forces at the constrained dofs at the free-dof increment x.
Vec2 support_reaction(IncrementEnergy& energy, const VecX& x) {
  VecX g;
  energy.evaluate_full(x, g);
  Vec2 r = Vec2::Zero();
  for (Index d : energy.model().dof_map().constrained_dofs()) r(d % 2) += g(d);
  return r;
}

Real max_normal_force(const BackendResult& r) {
  Real m = 0.0;
  for (const auto& c : r.contact) m = std::max(m, c.normal_force);
  return m;
}

// A pressed state of a small strip (8 x 3 Q4 on 8 x 3 mm, roller R = 20 pressed 0.02 mm) with
// a generic, non-equilibrium displacement x (~1e-3 mm, so slips are of the order of the
// regularization 1e-2 mm used with it) and normal-force guesses on the candidates under the
// roller, so that friction terms exist.
struct SmallPressed {
  explicit SmallPressed(Real youngs = 2.1e5, Real mu = 0.3)
      : model(make_strip(8.0, 3.0, 8, 3, false, youngs)),
        inc(*model, roller_motion({4.0, 23.0}, {4.0, 22.98}, 20.0, mu)) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> u(-1.0, 1.0);
    x = VecX(inc.problem.n_free());
    for (Index k = 0; k < x.size(); ++k) x(k) = 2e-3 * u(rng);
    for (auto& c : inc.problem.candidates())
      if (std::abs(c.position.x() - 4.0) < 1.5)
        c.normal_force_guess = 0.05 * youngs * (1.6 - std::abs(c.position.x() - 4.0));
  }
  std::unique_ptr<StripModel> model;
  Increment inc;
  VecX x;
};

// Relative error of `exact` against a central-difference approximation of `fun` at z.
template <class Fun>
MatX central_difference(const Fun& fun, const VecX& z, Real h) {
  const VecX f0 = fun(z);
  MatX d(f0.size(), z.size());
  for (Index k = 0; k < z.size(); ++k) {
    VecX zp = z, zm = z;
    zp(k) += h;
    zm(k) -= h;
    d.col(k) = (fun(zp) - fun(zm)) / (2 * h);
  }
  return d;
}

}  // namespace

TEST_CASE("ipopt NLP: gradient, Jacobian and Lagrangian Hessian equal their finite differences", "[ipopt]") {
  // "condensed, suspended": the roller's vertical step is the last primal variable.
  const std::string formulation = GENERATE("full", "condensed", "condensed, suspended");
  const bool suspended = formulation == "condensed, suspended";
  for (const std::string friction : {"none", "split", "regularized"}) {
    SECTION(friction) {
      INFO("formulation " << formulation);
      SmallPressed s(2.1e5, friction == "none" ? 0.0 : 0.3);
      ContactOptions o = ipopt_options(friction == "regularized" ? "regularized" : "split",
                                       formulation == "full" ? "full" : "condensed");
      o.ipopt.regularization = 1e-2;  // resolvable by the difference step below
      IncrementProblem& p = s.inc.problem;
      if (suspended) p.free_roller(RollerPotential{3e4, -50.0}, 1e-3);
      const auto sizes = ipopt_testing::evaluate_nlp(p, o);
      const long n = sizes.n_variables, m = sizes.n_constraints;
      const Index n_friction = friction == "split" ? 3 : 0;  // guesses on the nodes at x = 3, 4, 5
      const Index n_primal = n - 2 * n_friction;             // free dofs, or the condensed contact dofs
      const Index n_rows = m - n_friction;
      if (formulation == "full") {
        REQUIRE(n_rows == static_cast<Index>(p.candidates().size()));
        REQUIRE(n_primal == p.n_free());
      } else {
        // The working set: the candidates near the roller (those with guesses among them), each
        // with its free dofs; a small part of the strip.
        REQUIRE(n_rows >= 3);
        REQUIRE(n_primal >= 2 * n_rows - 2 + (suspended ? 1 : 0));
        REQUIRE(n_primal < p.n_free() / 2);
      }

      // A generic point: x, positive auxiliaries, multipliers ~ contact forces (negative).
      std::mt19937 rng(11);
      std::uniform_real_distribution<Real> u(0.1, 1.0);
      VecX z(n);
      z.head(n_primal) = s.x.head(n_primal);  // the roller's step, when suspended, ~1e-3 mm as well
      for (Index k = n_primal; k < n; ++k) z(k) = 1e-3 * u(rng);
      VecX lambda(m);
      for (Index k = 0; k < m; ++k) lambda(k) = -1e3 * u(rng);
      const Real sigma = 0.7;
      const auto at_z = ipopt_testing::evaluate_nlp(p, o, z, sigma, lambda);
      const VecX& grad = at_z.grad_f;
      const VecX& g = at_z.g;
      const MatX& jac = at_z.jacobian;
      const MatX& hess = at_z.hessian;

      // Constraint values are the problem's own kinematics (increment_problem.hpp).
      if (formulation == "full") {
        const VecX xf = z.head(p.n_free());
        for (Index k = 0; k < n_rows; ++k) CHECK(g(k) == Approx(p.gap(p.candidates()[k], xf)).margin(1e-14));
        for (Index j = 0; j < n_friction; ++j) {
          const auto& c = p.candidates()[3 + j];  // friction candidates are the ones with guesses
          REQUIRE(c.normal_force_guess > 0.0);
          CHECK(g(n_rows + j) ==
                Approx(p.slip(c, xf) - z(p.n_free() + j) + z(p.n_free() + n_friction + j)).margin(1e-14));
        }
      }

      auto objective = [&](const VecX& zz) {
        return VecX::Constant(1, ipopt_testing::evaluate_nlp(p, o, zz, sigma, lambda).f);
      };
      auto constraints = [&](const VecX& zz) { return ipopt_testing::evaluate_nlp(p, o, zz, sigma, lambda).g; };
      auto lagrangian_gradient = [&](const VecX& zz) {
        const auto e = ipopt_testing::evaluate_nlp(p, o, zz, sigma, lambda);
        return VecX(sigma * e.grad_f + e.jacobian.transpose() * lambda);
      };
      const Real h = 1e-6;  // mm; the displacements are ~1e-3 mm
      const MatX grad_fd = central_difference(objective, z, h).transpose();
      const MatX jac_fd = central_difference(constraints, z, h);
      const MatX hess_fd = central_difference(lagrangian_gradient, z, h);
      INFO("friction " << friction << ": |grad| " << grad.norm() << " |H| " << hess.norm());
      CHECK((grad - grad_fd).cwiseAbs().maxCoeff() <= 1e-7 * grad.cwiseAbs().maxCoeff());
      CHECK((jac - jac_fd).cwiseAbs().maxCoeff() <= 1e-8);
      CHECK((hess - hess_fd).cwiseAbs().maxCoeff() <= 1e-7 * hess.cwiseAbs().maxCoeff());
      CHECK((hess - hess.transpose()).norm() == 0.0);

      // The check is sharp enough to see the gap curvature: dropping lambda changes the
      // Hessian by far more than the tolerance above.
      const MatX hess0 = ipopt_testing::evaluate_nlp(p, o, z, sigma, VecX::Zero(m)).hessian;
      CHECK((hess - hess0).cwiseAbs().maxCoeff() > 100 * 1e-7 * hess.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("ipopt derivative checker (second order) reports no errors, with and without friction", "[ipopt]") {
  const std::string formulation = GENERATE("full", "condensed");
  // Ipopt's checker uses forward differences with a relative tolerance floored at an absolute
  // 1 (|exact - approx| / max(|approx|, 1) < 1e-4): its truncation error h K / 2 must stay below
  // 1e-4, so the strip is soft here (E = 2.1e3: K ~ 4e3 N/mm/mm). The stiff strip is covered by
  // the central-difference test above.
  for (const std::string friction : {"none", "split", "regularized"}) {
    SECTION(friction) {
      INFO("formulation " << formulation);
      SmallPressed s(2.1e3, friction == "none" ? 0.0 : 0.3);
      ContactOptions o = ipopt_options(friction == "regularized" ? "regularized" : "split", formulation);
      o.ipopt.regularization = 1e-2;
      const std::string out = ipopt_testing::derivative_checker_output(s.inc.problem, s.x, o, 1e-8);
      INFO(out);
      CHECK(out.find("Starting derivative checker") != std::string::npos);
      CHECK(out.find("No errors detected by derivative checker.") != std::string::npos);
      CHECK(out.find("Derivative checker detected") == std::string::npos);
    }
  }
}

namespace {

// The frictionless press of the brief: 40 x 10 mm strip, 40 x 10 Q4, E = 2.1e5, nu = 0.3, bottom
// on the symmetry plane with the bottom-centre node fixed in x; roller R = 100 from touching the
// top at x = 20, pressed 0.05 mm.
constexpr Real kRadius = 100.0;
const Vec2 kTouching(20.0, 10.0 + kRadius);
const Vec2 kPressed(20.0, 10.0 + kRadius - 0.05);

}  // namespace

TEST_CASE("ipopt frictionless press: feasible, complementary, in equilibrium, F_N = -lambda", "[ipopt]") {
  const std::string formulation = GENERATE("condensed", "full");
  INFO("formulation " << formulation);
  auto model = make_strip(40.0, 10.0, 40, 10, false);
  Increment inc(*model, roller_motion(kTouching, kPressed, kRadius, 0.0));
  IpoptBackend backend(ipopt_options("split", formulation));
  const VecX x0 = VecX::Zero(inc.problem.n_free());
  const BackendResult r = backend.solve(inc.problem, x0);
  INFO(r.brief_report());
  REQUIRE(r.converged());
  REQUIRE(r.contact.size() == inc.problem.candidates().size());
  CHECK(r.details.get<IpoptDetails>().fixed_point_iterations == 1);
  CHECK(r.details.get<IpoptDetails>().nlp_variables > 0);
  if (formulation == "full") {
    CHECK(r.details.get<IpoptDetails>().nlp_variables == inc.problem.n_free());  // mu = 0: no friction variables
  } else {
    CHECK(r.details.get<IpoptDetails>().nlp_variables == r.details.get<IpoptDetails>().condensed_dofs);
    CHECK(r.details.get<IpoptDetails>().nlp_variables < 0.2 * inc.problem.n_free());  // the contact dofs only
    CHECK(r.counters.factorizations == r.details.get<IpoptDetails>().linearisations);
  }
  CHECK(r.details.get<IpoptDetails>().constraint_violation < 1e-8 * kRadius);
  CHECK(r.max_penetration < 1e-8 * kRadius);
  CHECK(r.details.get<IpoptDetails>().complementarity < ContactOptions().ipopt.tol);
  CHECK(r.residual < 1e-8);

  // Sign of the multipliers: the roller pushes the nodes under it down (F_N > 0, n_y < 0).
  const Real fmax = max_normal_force(r);
  int n_contact = 0;
  for (std::size_t i = 0; i < r.contact.size(); ++i) {
    const auto& c = inc.problem.candidates()[i];
    const auto& nc = r.contact[i];
    if (nc.status == ContactStatus::Open) continue;
    ++n_contact;
    CHECK(std::abs(nc.gap) < 1e-8 * kRadius);
    CHECK(inc.problem.normal(c, r.x).y() < 0.0);
    CHECK(nc.tangential_force == 0.0);
  }
  CHECK(n_contact >= 5);
  CHECK(n_contact <= 9);  // the geometric overlap sqrt(2 R d) = 3.2 mm spans 7 nodes
  const auto centre = std::find_if(inc.problem.candidates().begin(), inc.problem.candidates().end(),
                                   [](const ContactCandidate& c) { return std::abs(c.position.x() - 20.0) < 1e-9; });
  REQUIRE(centre != inc.problem.candidates().end());
  CHECK(r.contact[centre - inc.problem.candidates().begin()].normal_force == Approx(fmax));

  // Global equilibrium: what the roller pushes, the support carries.
  VecX grad;
  inc.problem.strip_energy(r.x, &grad, nullptr);
  Vec2 contact_force = Vec2::Zero();
  for (std::size_t i = 0; i < r.contact.size(); ++i)
    contact_force += r.contact[i].normal_force * inc.problem.normal(inc.problem.candidates()[i], r.x);
  const Vec2 reaction = support_reaction(inc.energy, r.x);
  INFO("contact force " << contact_force.transpose() << ", support reaction " << reaction.transpose());
  CHECK(contact_force.y() < 0.0);
  CHECK(std::abs(contact_force.y() + reaction.y()) <= 1e-6 * std::abs(contact_force.y()));
  CHECK(std::abs(contact_force.x() + reaction.x()) <= 1e-6 * std::abs(contact_force.y()));

  // Nodal equilibrium: the multipliers are the nodal contact forces. grad Pi = f_int - f_ext is
  // the force the strip needs from outside, which the roller supplies: grad Pi = +F_N n at
  // every candidate (Ipopt's lambda = -F_N <= 0 enters its Lagrangian as grad Pi + lambda n = 0).
  for (std::size_t i = 0; i < r.contact.size(); ++i) {
    const auto& c = inc.problem.candidates()[i];
    const Vec2 f = r.contact[i].normal_force * inc.problem.normal(c, r.x);
    for (int k = 0; k < 2; ++k)
      if (c.free_dof[k] >= 0) CHECK(std::abs(grad(c.free_dof[k]) - f(k)) <= 1e-6 * fmax);
  }
}

TEST_CASE(
    "ipopt condensed: candidates that penetrate outside the working set join it, and reach the full formulation's "
    "answer",
    "[ipopt]") {
  // The start vector sinks the strip's top 0.25 mm below the roller's end position, so that no
  // candidate is within the working set's reach there (a small fraction of the step's length
  // scale): the first linearisation sees no contact, its step lifts the strip back into the
  // roller, and the candidates found penetrating must join the set until none is left out.
  auto model = make_strip(40.0, 10.0, 40, 10, false);
  Increment inc(*model, roller_motion(kTouching, kPressed, kRadius, 0.0));
  VecX x0 = VecX::Zero(inc.problem.n_free());
  for (Index a = 0; a < model->mesh().n_nodes(); ++a) {
    const Index dof = model->dof_map().free_index(2 * a + 1);
    if (dof >= 0) x0(dof) = -0.3 * model->mesh().nodes[a].y() / 10.0;
  }
  for (const auto& c : inc.problem.candidates()) REQUIRE(inc.problem.gap(c, x0) > 0.2);
  IpoptBackend condensed(ipopt_options("split", "condensed")), full(ipopt_options("split", "full"));
  const BackendResult r = condensed.solve(inc.problem, x0);
  INFO(r.brief_report());
  REQUIRE(r.converged());
  CHECK(!r.details.get<IpoptDetails>().condensed_fallback);
  CHECK(r.details.get<IpoptDetails>().linearisations >= 3);  // none in contact, then the set grows, then the answer
  CHECK(r.details.get<IpoptDetails>().condensed_dofs >= 10);
  const BackendResult f = full.solve(inc.problem, x0);
  REQUIRE(f.converged());
  const Real fmax = max_normal_force(f);
  REQUIRE(fmax > 0.0);
  int n_contact = 0;
  for (std::size_t i = 0; i < r.contact.size(); ++i) {
    INFO("candidate " << i);
    CHECK(std::abs(r.contact[i].normal_force - f.contact[i].normal_force) <= 1e-5 * fmax);
    CHECK(r.contact[i].gap >= -1e-8 * kRadius);
    n_contact += r.contact[i].status == ContactStatus::Open ? 0 : 1;
  }
  CHECK(n_contact >= 5);
  CHECK((r.x - f.x).lpNorm<Eigen::Infinity>() <= 1e-6 * 0.05);
}

TEST_CASE("ipopt: a lifted roller gives zero contact forces and a small reach gives no contact variables", "[ipopt]") {
  auto model = make_strip(40.0, 10.0, 40, 10, false);
  const Vec2 lifted = kTouching + Vec2(0.0, 0.1);
  const std::string formulation = GENERATE("condensed", "full");
  INFO("formulation " << formulation);
  IpoptBackend backend(ipopt_options("split", formulation));
  SECTION("all candidates kept") {
    Increment inc(*model, roller_motion(kTouching, lifted, kRadius, 0.3));
    const BackendResult r = backend.solve(inc.problem, VecX::Zero(inc.problem.n_free()));
    INFO(r.brief_report());
    REQUIRE(r.converged());
    REQUIRE(r.contact.size() == 41);
    // Full: every candidate; condensed: the working set (gap within 0.05 l_step = 0.005 mm of the
    // roller), empty here: the roller ends 0.1 mm above the strip.
    if (formulation == "full")
      CHECK(r.details.get<IpoptDetails>().nlp_constraints == 41);
    else
      CHECK(r.details.get<IpoptDetails>().nlp_constraints == 0);
    // Interior-point multipliers of inactive constraints are ~ barrier / gap, not exactly 0:
    // their complementarity F_N g is at Ipopt's tolerance (scaled by F_ref = E* |dc|), which
    // makes them ~1e-9 of the forces a 0.1 mm step could produce.
    const Real f_ref = inc.problem.plane_strain_modulus() * 0.1;
    const Real tol = ContactOptions().ipopt.tol;
    for (const auto& c : r.contact) {
      CHECK(c.status == ContactStatus::Open);
      CHECK(c.normal_force * c.gap <= tol * f_ref);
      CHECK(c.normal_force <= 1e-8 * f_ref);
      CHECK(c.tangential_force == 0.0);  // no friction variables for F_N estimates ~ 0
      CHECK(c.gap >= 0.1 - 1e-12);
    }
    // The strip's response to those barrier forces (<= 1e-8 f_ref each, a few nodes): 1e-8 of the
    // step (measured 2.2e-9 mm condensed, below 1e-9 mm full).
    CHECK(r.x.lpNorm<Eigen::Infinity>() <= 1e-7 * 0.1);
  }
  SECTION("candidates beyond the reach are left out") {
    Increment inc(*model, roller_motion(kTouching, lifted, kRadius, 0.3), 0.05);
    REQUIRE(inc.problem.candidates().empty());
    const BackendResult r = backend.solve(inc.problem, VecX::Zero(inc.problem.n_free()));
    INFO(r.brief_report());
    REQUIRE(r.converged());
    CHECK(r.contact.empty());
    CHECK(r.details.get<IpoptDetails>().nlp_constraints == 0);
    CHECK(r.details.get<IpoptDetails>().nlp_variables == (formulation == "full" ? inc.problem.n_free() : 0));
    CHECK(r.x.lpNorm<Eigen::Infinity>() == 0.0);
  }
}

namespace {

// Press with friction (mu = 0.3, clamped bottom), committed; returns the candidates' forces by node.
struct PressedWithFriction {
  static constexpr Real kMu = 0.3;
  explicit PressedWithFriction(const std::string& formulation) : model(make_strip(40.0, 10.0, 40, 10, true)) {
    Increment inc(*model, roller_motion(kTouching, kPressed, kRadius, kMu));
    IpoptBackend backend(ipopt_options("split", formulation));
    press = backend.solve(inc.problem, VecX::Zero(inc.problem.n_free()));
    if (!press.converged()) return;
    for (std::size_t i = 0; i < press.contact.size(); ++i) {
      normal[inc.problem.candidates()[i].node] = press.contact[i].normal_force;
      tangential[inc.problem.candidates()[i].node] = press.contact[i].tangential_force;
    }
    model->commit(inc.problem.full_increment(press.x));
  }
  // The next increment: the roller slides by dx without turning; guesses from the press.
  std::unique_ptr<Increment> slide(Real dx) {
    auto inc = std::make_unique<Increment>(*model, roller_motion(kPressed, kPressed + Vec2(dx, 0.0), kRadius, kMu));
    for (auto& c : inc->problem.candidates()) {
      c.normal_force_guess = normal[c.node];
      c.tangential_force = tangential[c.node];
    }
    return inc;
  }
  std::unique_ptr<StripModel> model;
  BackendResult press;
  std::map<Index, Real> normal, tangential;
};

// Coulomb's law at every candidate, to the accuracy the fixed point is iterated to: the pass's
// Fbar and the final F_N differ by at most max(fixed_point_tol max F_N, F_tol), F_tol = 1e-6 of
// the increment's force scale F_ref >= E* dx (docs/scenes.md, contact.ipopt.fixed_point_tol).
void check_coulomb(const IncrementProblem& p, const BackendResult& r, Real mu, Real fixed_point_tol, Real dx,
                   int* n_slip) {
  const Real fmax = max_normal_force(r);
  const Real tol = mu * std::max(fixed_point_tol * fmax, 1e-6 * p.plane_strain_modulus() * dx);
  *n_slip = 0;
  for (std::size_t i = 0; i < r.contact.size(); ++i) {
    const NodeContact& c = r.contact[i];
    INFO("candidate at x = " << p.candidates()[i].position.x() << ": F_N " << c.normal_force << " F_T "
                             << c.tangential_force << " slip " << c.slip << " status " << to_string(c.status));
    CHECK(std::abs(c.tangential_force) <= mu * c.normal_force + tol);
    if (c.status == ContactStatus::Slip && std::abs(c.slip) >= 1e-3 * dx) {
      ++*n_slip;
      CHECK(std::abs(c.tangential_force) >= mu * c.normal_force - tol);  // at the Coulomb bound
      CHECK(c.tangential_force * c.slip < 0.0);                          // opposing the slip
    }
  }
}

}  // namespace

TEST_CASE("ipopt with Coulomb friction: a sliding roller drags the surface at the Coulomb bound", "[ipopt]") {
  const std::string formulation = GENERATE("condensed", "full");
  INFO("formulation " << formulation);
  PressedWithFriction s(formulation);
  INFO("press: " << s.press.brief_report());
  REQUIRE(s.press.converged());
  // The press starts from F_N guesses 0: pass 1 is frictionless, later passes add friction.
  CHECK(nlp_solves(s.press) >= 2);
  const Real dx = 0.1;
  const Real mu = PressedWithFriction::kMu;

  SECTION("fixed point converged") {
    auto inc = s.slide(dx);
    const ContactOptions o = ipopt_options("split", formulation);
    IpoptBackend backend(o);
    const BackendResult r = backend.solve(inc->problem, VecX::Zero(inc->problem.n_free()));
    INFO(r.brief_report());
    REQUIRE(r.converged());
    CHECK(nlp_solves(r) >= 2);
    CHECK(r.details.get<IpoptDetails>().fixed_point_iterations <= o.ipopt.fixed_point_max);
    CHECK(r.details.get<IpoptDetails>().constraint_violation < 1e-8 * kRadius);
    CHECK(r.residual < 1e-8);
    int n_slip = 0;
    check_coulomb(inc->problem, r, mu, o.ipopt.fixed_point_tol, dx, &n_slip);
    CHECK(n_slip >= 3);
    // Global equilibrium, now with a tangential load on the strip.
    VecX grad;
    inc->problem.strip_energy(r.x, &grad, nullptr);
    Vec2 f = Vec2::Zero();
    for (std::size_t i = 0; i < r.contact.size(); ++i) {
      const auto& c = inc->problem.candidates()[i];
      f += r.contact[i].normal_force * inc->problem.normal(c, r.x) + r.contact[i].tangential_force * c.tangent;
    }
    const Vec2 reaction = support_reaction(inc->energy, r.x);
    INFO("contact force " << f.transpose() << " reaction " << reaction.transpose());
    CHECK(f.x() > 0.1 * mu * std::abs(f.y()));  // the roller drags the strip along +x
    CHECK((f + reaction).norm() <= 1e-6 * f.norm());

    // The default warm start (each linearisation's first pass from the last forces, the first
    // from the press's) reaches the solution of cold starts.
    REQUIRE(o.ipopt.warm_start);
    CHECK(r.details.get<IpoptDetails>().cold_restarts == 0);
    ContactOptions cold = o;
    cold.ipopt.warm_start = false;
    auto inc2 = s.slide(dx);
    const BackendResult c = IpoptBackend(cold).solve(inc2->problem, VecX::Zero(inc2->problem.n_free()));
    INFO("cold: " << c.brief_report());
    REQUIRE(c.converged());
    CHECK((c.x - r.x).lpNorm<Eigen::Infinity>() <= 1e-6 * r.x.lpNorm<Eigen::Infinity>());
  }
  SECTION("a warm start that fails is solved again from a cold start") {
    // Unusable tangential guesses (NaN) spoil the first pass's warm-start multipliers only: the
    // full formulation warm-starts its first pass from them, Ipopt fails, the pass is repeated
    // cold and counted.
    if (formulation != "full") return;
    auto inc = s.slide(dx);
    for (auto& c : inc->problem.candidates()) c.tangential_force = std::numeric_limits<Real>::quiet_NaN();
    const ContactOptions o = ipopt_options("split", formulation);
    const BackendResult r = IpoptBackend(o).solve(inc->problem, VecX::Zero(inc->problem.n_free()));
    INFO(r.brief_report());
    REQUIRE(r.converged());
    CHECK(r.details.get<IpoptDetails>().cold_restarts == 1);
    CHECK(r.details.get<IpoptDetails>().nlp_solves == r.details.get<IpoptDetails>().fixed_point_iterations + 1);
    auto clean = s.slide(dx);
    const BackendResult reference = IpoptBackend(o).solve(clean->problem, VecX::Zero(clean->problem.n_free()));
    REQUIRE(reference.converged());
    CHECK(reference.details.get<IpoptDetails>().cold_restarts == 0);
    CHECK((r.x - reference.x).lpNorm<Eigen::Infinity>() <= 1e-6 * reference.x.lpNorm<Eigen::Infinity>());
  }
  SECTION("a later pass of the same increment starts from the last pass's normal forces") {
    // The suspension's and the load's coupling solve an increment again with the roller moved a
    // little; here not at all. Seeded with the first solve's F_N and started from its x, the
    // second solve needs one linearisation and one friction pass; seeded with the press's F_N
    // (the previous increment's) it must redo the fixed point.
    if (formulation != "condensed") return;
    const ContactOptions o = ipopt_options("split", formulation);
    auto first = s.slide(dx);
    const BackendResult r = IpoptBackend(o).solve(first->problem, VecX::Zero(first->problem.n_free()));
    REQUIRE(r.converged());
    auto seeded = s.slide(dx);
    seed_normal_forces(seeded->problem.candidates(), first->problem.candidates(), r.contact);
    const BackendResult again = IpoptBackend(o).solve(seeded->problem, r.x);
    INFO(again.brief_report());
    REQUIRE(again.converged());
    CHECK(again.details.get<IpoptDetails>().linearisations == 1);
    CHECK(again.details.get<IpoptDetails>().nlp_solves == 1);
    CHECK((again.x - r.x).lpNorm<Eigen::Infinity>() <= 1e-6 * r.x.lpNorm<Eigen::Infinity>());
    auto unseeded = s.slide(dx);
    const BackendResult redo = IpoptBackend(o).solve(unseeded->problem, r.x);
    REQUIRE(redo.converged());
    CHECK(redo.details.get<IpoptDetails>().nlp_solves > again.details.get<IpoptDetails>().nlp_solves);
  }
  SECTION("single pass (the thesis's explicit variant)") {
    auto inc = s.slide(dx);
    ContactOptions o = ipopt_options("split", formulation);
    o.ipopt.fixed_point = FixedPointRule::Single;
    const BackendResult r = IpoptBackend(o).solve(inc->problem, VecX::Zero(inc->problem.n_free()));
    INFO(r.brief_report());
    REQUIRE(r.converged());
    CHECK(r.details.get<IpoptDetails>().fixed_point_iterations == 1);
    // The friction bound comes from the guesses (the press's F_N), not from this step's F_N.
    for (std::size_t i = 0; i < r.contact.size(); ++i)
      CHECK(std::abs(r.contact[i].tangential_force) <=
            mu * inc->problem.candidates()[i].normal_force_guess * (1 + 1e-12));
  }
  SECTION("Ipopt's dense and MUMPS linear solvers give one answer") {
    auto inc = s.slide(dx);
    ContactOptions o = ipopt_options("split", formulation);
    o.ipopt.kkt_solver = KktSolver::Dense;
    const BackendResult dense = IpoptBackend(o).solve(inc->problem, VecX::Zero(inc->problem.n_free()));
    auto inc2 = s.slide(dx);
    o.ipopt.kkt_solver = KktSolver::Mumps;
    const BackendResult mumps = IpoptBackend(o).solve(inc2->problem, VecX::Zero(inc2->problem.n_free()));
    INFO("dense: " << dense.brief_report() << "\nmumps: " << mumps.brief_report());
    REQUIRE(dense.converged());
    REQUIRE(mumps.converged());
    CHECK(dense.details.get<IpoptDetails>().nlp_solves == mumps.details.get<IpoptDetails>().nlp_solves);
    CHECK((dense.x - mumps.x).lpNorm<Eigen::Infinity>() <= 1e-8 * mumps.x.lpNorm<Eigen::Infinity>());
  }
  SECTION("regularized friction") {
    auto inc = s.slide(dx);
    ContactOptions o = ipopt_options("regularized", formulation);
    const BackendResult r = IpoptBackend(o).solve(inc->problem, VecX::Zero(inc->problem.n_free()));
    INFO(r.brief_report());
    REQUIRE(r.converged());
    int n_slip = 0;
    check_coulomb(inc->problem, r, mu, o.ipopt.fixed_point_tol, dx, &n_slip);
    CHECK(n_slip >= 3);
  }
}

TEST_CASE("ipopt: max_iter reached is NotConverged with a message naming the option", "[ipopt]") {
  auto model = make_strip(40.0, 10.0, 40, 10, false);
  Increment inc(*model, roller_motion(kTouching, kPressed, kRadius, 0.0));
  const std::string formulation = GENERATE("condensed", "full");
  INFO("formulation " << formulation);
  ContactOptions o = ipopt_options("split", formulation);
  o.ipopt.max_iter = 1;
  IpoptBackend backend(o);
  const BackendResult r = backend.solve(inc.problem, VecX::Zero(inc.problem.n_free()));
  CHECK(r.status == Termination::LimitReached);
  CHECK(r.counters.iterations == 1);
  CHECK_THAT(r.message, Catch::Contains("contact.ipopt.max_iter = 1") && Catch::Contains("smaller steps"));
  CHECK_THAT(r.brief_report(), Catch::Contains("FAILED"));
}

TEST_CASE("ipopt: make_contact_backend builds the ipopt backend", "[ipopt]") {
  const auto backend = make_contact_backend(ipopt_options(), NewtonOptions{});
  CHECK(backend->name() == "ipopt");
  ContactOptions bad = ipopt_options();
  bad.ipopt.tol = 2.0;  // outside (0, 1)
  CHECK_THROWS_AS(make_contact_backend(bad, NewtonOptions{}), InputError);
}
