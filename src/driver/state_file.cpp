// State files of a Simulation (simulation.hpp): CBOR documents (nlohmann::json's binary
// encoding keeps doubles exact) holding everything the next step reads.
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "roller/core/error.hpp"
#include "roller/core/json_vectors.hpp"
#include "roller/driver/simulation.hpp"

namespace roller {

namespace {

constexpr const char* kFormat = "roller-state";
constexpr int kVersion = 1;

}  // namespace

void Simulation::save_state(const std::filesystem::path& file) const {
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["scene"] = scene_.name;
  j["step"] = steps_done_;
  j["n_nodes"] = model_->mesh().n_nodes();
  j["n_elements"] = model_->mesh().n_elements();
  std::vector<Real> reference;
  for (const Vec2& x : model_->reference_coordinates()) reference.insert(reference.end(), {x.x(), x.y()});
  j["reference"] = reference;
  j["total_displacement"] = to_list(model_->total_displacement());
  std::vector<Real> states;
  for (const MaterialState& s : model_->states()) {
    states.insert(states.end(), s.stress.data(), s.stress.data() + 4);
    states.insert(states.end(), {s.eq_plastic_strain, s.plastic_work, s.yield_stress});
  }
  j["material_states"] = states;
  j["last_increment"] = to_list(last_increment_);
  j["last_length"] = last_length_;
  j["pose"] = {pose_.centre.x(), pose_.centre.y(), pose_.angle};
  j["friction_history"] = friction_.save();
  dynamics_.save(j);
  // Written beside and renamed: a kill while writing leaves the previous file intact.
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(j);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw InputError(fmt::format("{}: cannot write the state file", tmp.string()));
  }
  std::filesystem::rename(tmp, file);
}

void Simulation::load_state(const std::filesystem::path& file, bool strip_only) {
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
    throw InputError(fmt::format("{}: not a roller state file of version {}", file.string(), kVersion));
  try {
    const auto ref = j.at("reference").get<std::vector<Real>>();
    std::vector<Vec2> reference;
    for (std::size_t k = 0; k + 1 < ref.size(); k += 2) reference.emplace_back(ref[k], ref[k + 1]);
    const auto flat = j.at("material_states").get<std::vector<Real>>();
    std::vector<MaterialState> states(flat.size() / 7);
    for (std::size_t k = 0; k < states.size(); ++k) {
      const Real* p = flat.data() + 7 * k;
      states[k].stress = Vec4(p[0], p[1], p[2], p[3]);
      states[k].eq_plastic_strain = p[4];
      states[k].plastic_work = p[5];
      states[k].yield_stress = p[6];
    }
    try {
      model_->restore(std::move(reference), to_vec(j.at("total_displacement")), std::move(states));
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", file.string(), e.what()));
    }
    if (strip_only) return;
    steps_done_ = j.at("step").get<int>();
    last_increment_ = to_vec(j.at("last_increment"));
    last_length_ = j.at("last_length").get<Real>();
    const auto pose = j.at("pose").get<std::vector<Real>>();
    pose_.centre = Vec2(pose.at(0), pose.at(1));
    pose_.angle = pose.at(2);
    friction_.load(j.at("friction_history"));
    dynamics_.load(j, file.string());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: damaged state file ({})", file.string(), e.what()));
  }
}

}  // namespace roller
