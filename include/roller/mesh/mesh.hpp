#pragma once
// A 2D strip mesh: node coordinates, T3 or Q4 connectivity (counter-clockwise), named node sets.
//
// Numbering convention of the structured strip (the thesis's, so its node numbers are
// addressable): nodes are numbered column by column from the left edge, top to bottom within a
// column. Thesis node number N (1-based) is roller node N-1. With nx x ny elements the strip
// has (nx+1)(ny+1) nodes; e.g. Z4 (20x4 Q4): node 5 is the bottom-left corner, node 101 the
// top-right corner. Elements are numbered column by column, top to bottom, the same way.
#include <map>
#include <string>
#include <vector>

#include "roller/core/enum_names.hpp"
#include "roller/core/types.hpp"

namespace roller {

enum class ElementType { T3, Q4 };
template <>
struct EnumNames<ElementType> {
  static constexpr std::array<std::pair<ElementType, const char*>, 2> names{
      {{ElementType::Q4, "Q4"}, {ElementType::T3, "T3"}}};
};

inline int nodes_per_element(ElementType t) { return t == ElementType::T3 ? 3 : 4; }

struct Mesh {
  ElementType element_type = ElementType::Q4;
  std::vector<Vec2> nodes;                   // initial coordinates [mm]
  std::vector<std::vector<Index>> elements;  // node indices, counter-clockwise
  // Named node sets, each sorted by increasing x then y where that matters:
  //  "top", "bottom", "left", "right"     edges (top and bottom sorted by x; left/right by y)
  //  "top_left", "top_right", "bottom_left", "bottom_right"   single corner nodes
  //  "contact"                            contact candidates (default: the top edge)
  //  "all"                                every node
  std::map<std::string, std::vector<Index>> node_sets;
  // A periodic strip ([mesh] periodic, docs/model.md, Periodic strip): its right edge is its left
  // edge moved by `period` along x, so a node of the right edge is the left edge's node at the
  // same height (node_masters). 0: the strip has two free ends.
  Real period = 0.0;

  Index n_nodes() const { return static_cast<Index>(nodes.size()); }
  Index n_elements() const { return static_cast<Index>(elements.size()); }
  Index n_dofs() const { return 2 * n_nodes(); }

  // Node set by name, or throws InputError listing the known names.
  const std::vector<Index>& node_set(const std::string& name) const;
};

// Each node's master: the node itself, or for a periodic mesh's right edge the left edge's node
// at the same height (the "left" and "right" sets, both sorted by y).
std::vector<Index> node_masters(const Mesh& mesh);

// The centroid of element e's nodes (its initial coordinates).
Vec2 element_centroid(const Mesh& mesh, Index e);

// x moved by a whole number of periods to lie within half a period of `near` (a periodic mesh);
// x itself when the mesh is not periodic.
Real nearest_image_x(const Mesh& mesh, Real x, Real near);

}  // namespace roller
