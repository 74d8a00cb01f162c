#include "roller/contact/penalty_backend.hpp"

#include <cmath>
#include <limits>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

namespace {

struct Stiffness {
  Real normal, tangential;
};

// Contact forces of candidate c at x and, optionally, the 2x2 tangent block d(-f)/du of the
// force f = F_N n + F_T t acting on the node.
NodeContact contact_state(const IncrementProblem& p, const ContactCandidate& c, const Stiffness& k,
                          const VecX& x, Mat2* block) {
  NodeContact s;
  const Vec2 d = p.position(c, x) - p.roller().end.centre;
  const Real rho = d.norm();
  const Vec2 n = d / rho;
  s.gap = rho - p.roller().radius;
  s.slip = p.slip(c, x);
  if (block) block->setZero();
  if (s.gap >= 0.0) return s;  // open: no force, and the history is lost
  s.normal_force = -k.normal * s.gap;
  const Real mu = p.roller().friction;
  const Vec2& t = c.tangent;
  if (block)
    *block += k.normal * n * n.transpose() - s.normal_force * (Mat2::Identity() - n * n.transpose()) / rho;
  if (mu == 0.0) {
    s.status = ContactStatus::Slip;
    return s;
  }
  const Real trial = c.tangential_force - k.tangential * s.slip;
  const Real bound = mu * s.normal_force;
  if (std::abs(trial) <= bound) {
    s.tangential_force = trial;
    s.status = ContactStatus::Stick;
    if (block) *block += k.tangential * t * t.transpose();
  } else {
    const Real sign = trial > 0.0 ? 1.0 : -1.0;
    s.tangential_force = sign * bound;
    s.status = ContactStatus::Slip;
    if (block) *block += mu * k.normal * sign * t * n.transpose();  // unsymmetric
  }
  return s;
}

struct Evaluation {
  VecX residual;
  SparseMatrix jacobian;
  std::vector<NodeContact> contact;
  Real scale = 0.0;
  // Residual that round-off alone produces: the gap |x - c| - R of a node at distance rho from
  // the centre carries an absolute error ~ eps rho, which the penalty turns into a force
  // error ~ eps rho kN. Tolerances below it cannot be met.
  Real roundoff_floor = 0.0;
  bool symmetric = true;
};

// Residual r = dPi/dx - (contact forces) on the free dofs, and its Jacobian when asked.
void evaluate(IncrementProblem& p, const std::vector<Stiffness>& k, const VecX& x, bool want_jacobian,
              Evaluation& e) {
  p.strip_energy(x, &e.residual, want_jacobian ? &e.jacobian : nullptr);
  e.contact.assign(p.candidates().size(), NodeContact{});
  e.symmetric = true;
  Real contact_norm2 = 0.0, floor2 = 0.0;
  Mat2 block;
  for (std::size_t i = 0; i < p.candidates().size(); ++i) {
    const ContactCandidate& c = p.candidates()[i];
    NodeContact& s = e.contact[i];
    s = contact_state(p, c, k[i], x, want_jacobian ? &block : nullptr);
    if (s.status == ContactStatus::Open) continue;
    const Real floor_i = 10.0 * std::numeric_limits<Real>::epsilon() * k[i].normal *
                         (p.position(c, x) - p.roller().end.centre).norm();
    floor2 += floor_i * floor_i;
    const Vec2 n = p.normal(c, x);
    const Vec2 f = s.normal_force * n + s.tangential_force * c.tangent;
    contact_norm2 += f.squaredNorm();
    if (s.status == ContactStatus::Slip && p.roller().friction > 0.0) e.symmetric = false;
    for (int a = 0; a < 2; ++a) {
      if (c.free_dof[a] < 0) continue;
      e.residual(c.free_dof[a]) -= f(a);
      if (!want_jacobian) continue;
      for (int b = 0; b < 2; ++b)
        if (c.free_dof[b] >= 0) e.jacobian.coeffRef(c.free_dof[a], c.free_dof[b]) += block(a, b);
    }
  }
  e.scale = std::max(p.force_scale(x), std::sqrt(contact_norm2));
  e.roundoff_floor = std::sqrt(floor2);
}

bool solve_linear(const Evaluation& e, VecX& d) {
  if (e.symmetric) {
    Eigen::SimplicialLDLT<SparseMatrix> ldlt(e.jacobian);
    if (ldlt.info() == Eigen::Success) {
      d = ldlt.solve(-e.residual);
      if (d.allFinite()) return true;
    }
  }
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(e.jacobian);
  if (lu.info() != Eigen::Success) return false;
  d = lu.solve(-e.residual);
  return d.allFinite();
}

}  // namespace

