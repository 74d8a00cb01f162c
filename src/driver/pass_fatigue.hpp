#pragma once
// The fatigue indices of a pass that ended (analysis/fatigue.hpp; docs/model.md, Fatigue), the same
// for both step methods: its stress cycles by depth, the top layer's shear of its record, and the
// roller's force where it pressed hardest (its traction coefficient and Hertz's p0).
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "roller/analysis/fatigue.hpp"
#include "roller/analysis/pass_metrics.hpp"
#include "roller/analysis/shakedown.hpp"
#include "roller/io/roller_program.hpp"
#include "roller/io/scene.hpp"
#include "roller/io/vtu_writer.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

PassFatigue fatigue_of_pass(const Scene& scene, const PassRecord& record, Real x, const std::vector<DepthCycle>& cycles,
                            const Vec2& largest_force);

// summary.json's fatigue block and the state file's: an infinite life or index (no ratchet, no
// contact) is null, which JSON has for it.
void to_json(nlohmann::json& j, const FatigueAnswer& a);
void from_json(const nlohmann::json& j, FatigueAnswer& a);

// A stationary pass's cycles (its lanes', roller under way) framed by the strip before and after the
// pass at the same depths (the roller far away): the whole cycle a point takes.
std::vector<DepthCycle> framed(std::vector<DepthCycle> lanes, const std::vector<DepthSample>& before,
                               const std::vector<DepthSample>& after);

// A transient pass's cycles before its first step: at the middle of its travel segment, starting
// from the strip as the pass finds it (the roller far away).
PassCycles start_cycles(const Scene& scene, const RollerProgram& program, int pass, const StripModel& strip);

// The pass's indices as VTU cell fields (dang_van_index, fi_sub_index): each element whose centroid
// lies in the track window [window_start, window_end] takes the indices of the column's element
// nearest its depth (a steady pass's cycle is the same along the window); 0 elsewhere.
std::vector<VtuField> fatigue_cell_fields(const Mesh& mesh, Real strip_height, const PassFatigue& f, Real window_start,
                                          Real window_end);

}  // namespace roller
