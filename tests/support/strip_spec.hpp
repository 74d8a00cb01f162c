#pragma once
// A structured strip mesh spec in one line (tests build many small strips).
#include "roller/mesh/strip_mesher.hpp"

namespace roller::test {

inline StripMeshSpec strip_spec(ElementType element, Real length, Real height, int nx, int ny,
                                Diagonal diagonal = Diagonal::Rising) {
  StripMeshSpec spec;
  spec.element = element;
  spec.length = length;
  spec.height = height;
  spec.nx = nx;
  spec.ny = ny;
  spec.diagonal = diagonal;
  return spec;
}

}  // namespace roller::test
