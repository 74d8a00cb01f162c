#pragma once
// The contact of a solved increment node by node, as a run keeps it (the next increment's
// friction, the outputs, the stationary pass's load): positions, states and forces.
#include <vector>

#include "roller/contact/backend.hpp"
#include "roller/contact/increment_types.hpp"
#include "roller/core/types.hpp"

namespace roller {

// Contact result of one node at the end of a step (for output).
struct NodeContactRecord {
  Index node = 0;
  Vec2 position = Vec2::Zero();
  NodeContact contact;
  Real tributary_length = 0.0;
  Real element_size = 0.0;    // depth of the surface element under the node (penalty scale)
  Vec2 force = Vec2::Zero();  // force of the roller on the node [N per mm width]
};

// The contact of a converged increment, node by node, with the roller centred at `centre`.
std::vector<NodeContactRecord> contact_records(const IncrementSolution& solution, const Vec2& centre);

// The nodes of `contact` that touch the roller (status not open).
inline Index count_in_contact(const std::vector<NodeContactRecord>& contact) {
  Index n = 0;
  for (const auto& c : contact) n += c.contact.status != ContactStatus::Open ? 1 : 0;
  return n;
}

// The force of the strip on the roller: the nodes' contact forces on the strip, reversed [N per mm].
inline Vec2 force_on_roller(const std::vector<NodeContactRecord>& contact) {
  Vec2 f = Vec2::Zero();
  for (const auto& c : contact) f -= c.force;
  return f;
}

}  // namespace roller
