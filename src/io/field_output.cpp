#include "roller/io/field_output.hpp"

#include <string>

#include "roller/material/j2_plasticity.hpp"

namespace roller {

namespace {

// ParaView's order of a symmetric tensor's six components: it then offers eigenvalues, principal
// directions and tensor glyphs. The strip is plane: YZ = XZ = 0.
const std::vector<std::string> kTensorComponents{"XX", "YY", "ZZ", "XY", "YZ", "XZ"};
constexpr int kTensor = 6;

VtuField field(std::string name, int n_components, Index n_items, std::vector<std::string> component_names = {}) {
  VtuField f;
  f.name = std::move(name);
  f.n_components = n_components;
  f.values.assign(n_items * n_components, 0.0);
  f.component_names = std::move(component_names);
  return f;
}

// The kinematic laws' back-stresses as element averages: their sum "back_stress" (the centre of
// the yield surface), and each one as "back_stress_<i>" when the law has several.
std::vector<VtuField> back_stress_fields(const StripModel& model) {
  const int n_back = model.materials().max_back_stresses();
  if (n_back == 0) return {};
  const Index n_el = model.mesh().n_elements();
  const int n_q = model.points_per_element();
  std::vector<VtuField> out{field("back_stress", kTensor, n_el, kTensorComponents)};
  for (int i = 0; n_back > 1 && i < n_back; ++i)
    out.push_back(field("back_stress_" + std::to_string(i + 1), kTensor, n_el, kTensorComponents));
  for (Index e = 0; e < n_el; ++e)
    for (int q = 0; q < n_q; ++q)
      for (int i = 0; i < n_back; ++i)
        for (int c = 0; c < 4; ++c) {
          const Real value = model.state(e, q).back_stress[static_cast<std::size_t>(i)](c) / n_q;
          out[0].values[kTensor * e + c] += value;
          if (n_back > 1) out[static_cast<std::size_t>(i) + 1].values[kTensor * e + c] += value;
        }
  return out;
}

}  // namespace

StripFields strip_fields(const StripModel& model, const VecX& step_increment) {
  const Mesh& mesh = model.mesh();
  const Index n_el = mesh.n_elements();
  const Index n_nodes = mesh.n_nodes();
  const int n_q = model.points_per_element();

  StripFields out;
  VtuField displacement = field("displacement", 3, n_nodes);
  for (Index a = 0; a < n_nodes; ++a) {
    displacement.values[3 * a] = model.total_displacement()(2 * a);
    displacement.values[3 * a + 1] = model.total_displacement()(2 * a + 1);
  }

  VtuField stress = field("stress", kTensor, n_el, kTensorComponents);
  VtuField strain = field("strain", kTensor, n_el, kTensorComponents);
  VtuField strain_inc = field("strain_increment", kTensor, n_el, kTensorComponents);
  VtuField sqrt_i2 = field("sqrt_I2", 1, n_el);
  VtuField mises = field("von_mises", 1, n_el);
  VtuField eps_p = field("eq_plastic_strain", 1, n_el);
  VtuField w_pl = field("plastic_work", 1, n_el);
  for (Index e = 0; e < n_el; ++e) {
    Vec4 s_avg = Vec4::Zero(), e_avg = Vec4::Zero(), de_avg = Vec4::Zero();
    const auto total = model.total_strain(e);
    const auto increment = model.increment_strain(e, step_increment);
    for (int q = 0; q < n_q; ++q) {
      const MaterialState& st = model.state(e, q);
      s_avg += st.stress / n_q;
      e_avg += total[q] / n_q;
      de_avg += increment[q] / n_q;
      sqrt_i2.values[e] += sqrt_j2(st.stress) / n_q;
      mises.values[e] += von_mises(st.stress) / n_q;
      eps_p.values[e] += st.eq_plastic_strain / n_q;
      w_pl.values[e] += st.plastic_work / n_q;
    }
    e_avg(3) *= 0.5;  // output the tensor shear component, like the stress
    de_avg(3) *= 0.5;
    for (int c = 0; c < 4; ++c) {
      stress.values[kTensor * e + c] = s_avg(c);
      strain.values[kTensor * e + c] = e_avg(c);
      strain_inc.values[kTensor * e + c] = de_avg(c);
    }
  }

  // Nodal averages of the element values, weighted equally per adjacent element.
  std::vector<Real> count(n_nodes, 0.0);
  VtuField stress_n = field("stress_nodal", kTensor, n_nodes, kTensorComponents);
  VtuField sqrt_i2_n = field("sqrt_I2_nodal", 1, n_nodes);
  VtuField mises_n = field("von_mises_nodal", 1, n_nodes);
  VtuField eps_p_n = field("eq_plastic_strain_nodal", 1, n_nodes);
  VtuField strain_n = field("strain_nodal", kTensor, n_nodes, kTensorComponents);
  VtuField strain_inc_n = field("strain_increment_nodal", kTensor, n_nodes, kTensorComponents);
  const std::vector<std::pair<VtuField*, const VtuField*>> averaged{{&stress_n, &stress}, {&sqrt_i2_n, &sqrt_i2},
                                                                    {&mises_n, &mises},   {&eps_p_n, &eps_p},
                                                                    {&strain_n, &strain}, {&strain_inc_n, &strain_inc}};
  for (Index e = 0; e < n_el; ++e)
    for (Index a : mesh.elements[e]) {
      count[a] += 1.0;
      for (auto [nodal, cell] : averaged)
        for (int c = 0; c < nodal->n_components; ++c)
          nodal->values[nodal->n_components * a + c] += cell->values[nodal->n_components * e + c];
    }
  for (Index a = 0; a < n_nodes; ++a) {
    if (count[a] == 0.0) continue;
    for (const auto& pair : averaged)
      for (int c = 0; c < pair.first->n_components; ++c)
        pair.first->values[pair.first->n_components * a + c] /= count[a];
  }

  out.point_data = {displacement, stress_n, sqrt_i2_n, mises_n, eps_p_n, strain_n, strain_inc_n};
  // The strip's make-up (docs/model.md, Layered strips and hardness profiles): each element's band
  // (0 = the top [[layer]], the number of layers = [material]) and initial yield stress (0 elastic).
  VtuField layer = field("layer", 1, n_el);
  VtuField yield0 = field("initial_yield_stress", 1, n_el);
  for (Index e = 0; e < n_el; ++e) {
    const MaterialParams& m = model.material(e);
    layer.values[e] = model.materials().layer_of(e);
    yield0.values[e] = m.plastic ? m.yield_stress : 0.0;
  }
  out.cell_data = {stress, strain, strain_inc, sqrt_i2, mises, eps_p, w_pl, layer, yield0};
  for (VtuField& f : back_stress_fields(model)) out.cell_data.push_back(std::move(f));
  return out;
}

}  // namespace roller
