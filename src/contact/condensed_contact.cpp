#include "roller/contact/condensed_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "roller/core/error.hpp"

namespace roller {

namespace {

// Newton's steps on the gaps, and active-set passes per step: the normals move by about the
// strip's strain under the roller (1e-3), so Newton's method converges to round-off in three or
// four steps; the active set settles in a few passes from the last press's.
constexpr int kNewtonSteps = 50;
constexpr int kActiveSetPasses = 50;

}  // namespace

CondensedContact::CondensedContact(const SparseMatrix& tangent, const DofMap& dofs, std::vector<Index> nodes,
                                   std::vector<Vec2> positions, Real centre_x, Real radius,
                                   const LinearSolverOptions& linear_solver)
    : centre_x_(centre_x),
      radius_(radius),
      nodes_(std::move(nodes)),
      reference_(std::move(positions)),
      solver_(MumpsSolver::Symmetry::Symmetric, linear_solver) {
  ROLLER_ASSERT(nodes_.size() == reference_.size() && nodes_.size() >= 3, "three condensed nodes or more, placed");
  const auto n = static_cast<Index>(nodes_.size());
  for (Index i = 0; i < n; ++i) {
    const Index a = nodes_[static_cast<std::size_t>(i)];
    ROLLER_ASSERT(!dofs.is_constrained(2 * a) && !dofs.is_constrained(2 * a + 1), "condensed nodes are free");
    ROLLER_ASSERT(
        i == 0 || reference_[static_cast<std::size_t>(i)].x() >= reference_[static_cast<std::size_t>(i - 1)].x(),
        "condensed nodes by x");
    schur_.push_back(dofs.free_index(2 * a));
    schur_.push_back(dofs.free_index(2 * a + 1));
  }
  for (Index i = 0; i < n; ++i) {
    const Real left = reference_[static_cast<std::size_t>(std::max<Index>(i - 1, 0))].x();
    const Real right = reference_[static_cast<std::size_t>(std::min<Index>(i + 1, n - 1))].x();
    tributary_.push_back(0.5 * (right - left));
  }
  MatX s;
  if (!solver_.factorize_with_schur(tangent, schur_, &s))
    throw NumericalError(fmt::format("the roller's contact: the strip's tangent is singular: {}", solver_.message()));
  compliance_ = Eigen::LLT<MatX>(s).solve(MatX::Identity(s.rows(), s.cols()));
  active_.assign(nodes_.size(), false);
}

CondensedContact::~CondensedContact() = default;

CondensedContact::Small CondensedContact::solve_small(const std::vector<Vec2>& base, const VecX& reduced,
                                                      Real force) const {
  const auto n = static_cast<Index>(nodes_.size());
  const Real tolerance = 1e-12 * radius_;
  Small out;
  const VecX v0 = compliance_ * reduced;  // the nodes' displacement without contact
  out.v = v0;
  out.lambda = VecX::Zero(n);
  out.active = active_;
  out.height = height_;
  if (std::none_of(active_.begin(), active_.end(), [](bool a) { return a; })) {
    // The roller touching the strip's highest point under it, that node in contact.
    Index top = 0;
    out.height = -std::numeric_limits<Real>::infinity();
    for (Index i = 0; i < n; ++i) {
      const Real dx = base[static_cast<std::size_t>(i)].x() - centre_x_;
      if (std::abs(dx) >= radius_) continue;
      const Real y = base[static_cast<std::size_t>(i)].y() + v0(2 * i + 1) + std::sqrt(radius_ * radius_ - dx * dx);
      if (y > out.height) out.height = y, top = i;
    }
    out.active[static_cast<std::size_t>(top)] = true;
  }
  for (int step = 0; step < kNewtonSteps; ++step) {
    // The gaps, their normals and their slopes in the roller's height at the nodes' present v.
    std::vector<Vec2> normal(nodes_.size());
    VecX gap(n), slope(n);
    const Vec2 centre(centre_x_, out.height);
    for (Index i = 0; i < n; ++i) {
      const Vec2 d = base[static_cast<std::size_t>(i)] + out.v.segment<2>(2 * i) - centre;
      const Real rho = d.norm();
      normal[static_cast<std::size_t>(i)] = d / rho;
      gap(i) = rho - radius_;
      slope(i) = -d.y() / rho;  // dg/dc_y: the force's share that carries the roller
    }
    bool settled_gaps = step > 0;
    for (Index i = 0; i < n && settled_gaps; ++i)
      settled_gaps = out.active[static_cast<std::size_t>(i)] ? std::abs(gap(i)) <= tolerance : gap(i) >= -tolerance;
    if (settled_gaps) return out;
    // The linear complementarity problem of the step: g = q + M lambda + slope dy >= 0, lambda >= 0,
    // lambda g = 0, slope . lambda = P, by the primal-dual active set.
    // C N and N^T C N, N the normals as columns (two entries each).
    MatX cn(2 * n, n), m(n, n);
    for (Index i = 0; i < n; ++i) {
      const Vec2& ni = normal[static_cast<std::size_t>(i)];
      cn.col(i) = compliance_.col(2 * i) * ni.x() + compliance_.col(2 * i + 1) * ni.y();
    }
    for (Index i = 0; i < n; ++i) {
      const Vec2& ni = normal[static_cast<std::size_t>(i)];
      m.row(i) = ni.x() * cn.row(2 * i) + ni.y() * cn.row(2 * i + 1);
    }
    VecX q = gap;
    for (Index i = 0; i < n; ++i) q(i) += normal[static_cast<std::size_t>(i)].dot((v0 - out.v).segment<2>(2 * i));
    std::vector<bool> active = out.active;
    VecX lambda = VecX::Zero(n);
    Real dy = 0.0;
    bool settled = false;
    for (int pass = 0; pass < kActiveSetPasses && !settled; ++pass) {
      std::vector<Index> on;
      for (Index i = 0; i < n; ++i)
        if (active[static_cast<std::size_t>(i)]) on.push_back(i);
      const auto k = static_cast<Index>(on.size());
      MatX a = MatX::Zero(k + 1, k + 1);
      VecX rhs(k + 1);
      for (Index r = 0; r < k; ++r) {
        for (Index c = 0; c < k; ++c) a(r, c) = m(on[r], on[c]);
        a(r, k) = slope(on[r]);
        a(k, r) = slope(on[r]);
        rhs(r) = -q(on[r]);
      }
      rhs(k) = force;
      const VecX x = Eigen::FullPivLU<MatX>(a).solve(rhs);
      lambda.setZero();
      for (Index r = 0; r < k; ++r) lambda(on[r]) = x(r);
      dy = x(k);
      const VecX g = q + m * lambda + slope * dy;
      std::vector<bool> next(active.size());
      for (Index i = 0; i < n; ++i) next[static_cast<std::size_t>(i)] = lambda(i) - g(i) / m(i, i) > 0.0;
      settled = next == active;
      active = std::move(next);
      if (std::none_of(active.begin(), active.end(), [](bool b) { return b; })) {
        out.message = "the roller's contact: no node carries the load";
        return out;
      }
    }
    if (!settled) {
      out.message =
          fmt::format("the roller's contact: its nodes in contact do not settle in {} passes", kActiveSetPasses);
      return out;
    }
    out.v = v0 + cn * lambda;
    out.lambda = lambda;
    out.height += dy;
    out.active = active;
  }
  out.message = fmt::format("the roller's contact: its gaps do not close in {} Newton steps", kNewtonSteps);
  return out;
}

CondensedContact::Press CondensedContact::solve(const VecX& u, const VecX& b, Real force) {
  std::vector<Vec2> base;
  for (std::size_t i = 0; i < nodes_.size(); ++i) base.push_back(reference_[i] + u.segment<2>(2 * nodes_[i]));
  Small small;
  Press out;
  out.du = solver_.solve_with_schur(b, [&](const VecX& reduced) {
    small = solve_small(base, reduced, force);
    return small.message.empty() ? small.v : VecX::Zero(reduced.size());
  });
  if (!small.message.empty()) return {VecX(), {}, {}, small.message};
  const auto n = static_cast<Index>(nodes_.size());
  if (small.lambda(0) > 0.0 || small.lambda(n - 1) > 0.0)
    return {VecX(),
            {},
            {},
            fmt::format("the roller's contact reaches the end of the nodes condensed under it ({:.6g} to {:.6g} mm)",
                        reference_.front().x(), reference_.back().x())};
  active_ = small.active;
  height_ = small.height;
  out.pose.centre = Vec2(centre_x_, small.height);
  for (Index i = 0; i < n; ++i) {
    NodeContactRecord c;
    c.node = nodes_[static_cast<std::size_t>(i)];
    c.position = base[static_cast<std::size_t>(i)] + small.v.segment<2>(2 * i);
    const Vec2 d = c.position - out.pose.centre;
    const bool touches = small.active[static_cast<std::size_t>(i)];
    c.contact.normal_force = touches ? small.lambda(i) : 0.0;
    c.contact.gap = d.norm() - radius_;
    c.contact.status = touches ? ContactStatus::Slip : ContactStatus::Open;  // frictionless
    c.tributary_length = tributary_[static_cast<std::size_t>(i)];
    c.force = c.contact.normal_force * d.normalized();
    out.contact.push_back(c);
  }
  return out;
}

}  // namespace roller
