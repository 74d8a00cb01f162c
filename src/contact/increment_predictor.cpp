#include "roller/contact/increment_predictor.hpp"

#include "roller/contact/arc_predictor.hpp"
#include "roller/contact/rolling_predictor.hpp"

namespace roller {

VecX increment_predictor(const StripModel& model, const std::vector<Index>& candidate_nodes, const VecX& last,
                         Real last_length, Real length, const RollerMotion* motion, IncrementPredictor mode) {
  VecX predictor = VecX::Zero(model.n_dofs());
  if (last.size() == model.n_dofs() && last_length > 0.0) predictor = last * (length / last_length);
  if (motion && mode == IncrementPredictor::Rolling)
    predictor = translate_increment(model.mesh(), model.current_coordinates(), predictor,
                                    motion->end.centre.x() - motion->start.centre.x());
  if (motion && mode == IncrementPredictor::Arc)
    apply_arc_predictor(candidate_nodes, model.current_coordinates(), model.dof_map(), *motion, predictor);
  return predictor;
}

}  // namespace roller
