#include "roller/fem/element_kernel.hpp"

#include <array>

#include "roller/core/error.hpp"

namespace roller {

namespace {

// The kernel works on fixed-size matrices of its element (N nodes, 2N dofs): Eigen then unrolls
// the small products (B^T C B per point) instead of calling its general matrix product, which
// took a third of the kernel's time with dynamic sizes.
template <int N>
using Dofs = Eigen::Matrix<Real, 2 * N, 1>;
template <int N>
using Gradients = Eigen::Matrix<Real, N, 2>;
template <int N>
using StrainJacobian = Eigen::Matrix<Real, 4, 2 * N>;  // dE/du, rows [xx,yy,zz,2xy]
template <int N>
using RowJacobian = Eigen::Matrix<Real, 1, 2 * N>;
template <int N>
using Tangent = Eigen::Matrix<Real, 2 * N, 2 * N>;

Mat2 displacement_gradient(const PointGeometry& g, const ElementVector& u) {
  Mat2 h = Mat2::Zero();  // H_ij = du_i/dX_j
  for (Index a = 0; a < g.gradients.rows(); ++a) {
    h(0, 0) += u(2 * a) * g.gradients(a, 0);
    h(0, 1) += u(2 * a) * g.gradients(a, 1);
    h(1, 0) += u(2 * a + 1) * g.gradients(a, 0);
    h(1, 1) += u(2 * a + 1) * g.gradients(a, 1);
  }
  return h;
}

// Strain vector [E_xx, E_yy, 0, 2E_xy] and its Jacobian dE/du; with F = I + H,
// dE_ij/du_aA = 1/2 (F_ai N_A,j + F_aj N_A,i).
template <int N>
void strain_and_jacobian(const Gradients<N>& grad, const Dofs<N>& u, bool finite, Vec4& e, StrainJacobian<N>& b) {
  Mat2 h = Mat2::Zero();  // H_ij = du_i/dX_j
  for (int a = 0; a < N; ++a) {
    h.row(0) += u(2 * a) * grad.row(a);
    h.row(1) += u(2 * a + 1) * grad.row(a);
  }
  Mat2 strain = 0.5 * (h + h.transpose());
  Mat2 f = Mat2::Identity();
  if (finite) {
    strain += 0.5 * h.transpose() * h;
    f += h;
    // Green-Lagrange strain cannot tell an inverted element (det F < 0) from a valid one.
    if (!(f.determinant() > 0.0))
      throw NumericalError(
          "an element inverts within the increment (det F <= 0); use smaller steps (a larger steps.count, or "
          "steps.max_cuts)");
  }
  e << strain(0, 0), strain(1, 1), 0.0, 2.0 * strain(0, 1);
  b.setZero();
  for (int a = 0; a < N; ++a) {
    const Real nx = grad(a, 0), ny = grad(a, 1);
    for (int i = 0; i < 2; ++i) {  // displacement component of node a
      b(0, 2 * a + i) = f(i, 0) * nx;
      b(1, 2 * a + i) = f(i, 1) * ny;
      b(3, 2 * a + i) = f(i, 0) * ny + f(i, 1) * nx;
    }
  }
}

// Adds w * sum_ij s_ij N_A,i N_B,j to the (x,x) and (y,y) blocks: the geometric stiffness.
template <int N>
void add_geometric(const Gradients<N>& grad, const Mat2& s, Real w, Tangent<N>& k) {
  const Eigen::Matrix<Real, N, N> v = w * grad * s * grad.transpose();
  for (int a = 0; a < N; ++a)
    for (int c = 0; c < N; ++c) {
      k(2 * a, 2 * c) += v(a, c);
      k(2 * a + 1, 2 * c + 1) += v(a, c);
    }
}

// Adds w * (N_A,x N_B,x + N_A,y N_B,y) to the (x,x) and (y,y) blocks: d2(tr E)/du2 scaled by w.
template <int N>
void add_trace_hessian(const Gradients<N>& grad, Real w, Tangent<N>& k) {
  add_geometric<N>(grad, Mat2::Identity(), w, k);
}

// Each point's strain of the increment u and its Jacobian dE/du, with B-bar's average of the
// volumetric strain applied (Q4 only): what the material update sees. Returns the element's
// volume (the sum of the weights).
template <int N>
Real strains_and_jacobians(const ElementOptions& options, ElementType type, const std::vector<PointGeometry>& geometry,
                           const Dofs<N>& u, std::array<Gradients<N>, 4>& grad, std::array<Vec4, 4>& strain,
                           std::array<StrainJacobian<N>, 4>& jac) {
  const std::size_t n_points = geometry.size();
  const bool finite = options.kinematics == Kinematics::Finite;
  Real volume = 0.0;
  for (std::size_t q = 0; q < n_points; ++q) {
    grad[q] = geometry[q].gradients;
    strain_and_jacobian<N>(grad[q], u, finite, strain[q], jac[q]);
    volume += geometry[q].weight;
  }
  if (type != ElementType::Q4 || options.q4 != Q4Formulation::BBar) return volume;
  // B-bar: replace each point's volumetric strain by the element average.
  const Vec4 m(1.0, 1.0, 1.0, 0.0);
  Real trace_avg = 0.0;
  RowJacobian<N> trace_jac_avg = RowJacobian<N>::Zero();
  for (std::size_t q = 0; q < n_points; ++q) {
    const Real w = geometry[q].weight;
    trace_avg += w * (strain[q](0) + strain[q](1));
    trace_jac_avg += w * (jac[q].row(0) + jac[q].row(1));
  }
  trace_avg /= volume;
  trace_jac_avg /= volume;
  for (std::size_t q = 0; q < n_points; ++q) {
    const Real tr = strain[q](0) + strain[q](1);
    strain[q] += (trace_avg - tr) / 3.0 * m;
    const RowJacobian<N> dtr = jac[q].row(0) + jac[q].row(1);
    jac[q] += m * ((trace_jac_avg - dtr) / 3.0);
  }
  return volume;
}

template <int N>
void evaluate(const ElementOptions& options, const MaterialParams& material, const ElementInput& in, bool want_residual,
              bool want_tangent, ElementOutput& out) {
  const auto& geometry = *in.geometry;
  const std::size_t n_points = geometry.size();
  const bool finite = options.kinematics == Kinematics::Finite;
  const bool bbar = in.type == ElementType::Q4 && options.q4 == Q4Formulation::BBar;
  const Dofs<N> u = in.displacement;

  std::array<Gradients<N>, 4> grad;
  std::array<Vec4, 4> strain;
  std::array<StrainJacobian<N>, 4> jac;
  const Real volume = strains_and_jacobians<N>(options, in.type, geometry, u, grad, strain, jac);

  out.energy = 0.0;
  out.any_yielded = false;
  out.points.resize(n_points);
  Dofs<N> residual = Dofs<N>::Zero();
  Tangent<N> tangent = Tangent<N>::Zero();
  Real weighted_pressure_sum = 0.0;  // sum_q w_q tr(S_q)/3, for the B-bar geometric term
  for (std::size_t q = 0; q < n_points; ++q) {
    MaterialUpdate& mu = out.points[q];
    mu = in.frozen_recovery
             ? update_material(material, strain[q], in.committed[q], FrozenRecovery{in.frozen_recovery[q]})
             : update_material(material, strain[q], in.committed[q]);
    const Real w = geometry[q].weight;
    out.energy += w * mu.energy;
    out.any_yielded = out.any_yielded || mu.yielded;
    if (want_residual) residual.noalias() += w * jac[q].transpose() * mu.stress;
    if (!want_tangent) continue;
    const StrainJacobian<N> cb = mu.tangent * jac[q];
    // lazyProduct: at 8 x 4 x 8 (Q4) Eigen would otherwise call its general matrix product, whose
    // packing costs more than the 256 multiply-adds (5 % of a Z3 run in perf).
    tangent.noalias() += w * jac[q].transpose().lazyProduct(cb);
    if (finite) {
      Mat2 s;
      s << mu.stress(0), mu.stress(3), mu.stress(3), mu.stress(1);
      add_geometric<N>(grad[q], s, w, tangent);
      if (bbar) {
        // d2(E_bar)/du2 adds 1/3 m (avg d2trE - d2trE_q): contracted with S it is
        // p_q (avg d2trE - d2trE_q), p_q = tr(S_q)/3 (zz included).
        const Real p = (mu.stress(0) + mu.stress(1) + mu.stress(2)) / 3.0;
        weighted_pressure_sum += w * p;
        add_trace_hessian<N>(grad[q], -w * p, tangent);
      }
    }
  }
  if (want_tangent && finite && bbar) {
    for (std::size_t q = 0; q < n_points; ++q)
      add_trace_hessian<N>(grad[q], weighted_pressure_sum * geometry[q].weight / volume, tangent);
  }
  if (want_residual) out.residual = residual;
  if (want_tangent) out.tangent = tangent;
}

}  // namespace

void evaluate_element(const ElementOptions& options, const MaterialParams& material, const ElementInput& in,
                      bool want_residual, bool want_tangent, ElementOutput& out) {
  ROLLER_ASSERT(in.geometry && in.committed, "an element is evaluated with its geometry and committed states");
  ROLLER_ASSERT(in.displacement.size() == 2 * nodes_per_element(in.type), "two dofs per node of the element");
  if (in.type == ElementType::Q4)
    evaluate<4>(options, material, in, want_residual, want_tangent, out);
  else
    evaluate<3>(options, material, in, want_residual, want_tangent, out);
}

namespace {

template <int N>
std::vector<Vec4> strains_of(const ElementOptions& options, ElementType type,
                             const std::vector<PointGeometry>& geometry, const ElementVector& displacement) {
  std::array<Gradients<N>, 4> grad;
  std::array<Vec4, 4> strain;
  std::array<StrainJacobian<N>, 4> jac;
  strains_and_jacobians<N>(options, type, geometry, Dofs<N>(displacement), grad, strain, jac);
  return std::vector<Vec4>(strain.begin(), strain.begin() + static_cast<std::ptrdiff_t>(geometry.size()));
}

template <int N>
ElementVector forces_of(const ElementOptions& options, ElementType type, const std::vector<PointGeometry>& geometry,
                        const Vec4* stresses) {
  std::array<Gradients<N>, 4> grad;
  std::array<Vec4, 4> strain;
  std::array<StrainJacobian<N>, 4> jac;
  strains_and_jacobians<N>(options, type, geometry, Dofs<N>::Zero(), grad, strain, jac);
  Dofs<N> f = Dofs<N>::Zero();
  for (std::size_t q = 0; q < geometry.size(); ++q)
    f.noalias() += geometry[q].weight * jac[q].transpose() * stresses[q];
  return f;
}

}  // namespace

std::vector<Vec4> element_strains(const ElementOptions& options, ElementType type,
                                  const std::vector<PointGeometry>& geometry, const ElementVector& displacement) {
  ROLLER_ASSERT(options.kinematics == Kinematics::Small, "element_strains is for small kinematics");
  return type == ElementType::Q4 ? strains_of<4>(options, type, geometry, displacement)
                                 : strains_of<3>(options, type, geometry, displacement);
}

ElementVector element_forces(const ElementOptions& options, ElementType type,
                             const std::vector<PointGeometry>& geometry, const Vec4* stresses) {
  ROLLER_ASSERT(options.kinematics == Kinematics::Small, "element_forces is for small kinematics");
  return type == ElementType::Q4 ? forces_of<4>(options, type, geometry, stresses)
                                 : forces_of<3>(options, type, geometry, stresses);
}

std::vector<Mat2> deformation_gradients(const std::vector<PointGeometry>& geometry, const ElementVector& displacement) {
  std::vector<Mat2> f;
  f.reserve(geometry.size());
  for (const auto& g : geometry) f.push_back(Mat2::Identity() + displacement_gradient(g, displacement));
  return f;
}

Vec4 push_forward(const Mat2& f, const Vec4& second_piola) {
  Mat2 s;
  s << second_piola(0), second_piola(3), second_piola(3), second_piola(1);
  const Real j = f.determinant();
  const Mat2 sigma = f * s * f.transpose() / j;
  return Vec4(sigma(0, 0), sigma(1, 1), second_piola(2) / j, 0.5 * (sigma(0, 1) + sigma(1, 0)));
}

ElementMatrix element_mass(ElementType type, const std::vector<PointGeometry>& geometry, Real density, bool lumped) {
  const Index n = geometry.front().shape.size();
  ElementMatrix mass = ElementMatrix::Zero(2 * n, 2 * n);
  if (type == ElementType::T3) {
    // The stiffness rule (1 point) cannot integrate N_a N_b; the exact T3 result is
    // rho A / 12 (1 + delta_ab).
    const Real area = geometry.front().weight;
    for (Index a = 0; a < n; ++a)
      for (Index c = 0; c < n; ++c) {
        const Real v = density * area / 12.0 * (a == c ? 2.0 : 1.0);
        mass(2 * a, 2 * c) = v;
        mass(2 * a + 1, 2 * c + 1) = v;
      }
  } else {
    for (const auto& g : geometry)
      for (Index a = 0; a < n; ++a)
        for (Index c = 0; c < n; ++c) {
          const Real v = density * g.weight * g.shape(a) * g.shape(c);
          mass(2 * a, 2 * c) += v;
          mass(2 * a + 1, 2 * c + 1) += v;
        }
  }
  if (lumped) {
    const ElementVector rows = mass.rowwise().sum();
    mass.setZero();
    mass.diagonal() = rows;
  }
  return mass;
}

}  // namespace roller
