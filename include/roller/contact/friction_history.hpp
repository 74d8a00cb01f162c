#pragma once
// The friction history: the committed contact of every node that touched the roller in the last
// converged increment. The next increment starts its friction law from it (the tangential force
// F_T^n of the penalty return map, the normal force that starts the ipopt fixed point;
// docs/model.md, Friction fixed point). Open nodes carry no history.
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "roller/contact/backend.hpp"

namespace roller {

class FrictionHistory {
 public:
  // Gives each candidate its node's committed forces (candidates without history keep zeros).
  void seed(std::vector<ContactCandidate>& candidates) const;
  // Replaces the history by the contact of a converged increment (same order as candidates).
  void record(const std::vector<ContactCandidate>& candidates, const std::vector<NodeContact>& contact);
  // Whether any node touched the roller at the end of the last converged increment (kept in the
  // state files, so a resumed run knows it too).
  bool touching() const { return !nodes_.empty(); }

  // State files: [node, F_N, F_T, gap, slip, status] per node, and back (throws
  // nlohmann::json::exception on a damaged list).
  nlohmann::json save() const;
  void load(const nlohmann::json& list);

 private:
  std::map<Index, NodeContact> nodes_;
};

// Within one increment: gives each candidate the normal force of the same node in an earlier
// solve (`last`, with its result `contact`, same order), open nodes zero; nodes that were no
// candidate keep their seed. Only the ipopt fixed point's start changes (normal_force_guess):
// the committed tangential forces stay the penalty return map's history.
void seed_normal_forces(std::vector<ContactCandidate>& candidates, const std::vector<ContactCandidate>& last,
                        const std::vector<NodeContact>& contact);

}  // namespace roller
