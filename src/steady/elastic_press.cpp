#include "roller/steady/elastic_press.hpp"

#include <utility>

#include <fmt/format.h>

#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/backend_factory.hpp"
#include "roller/contact/increment_predictor.hpp"
#include "roller/core/error.hpp"
#include "roller/io/contact_settings.hpp"
#include "roller/io/roller_start.hpp"
#include "roller/io/scene_strip.hpp"

namespace roller {

ElasticPress::ElasticPress(Scene elastic, const Mesh& mesh)
    : scene_(std::move(elastic)),
      strip_(std::make_unique<StripModel>(mesh, assign_materials(mesh, scene_.strip_material()), scene_.element)),
      loads_(scene_, mesh),
      backend_(make_increment_backend(true, scene_.contact, scene_.newton)),
      session_(contact_session_settings(scene_, mesh), *backend_, contact_candidate_nodes(scene_, mesh)) {
  strip_->set_dof_map(loads_.dof_map());
  const Vec2 start = start_centre_on(scene_, *strip_, session_.candidate_nodes());
  pose_ = roller_pose(*scene_.roller, start, 0.0);
  program_ = RollerProgram(scene_.roller, scene_.passes, scene_.steps.n_steps, start);
}

ElasticPress::~ElasticPress() = default;

IncrementReport ElasticPress::press(Real s_from, Real s_to) {
  IncrementReport report;
  const VecX prescribed = loads_.prescribed_displacement(s_to) - strip_->total_displacement();
  IncrementEnergy energy(*strip_, prescribed, loads_.external_force(s_to));  // quasi-static
  IncrementStart start;
  start.friction = &friction_;
  if (rim_.size() > 0) start.rim = &rim_;
  start.load_offset = load_offset_;
  start.load_stiffness = load_stiffness_;
  start.motion.radius = scene_.roller->radius;
  start.motion.start = pose_;
  start.motion.end = program_.pose(s_to);
  start.motion.end.centre += load_offset_;
  start.motion.friction = program_.friction(s_to, scene_.contact.friction);
  start.force = program_.force(s_to);
  start.roller_force = roller_force();
  const VecX predictor = increment_predictor(*strip_, session_.candidate_nodes(), last_increment_, last_length_,
                                             s_to - s_from, &start.motion, scene_.contact.predictor);
  const IncrementSolution solution = session_.solve(energy, prescribed, predictor, start, report);
  if (!report.converged()) return report;
  try {
    strip_->commit(solution.u);
  } catch (const NumericalError& e) {  // as a run's increment: not admissible, nothing committed
    report.status = Termination::Failed;
    report.message = fmt::format("the increment's solution is not admissible: {}", e.what());
    return report;
  }
  last_increment_ = solution.u;
  if (solution.contact.rim.size() > 0) rim_ = solution.contact.rim;
  last_length_ = s_to - s_from;
  load_offset_ = solution.load_offset;
  load_stiffness_ = solution.load_stiffness;
  pose_ = start.motion.end;
  contact_ = contact_records(solution, pose_.centre);
  friction_.record(solution.candidates, solution.contact.contact);
  return report;
}

}  // namespace roller
