#pragma once
// Fields of the strip written per step (docs/scenes.md, Outputs): displacement at nodes; per
// element the integration-point averages of stress, sqrt(I2), von Mises stress, total strain,
// equivalent plastic strain and plastic work; the same stress quantities averaged to the nodes
// (for smooth contour maps).
#include <vector>

#include "roller/assembly/strip_model.hpp"
#include "roller/io/vtu_writer.hpp"

namespace roller {

struct StripFields {
  std::vector<VtuField> point_data;
  std::vector<VtuField> cell_data;
};

StripFields strip_fields(const StripModel& model);

}  // namespace roller
