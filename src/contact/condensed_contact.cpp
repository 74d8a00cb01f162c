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
// The stick trial lambda_t - c s takes c as this share of the slip rows' diagonal's inverse. The
// steady slip rows are not symmetric; with the full inverse two identical elastic bodies (an
// elastic roller of the strip's material) flip their slip zone's sign from pass to pass without
// end, with half of it they settle (docs/model.md, Stationary pass).
constexpr Real kStickTrialScale = 0.5;

CondensedPlace place_of(const DofMap& dofs, std::vector<Index> nodes, std::vector<Vec2> positions, Real centre_x) {
  CondensedPlace p;
  for (const Index a : nodes) {
    ROLLER_ASSERT(!dofs.is_constrained(2 * a) && !dofs.is_constrained(2 * a + 1), "condensed nodes are free");
    p.unknowns.push_back(dofs.free_index(2 * a));
    p.unknowns.push_back(dofs.free_index(2 * a + 1));
  }
  p.nodes = std::move(nodes);
  p.positions = std::move(positions);
  p.centre_x = centre_x;
  return p;
}

}  // namespace

CondensedContact::CondensedContact(const SparseMatrix& tangent, const DofMap& dofs, std::vector<Index> nodes,
                                   std::vector<Vec2> positions, Real centre_x, Real radius,
                                   const LinearSolverOptions& linear_solver, MumpsSolver::Symmetry symmetry)
    : radius_(radius), free_(dofs.n_free()), solver_(symmetry, linear_solver) {
  places_.push_back(place_of(dofs, std::move(nodes), std::move(positions), centre_x));
  build(tangent, symmetry);
}

CondensedContact::CondensedContact(const SparseMatrix& tangent, Index free, std::vector<CondensedPlace> places,
                                   Real radius, const LinearSolverOptions& linear_solver,
                                   MumpsSolver::Symmetry symmetry)
    : radius_(radius), places_(std::move(places)), free_(free), solver_(symmetry, linear_solver) {
  build(tangent, symmetry);
}

void CondensedContact::build(const SparseMatrix& tangent, MumpsSolver::Symmetry symmetry) {
  unknowns_ = tangent.rows();
  ROLLER_ASSERT(!places_.empty() && free_ <= unknowns_, "a place, and the free dofs among the unknowns");
  for (std::size_t k = 0; k < places_.size(); ++k) {
    const CondensedPlace& p = places_[k];
    const auto n = static_cast<Index>(p.nodes.size());
    ROLLER_ASSERT(p.positions.size() == p.nodes.size() && n >= 3 && p.unknowns.size() == 2 * p.nodes.size(),
                  "three condensed nodes or more a place, placed, with their unknowns");
    first_.push_back(static_cast<Index>(nodes_.size()));
    for (Index i = 0; i < n; ++i) {
      const auto s = static_cast<std::size_t>(i);
      ROLLER_ASSERT(i == 0 || p.positions[s].x() >= p.positions[s - 1].x(), "condensed nodes by x");
      const Real left = p.positions[static_cast<std::size_t>(std::max<Index>(i - 1, 0))].x();
      const Real right = p.positions[static_cast<std::size_t>(std::min<Index>(i + 1, n - 1))].x();
      nodes_.push_back(p.nodes[s]);
      reference_.push_back(p.positions[s]);
      place_of_.push_back(static_cast<int>(k));
      tributary_.push_back(0.5 * (right - left));
      schur_.push_back(p.unknowns[2 * s]);
      schur_.push_back(p.unknowns[2 * s + 1]);
    }
  }
  first_.push_back(static_cast<Index>(nodes_.size()));
  MatX s;
  if (!solver_.factorize_with_schur(tangent, schur_, &s))
    throw NumericalError(fmt::format("the roller's contact: the strip's tangent is singular: {}", solver_.message()));
  const MatX identity = MatX::Identity(s.rows(), s.cols());
  compliance_ = symmetry == MumpsSolver::Symmetry::Symmetric ? MatX(Eigen::LLT<MatX>(s).solve(identity))
                                                             : MatX(Eigen::PartialPivLU<MatX>(s).solve(identity));
  restart();
}

