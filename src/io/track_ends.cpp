#include "roller/io/track_ends.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "roller/contact/roller.hpp"
#include "roller/io/roller_start.hpp"

namespace roller {

Real TrackEnds::window_to_end() const { return std::min(window_start - start, end - window_end) / half_width; }

std::string TrackEnds::note() const {
  switch (kind) {
    case TrackKind::Long: return "the residual stress is a long track's (stationary passes)";
    case TrackKind::Endless:
      return "the residual stress is an endless track's (a periodic strip rolled over its whole period)";
    case TrackKind::Finite: break;
  }
  // A track shorter than 4a is its own window.
  const Real distance = window_to_end();
  const std::string where = distance < 0.05 ? std::string("bound passes.csv's window")
                                            : fmt::format("lie {:.2g}a from passes.csv's window", distance);
  return fmt::format(
      "the residual stress is a finite track's: the track's ends (the roller's centre at x = {:.4g} and {:.4g} mm) "
      "{} (x = {:.4g} to {:.4g} mm) and hold the rolled layer back; for a long track's, passes.method = "
      "\"stationary\" or a periodic strip rolled over its whole period (docs/validation.md, Stationary passes "
      "against transient passes)",
      start, end, where, window_start, window_end);
}

nlohmann::json TrackEnds::to_json() const {
  nlohmann::json j{{"kind", enum_name(kind)},
                   {"window_mm", {window_start, window_end}},
                   {"half_width_mm", half_width},
                   {"note", note()}};
  if (kind == TrackKind::Finite) {
    j["ends_mm"] = {start, end};
    j["window_to_end_over_a"] = window_to_end();
  }
  return j;
}

std::optional<TrackEnds> track_ends(const Scene& scene, const PassRecord& pass) {
  if (!scene.roller || !(pass.contact_half_width > 0.0) || !(pass.track_end > pass.track_start)) return std::nullopt;
  const PathSegment* travel = travel_segment(*scene.roller);
  if (!travel) return std::nullopt;
  TrackEnds out;
  out.window_start = pass.track_start;
  out.window_end = pass.track_end;
  out.half_width = pass.contact_half_width;
  if (scene.passes.method == PassMethod::Stationary) {
    out.kind = TrackKind::Long;
  } else if (scene.mesh.periodic && std::abs(travel->dx) >= scene.mesh.length * (1.0 - 1e-9)) {
    out.kind = TrackKind::Endless;
  } else {
    const Vec2 centre = given_start_centre(scene);
    const Real from = roller_pose(*scene.roller, centre, travel->first_step - 1).centre.x();
    const Real to = roller_pose(*scene.roller, centre, travel->last_step).centre.x();
    out.start = std::min(from, to);
    out.end = std::max(from, to);
  }
  return out;
}

}  // namespace roller
