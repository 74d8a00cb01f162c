#pragma once
// Where the roller starts (roller.centre, roller.touch_strip) and the checks that it starts
// where a first increment is possible: InputErrors naming the scene's keys.
#include <vector>

#include "roller/assembly/strip_model.hpp"
#include "roller/io/scene.hpp"

namespace roller {

// The scene's start centre: roller.centre, or touching the top of the strip at mid-length.
Vec2 given_start_centre(const Scene& scene);

// roller.touch_strip: how far the given start centre moves up (> 0) or down to touch the strip
// whose nodes are at `x`; InputError when no contact candidate lies under the roller.
Real touching_lift(const Scene& scene, const std::vector<Vec2>& x, const std::vector<Index>& candidates);

// InputError naming roller.centre when the roller centred at `centre` lies inside the strip or
// entirely below it.
void check_roller_starts_outside(const Scene& scene, const std::vector<Vec2>& x, const std::vector<Index>& candidates,
                                 const Vec2& centre);

// Where the scene's roller starts on `strip`: the given centre, moved by roller.touch_strip to
// touch it, checked to start outside it (InputErrors as above).
Vec2 start_centre_on(const Scene& scene, const StripModel& strip, const std::vector<Index>& candidates);

}  // namespace roller
