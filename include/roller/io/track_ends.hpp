#pragma once
// Where a run's residual stress is a finite track's: a transient pass rolls the roller over a
// stretch of the strip, and the unrolled strip beyond the track's ends holds the rolled layer
// back, so the residual stress and ratchet measured in passes.csv's window differ from a long
// track's (docs/validation.md, Stationary passes against transient passes). A stationary pass,
// and a periodic strip rolled over its whole period, have no track ends.
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "roller/analysis/shakedown.hpp"
#include "roller/io/scene.hpp"

namespace roller {

enum class TrackKind { Finite, Endless, Long };
template <>
struct EnumNames<TrackKind> {
  static constexpr std::array<std::pair<TrackKind, const char*>, 3> names{
      {{TrackKind::Finite, "finite"}, {TrackKind::Endless, "periodic"}, {TrackKind::Long, "long"}}};
};

struct TrackEnds {
  TrackKind kind = TrackKind::Finite;
  Real start = 0.0, end = 0.0;                // the roller's centre at the travel's ends, start <= end [mm] (finite)
  Real window_start = 0.0, window_end = 0.0;  // passes.csv's window [mm]
  Real half_width = 0.0;                      // the pass's contact half-width a [mm]
  // The window's distance to the nearer end, in a (finite tracks).
  Real window_to_end() const;
  // What the residual stress of the window is, and how to get a long track's.
  std::string note() const;
  nlohmann::json to_json() const;
};

// The track of a pass run of `scene` whose record is `pass`; none when the scene has no roller
// travelling along the strip or the pass saw no contact.
std::optional<TrackEnds> track_ends(const Scene& scene, const PassRecord& pass);

}  // namespace roller
