#include "roller/analysis/monotonicity.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <Eigen/Cholesky>

#include "roller/assembly/strip_model.hpp"
#include "roller/core/eigenvalues.hpp"
#include "roller/core/error.hpp"
#include "roller/fem/element_kernel.hpp"
#include "roller/fem/shape_functions.hpp"
#include "roller/solver/mumps_factorization.hpp"

namespace roller {

namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

using Mat3 = Eigen::Matrix<Real, 3, 3>;

}  // namespace

// ---- Parameters ------------------------------------------------------------------------------

ThesisParameters thesis_parameters(const Vec4& stress) {
  return {2.0 * stress(0) - stress(1), 2.0 * stress(1) - stress(0), stress(3)};
}

Vec4 stress_from_parameters(const ThesisParameters& p, OutOfPlaneStress rule, Real poisson_ratio) {
  const Real t11 = (2.0 * p.a + p.b) / 3.0;
  const Real t22 = (2.0 * p.b + p.a) / 3.0;
  const Real t33 = rule == OutOfPlaneStress::Zero ? 0.0 : poisson_ratio * (t11 + t22);
  return Vec4(t11, t22, t33, p.c);
}

// ---- 4x4 matrices ----------------------------------------------------------------------------

std::string to_string(GradientLayout layout) {
  switch (layout) {
    case GradientLayout::Thesis: return "thesis";
    case GradientLayout::Navier: return "navier";
    case GradientLayout::Gradient: return "gradient";
  }
  return "?";
}

GradientLayout parse_gradient_layout(const std::string& name) {
  if (name == "thesis") return GradientLayout::Thesis;
  if (name == "navier") return GradientLayout::Navier;
  if (name == "gradient") return GradientLayout::Gradient;
  throw InputError(fmt::format("layout '{}': expected one of thesis, navier, gradient", name));
}

Mat4 gradient_tangent(const Mat4& tangent, Real shear_modulus, GradientLayout layout) {
  static constexpr int kInPlane[3] = {0, 1, 3};  // xx, yy, xy of the 4-vectors
  Mat3 c3;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c3(i, j) = tangent(kInPlane[i], kInPlane[j]);
  Eigen::Matrix<Real, 3, 4> p;  // [e11, e22, 2 e12] = P [u1,1, u2,2, u1,2, u2,1]
  p << 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1;
  Mat4 c = p.transpose() * c3 * p;
  if (layout != GradientLayout::Gradient) {
    // Elastic C_1221 = C_2112 = G out of the shear block ...
    c(2, 3) -= shear_modulus;
    c(3, 2) -= shear_modulus;
  }
  if (layout == GradientLayout::Navier) {
    // ... and into the normal block: + 2G (u1,1 u2,2 - u1,2 u2,1), a null Lagrangian.
    c(0, 1) += shear_modulus;
    c(1, 0) += shear_modulus;
  }
  return c;
}

Mat4 initial_stress_matrix(const Vec4& stress) {
  const Real t11 = stress(0), t22 = stress(1), t12 = stress(3);
  Mat4 t;
  t << t11, 0, t12, 0,  //
      0, t22, 0, t12,   //
      t12, 0, t22, 0,   //
      0, t12, 0, t11;
  return t;
}

Real initial_stress_min_eigenvalue(const Vec4& stress) {
  const Real half_sum = 0.5 * (stress(0) + stress(1));
  const Real half_diff = 0.5 * (stress(0) - stress(1));
  return half_sum - std::hypot(half_diff, stress(3));
}

Real initial_stress_min_eigenvalue(const ThesisParameters& p) {
  return 0.5 * ((p.a + p.b) - std::sqrt((p.a - p.b) * (p.a - p.b) / 9.0 + 4.0 * p.c * p.c));
}

Mat4 thesis_elastic_split(Real poisson_ratio) {
  const Real nu = poisson_ratio;
  Mat4 s = Mat4::Zero();
  s(0, 0) = s(1, 1) = (1.0 - nu) / (1.0 - 2.0 * nu);
  s(0, 1) = s(1, 0) = nu / (1.0 - 2.0 * nu);
  s(2, 2) = s(3, 3) = 0.5;
  return s;
}

Mat4 thesis_plastic_pattern() {
  const Vec4 w(1.0 / 3.0, 1.0 / 3.0, 1.0, 1.0);
  return w * w.transpose();
}

namespace {

Mat4 operator_a_of_tangent(const MaterialParams& material, const Mat4& tangent, const Vec4& stress,
                           const OperatorOptions& options) {
  Mat4 a = gradient_tangent(tangent, material.shear_modulus(), options.layout);
  if (options.initial_stress) a += initial_stress_matrix(stress);
  a.diagonal().array() += options.mass_scale;
  return a;
}

}  // namespace

