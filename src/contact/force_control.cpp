#include "roller/contact/force_control.hpp"

#include <cmath>

#include <fmt/format.h>

namespace roller {

namespace {

struct Sample {
  Real w = 0.0;
  Real r = 0.0;           // F(w) - target: positive when the roller is too deep (too far back)
  bool touching = false;  // on the force law's smooth part: vertical F(w) > 0; horizontal always
};

// The words of the messages for each axis.
struct AxisWords {
  const char* position;  // what w moves
  const char* motion;    // the key that prescribes the motion instead
  const char* cause;     // why nothing may carry the load
};

AxisWords words(ForceAxis axis) {
  if (axis == ForceAxis::Vertical)
    return {"height", "dy",
            "the roller has left the strip, or the strip gives way under it; check the load and the "
            "roller's start"};
  return {"x", "dx",
          "the roller slides: |fx| must stay below about friction x fy, and the strip carries no "
          "horizontal force without friction or an indentation to push against; lower fx, raise the "
          "friction or the vertical load"};
}

}  // namespace

ForceControlResult solve_for_force(Real target, Real w0, const ForceControlSettings& settings,
                                   const std::function<std::optional<Real>(Real)>& force_at) {
  ForceControlResult out;
  // The bracket: r > 0 below the root (deep), r < 0 above it (shallow). `weight` is the residual
  // false position uses: Illinois halves the one kept at an end that survives twice in a row.
  struct End {
    Sample s;
    Real weight = 0.0;
  };
  std::optional<End> deep, shallow;
  enum class Side { None, Deep, Shallow } last_replaced = Side::None;
  std::optional<Sample> last_touching;  // for the secant slope: only samples in contact (the
                                        // force law has a kink where contact is lost)
  Real slope = settings.stiffness_guess;
  // Newton's step is multiplied by `growth`, doubled each time a sample in contact moves the force
  // away from the target or not at all (a sliding roller's force stays at the Coulomb bound), so
  // that a load nothing carries reaches max_offset_change in a few solves instead of a crawl.
  Real growth = 1.0;
  Real search_step = 0.0;  // above the strip: the last step down, doubled each time
  Real w = w0;
  for (int it = 1; it <= settings.max_iterations; ++it) {
    const std::optional<Real> f = force_at(w);
    out.iterations = it;
    out.offset = w;
    if (!f) {
      out.message = fmt::format("the contact solve failed with the roller centre's {} {:.6g} mm off its path",
                                words(settings.axis).position, w);
      return out;
    }
    out.force = *f;
    const Sample now{w, *f - target, settings.axis == ForceAxis::Horizontal || *f > 0.0};
    if (std::abs(now.r) <= settings.force_tolerance) {
      out.status = Termination::Converged;
      out.stiffness = slope;
      return out;
    }
    if (now.touching) {
      if (last_touching && last_touching->w != now.w) {
        const Real secant = -(now.r - last_touching->r) / (now.w - last_touching->w);
        if (secant > 0.0 && std::isfinite(secant)) {
          slope = secant;
          growth = 1.0;
        } else {
          growth *= 2.0;
        }
      }
      last_touching = now;
    }
    const bool bracketed = deep && shallow;
    if (now.r > 0.0) {
      if (bracketed && last_replaced == Side::Deep) shallow->weight *= 0.5;
      deep = End{now, now.r};
      last_replaced = Side::Deep;
    } else {
      if (bracketed && last_replaced == Side::Shallow) deep->weight *= 0.5;
      shallow = End{now, now.r};
      last_replaced = Side::Shallow;
    }
    // Newton with the contact's slope from the last sample in contact; above the strip (no sample
    // in contact yet), a search downwards whose step doubles.
    Real w_next;
    if (now.touching || last_touching) {
      const Sample& from = now.touching ? now : *last_touching;
      w_next = from.w + growth * from.r / slope;
    } else {
      search_step = search_step == 0.0 ? now.r / slope : 2.0 * search_step;
      w_next = now.w + search_step;
    }
    if (deep && shallow) {
      const Real lo = std::min(deep->s.w, shallow->s.w), hi = std::max(deep->s.w, shallow->s.w);
      if (hi - lo <= 1e-14 * std::max(1.0, std::abs(w))) {
        const Sample& best = std::abs(deep->s.r) < std::abs(shallow->s.r) ? deep->s : shallow->s;
        if (std::abs(best.r) <= settings.jump_tolerance) {
          // The last solve is the solution the increment keeps: solve at the better end again.
          const std::optional<Real> again = best.w == w ? f : force_at(best.w);
          if (again && std::abs(*again - target) <= settings.jump_tolerance) {
            out.iterations = it + (best.w == w ? 0 : 1);
            out.offset = best.w;
            out.force = *again;
            out.status = Termination::Converged;
            out.stiffness = slope;
            return out;
          }
        }
        out.message = fmt::format(
            "the force on the roller jumps across the prescribed {:.6g} N/mm within {:.3g} mm of the centre's {} "
            "(last {:.6g} N/mm): take smaller steps (a larger steps.count, or steps.max_cuts)",
            target, hi - lo, words(settings.axis).position, out.force);
        return out;
      }
      if (!(w_next > lo && w_next < hi))  // Newton left the bracket: Illinois false position
        w_next = deep->s.w - deep->weight * (shallow->s.w - deep->s.w) / (shallow->weight - deep->weight);
    }
    if (!(std::abs(w_next - w0) <= settings.max_offset_change)) {
      const AxisWords wd = words(settings.axis);
      out.message = fmt::format(
          "the roller's {} would have to move more than {:.3g} mm to bring the force from {:.6g} to the prescribed "
          "{:.6g} N/mm: nothing carries the load ({}), or prescribe the motion ({}) instead",
          wd.position, settings.max_offset_change, *f, target, wd.cause, wd.motion);
      return out;
    }
    w = w_next;
  }
  out.status = Termination::LimitReached;
  out.message = fmt::format(
      "the roller's {} under the prescribed force {:.6g} N/mm did not converge in {} contact solves (force {:.6g} "
      "N/mm): take smaller steps (a larger steps.count, or steps.max_cuts)",
      words(settings.axis).position, target, settings.max_iterations, out.force);
  return out;
}

}  // namespace roller
