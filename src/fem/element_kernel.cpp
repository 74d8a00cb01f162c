#include "roller/fem/element_kernel.hpp"

#include <array>

#include "roller/core/error.hpp"

namespace roller {

namespace {

using StrainJacobian = Eigen::Matrix<Real, 4, Eigen::Dynamic, 0, 4, 8>;  // dE/du, rows [xx,yy,zz,2xy]
using RowJacobian = Eigen::Matrix<Real, 1, Eigen::Dynamic, Eigen::RowMajor, 1, 8>;

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
void strain_and_jacobian(const PointGeometry& g, const ElementVector& u, bool finite, Vec4& e, StrainJacobian& b) {
  const Mat2 h = displacement_gradient(g, u);
  Mat2 strain = 0.5 * (h + h.transpose());
  Mat2 f = Mat2::Identity();
  if (finite) {
    strain += 0.5 * h.transpose() * h;
    f += h;
    // Green-Lagrange strain cannot tell an inverted element (det F < 0) from a valid one.
    if (!(f.determinant() > 0.0))
      throw NumericalError("an element inverts within the increment (det F <= 0); use smaller steps");
  }
  e << strain(0, 0), strain(1, 1), 0.0, 2.0 * strain(0, 1);
  const Index n = g.gradients.rows();
  b.setZero(4, 2 * n);
  for (Index a = 0; a < n; ++a) {
    const Real nx = g.gradients(a, 0), ny = g.gradients(a, 1);
    for (int i = 0; i < 2; ++i) {  // displacement component of node a
      b(0, 2 * a + i) = f(i, 0) * nx;
      b(1, 2 * a + i) = f(i, 1) * ny;
      b(3, 2 * a + i) = f(i, 0) * ny + f(i, 1) * nx;
    }
  }
}

// Adds w * sum_ij s_ij N_A,i N_B,j to the (x,x) and (y,y) blocks: the geometric stiffness.
void add_geometric(const PointGeometry& g, const Mat2& s, Real w, ElementMatrix& k) {
  const Index n = g.gradients.rows();
  for (Index a = 0; a < n; ++a) {
    const Eigen::Matrix<Real, 1, 2> sa = g.gradients.row(a) * s;
    for (Index c = 0; c < n; ++c) {
      const Real v = w * sa.dot(g.gradients.row(c));
      k(2 * a, 2 * c) += v;
      k(2 * a + 1, 2 * c + 1) += v;
    }
  }
}

// Adds w * (N_A,x N_B,x + N_A,y N_B,y) to the (x,x) and (y,y) blocks: d2(tr E)/du2 scaled by w.
void add_trace_hessian(const PointGeometry& g, Real w, ElementMatrix& k) { add_geometric(g, Mat2::Identity(), w, k); }

}  // namespace

void evaluate_element(const ElementOptions& options, const MaterialParams& material, const ElementInput& in,
                      bool want_residual, bool want_tangent, ElementOutput& out) {
  const auto& geometry = *in.geometry;
  const std::size_t n_points = geometry.size();
  const Index n_dof = in.displacement.size();
  const bool finite = options.kinematics == Kinematics::Finite;
  const bool bbar = in.type == ElementType::Q4 && options.q4 == Q4Formulation::BBar;

  std::array<Vec4, 4> strain;
  std::array<StrainJacobian, 4> jac;
  for (std::size_t q = 0; q < n_points; ++q)
    strain_and_jacobian(geometry[q], in.displacement, finite, strain[q], jac[q]);

  // B-bar: replace each point's volumetric strain by the element average.
  const Vec4 m(1.0, 1.0, 1.0, 0.0);
  RowJacobian trace_jac_avg;
  Real volume = 0.0;
  if (bbar) {
    Real trace_avg = 0.0;
    trace_jac_avg.setZero(1, n_dof);
    for (std::size_t q = 0; q < n_points; ++q) {
      const Real w = geometry[q].weight;
      volume += w;
      trace_avg += w * (strain[q](0) + strain[q](1));
      trace_jac_avg += w * (jac[q].row(0) + jac[q].row(1));
    }
    trace_avg /= volume;
    trace_jac_avg /= volume;
    for (std::size_t q = 0; q < n_points; ++q) {
      const Real tr = strain[q](0) + strain[q](1);
      strain[q] += (trace_avg - tr) / 3.0 * m;
      const RowJacobian dtr = jac[q].row(0) + jac[q].row(1);
      jac[q] += m * ((trace_jac_avg - dtr) / 3.0);
    }
  }

  out.energy = 0.0;
  out.any_yielded = false;
  out.points.resize(n_points);
  if (want_residual) out.residual.setZero(n_dof);
  if (want_tangent) out.tangent.setZero(n_dof, n_dof);
  Real weighted_pressure_sum = 0.0;  // sum_q w_q tr(S_q)/3, for the B-bar geometric term
  for (std::size_t q = 0; q < n_points; ++q) {
    MaterialUpdate& mu = out.points[q];
    mu = update_material(material, strain[q], in.committed[q]);
    const Real w = geometry[q].weight;
    out.energy += w * mu.energy;
    out.any_yielded = out.any_yielded || mu.yielded;
    if (want_residual) out.residual.noalias() += w * jac[q].transpose() * mu.stress;
    if (!want_tangent) continue;
    out.tangent.noalias() += w * jac[q].transpose() * mu.tangent * jac[q];
    if (finite) {
      Mat2 s;
      s << mu.stress(0), mu.stress(3), mu.stress(3), mu.stress(1);
      add_geometric(geometry[q], s, w, out.tangent);
      if (bbar) {
        // d2(E_bar)/du2 adds 1/3 m (avg d2trE - d2trE_q): contracted with S it is
        // p_q (avg d2trE - d2trE_q), p_q = tr(S_q)/3 (zz included).
        const Real p = (mu.stress(0) + mu.stress(1) + mu.stress(2)) / 3.0;
        weighted_pressure_sum += w * p;
        add_trace_hessian(geometry[q], -w * p, out.tangent);
      }
    }
  }
  if (want_tangent && finite && bbar) {
    for (std::size_t q = 0; q < n_points; ++q)
      add_trace_hessian(geometry[q], weighted_pressure_sum * geometry[q].weight / volume, out.tangent);
  }
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
