// State files of a Simulation (simulation.hpp): CBOR documents (nlohmann::json's binary
// encoding keeps doubles exact) holding everything the next step reads.
#include <cmath>
#include <fstream>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pass_fatigue.hpp"
#include "roller/core/error.hpp"
#include "roller/core/json_vectors.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/atomic_file.hpp"
#include "roller/io/checksum.hpp"
#include "roller/io/scene_loader.hpp"
#include "run_model.hpp"

namespace roller {

// With defaults: a state file written before a field was added reads it as zero.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PassRecord, pass, max_plastic_increment, mean_plastic_increment,
                                                band_plastic_increment, surface_ux, surface_uy, surface_dux,
                                                surface_duy, shear_depth, residual_shear_strain,
                                                residual_shear_increment, surface_shear_increment, peak_pressure,
                                                contact_half_width, track_start, track_end, creep)

namespace {

constexpr const char* kFormat = "roller-state";
// 2: a checksum of the document and the fingerprint of the scene that wrote it.
// 3: vectors as byte strings of doubles (core/json_vectors.hpp).
constexpr int kVersion = 3;

std::string checksum(const nlohmann::json& j) {
  const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(j);
  return fnv1a_hex(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// The resolved scene without what a resumed run may change (the number of steps, or of passes
// when the run repeats a pass of steps.count steps: a shortened run is continued with more), so
// that a checkpoint continues only the run that wrote it.
std::string scene_fingerprint(const Scene& scene) {
  Scene s = scene;
  if (s.passes.count > 1)
    s.passes.count = 2;  // still a multi-pass run: the pass's steps.count must stay
  else
    s.steps.n_steps = 1;
  const std::string text = scene_to_toml(s);
  return fnv1a_hex(text);
}

// Force control's offsets and slopes: [x, y]; a single number (files written before horizontal
// force control) is the y; absent in files of runs without force control.
Vec2 offset_pair(const nlohmann::json& j, const char* key) {
  if (!j.contains(key)) return Vec2::Zero();
  const nlohmann::json& v = j.at(key);
  if (v.is_number()) return Vec2(0.0, v.get<Real>());
  return Vec2(v.at(0).get<Real>(), v.at(1).get<Real>());
}

// The run state (driver/run_state.hpp) into the document and back: every field a later step
// reads, under the keys of state-file version 3 (the contact and the roller's velocity are the
// last step's, recomputed by the next one: not saved).
void save_run_state(const RunState& s, bool multi_pass, nlohmann::json& j) {
  j["step"] = s.steps_done;
  j["last_increment"] = to_list(s.last_increment);
  j["last_length"] = s.last_length;
  j["next_pass_start"] = to_list(s.next_pass_start);
  j["pose"] = {s.pose.centre.x(), s.pose.centre.y(), s.pose.angle};
  j["load_offset"] = {s.load_offset.x(), s.load_offset.y()};
  j["load_stiffness"] = {s.load_stiffness.x(), s.load_stiffness.y()};
  if (multi_pass) {
    j["pass_track"] = s.pass_track.save();
    j["pass_baseline"] = s.pass_baseline.save();
    j["pass_records"] = s.pass_records;
    j["pass_cycles"] = s.pass_cycles.save();
    if (s.fatigue) j["fatigue"] = *s.fatigue;
  }
  j["totals"] = {
      {"iterations", s.totals.iterations}, {"cuts", s.totals.cuts}, {"max_penetration", s.totals.max_penetration}};
  j["friction_history"] = s.friction.save();
  if (s.rim.size() > 0) j["roller_rim"] = to_list(s.rim);
  j["warnings"] = s.warnings;
  j["pointwise_loss_reported"] = s.pointwise_loss_reported;
}

void load_run_state(const nlohmann::json& j, bool multi_pass, RunState& s) {
  s.steps_done = j.at("step").get<int>();
  s.last_increment = to_vec(j.at("last_increment"));
  s.last_length = j.at("last_length").get<Real>();
  if (j.contains("next_pass_start"))
    s.next_pass_start = to_vec(j.at("next_pass_start"));
  else if (s.last_length == 0.0)  // files of roller before 2026-12-02: a stationary run's, in the increment's place
    s.next_pass_start = std::exchange(s.last_increment, VecX());
  const auto pose = j.at("pose").get<std::vector<Real>>();
  s.pose.centre = Vec2(pose.at(0), pose.at(1));
  s.pose.angle = pose.at(2);
  s.load_offset = offset_pair(j, "load_offset");
  s.load_stiffness = offset_pair(j, "load_stiffness");
  if (multi_pass && j.contains("pass_track")) {
    s.pass_track = PassTrack::load(j.at("pass_track"));
    s.pass_baseline = PassBaseline::load(j.at("pass_baseline"));
    s.pass_records = j.at("pass_records").get<std::vector<PassRecord>>();
    if (j.contains("pass_cycles")) s.pass_cycles = PassCycles::load(j.at("pass_cycles"));  // since 2026-12-02
    if (j.contains("fatigue")) s.fatigue = j.at("fatigue").get<FatigueAnswer>();
  }
  if (j.contains("totals")) {  // files of roller before 2026-11-26 hold none
    const nlohmann::json& t = j.at("totals");
    s.totals = RunTotals{t.at("iterations").get<int>(), t.at("cuts").get<int>(), t.at("max_penetration").get<Real>()};
  }
  s.friction.load(j.at("friction_history"));
  if (j.contains("roller_rim")) s.rim = to_vec(j.at("roller_rim"));
  if (j.contains("warnings")) {  // files of roller before 2026-12-02 hold none
    s.warnings = j.at("warnings").get<std::vector<std::string>>();
    s.pointwise_loss_reported = j.at("pointwise_loss_reported").get<bool>();
  }
}

// The back-stresses of a kinematic law. A restart of the same run needs them; an initial state
// from a run of a law without back-stresses starts them at zero (no plastic flow has moved
// the yield surface's centre yet in this law's terms).
void read_back_stresses(const nlohmann::json& j, int n_back, bool strip_only, const std::filesystem::path& file,
                        std::vector<MaterialState>& states) {
  if (n_back == 0) return;
  if (!j.contains("back_stresses")) {
    if (strip_only) return;
    throw InputError(
        fmt::format("{}: the state file has no back-stresses, but the scene's hardening law has {}; "
                    "resume with the scene that wrote it",
                    file.string(), n_back));
  }
  const auto back = to_reals(j.at("back_stresses"));
  const std::size_t per_state = 4 * static_cast<std::size_t>(n_back);
  if (back.size() != per_state * states.size())
    throw InputError(
        fmt::format("{}: the state file holds {} back-stress values, the scene needs {} "
                    "({} per integration point); use a state file of this scene",
                    file.string(), back.size(), per_state * states.size(), per_state));
  for (std::size_t k = 0; k < states.size(); ++k)
    for (int i = 0; i < n_back; ++i) {
      const Real* p = back.data() + per_state * k + 4 * static_cast<std::size_t>(i);
      states[k].back_stress[static_cast<std::size_t>(i)] = Vec4(p[0], p[1], p[2], p[3]);
    }
}

}  // namespace

void Simulation::save_state(const std::filesystem::path& file) const { state_writer(file)(); }

std::function<void()> Simulation::state_writer(const std::filesystem::path& file) const {
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["scene"] = run_->scene.name;
  j["n_nodes"] = run_->strip->mesh().n_nodes();
  j["n_elements"] = run_->strip->mesh().n_elements();
  std::vector<Real> reference;
  for (const Vec2& x : run_->strip->reference_coordinates()) reference.insert(reference.end(), {x.x(), x.y()});
  j["reference"] = to_list(reference);
  j["total_displacement"] = to_list(run_->strip->total_displacement());
  std::vector<Real> states;
  for (const MaterialState& s : run_->strip->states()) {
    states.insert(states.end(), s.stress.data(), s.stress.data() + 4);
    states.insert(states.end(), {s.eq_plastic_strain, s.plastic_work, s.yield_stress});
  }
  j["material_states"] = to_list(states);
  // Back-stresses only for the kinematic laws: the files of the other laws keep their layout.
  const int n_back = run_->strip->materials().max_back_stresses();
  if (n_back > 0) {
    std::vector<Real> back;
    for (const MaterialState& s : run_->strip->states())
      for (int i = 0; i < n_back; ++i) {
        const Vec4& alpha = s.back_stress[static_cast<std::size_t>(i)];
        back.insert(back.end(), alpha.data(), alpha.data() + 4);
      }
    j["back_stresses"] = to_list(back);
  }
  save_run_state(run_->state, run_->scene.passes.count > 1, j);
  run_->dynamics.save(j);
  j["scene_fingerprint"] = scene_fingerprint(run_->scene);
  return [j = std::move(j), file]() mutable {
    j["checksum"] = checksum(j);  // of everything above
    // Written beside and renamed: a kill while writing leaves the previous file intact.
    const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(j);
    write_file_atomically(file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                          "the state file");
  };
}

void Simulation::load_state(const std::filesystem::path& file, bool strip_only) {
  // Only a regular file: a directory gives a raw stream error, a device or a FIFO reads forever.
  std::error_code ec;
  if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
    throw InputError(
        fmt::format("{}: not a regular file (a state file is the state_final.cbor or checkpoint.cbor "
                    "a run writes into its output folder)",
                    file.string()));
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(
        fmt::format("{}: cannot open the state file (a run writes state_final.cbor and "
                    "checkpoint.cbor into its output folder)",
                    file.string()));
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  nlohmann::json j;
  try {
    j = nlohmann::json::from_cbor(bytes);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not a roller state file ({})", file.string(), e.what()));
  }
  if (j.value("format", "") != kFormat || j.value("version", 0) != kVersion)
    throw InputError(
        fmt::format("{}: not a roller state file of version {} (a file of an older roller: run "
                    "the scene again to write a new one)",
                    file.string(), kVersion));
  {
    // The checksum covers the document without itself (save_state adds it last).
    const std::string stored = j.value("checksum", "");
    j.erase("checksum");
    if (stored != checksum(j))
      throw InputError(
          fmt::format("{}: the state file is damaged (its checksum does not match); use another "
                      "state file or run the scene again",
                      file.string()));
  }
  try {
    const auto ref = to_reals(j.at("reference"));
    std::vector<Vec2> reference;
    for (std::size_t k = 0; k + 1 < ref.size(); k += 2) reference.emplace_back(ref[k], ref[k + 1]);
    const auto flat = to_reals(j.at("material_states"));
    std::vector<MaterialState> states(flat.size() / 7);
    for (std::size_t k = 0; k < states.size(); ++k) {
      const Real* p = flat.data() + 7 * k;
      states[k].stress = Vec4(p[0], p[1], p[2], p[3]);
      states[k].eq_plastic_strain = p[4];
      states[k].plastic_work = p[5];
      states[k].yield_stress = p[6];
    }
    read_back_stresses(j, run_->strip->materials().max_back_stresses(), strip_only, file, states);
    try {
      run_->strip->restore(std::move(reference), to_vec(j.at("total_displacement")), std::move(states));
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", file.string(), e.what()));
    }
    if (strip_only) return;
    // Continuing a run: only the run that wrote the checkpoint, and only forward.
    if (j.at("scene_fingerprint").get<std::string>() != scene_fingerprint(run_->scene))
      throw InputError(
          fmt::format("{}: written by a run of another scene or with other values (the resolved "
                      "scenes differ); resume with the same scene file and --set values, or start "
                      "afresh without --resume",
                      file.string()));
    if (j.at("step").get<int>() > run_->scene.total_steps())
      throw InputError(
          fmt::format("{}: the checkpoint is after step {} but the run has {} steps (steps.count or "
                      "--steps, times passes.count); give at least {} steps",
                      file.string(), j.at("step").get<int>(), run_->scene.total_steps(), j.at("step").get<int>()));
    load_run_state(j, run_->scene.passes.count > 1, run_->state);
    run_->dynamics.load(j, file.string());
  } catch (const nlohmann::json::exception& e) {
    if (e.id == 403)  // out_of_range.403: a key not found (an index past an array's end is damage)
      throw InputError(
          fmt::format("{}: a key this roller reads is missing ({}): a state file of an older roller; run the "
                      "scene again without --resume",
                      file.string(), e.what()));
    throw InputError(fmt::format("{}: damaged state file ({})", file.string(), e.what()));
  }
}

}  // namespace roller
