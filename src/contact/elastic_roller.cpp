#include "roller/contact/elastic_roller.hpp"

#include <fmt/format.h>
#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>

#include "roller/assembly/strip_model.hpp"
#include "roller/core/error.hpp"
#include "roller/solver/schur_condenser.hpp"

namespace roller {

namespace {

// Beyond the fine stretch the steps grow by this ratio (elements of at most 1:1.15 neighbours),
// up to a largest step.
constexpr Real kGrowth = 1.15;
// A solid disc is held at a hub of this fraction of its radius (its axle).
constexpr Real kHubFraction = 0.1;

// Steps from `fine` growing by kGrowth (at most `largest`) that add up to `length` exactly: the
// grown steps are scaled to fit.
std::vector<Real> graded_steps(Real fine, Real length, Real largest) {
  std::vector<Real> steps;
  Real sum = 0.0, step = fine;
  while (sum + step < length) {
    steps.push_back(step);
    sum += step;
    step = std::min(step * kGrowth, largest);
  }
  if (steps.empty()) return {length};
  // The remainder goes to the last step when it is large enough, else it is spread over all.
  const Real rest = length - sum;
  if (rest > 0.5 * steps.back()) {
    steps.push_back(rest);
  } else {
    for (Real& s : steps) s *= length / sum;
  }
  return steps;
}

void check(const ElasticRollerSpec& r, const RimArc& arc) {
  require(r.radius > 0.0 && std::isfinite(r.radius), fmt::format("elastic roller: radius {} must be > 0", r.radius));
  require(r.inner_radius >= 0.0 && r.inner_radius < r.radius,
          fmt::format("elastic roller: inner_radius {} must lie in [0, radius = {})", r.inner_radius, r.radius));
  require(r.youngs_modulus > 0.0, fmt::format("elastic roller: E = {} must be > 0", r.youngs_modulus));
  require(r.poisson_ratio > -1.0 && r.poisson_ratio < 0.5,
          fmt::format("elastic roller: nu = {} must lie in (-1, 0.5)", r.poisson_ratio));
  require(arc.spacing > 0.0 && arc.half_length >= arc.spacing,
          fmt::format("elastic roller: the rim arc's half-length {} must be at least its spacing {} > 0",
                      arc.half_length, arc.spacing));
  require(arc.half_length < 0.5 * M_PI * r.radius,
          fmt::format("elastic roller: the rim arc's half-length {} must be below a quarter of the rim ({})",
                      arc.half_length, 0.5 * M_PI * r.radius));
}

}  // namespace

RollerDiscMesh roller_disc_mesh(const ElasticRollerSpec& roller, const RimArc& arc) {
  check(roller, arc);
  const Real R = roller.radius;
  // Angles from the bottom: the fine arc, then graded steps to the top (angle pi) on either side.
  const Real fine_angle = arc.spacing / R;
  const int n_fine = static_cast<int>(std::ceil(arc.half_length / arc.spacing - 1e-9));
  std::vector<Real> side;  // 0 < angles <= pi
  for (int k = 1; k <= n_fine; ++k) side.push_back(k * fine_angle);
  Real at = side.back();
  for (Real s : graded_steps(fine_angle, M_PI - at, M_PI / 16.0)) side.push_back(at += s);
  side.back() = M_PI;
  std::vector<Real> angles;  // increasing, -pi excluded (it is pi)
  for (auto it = side.rbegin() + 1; it != side.rend(); ++it) angles.push_back(-*it);
  angles.push_back(0.0);
  angles.insert(angles.end(), side.begin(), side.end());
  // Radii from the rim inwards: fine to a quarter of the arc's half-length (about a Hertz a, where
  // the contact's stresses peak), graded to the bore or hub. Fine to the whole half-length, as
  // before, gave the same contact within 0.1 % at three times the elements (docs/model.md).
  const Real inner = roller.inner_radius > 0.0 ? roller.inner_radius : kHubFraction * R;
  const Real fine_depth = std::min(0.25 * arc.half_length, 0.5 * (R - inner));
  std::vector<Real> radii{R};
  const int n_deep = static_cast<int>(std::ceil(fine_depth / arc.spacing - 1e-9));
  for (int k = 1; k <= n_deep; ++k) radii.push_back(R - k * fine_depth / n_deep);
  for (Real s : graded_steps(fine_depth / n_deep, radii.back() - inner, 0.25 * (R - inner)))
    radii.push_back(radii.back() - s);
  radii.back() = inner;
  std::reverse(radii.begin(), radii.end());  // ring 0: the bore

  RollerDiscMesh out;
  Mesh& m = out.mesh;
  m.element_type = ElementType::Q4;
  const Index n_angles = static_cast<Index>(angles.size());
  for (Real r : radii)
    for (Real a : angles) m.nodes.push_back(Vec2(r * std::sin(a), -r * std::cos(a)));
  auto node = [&](Index ring, Index j) { return ring * n_angles + (j % n_angles); };
  for (Index i = 0; i + 1 < static_cast<Index>(radii.size()); ++i)
    for (Index j = 0; j < n_angles; ++j)
      m.elements.push_back({node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
  for (Index j = 0; j < n_angles; ++j) out.bore.push_back(node(0, j));
  const Index rim = static_cast<Index>(radii.size()) - 1;
  for (Index j = 0; j < n_angles; ++j)
    if (std::abs(angles[j]) <= n_fine * fine_angle * (1.0 + 1e-12)) out.arc.push_back(node(rim, j));
  std::vector<Index> all(m.nodes.size());
  for (Index a = 0; a < static_cast<Index>(all.size()); ++a) all[a] = a;
  m.node_sets["all"] = all;
  m.node_sets["contact"] = out.arc;
  return out;
}

std::unique_ptr<StripModel> roller_disc_model(const ElasticRollerSpec& roller, const RollerDiscMesh& disc) {
  MaterialParams elastic;
  elastic.youngs_modulus = roller.youngs_modulus;
  elastic.poisson_ratio = roller.poisson_ratio;
  auto model = std::make_unique<StripModel>(disc.mesh, elastic, ElementOptions{Kinematics::Small, Q4Formulation::BBar});
  std::vector<bool> held(model->n_dofs(), false);
  for (Index a : disc.bore) held[2 * a] = held[2 * a + 1] = true;
  model->set_dof_map(DofMap(held));
  return model;
}

RimStiffness condensed_rim_stiffness(const ElasticRollerSpec& roller, const RimArc& arc) {
  const RollerDiscMesh disc = roller_disc_mesh(roller, arc);
  const std::unique_ptr<StripModel> disc_model = roller_disc_model(roller, disc);
  StripModel& model = *disc_model;
  SparseMatrix k;
  model.evaluate(VecX::Zero(model.n_dofs()), nullptr, &k);

  // The retained dofs (the arc's, x then y by node, as free indices) and the rest condensed out.
  std::vector<Index> kept;
  for (Index a : disc.arc)
    for (int c = 0; c < 2; ++c) kept.push_back(model.dof_map().free_index(2 * a + c));
  MatX schur;
  SchurCondenser condenser;
  if (condenser.condense(k, kept, kept, &schur) == SchurCondenser::Outcome::Failed)
    throw NumericalError("elastic roller: the disc's stiffness away from its rim arc is singular: " +
                         condenser.message());
  RimStiffness out;
  out.stiffness = 0.5 * (schur + schur.transpose());  // symmetric to round-off
  for (Index a : disc.arc) out.positions.push_back(disc.mesh.nodes[a]);
  return out;
}

Real rim_angle(const Vec2& from_centre) { return std::atan2(from_centre.x(), -from_centre.y()); }

Vec2 rim_radial(Real angle) { return Vec2(std::sin(angle), -std::cos(angle)); }

Real RimStiffness::arc_half_length() const {
  return positions.empty() ? 0.0 : positions.back().norm() * std::abs(rim_angle(positions.back()));
}

RimPoint rim_point(const std::vector<Vec2>& positions, Real angle) {
  const Index n = static_cast<Index>(positions.size());
  ROLLER_ASSERT(n >= 2, "rim_point: an arc of at least two nodes");
  const Real first = rim_angle(positions.front()), last = rim_angle(positions.back());
  if (!(angle >= first && angle <= last))
    throw NumericalError(
        fmt::format("elastic roller: a contact point at {:.4g} rad from the lowest point lies "
                    "outside the rim arc [{:.4g}, {:.4g}] rad: the arc is too short for the contact",
                    angle, first, last));
  RimPoint p;
  p.segment = 0;
  while (p.segment + 2 < n && rim_angle(positions[p.segment + 1]) < angle) ++p.segment;
  const Real t0 = rim_angle(positions[p.segment]), t1 = rim_angle(positions[p.segment + 1]);
  p.weight = (angle - t0) / (t1 - t0);
  return p;
}

std::vector<RimWeight> rim_sample(const std::vector<Vec2>& positions, Real angle, Real reach) {
  const Index n = static_cast<Index>(positions.size());
  const Real first = rim_angle(positions.front()), last = rim_angle(positions.back());
  if (!(reach > 0.0)) {
    const RimPoint p = rim_point(positions, std::clamp(angle, first, last));
    return {{p.segment, 1.0 - p.weight}, {p.segment + 1, p.weight}};
  }
  // The dual function psi = 2 - 3 |t - angle| / reach on [angle - reach, angle + reach], times the
  // arc nodes' hats: products of linear functions on each piece, exact with two Gauss points.
  const Real g = 0.5 / std::sqrt(3.0);
  auto psi = [&](Real t) { return 2.0 - 3.0 * std::abs(t - angle) / reach; };
  std::vector<Real> weight(static_cast<std::size_t>(n), 0.0);
  Real total = 0.0;
  Index lowest = n, highest = -1;
  for (Index s = 0; s + 1 < n; ++s) {
    const Real t0 = rim_angle(positions[s]), t1 = rim_angle(positions[s + 1]);
    for (auto [lo, hi] : {std::pair{angle - reach, angle}, {angle, angle + reach}}) {
      const Real a = std::max(lo, t0), b = std::min(hi, t1);
      if (!(b > a)) continue;
      for (Real q : {0.5 - g, 0.5 + g}) {
        const Real t = a + q * (b - a), wq = 0.5 * (b - a) * psi(t);
        const Real second = (t - t0) / (t1 - t0);
        weight[static_cast<std::size_t>(s)] += wq * (1.0 - second);
        weight[static_cast<std::size_t>(s) + 1] += wq * second;
        total += wq;
      }
      lowest = std::min(lowest, s);
      highest = std::max(highest, s + 1);
    }
  }
  // Beyond the arc's ends the rim is not held: the part inside it, normalised (far from contact).
  if (!(std::abs(total) > 0.0)) return rim_sample(positions, angle, 0.0);
  std::vector<RimWeight> out;
  for (Index k = lowest; k <= highest; ++k) out.push_back({k, weight[static_cast<std::size_t>(k)] / total});
  return out;
}

MatX rim_compliance(const RimStiffness& rim, const std::vector<Real>& angles, const std::vector<Real>& reaches) {
  ROLLER_ASSERT(angles.size() == reaches.size(), "rim_compliance: a reach per point");
  const auto m = static_cast<Index>(rim.positions.size()), n = static_cast<Index>(angles.size());
  MatX w = MatX::Zero(2 * m, 2 * n);
  for (Index j = 0; j < n; ++j) {
    const auto s = static_cast<std::size_t>(j);
    for (const RimWeight& k : rim_sample(rim.positions, angles[s], reaches[s])) {
      w(2 * k.node, 2 * j) += k.weight;
      w(2 * k.node + 1, 2 * j + 1) += k.weight;
    }
  }
  return w.transpose() * Eigen::LLT<MatX>(rim.stiffness).solve(w);
}

}  // namespace roller