void CondensedContact::restart() {
  sets_.zone.assign(nodes_.size(), Zone::Open);
  sets_.slip_sign.assign(nodes_.size(), 1.0);
  height_ = VecX::Zero(n_places());
  creep_ = VecX::Zero(n_places());
}

CondensedContact::~CondensedContact() = default;

void CondensedContact::start_from(const CondensedContact& other, int from, int to) {
  const auto f = static_cast<std::size_t>(from), t = static_cast<std::size_t>(to);
  ROLLER_ASSERT(other.places_[f].nodes.size() == places_[t].nodes.size(), "the same nodes condensed");
  std::copy_n(other.sets_.zone.begin() + other.first_[f], places_[t].nodes.size(), sets_.zone.begin() + first_[t]);
  std::copy_n(other.sets_.slip_sign.begin() + other.first_[f], places_[t].nodes.size(),
              sets_.slip_sign.begin() + first_[t]);
  height_(to) = other.height_(from);
  creep_(to) = other.creep_(from);
}

void CondensedContact::set_roller(const RimStiffness& rim) {
  roller_compliance_ = MatX::Zero(compliance_.rows(), compliance_.cols());
  for (std::size_t k = 0; k < places_.size(); ++k) {
    std::vector<Real> angles, reaches;
    for (Index i = first_[k]; i < first_[k + 1]; ++i) {
      const auto s = static_cast<std::size_t>(i);
      angles.push_back(std::asin(std::clamp((reference_[s].x() - places_[k].centre_x) / radius_, -1.0, 1.0)));
      reaches.push_back(tributary_[s] / radius_);
    }
    const Index size = 2 * (first_[k + 1] - first_[k]);
    roller_compliance_.block(2 * first_[k], 2 * first_[k], size, size) = rim_compliance(rim, angles, reaches);
  }
}

Index CondensedContact::upstream(Index i, Real travel_sign) const {
  const Index j = i + (travel_sign > 0.0 ? 1 : -1);  // the nodes by x; the material comes from ahead
  const int k = place_of_[static_cast<std::size_t>(i)];
  return j >= first_[static_cast<std::size_t>(k)] && j < first_[static_cast<std::size_t>(k) + 1] ? j : -1;
}

