#pragma once
// Fields of the strip written per step (docs/scenes.md, Outputs): displacement at nodes; per
// element the integration-point averages of stress, sqrt(I2), von Mises stress, total strain,
// equivalent plastic strain and plastic work, the element's layer and initial yield stress, and
// the strain of the step's increment (the thesis's updated-Lagrangian strain,
// StripModel::increment_strain); stress and strains averaged to the nodes (for smooth contour
// maps). Tensors have ParaView's six components XX, YY, ZZ, XY,
// YZ, XZ (YZ = XZ = 0).
#include <vector>

#include "roller/assembly/strip_model.hpp"
#include "roller/io/vtu_writer.hpp"

namespace roller {

struct StripFields {
  std::vector<VtuField> point_data;
  std::vector<VtuField> cell_data;
};

// `step_increment`: the step's displacement increment over all dofs (zero at step 0).
StripFields strip_fields(const StripModel& model, const VecX& step_increment);

}  // namespace roller
