// Where a run's residual stress is a finite track's: the track's ends from the scene's travel and
// their distance from passes.csv's window, for a transient pass, a stationary one and a periodic
// strip rolled over part or all of its period.
#include <catch2/catch.hpp>

#include <string>

#include <nlohmann/json.hpp>

#include "roller/io/scene_loader.hpp"
#include "roller/io/track_ends.hpp"

using namespace roller;

namespace {

const std::string kShakedown = std::string(ROLLER_SOURCE_DIR) + "/problems/shakedown_p45.toml";
const std::string kPeriodic = std::string(ROLLER_SOURCE_DIR) + "/problems/periodic_rolling.toml";

PassRecord window(Real start, Real end, Real half_width) {
  PassRecord pass;
  pass.track_start = start;
  pass.track_end = end;
  pass.contact_half_width = half_width;
  return pass;
}

}  // namespace

TEST_CASE("track ends: a transient pass on a finite strip names its ends and their distance from the window",
          "[io][passes]") {
  // shakedown_p45 rolls the roller's centre from x = 92 to 108 mm (8a, a = 2 mm); its window is the middle half.
  const std::optional<TrackEnds> finite = track_ends(load_scene(kShakedown), window(96.0, 104.0, 2.0));
  REQUIRE(finite);
  CHECK(finite->kind == TrackKind::Finite);
  CHECK(finite->start == Approx(92.0));
  CHECK(finite->end == Approx(108.0));
  CHECK(finite->window_to_end() == Approx(2.0));
  CHECK_THAT(finite->note(), Catch::Contains("a finite track's") && Catch::Contains("x = 92 and 108 mm") &&
                                 Catch::Contains("2a from passes.csv's window (x = 96 to 104 mm)") &&
                                 Catch::Contains("passes.method = \"stationary\""));
  const nlohmann::json j = finite->to_json();
  CHECK(j["kind"] == "finite");
  CHECK(j["ends_mm"][0].get<double>() == Approx(92.0));
  CHECK(j["ends_mm"][1].get<double>() == Approx(108.0));
  CHECK(j["window_to_end_over_a"].get<double>() == Approx(2.0));
  // A window off the middle: the nearer end counts.
  CHECK(track_ends(load_scene(kShakedown), window(93.0, 100.0, 0.5))->window_to_end() == Approx(2.0));
  // Rolled the other way (from x = 108 to 92 mm) the ends are the same.
  const std::optional<TrackEnds> back =
      track_ends(load_scene(kShakedown, {{"roller.centre", "[108.0, 200.0]"}, {"roller.path[1].dx", "-16.0"}}),
                 window(96.0, 104.0, 2.0));
  CHECK(back->start == Approx(92.0));
  CHECK(back->end == Approx(108.0));
  CHECK(back->window_to_end() == Approx(2.0));
  // A pass without contact has no track.
  CHECK_FALSE(track_ends(load_scene(kShakedown), PassRecord{}));
}

TEST_CASE("track ends: a stationary pass and a periodic strip rolled over its whole period have none", "[io][passes]") {
  const std::optional<TrackEnds> stationary =
      track_ends(load_scene(kShakedown, {{"passes.method", "\"stationary\""}}), window(96.0, 104.0, 2.0));
  REQUIRE(stationary);
  CHECK(stationary->kind == TrackKind::Long);
  CHECK_THAT(stationary->note(), Catch::Contains("a long track's"));
  CHECK_FALSE(stationary->to_json().contains("ends_mm"));
  // periodic_rolling rolls 24 mm of its 40 mm period: a finite track on a periodic strip.
  const PassRecord ring = window(36.0, 48.0, 1.0);
  CHECK(track_ends(load_scene(kPeriodic), ring)->kind == TrackKind::Finite);
  const std::optional<TrackEnds> endless = track_ends(
      load_scene(kPeriodic,
                 {{"steps.count", "42"}, {"roller.path[1].steps", "[3, 42]"}, {"roller.path[1].dx", "40.0"}}),
      ring);
  CHECK(endless->kind == TrackKind::Endless);
  CHECK_THAT(endless->note(), Catch::Contains("whole period"));
}
