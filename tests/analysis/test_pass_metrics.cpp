// The per-pass record's window (analysis/pass_metrics): its scale is Hertz's half-width of the
// largest contact force, so a node at the contact's edge that carries a small force under one
// backend and none under the other does not move the window (docs/scenes.md, passes.csv).
#include <catch2/catch.hpp>

#include <vector>

#include "../support/strip_spec.hpp"
#include "roller/analysis/pass_metrics.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/mesh/strip_mesher.hpp"

using namespace roller;

namespace {

// A pass of three steps over nodes 0.5 mm apart; `edge_node` adds a node with a small pressure
// at the leading edge of the middle step, as a penalty contact may count where ipopt does not.
PassTrack rolled_track(bool edge_node) {
  PassTrack t;
  for (int step = 0; step < 3; ++step) {
    const Real centre = 3.0 + step;
    std::vector<Real> x{centre - 0.5, centre, centre + 0.5}, p{400.0, 800.0, 400.0};
    if (edge_node && step == 1) {
      x.push_back(centre + 1.0);
      p.push_back(1.0);
    }
    t.observe(centre, x, p, 0.6);
  }
  return t;
}

}  // namespace

TEST_CASE("pass record: the window's depth is Hertz's half-width of the force, not the outermost node in contact",
          "[passes]") {
  MaterialParams elastic;  // the strip is only measured: its material does not matter
  elastic.youngs_modulus = 2.1e5;
  StripModel strip(make_strip_mesh(test::strip_spec(ElementType::Q4, 8.0, 4.0, 16, 8)), elastic,
                   ElementOptions{Kinematics::Small, Q4Formulation::BBar});
  const PassBaseline start = PassBaseline::of(strip);
  const PassTrack without = rolled_track(false), with = rolled_track(true);
  // The outermost nodes say 0.5 mm, and 0.75 mm with the edge node; the force's scale is 0.6.
  CHECK(without.half_width == Approx(0.5));
  CHECK(with.half_width == Approx(0.75));
  CHECK(with.load_half_width == without.load_half_width);

  const PassRecord a = measure_pass(1, strip, 4.0, without, start);
  const PassRecord b = measure_pass(1, strip, 4.0, with, start);
  CHECK(a.shear_depth == Approx(0.78 * 0.6));
  CHECK(b.shear_depth == a.shear_depth);
  CHECK(b.track_start == a.track_start);
  CHECK(b.track_end == a.track_end);
  CHECK(b.contact_half_width == Approx(0.75));  // reported as measured
  CHECK(b.peak_pressure == Approx(800.0));
}