CondensedContact::Small CondensedContact::solve_small(const std::vector<Vec2>& base, const VecX& reduced,
                                                      const CondensedLoad& load) const {
  const auto n = static_cast<Index>(nodes_.size());
  const Index places = n_places();
  const Real tolerance = 1e-12 * radius_;
  const Real mu = load.friction;
  const Real travel = load.travel_sign;
  const bool carries_q = mu > 0.0 && load.horizontal_force.has_value();  // the creep an unknown that carries Q
  auto place = [&](Index i) { return static_cast<Index>(place_of_[static_cast<std::size_t>(i)]); };
  Small out;
  const VecX v0 = compliance_ * reduced;  // the nodes' displacement without contact
  out.v = v0;
  out.rim = VecX::Zero(2 * n);
  const bool elastic = roller_compliance_.size() != 0;
  out.lambda_n = VecX::Zero(n);
  out.lambda_t = VecX::Zero(n);
  out.slip = VecX::Zero(n);
  out.sets = sets_;
  out.height = height_;
  out.creep = carries_q ? creep_ : VecX::Constant(places, load.creep);
  for (Index k = 0; k < places; ++k) {
    const auto b = out.sets.zone.begin() + first_[static_cast<std::size_t>(k)];
    const auto e = out.sets.zone.begin() + first_[static_cast<std::size_t>(k) + 1];
    if (std::any_of(b, e, [](Zone z) { return z != Zone::Open; })) continue;
    // The roller touching the strip's highest point under it, that node in contact.
    const Real centre_x = places_[static_cast<std::size_t>(k)].centre_x;
    Index top = first_[static_cast<std::size_t>(k)];
    out.height(k) = -std::numeric_limits<Real>::infinity();
    for (Index i = first_[static_cast<std::size_t>(k)]; i < first_[static_cast<std::size_t>(k) + 1]; ++i) {
      const Real dx = base[static_cast<std::size_t>(i)].x() - centre_x;
      if (std::abs(dx) >= radius_) continue;
      const Real y = base[static_cast<std::size_t>(i)].y() + v0(2 * i + 1) + std::sqrt(radius_ * radius_ - dx * dx);
      if (y > out.height(k)) out.height(k) = y, top = i;
    }
    out.sets.zone[static_cast<std::size_t>(top)] = carries_q ? Zone::Stick : Zone::Slip;
  }
  // The reference's step from each node's upstream neighbour: the roller's travel while the
  // material walks it.
  VecX step = VecX::Zero(n);
  for (Index i = 0; i < n; ++i)
    if (const Index j = upstream(i, travel); j >= 0)
      step(i) = std::abs(reference_[static_cast<std::size_t>(j)].x() - reference_[static_cast<std::size_t>(i)].x());
  VecX last_v = out.v;
  for (int newton = 0; newton < kNewtonSteps; ++newton) {
    // The gaps, normals, tangents and slips at the nodes' present v; the slip of node i is its
    // material's tangential displacement against the roller's rim over the step from upstream,
    // t . (x_i - x_up) + travel (1 - creep) step (the transient's t . (du - dc) - R dphi).
    std::vector<Vec2> normal(nodes_.size()), tangent(nodes_.size());
    VecX gap(n), slope(n), slip = VecX::Zero(n);
    // Where node i touches: the strip's point moved by v, against a rim moved by -(H f).
    auto at = [&](Index i) { return base[static_cast<std::size_t>(i)] + (out.v + out.rim).segment<2>(2 * i); };
    for (Index i = 0; i < n; ++i) {
      const Vec2 d = at(i) - Vec2(places_[static_cast<std::size_t>(place(i))].centre_x, out.height(place(i)));
      const Real rho = d.norm();
      normal[static_cast<std::size_t>(i)] = d / rho;
      tangent[static_cast<std::size_t>(i)] = Vec2(-d.y(), d.x()) / rho;
      gap(i) = rho - radius_;
      slope(i) = -d.y() / rho;  // dg/dc_y: the normal force's share that carries the roller
    }
    for (Index i = 0; i < n; ++i)
      if (const Index j = upstream(i, travel); j >= 0)
        slip(i) =
            tangent[static_cast<std::size_t>(i)].dot(at(i) - at(j)) + travel * (1.0 - out.creep(place(i))) * step(i);
    out.slip = slip;
    // Settled: the last step moved no node by more than the tolerance (the normals, and so the
    // forces' directions, are the step's), and every node meets its zone's conditions.
    bool settled = newton > 0 && (out.v + out.rim - last_v).cwiseAbs().maxCoeff() <= tolerance;
    for (Index i = 0; i < n && settled; ++i) {
      const auto k = static_cast<std::size_t>(i);
      switch (out.sets.zone[k]) {
        case Zone::Open: settled = gap(i) >= -tolerance; break;
        case Zone::Stick: settled = std::abs(gap(i)) <= tolerance && std::abs(slip(i)) <= tolerance; break;
        case Zone::Slip:
          settled = std::abs(gap(i)) <= tolerance && (mu == 0.0 || out.sets.slip_sign[k] * slip(i) <= tolerance);
      }
    }
    if (settled) return out;
    // The step's linear problem in the forces: C N and C T (N, T the normals and tangents as
    // columns), the gaps' and slips' responses, linear in the forces, with normals and tangents held.
    MatX cn(2 * n, n), ct(2 * n, n), hn, ht;
    for (Index i = 0; i < n; ++i) {
      const Vec2& ni = normal[static_cast<std::size_t>(i)];
      const Vec2& ti = tangent[static_cast<std::size_t>(i)];
      cn.col(i) = compliance_.col(2 * i) * ni.x() + compliance_.col(2 * i + 1) * ni.y();
      ct.col(i) = compliance_.col(2 * i) * ti.x() + compliance_.col(2 * i + 1) * ti.y();
    }
    if (elastic) {  // the rollers' share: (H N) and (H T)
      hn.resize(2 * n, n), ht.resize(2 * n, n);
      for (Index i = 0; i < n; ++i) {
        const Vec2& ni = normal[static_cast<std::size_t>(i)];
        const Vec2& ti = tangent[static_cast<std::size_t>(i)];
        hn.col(i) = roller_compliance_.col(2 * i) * ni.x() + roller_compliance_.col(2 * i + 1) * ni.y();
        ht.col(i) = roller_compliance_.col(2 * i) * ti.x() + roller_compliance_.col(2 * i + 1) * ti.y();
      }
    }
    // Rows of the gaps (n . v at the node) and the slips (t . (v_i - v_up)) of a matrix over v.
    auto gap_rows = [&](const MatX& x) {
      MatX rows(n, x.cols());
      for (Index i = 0; i < n; ++i) {
        const Vec2& ni = normal[static_cast<std::size_t>(i)];
        rows.row(i) = ni.x() * x.row(2 * i) + ni.y() * x.row(2 * i + 1);
      }
      return rows;
    };
    auto slip_rows = [&](const MatX& x) {
      MatX rows = MatX::Zero(n, x.cols());
      for (Index i = 0; i < n; ++i) {
        const Index j = upstream(i, travel);
        if (j < 0) continue;
        const Vec2& ti = tangent[static_cast<std::size_t>(i)];
        rows.row(i) = ti.x() * (x.row(2 * i) - x.row(2 * j)) + ti.y() * (x.row(2 * i + 1) - x.row(2 * j + 1));
      }
      return rows;
    };
    MatX m_nn = gap_rows(cn), m_nt = gap_rows(ct), m_sn = slip_rows(cn), m_st = slip_rows(ct);
    if (elastic) {  // the gaps and slips answer to the strip's and the rollers' compliance together
      m_nn += gap_rows(hn), m_nt += gap_rows(ht), m_sn += slip_rows(hn), m_st += slip_rows(ht);
    }
    const VecX dv = v0 - out.v - out.rim;
    const VecX q_n = gap + gap_rows(dv), q_s = slip + slip_rows(dv);
    Sets sets = out.sets;
    VecX lambda_n, lambda_t, dh, dcreep;
    bool stable = false;
    for (int pass = 0; pass < kActiveSetPasses && !stable; ++pass) {
      // Unknowns: lambda_n of the nodes in contact, lambda_t of the sticking ones, each roller's
      // height's and (carrying Q) creep's change. Rows: their gaps, their slips, each P and Q.
      std::vector<Index> on, stick;
      for (Index i = 0; i < n; ++i) {
        const Zone z = sets.zone[static_cast<std::size_t>(i)];
        if (z != Zone::Open) on.push_back(i);
        if (z == Zone::Stick) stick.push_back(i);
      }
      const auto kn = static_cast<Index>(on.size()), ks = static_cast<Index>(stick.size());
      const Index rollers = kn + ks, creeps = rollers + places;  // the first column of each
      const Index size = creeps + (carries_q ? places : 0);
      MatX a = MatX::Zero(size, size);
      VecX rhs = VecX::Zero(size);
      // A slipping node's lambda_t = slip_sign mu lambda_n rides on its lambda_n's column.
      auto tangential_share = [&](Index i) {
        const auto k = static_cast<std::size_t>(i);
        return sets.zone[k] == Zone::Slip ? sets.slip_sign[k] * mu : 0.0;
      };
      for (Index c = 0; c < kn; ++c) {
        const Index i = on[c];
        const Real share = tangential_share(i);
        for (Index r = 0; r < kn; ++r) a(r, c) = m_nn(on[r], i) + share * m_nt(on[r], i);
        for (Index r = 0; r < ks; ++r) a(kn + r, c) = m_sn(stick[r], i) + share * m_st(stick[r], i);
        const Vec2& ni = normal[static_cast<std::size_t>(i)];
        const Vec2& ti = tangent[static_cast<std::size_t>(i)];
        a(rollers + place(i), c) = -ni.y() - share * ti.y();
        if (carries_q) a(creeps + place(i), c) = ni.x() + share * ti.x();
      }
      for (Index c = 0; c < ks; ++c) {
        const Index i = stick[c];
        for (Index r = 0; r < kn; ++r) a(r, kn + c) = m_nt(on[r], i);
        for (Index r = 0; r < ks; ++r) a(kn + r, kn + c) = m_st(stick[r], i);
        const Vec2& ti = tangent[static_cast<std::size_t>(i)];
        a(rollers + place(i), kn + c) = -ti.y();
        if (carries_q) a(creeps + place(i), kn + c) = ti.x();
      }
      for (Index r = 0; r < kn; ++r) a(r, rollers + place(on[r])) = slope(on[r]), rhs(r) = -q_n(on[r]);
      for (Index r = 0; r < ks; ++r) {
        rhs(kn + r) = -q_s(stick[r]);
        if (carries_q) a(kn + r, creeps + place(stick[r])) = -travel * step(stick[r]);  // ds/dcreep
      }
      for (Index k = 0; k < places; ++k) {
        rhs(rollers + k) = load.force;
        // The strip's horizontal force on the roller is minus the sum of the nodes' forces.
        if (carries_q) rhs(creeps + k) = -*load.horizontal_force;
      }
      const VecX x = Eigen::FullPivLU<MatX>(a).solve(rhs);
      lambda_n = VecX::Zero(n);
      lambda_t = VecX::Zero(n);
      for (Index r = 0; r < kn; ++r) lambda_n(on[r]) = x(r), lambda_t(on[r]) = tangential_share(on[r]) * x(r);
      for (Index r = 0; r < ks; ++r) lambda_t(stick[r]) = x(kn + r);
      dh = x.segment(rollers, places);
      dcreep = carries_q ? VecX(x.segment(creeps, places)) : VecX::Zero(places);
      VecX g = q_n + m_nn * lambda_n + m_nt * lambda_t;
      VecX s = q_s + m_sn * lambda_n + m_st * lambda_t;
      for (Index i = 0; i < n; ++i) g(i) += slope(i) * dh(place(i)), s(i) -= travel * step(i) * dcreep(place(i));
      // The next sets: in contact where lambda_n - g / m_nn > 0; of those, sticking where
      // |lambda_t - s / m_st| <= mu (lambda_n - g / m_nn), slipping against the slip otherwise.
      Sets next = sets;
      for (Index i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const Real normal_trial = lambda_n(i) - g(i) / m_nn(i, i);
        if (normal_trial <= 0.0) {
          next.zone[k] = Zone::Open;
          continue;
        }
        if (mu == 0.0) {
          next.zone[k] = Zone::Slip;
          continue;
        }
        const Real c_t = kStickTrialScale * (m_st(i, i) > 0.0 ? 1.0 / m_st(i, i) : 1.0 / m_nn(i, i));
        const Real tangential_trial = lambda_t(i) - c_t * s(i);
        if (std::abs(tangential_trial) <= mu * normal_trial) {
          next.zone[k] = Zone::Stick;
        } else {
          next.zone[k] = Zone::Slip;
          next.slip_sign[k] = tangential_trial > 0.0 ? 1.0 : -1.0;
        }
      }
      for (Index k = 0; k < places; ++k) {
        const Index begin = first_[static_cast<std::size_t>(k)], end = first_[static_cast<std::size_t>(k) + 1];
        bool touches = false, sticks = false;
        for (Index i = begin; i < end; ++i) {
          touches = touches || next.zone[static_cast<std::size_t>(i)] != Zone::Open;
          sticks = sticks || next.zone[static_cast<std::size_t>(i)] == Zone::Stick;
        }
        if (!touches) {
          out.message = "the roller's contact: no node carries the load";
          return out;
        }
        if (!carries_q || sticks) continue;
        // Q below mu P needs a stick zone: the leading node in contact sticks.
        for (Index m = 0; m < end - begin; ++m) {
          const Index i = travel > 0.0 ? end - 1 - m : begin + m;
          if (next.zone[static_cast<std::size_t>(i)] == Zone::Open) continue;
          next.zone[static_cast<std::size_t>(i)] = Zone::Stick;
          break;
        }
      }
      stable = next == sets;
      sets = std::move(next);
    }
    if (!stable) {
      out.message = fmt::format("the roller's contact: its nodes in contact and sticking do not settle in {} passes",
                                kActiveSetPasses);
      return out;
    }
    last_v = out.v + out.rim;
    out.v = v0 + cn * lambda_n + ct * lambda_t;
    if (elastic) out.rim = hn * lambda_n + ht * lambda_t;
    out.lambda_n = lambda_n;
    out.lambda_t = lambda_t;
    out.height += dh;
    out.creep += dcreep;
    out.sets = sets;
  }
  out.message = fmt::format("the roller's contact: its gaps and slips do not settle in {} Newton steps", kNewtonSteps);
  return out;
}

