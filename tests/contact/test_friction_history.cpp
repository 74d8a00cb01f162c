// Seeding the friction fixed point within one increment (contact/friction_history.hpp): a later
// pass takes each node's normal force from the earlier solve, by node, open nodes zero, and
// leaves nodes that were no candidate then, and the penalty's tangential history, alone.
#include <catch2/catch.hpp>

#include "roller/contact/friction_history.hpp"

using namespace roller;

TEST_CASE("seed_normal_forces takes the last pass's normal forces by node", "[contact][friction]") {
  auto candidate = [](Index node, Real fn_guess, Real ft) {
    ContactCandidate c;
    c.node = node;
    c.normal_force_guess = fn_guess;
    c.tangential_force = ft;
    return c;
  };
  auto contact = [](ContactStatus status, Real fn) {
    NodeContact n;
    n.status = status;
    n.normal_force = fn;
    return n;
  };
  // Last pass: nodes 7 (stick, 5 N), 3 (open with a stale force), 9 (slip, 2 N).
  const std::vector<ContactCandidate> last{candidate(7, 0, 0), candidate(3, 0, 0), candidate(9, 0, 0)};
  const std::vector<NodeContact> result{contact(ContactStatus::Stick, 5.0), contact(ContactStatus::Open, 1.0),
                                        contact(ContactStatus::Slip, 2.0)};
  // This pass: another order, node 4 new.
  std::vector<ContactCandidate> next{candidate(9, 8.0, -1.0), candidate(4, 6.0, 0.5), candidate(3, 4.0, 0.0),
                                     candidate(7, 1.0, 0.25)};
  seed_normal_forces(next, last, result);
  CHECK(next[0].normal_force_guess == 2.0);
  CHECK(next[1].normal_force_guess == 6.0);  // no earlier solve: the committed seed stays
  CHECK(next[2].normal_force_guess == 0.0);  // open in the last pass
  CHECK(next[3].normal_force_guess == 5.0);
  // The committed tangential forces are untouched.
  CHECK(next[0].tangential_force == -1.0);
  CHECK(next[1].tangential_force == 0.5);
  CHECK(next[3].tangential_force == 0.25);
}
