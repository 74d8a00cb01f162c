#include "roller/dynamics/dynamics_state.hpp"

#include <fmt/format.h>

#include "roller/core/error.hpp"
#include "roller/core/json_vectors.hpp"

namespace roller {

namespace {

// M restricted to the free dofs (rows and columns in free numbering).
SparseMatrix restrict_to_free(const SparseMatrix& m, const DofMap& dofs) {
  std::vector<Triplet> t;
  for (int k = 0; k < m.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(m, k); it; ++it) {
      const Index i = dofs.free_index(it.row()), j = dofs.free_index(it.col());
      if (i >= 0 && j >= 0) t.emplace_back(static_cast<int>(i), static_cast<int>(j), it.value());
    }
  SparseMatrix out(dofs.n_free(), dofs.n_free());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

nlohmann::json history_json(const HouboltHistory& h) {
  return {{"dt", h.dt()}, {"u_n", to_list(h.u_n())}, {"u_nm1", to_list(h.u_nm1())}, {"u_nm2", to_list(h.u_nm2())}};
}

HouboltHistory history_from(const nlohmann::json& j) {
  return HouboltHistory::from_values(to_vec(j.at("u_n")), to_vec(j.at("u_nm1")), to_vec(j.at("u_nm2")),
                                     j.at("dt").get<Real>());
}

}  // namespace

DynamicsState::DynamicsState(const StripModel& model, bool strip_inertia, bool lumped_mass,
                             const std::optional<SuspensionSpec>& suspension, Real dt)
    : strip_inertia_(strip_inertia) {
  if (strip_inertia_) {
    mass_ = model.mass_matrix(lumped_mass);
    mass_free_ = restrict_to_free(mass_, model.dof_map());
    strip_step_history_ = HouboltHistory::at_rest(model.total_displacement(), dt);
    strip_history_ = strip_step_history_;
    velocity_ = VecX::Zero(model.n_dofs());
    acceleration_ = VecX::Zero(model.n_dofs());
  }
  if (suspension) {
    suspension_step_ = Suspension(*suspension, HouboltHistory::at_rest(VecX::Zero(1), dt));
    suspension_ = suspension_step_;
  }
}

std::optional<InertiaTerm> DynamicsState::begin_increment(Real h) {
  if (suspension_ && suspension_->history().dt() != h) suspension_->history() = suspension_->history().resampled(h);
  if (!strip_inertia_) return std::nullopt;
  if (strip_history_.dt() != h) strip_history_ = strip_history_.resampled(h);
  return InertiaTerm{&mass_, &mass_free_, strip_history_.acceleration_coefficient(),
                     mass_ * (strip_history_.acceleration_coefficient() * strip_history_.u_n() +
                              strip_history_.acceleration_offset())};
}

void DynamicsState::commit_increment(const VecX& total_displacement, Real deflection) {
  if (strip_inertia_) strip_history_.advance(total_displacement);
  if (suspension_) suspension_->history().advance(VecX::Constant(1, deflection));
}

void DynamicsState::finish_step(const VecX& total_displacement) {
  if (strip_inertia_) {
    velocity_ = strip_step_history_.velocity(total_displacement);
    acceleration_ = strip_step_history_.acceleration(total_displacement);
    strip_step_history_.advance(total_displacement);
    strip_history_ = strip_step_history_;
  }
  if (suspension_) {
    const Real w = suspension_->deflection();
    suspension_velocity_ = suspension_step_->velocity(w);
    suspension_acceleration_ = suspension_step_->acceleration(w);
    suspension_step_->history().advance(VecX::Constant(1, w));
    suspension_ = suspension_step_;
  }
}

Real DynamicsState::kinetic_energy() const {
  if (velocity_.size() == 0) return 0.0;
  return 0.5 * velocity_.dot(mass_ * velocity_);
}

void DynamicsState::save(nlohmann::json& j) const {
  if (strip_inertia_) {
    j["strip_history"] = history_json(strip_step_history_);
    j["velocity"] = to_list(velocity_);
    j["acceleration"] = to_list(acceleration_);
  }
  if (suspension_step_) j["suspension_history"] = history_json(suspension_step_->history());
}

void DynamicsState::load(const nlohmann::json& j, const std::string& file) {
  if (j.contains("strip_history") != strip_inertia_ || j.contains("suspension_history") != suspension_step_.has_value())
    throw InputError(
        fmt::format("{}: the saved state's dynamics (strip inertia, suspension) differ from the "
                    "scene's",
                    file));
  if (strip_inertia_) {
    strip_step_history_ = history_from(j.at("strip_history"));
    strip_history_ = strip_step_history_;
    velocity_ = to_vec(j.at("velocity"));
    acceleration_ = to_vec(j.at("acceleration"));
  }
  if (suspension_step_) {
    suspension_step_->history() = history_from(j.at("suspension_history"));
    suspension_ = suspension_step_;
  }
}

}  // namespace roller