CondensedContact::Press CondensedContact::solve(const VecX& u, const VecX& b, const CondensedLoad& load) {
  std::vector<Vec2> base;
  for (std::size_t i = 0; i < nodes_.size(); ++i) base.push_back(reference_[i] + u.segment<2>(2 * nodes_[i]));
  Small small;
  Press out;
  ROLLER_ASSERT(b.size() == free_, "a load on the free dofs");
  VecX padded = VecX::Zero(unknowns_);  // the tangent's unknowns after the free dofs carry no load
  padded.head(b.size()) = b;
  out.du = solver_.solve_with_schur(padded, [&](const VecX& reduced) {
    small = solve_small(base, reduced, load);
    return small.message.empty() ? small.v : VecX::Zero(reduced.size());
  });
  if (!small.message.empty()) return {VecX(), {}, {}, 0.0, small.message};
  for (std::size_t k = 0; k < places_.size(); ++k)
    if (small.lambda_n(first_[k]) > 0.0 || small.lambda_n(first_[k + 1] - 1) > 0.0)
      return {VecX(),
              {},
              {},
              0.0,
              fmt::format("the roller's contact reaches the end of the nodes condensed under it ({:.6g} to {:.6g} mm)",
                          places_[k].positions.front().x(), places_[k].positions.back().x())};
  out.du.conservativeResize(b.size());
  sets_ = small.sets;
  height_ = small.height;
  creep_ = small.creep;
  out.pose.centre = Vec2(places_.front().centre_x, small.height(0));
  out.creep = small.creep(0);
  const auto n = static_cast<Index>(nodes_.size());
  for (Index i = 0; i < n; ++i) {
    NodeContactRecord c;
    c.node = nodes_[static_cast<std::size_t>(i)];
    c.position = base[static_cast<std::size_t>(i)] + small.v.segment<2>(2 * i);
    const int k = place_of_[static_cast<std::size_t>(i)];
    const Vec2 d =
        c.position + small.rim.segment<2>(2 * i) - Vec2(places_[static_cast<std::size_t>(k)].centre_x, small.height(k));
    const Zone zone = small.sets.zone[static_cast<std::size_t>(i)];
    c.contact.normal_force = zone != Zone::Open ? small.lambda_n(i) : 0.0;
    c.contact.tangential_force = zone != Zone::Open ? small.lambda_t(i) : 0.0;
    c.contact.gap = d.norm() - radius_;
    c.contact.slip = small.slip(i);
    // Frictionless contact slips wherever it touches.
    c.contact.status = zone == Zone::Open    ? ContactStatus::Open
                       : zone == Zone::Stick ? ContactStatus::Stick
                                             : ContactStatus::Slip;
    c.tributary_length = tributary_[static_cast<std::size_t>(i)];
    const Vec2 normal = d.normalized();
    c.force = c.contact.normal_force * normal + c.contact.tangential_force * Vec2(-normal.y(), normal.x());
    out.contact.push_back(c);
  }
  return out;
}

}  // namespace roller
