// The open/stick/slip status of a node at an interior-point solution: the rule on its own, and
// the contact edges of a Cattaneo-Mindlin case at nu = 0.3, where the barrier leaves force on
// nodes that are apart (docs/model.md, "Stick, slip and open at an interior-point solution").
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <string>

#include "contact/ipopt/ipopt_common.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;
using roller::ipopt_detail::contact_status;
using roller::ipopt_detail::open_force;

TEST_CASE("contact status: open below the force floor, slip when it slips or slips on the cone, stick otherwise",
          "[contact][status]") {
  // Values of the refine-2 case below (steps 5-8: the roller moves about 5e-3 mm a step).
  const Real mu = 0.15, fn_max = 442.0, length = 5e-3;
  const Real floor = open_force(fn_max, 1e3);
  CHECK(floor == Approx(0.0442));
  CHECK(open_force(1e-9, 1e4) == Approx(1e-2));  // a lifted roller: the problem's force scale
  auto status = [&](Real fn, Real ft, Real gap, Real slip) {
    NodeContact c;
    c.normal_force = fn;
    c.tangential_force = ft;
    c.gap = gap;
    c.slip = slip;
    return contact_status(c, floor, mu * fn, length);
  };
  CHECK(status(0.0045, 1e-5, 2.1e-4, -2.0e-4) == ContactStatus::Open);  // apart, the barrier's force
  // At the edge, barely touching: its slip is its neighbours', its traction off the cone.
  CHECK(status(0.0893, 0.00983, 1.3e-5, -3.0e-4) == ContactStatus::Slip);
  CHECK(status(5.4, 0.81, 1.8e-7, -3.66e-4) == ContactStatus::Slip);     // on the cone, slipping
  CHECK(status(442.0, 59.3, 2.8e-9, -1.64e-7) == ContactStatus::Stick);  // the barrier's slip of a stick node
  CHECK(status(300.0, 44.99, 3e-9, 1e-11) == ContactStatus::Stick);      // on the cone, not moving: the stick edge
  CHECK(status(300.0, 44.9, 3e-9, 1e-7) == ContactStatus::Slip);         // on the cone, moving a little
  CHECK(status(300.0, 43.0, 3e-9, 1e-7) == ContactStatus::Stick);        // off the cone, moving a little
  CHECK(status(0.01, 0.0, 0.0, 0.0) == ContactStatus::Stick);  // touching (no gap) below the floor: in contact
  // Without friction: slip when it moves.
  NodeContact frictionless;
  frictionless.normal_force = 300.0;
  frictionless.slip = 1e-7;
  CHECK(contact_status(frictionless, floor, 0.0, length) == ContactStatus::Slip);
  frictionless.slip = 1e-9;
  CHECK(contact_status(frictionless, floor, 0.0, length) == ContactStatus::Stick);
}

TEST_CASE(
    "contact status: at the edges of a Cattaneo-Mindlin contact the nodes that slip are slip and the ones "
    "apart are open",
    "[contact][status][cattaneo]") {
  // Before: at refine 2, nu = 0.3, outermost nodes carried 0.005-0.09 N/mm (up to 2e-4 of the
  // largest) at gaps of 1e-5 to 2e-4 mm, slipped 2e-4 to 3e-4 mm like their slipping neighbours
  // and were labelled stick.
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/cattaneo_mindlin.toml",
                            {{"material.nu", "0.3"}, {"mesh.refine", "2"}}));
  int n_stick = 0, n_slip = 0;
  for (int step = 1; step <= sim.scene().total_steps(); ++step) {
    REQUIRE(sim.advance_step(step).converged());
    if (step < 5) continue;  // the frictionless press
    Real fn_max = 0.0;
    for (const auto& c : sim.state().contact) fn_max = std::max(fn_max, c.contact.normal_force);
    for (const auto& c : sim.state().contact) {
      const NodeContact& n = c.contact;
      INFO("step " << step << " node " << c.node << " x " << c.position.x() << " F_N " << n.normal_force << " F_T "
                   << n.tangential_force << " gap " << n.gap << " slip " << n.slip);
      switch (n.status) {
        case ContactStatus::Open: CHECK(n.normal_force <= 1e-4 * fn_max); break;
        case ContactStatus::Stick:
          ++n_stick;
          CHECK(std::abs(n.slip) < 1e-6);  // the steps move the roller 5e-3 mm
          break;
        case ContactStatus::Slip:
          ++n_slip;
          CHECK(std::abs(n.slip) > 1e-8);
          // Off the edge (the barrier's force at the edge leaves the cone unreached), on the cone.
          if (n.normal_force > 1e-2 * fn_max) CHECK(std::abs(n.tangential_force) >= 0.99 * 0.15 * n.normal_force);
          break;
      }
      // A node that slips like the slip zone (1e-5 mm and more) and carries force is labelled slip.
      if (std::abs(n.slip) > 1e-5 && n.normal_force > 1e-4 * fn_max) CHECK(n.status == ContactStatus::Slip);
    }
  }
  CHECK(n_stick > 0);
  CHECK(n_slip > 0);
}
