#include "roller/analysis/hertz.hpp"

#include <algorithm>
#include <cmath>

namespace roller {

namespace {

// Integral of p(x) w(x) over [x0, x1] for a smooth weight w. Inside the contact p = p0 cos(t) with
// x = a sin(t): the substitution removes the square-root edge, so composite Simpson in t is
// accurate to round-off for the few-element segments it is used on.
template <class Weight>
Real integrate_pressure(const HertzSolution& h, Real x0, Real x1, Weight w) {
  const Real lo = std::max(x0, -h.half_width), hi = std::min(x1, h.half_width);
  if (!(hi > lo)) return 0.0;
  const Real t0 = std::asin(lo / h.half_width), t1 = std::asin(hi / h.half_width);
  constexpr int kIntervals = 64;  // even
  const Real dt = (t1 - t0) / kIntervals;
  Real sum = 0.0;
  for (int k = 0; k <= kIntervals; ++k) {
    const Real t = t0 + k * dt;
    const Real c = std::cos(t);
    const Real f = h.peak * c * w(h.half_width * std::sin(t)) * h.half_width * c;
    sum += (k == 0 || k == kIntervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0)) * f;
  }
  return sum * dt / 3.0;
}

// Half the distance between the neighbours of sample i (one-sided at the ends).
Real tributary_length(const std::vector<PressureSample>& s, std::size_t i) {
  return 0.5 * ((i + 1 < s.size() ? s[i + 1].x : s[i].x) - (i > 0 ? s[i - 1].x : s[i].x));
}

// Relative discrete L2 norm of p_h - p_ref with weights = tributary lengths.
template <class Reference>
Real relative_l2(const std::vector<PressureSample>& s, Reference ref) {
  Real num = 0, den = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Real w = tributary_length(s, i);
    const Real r = ref(i);
    num += w * (s[i].p - r) * (s[i].p - r);
    den += w * r * r;
  }
  return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

}  // namespace

std::vector<Real> hertz_nodal_forces(const HertzSolution& h, const std::vector<Real>& x) {
  std::vector<Real> force(x.size(), 0.0);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const Real x0 = x[i], x1 = x[i + 1];
    force[i] += integrate_pressure(h, x0, x1, [&](Real s) { return (x1 - s) / (x1 - x0); });
    force[i + 1] += integrate_pressure(h, x0, x1, [&](Real s) { return (s - x0) / (x1 - x0); });
  }
  return force;
}

Real HertzSolution::pressure(Real x) const {
  const Real r = x / half_width;
  return std::abs(r) < 1.0 ? peak * std::sqrt(1.0 - r * r) : 0.0;
}

HertzSolution hertz_line_contact(Real load, Real radius, Real plane_strain_modulus) {
  HertzSolution h;
  h.load = load;
  h.half_width = std::sqrt(4.0 * load * radius / (M_PI * plane_strain_modulus));
  h.peak = 2.0 * load / (M_PI * h.half_width);
  return h;
}

Real hertz_line_load(Real peak_pressure, Real radius, Real plane_strain_modulus) {
  return M_PI * radius * peak_pressure * peak_pressure / plane_strain_modulus;
}

HertzComparison compare_with_hertz(const std::vector<PressureSample>& samples, Real load, Real radius,
                                   Real plane_strain_modulus) {
  HertzComparison c;
  c.analytic = hertz_line_contact(load, radius, plane_strain_modulus);
  // Fit p^2 = A - B x^2 (linear least squares in A, B) over the loaded samples. "Loaded" means
  // above 1e-6 of the peak: an interior-point solution leaves barrier-size forces (~1e-9 of the
  // peak) on open nodes, which are not contact.
  Real s1 = 0, sx2 = 0, sx4 = 0, sp2 = 0, sx2p2 = 0;
  for (const auto& s : samples) c.peak = std::max(c.peak, s.p);
  for (const auto& s : samples) {
    if (s.p <= 1e-6 * c.peak) continue;
    const Real x2 = s.x * s.x, p2 = s.p * s.p;
    s1 += 1;
    sx2 += x2;
    sx4 += x2 * x2;
    sp2 += p2;
    sx2p2 += x2 * p2;
  }
  const Real det = s1 * sx4 - sx2 * sx2;
  if (s1 >= 3 && det > 0.0) {
    const Real a_coef = (sp2 * sx4 - sx2 * sx2p2) / det;
    const Real b_coef = (sp2 * sx2 - s1 * sx2p2) / det;  // = B (positive for a cap)
    if (a_coef > 0.0 && b_coef > 0.0) c.half_width = std::sqrt(a_coef / b_coef);
  }
  c.half_width_error = (c.half_width - c.analytic.half_width) / c.analytic.half_width;
  c.peak_error = (c.peak - c.analytic.peak) / c.analytic.peak;
  Real num = 0, den = 0;
  for (std::size_t i = 0; i + 1 < samples.size(); ++i) {
    const Real dx = samples[i + 1].x - samples[i].x;
    auto sq_err = [&](const PressureSample& s) {
      const Real e = s.p - c.analytic.pressure(s.x);
      return e * e;
    };
    auto sq_ref = [&](const PressureSample& s) {
      const Real r = c.analytic.pressure(s.x);
      return r * r;
    };
    num += 0.5 * dx * (sq_err(samples[i]) + sq_err(samples[i + 1]));
    den += 0.5 * dx * (sq_ref(samples[i]) + sq_ref(samples[i + 1]));
  }
  c.l2_error = den > 0.0 ? std::sqrt(num / den) : 0.0;
  std::vector<Real> x;
  for (const auto& s : samples) x.push_back(s.x);
  const std::vector<Real> force = hertz_nodal_forces(c.analytic, x);
  c.l2_error_averaged = relative_l2(samples, [&](std::size_t i) {
    const Real tributary = tributary_length(samples, i);
    return tributary > 0.0 ? force[i] / tributary : 0.0;
  });
  return c;
}

}  // namespace roller
