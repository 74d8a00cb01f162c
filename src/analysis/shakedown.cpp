#include "roller/analysis/shakedown.hpp"

#include <cmath>

#include <fmt/format.h>

namespace roller {

ShakedownClassification classify_passes(const std::vector<PassRecord>& passes, const ShakedownCriteria& c) {
  ShakedownClassification out;
  if (static_cast<int>(passes.size()) < c.min_passes) {
    out.criterion = fmt::format("{} passes: at least {} are needed to tell how the plastic strain develops",
                                passes.size(), c.min_passes);
    return out;
  }
  const PassRecord& first = passes.front();
  const PassRecord& last = passes.back();
  if (first.max_plastic_increment == 0.0) {
    out.verdict = ShakedownVerdict::ElasticShakedown;
    out.criterion = "no plastic strain in pass 1: the strip stays elastic";
    return out;
  }
  const Real ratio = last.mean_plastic_increment / first.mean_plastic_increment;
  if (ratio <= c.elastic_fraction) {
    out.verdict = ShakedownVerdict::ElasticShakedown;
    out.criterion = fmt::format(
        "the mean increment of equivalent plastic strain in the track fell to {:.3g} of pass 1's in pass {} (elastic "
        "shakedown: <= {:g})",
        ratio, last.pass, c.elastic_fraction);
    return out;
  }
  // Still falling: under a sliding traction every plastic increment shears one way, so the net
  // shear test below would call increments that die out ratchetting.
  const PassRecord& before = passes.size() >= 2 ? passes[passes.size() - 2] : last;
  if (before.mean_plastic_increment > 0.0 &&
      last.mean_plastic_increment < c.settled_ratio * before.mean_plastic_increment) {
    out.criterion = fmt::format(
        "the mean increment of equivalent plastic strain is {:.3g} of pass 1's in pass {} (elastic shakedown: <= {:g}) "
        "and still falls: {:.3g} of pass {}'s (settled: >= {:g}); run more passes",
        ratio, last.pass, c.elastic_fraction, last.mean_plastic_increment / before.mean_plastic_increment, before.pass,
        c.settled_ratio);
    return out;
  }
  // Plastic strain still grows: a closed cycle adds no net strain, ratchetting does.
  const Real accumulated = std::sqrt(3.0) * last.band_plastic_increment;
  const Real net = std::abs(last.residual_shear_increment);
  const Real share = accumulated > 0.0 ? net / accumulated : 0.0;
  out.verdict = share > c.ratchet_fraction ? ShakedownVerdict::Ratchetting : ShakedownVerdict::PlasticShakedown;
  out.criterion = fmt::format(
      "the mean increment of equivalent plastic strain stays at {:.3g} of pass 1's in pass {} (elastic shakedown: <= "
      "{:g}); at the depth of maximum shear the net shear strain of that pass is {:.3g} of its accumulated plastic "
      "shear sqrt(3) d(eps_p) ({}: {} {:g})",
      ratio, last.pass, c.elastic_fraction, share, share > c.ratchet_fraction ? "ratchetting" : "closed cycle",
      share > c.ratchet_fraction ? ">" : "<=", c.ratchet_fraction);
  return out;
}

}  // namespace roller