Mat4 operator_a(const MaterialParams& material, const Vec4& stress, Real yield_stress, const OperatorOptions& options) {
  Mat4 tangent;
  switch (options.tangent) {
    case TangentKind::Elastic: tangent = elastic_matrix(material); break;
    case TangentKind::Continuum: tangent = continuum_tangent(material, stress, yield_stress); break;
    case TangentKind::PlasticBranch: tangent = plastic_tangent(material, stress, yield_stress); break;
  }
  return operator_a_of_tangent(material, tangent, stress, options);
}

Mat4 operator_a(const MaterialParams& material, const MaterialState& state, const OperatorOptions& options) {
  if (options.tangent != TangentKind::Continuum) return operator_a(material, state.stress, state.yield_stress, options);
  return operator_a_of_tangent(material, continuum_tangent(material, state), state.stress, options);
}

Mat4 operator_a_algorithmic(const MaterialParams& material, const MaterialState& committed,
                            const Vec4& strain_increment, const OperatorOptions& options) {
  const MaterialUpdate u = update_material(material, strain_increment, committed);
  return operator_a_of_tangent(material, u.tangent, u.stress, options);
}

// ---- Definiteness ----------------------------------------------------------------------------

Definiteness definiteness(const Mat4& a) {
  Definiteness d;
  d.lambda_min = symmetric_eigenvalues(a)(0);
  d.by_eigenvalue = d.lambda_min > 0.0;
  d.by_cholesky = Eigen::LLT<Mat4>(a).info() == Eigen::Success;
  d.leading_minors << a(0, 0), a.topLeftCorner<2, 2>().determinant(), a.topLeftCorner<3, 3>().determinant(),
      a.determinant();
  d.by_minors = (d.leading_minors.array() > 0.0).all();
  return d;
}

// ---- Dynamics --------------------------------------------------------------------------------

Real mass_scale(Real density, Real h, Real dt) {
  require(density >= 0.0 && h >= 0.0 && dt >= 0.0, "mass_scale: density, h and dt must be >= 0");
  if (dt == 0.0) return 0.0;
  return density * h * h / (dt * dt);
}

Real restoring_time_step(Real density, Real h, Real lambda_min) {
  require(density >= 0.0 && h >= 0.0, "restoring_time_step: density and h must be >= 0");
  if (lambda_min > 0.0) return kInfinity;
  if (lambda_min == 0.0) return density * h > 0.0 ? kInfinity : 0.0;  // any dt > 0 lifts it
  return h * std::sqrt(density / -lambda_min);
}

Real inverse_estimate_length(ElementType type, const std::vector<Vec2>& coordinates, bool lumped_mass) {
  const std::vector<PointGeometry> geometry = element_geometry(type, coordinates, -1);
  const Index n = geometry.front().shape.size();
  MatX laplacian = MatX::Zero(n, n);
  for (const auto& g : geometry) laplacian += g.weight * g.gradients * g.gradients.transpose();
  const ElementMatrix vector_mass = element_mass(type, geometry, 1.0, lumped_mass);
  MatX mass(n, n);
  for (Index a = 0; a < n; ++a)
    for (Index b = 0; b < n; ++b) mass(a, b) = vector_mass(2 * a, 2 * b);
  return 1.0 / std::sqrt(generalized_symmetric_eigen(laplacian, mass, Eigenvectors::skip).values(n - 1));
}

// ---- The strip -------------------------------------------------------------------------------

std::string StripMonotonicity::brief_report() const {
  const std::string mode = dt > 0.0 ? fmt::format("dt = {:.3e} s", dt) : std::string("quasistatic");
  if (n_not_pd == 0) {
    return fmt::format(
        "monotonicity ({}): A positive definite at all {} integration points, "
        "min lambda = {:.4g} MPa (element {}, point {})",
        mode, n_points, lambda_min, worst.element, worst.point);
  }
  std::string remedy;
  if (dt_restore_all > 0.0) {
    remedy = fmt::format("; dt < {:.3e} s restores the worst point, dt < {:.3e} s every point", dt_restore_worst,
                         dt_restore_all);
  } else {
    remedy = "; no time step restores it (zero density)";
  }
  return fmt::format(
      "monotonicity ({}): A not positive definite at {} of {} integration points, "
      "min lambda = {:.4g} MPa at element {}, point {}{}",
      mode, n_not_pd, n_points, lambda_min, worst.element, worst.point, remedy);
}