PenaltyBackend::PenaltyBackend(ContactOptions options, NewtonOptions newton)
    : options_(std::move(options)), newton_(newton) {}

BackendResult PenaltyBackend::do_solve(IncrementProblem& problem, const VecX& x0) {
  BackendResult result;
  std::vector<Stiffness> k;
  const Real e_star = problem.plane_strain_modulus();
  for (const auto& c : problem.candidates()) {
    const Real kn = options_.penalty.factor * e_star * c.tributary_length / c.element_size;
    k.push_back({kn, options_.penalty.tangential_factor * kn});
  }
  VecX x = x0, d, x_trial;
  Evaluation e, trial;
  try {
    evaluate(problem, k, x, true, e);
  } catch (const NumericalError& err) {
    result.message = fmt::format("cannot evaluate the start of the increment: {}", err.what());
    return result;
  }
  for (int it = 0;; ++it) {
    const Real rnorm = e.residual.norm();
    if (std::getenv("ROLLER_DEBUG")) { int nc = 0; for (auto& c : e.contact) nc += c.status != ContactStatus::Open; fmt::print("  it {} r {:.3e} scale {:.3e} contact {}\n", it, rnorm, e.scale, nc); }
    result.iterations = it;
    result.residual = rnorm / std::max(e.scale, 1e-300);
    if (!std::isfinite(rnorm)) {
      result.message = "the residual is not finite: the increment diverged; use smaller steps";
      return result;
    }
    if (result.residual <= newton_.residual_tolerance || rnorm <= e.roundoff_floor) {
      result.status = NewtonStatus::Converged;
      break;
    }
    if (it >= newton_.max_iterations) {
      result.status = NewtonStatus::NotConverged;
      result.message = fmt::format(
          "penalty Newton: no convergence in {} iterations (|r|/F = {:.2e}); use smaller steps, "
          "a smaller contact.penalty.factor, or the ipopt backend",
          it, result.residual);
      break;
    }
    ++result.factorizations;
    if (!solve_linear(e, d)) {
      result.message = "penalty Newton: the tangent matrix is singular (missing supports, or a "
                       "mechanism); check the boundary conditions";
      return result;
    }
    // Backtracking on ||r||; the contact set can change along the step, so no energy exists
    // to backtrack on once friction slips.
    Real alpha = 1.0;
    bool accepted = false;
    for (int ls = 0; ls < 12; ++ls, alpha *= 0.5) {
      x_trial = x + alpha * d;
      try {
        evaluate(problem, k, x_trial, false, trial);
      } catch (const NumericalError&) {
        continue;
      }
      if (!newton_.line_search || trial.residual.norm() <= (1.0 - 1e-4 * alpha) * rnorm) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      // No decrease along the Newton direction: take a short step anyway; the iteration limit
      // bounds the cost and the failure is reported if it never recovers.
      x_trial = x + 1e-2 * d;
    }
    x = x_trial;
    try {
      evaluate(problem, k, x, true, e);
    } catch (const NumericalError& err) {
      result.message = err.what();
      return result;
    }
  }
  result.x = x;
  result.contact = e.contact;
  return result;
}

}  // namespace roller