StripMonotonicity check_strip(const StripModel& model, Real dt, const StripMonotonicityOptions& options) {
  require(dt >= 0.0, "check_strip: dt must be >= 0 (0 = quasistatic)");
  const ElementMaterials& materials = model.materials();  // each element's own (layers, profile)
  const Mesh& mesh = model.mesh();
  OperatorOptions op;
  op.layout = options.layout;
  op.tangent = TangentKind::Continuum;
  switch (options.initial_stress) {
    case InitialStressTerm::FollowKinematics:
      op.initial_stress = model.options().kinematics == Kinematics::Finite;
      break;
    case InitialStressTerm::Always: op.initial_stress = true; break;
    case InitialStressTerm::Never: op.initial_stress = false; break;
  }
  require(options.mass_factor > 0.0, "check_strip: mass_factor must be > 0");
  // The mass term c M/dt^2 acts as a density c rho in (3.15)-(3.18) (docs/model.md, Time step
  // bound).

  StripMonotonicity out;
  out.dt = dt;
  Real lambda_static_worst = kInfinity;
  Real h_worst = 0.0;
  Real rho_worst = 0.0;
  // Without a plastic branch and an initial-stress term A is C at every point: its eigenvalue is
  // computed once (at 2.9e5 dofs the per-point eigenvalues were 0.4 s of a 0.9 s step). h, which
  // only the mass term and the restoring time step need, is then computed only for them. Each
  // distinct material of a layered strip has its own.
  const bool uniform = !materials.any_plastic() && !op.initial_stress;
  std::vector<std::optional<Real>> uniform_lambda(materials.table.size());
  std::vector<Vec2> xe;
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const MaterialParams& material = materials.of(e);
    const Real rho = options.mass_factor * material.density;
    const bool mass_term = dt > 0.0 && rho > 0.0;
    std::optional<Real> h_known;
    auto h_of_element = [&]() {
      if (!h_known) {
        xe.clear();
        for (Index a : mesh.elements[e]) xe.push_back(model.reference_coordinates()[a]);
        h_known = inverse_estimate_length(mesh.element_type, xe, options.lumped_mass);
      }
      return *h_known;
    };
    // kappa >= 0 needs h, a generalised eigenproblem per element: computed only for the elements
    // with a point that reaches the eigenvalues below (the screen holds without it).
    std::optional<Real> kappa_known;
    auto kappa_of_element = [&]() {
      if (!kappa_known) kappa_known = mass_term ? mass_scale(rho, h_of_element(), dt) : 0.0;
      return *kappa_known;
    };
    for (int q = 0; q < model.points_per_element(); ++q) {
      const MaterialState& s = model.state(e, q);
      auto eigenvalue = [](const Mat4& a) { return symmetric_eigenvalues(a)(0); };
      std::optional<Real>& known = uniform_lambda[materials.index[e]];
      if (uniform && !known) known = eigenvalue(operator_a(material, s, op));
      Real lambda_static = 0.0;
      if (uniform) {
        lambda_static = *known;
      } else {
        // A point whose A - s I has a Cholesky factor, s = max(lambda_min so far, 0), is neither a
        // new minimum nor a loss of definiteness (its lambda = lambda_static + kappa exceeds s,
        // kappa >= 0) and changes nothing below: a 4x4 Cholesky instead of the eigenvalues (a
        // quarter of the monitor's time on Z3).
        // Where the mass term is large (impact), the screen is tried again with this element's kappa.
        const Mat4 a = operator_a(material, s, op);
        const auto screened = [&](Real kappa) {
          return std::isfinite(out.lambda_min) &&
                 Eigen::LLT<Mat4>(a - (std::max(out.lambda_min, 0.0) - kappa) * Mat4::Identity()).info() ==
                     Eigen::Success;
        };
        if (screened(0.0) || (mass_term && screened(kappa_of_element()))) {
          ++out.n_points;
          continue;
        }
        lambda_static = eigenvalue(a);
      }
      const Real lambda = lambda_static + kappa_of_element();  // the mass term shifts every eigenvalue
      ++out.n_points;
      if (lambda < out.lambda_min) {
        out.lambda_min = lambda;
        out.worst = {e, q};
        lambda_static_worst = lambda_static;
        h_worst = h_of_element();
        rho_worst = rho;
      }
      if (!(lambda > 0.0)) {
        ++out.n_not_pd;
        out.not_pd.push_back({e, q});
        out.dt_restore_all = std::min(out.dt_restore_all, restoring_time_step(rho, h_of_element(), lambda_static));
      }
    }
  }
  if (out.n_not_pd > 0) out.dt_restore_worst = restoring_time_step(rho_worst, h_worst, lambda_static_worst);
  return out;
}

// ---- Sparse ----------------------------------------------------------------------------------

SparseDefiniteness sparse_definiteness(const SparseMatrix& k, MumpsSolver& solver) {
  require(k.rows() == k.cols(), "sparse_definiteness: the matrix must be square");
  SparseDefiniteness out;
  if (k.rows() == 0) {
    out.factorized = true;
    return out;
  }
  solver.detect_null_pivots(1e-12);
  out.factorized = solver.factorize(k);
  if (!out.factorized) {
    out.message = solver.message();
    return out;
  }
  out.n_negative = solver.negative_pivots();
  out.n_zero = solver.null_pivots();
  return out;
}

SparseDefiniteness sparse_definiteness(const SparseMatrix& k) {
  MumpsSolver solver(MumpsSolver::Symmetry::Symmetric);
  return sparse_definiteness(k, solver);
}

bool is_positive_definite(const SparseMatrix& k_eff) { return sparse_definiteness(k_eff).positive_definite(); }

}  // namespace roller
