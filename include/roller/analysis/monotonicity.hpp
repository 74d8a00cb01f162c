#pragma once
// Monotonicity of operator A (thesis ch. 3; docs/model.md, Monotonicity): pointwise 4x4 matrix
// A = C + T at a stress state, three positive-definiteness tests, the dynamic term and the
// Courant-type time step bound (3.18), a check over every integration point of a strip, and the
// positive definiteness of an assembled sparse operator. The derivations are in
// docs/monotonicity.md.
//
// Pointwise form. With the displacement gradient ordered g = [u1,1  u2,2  u1,2  u2,1]^T the
// bilinear form of the increment (docs/model.md, Increment energy) has the integrand g^T A g,
// A = C + T (3.3) [MPa]:
//   C   the elastoplastic tangent as a quadratic form on gradients: with P g = [e11, e22, 2e12]
//       (P = [1 0 0 0; 0 1 0 0; 0 0 1 1]) and C3 the in-plane block of the material tangent,
//       g^T (P^T C3 P) g = e:C:e  ("gradient" layout, the integrand of K_L). Its shear block is
//       G [1 1; 1 1]: a rotation (u1,2 = -u2,1) costs nothing, so this layout is at best positive
//       semi-definite at zero stress. The thesis's (3.4)/(3.10) drop the elastic C_1221 = C_2112
//       = G entries ("thesis" layout, shear block G I, elastic eigenvalues 2G {1, 1/(1-2nu),
//       1/2, 1/2}); the "navier" layout adds the null Lagrangian 2G (u1,1 u2,2 - u1,2 u2,1)
//       instead (integral-equivalent to "gradient" for displacements vanishing on the boundary;
//       elastic form G |grad u|^2 + (lambda + G)(div u)^2).
//   T   (3.5) the initial-stress matrix, g^T T g = tau_kl u_i,k u_i,l:
//       T = [t11 0 t12 0; 0 t22 0 t12; t12 0 t22 0; 0 t12 0 t11]. Its eigenvalues are the two
//       in-plane principal stresses, each twice, so
//       lambda_min(T) = (t11 + t22)/2 - sqrt((t11 - t22)^2/4 + t12^2)
//                     = 1/2 [(a + b) - sqrt((a - b)^2/9 + 4 c^2)].
// Dynamic term. (1/dt^2) int rho u.v enters as rho h^2/dt^2 times the 4x4 identity, h the
// inverse-estimate length of the element (int |grad u|^2 <= h^-2 int |u|^2 on the element,
// thesis (3.16)); A + rho h^2/dt^2 I is positive definite iff dt < h sqrt(rho / -lambda_min(A))
// (the Courant-type bound (3.18), dt/h <= alpha_1).
#include <limits>
#include <string>
#include <vector>

#include "roller/core/types.hpp"
#include "roller/material/j2_plasticity.hpp"
#include "roller/mesh/mesh.hpp"

namespace roller {

class StripModel;
class MumpsSolver;  // solver/mumps_factorization.hpp

// ---- The thesis's stress parameters ------------------------------------------------------

// a = 2 t11 - t22, b = 2 t22 - t11, c = t12 [MPa] (thesis (3.4)); a = 3 s11 and b = 3 s22 only
// when t33 = 0.
struct ThesisParameters {
  Real a = 0.0;
  Real b = 0.0;
  Real c = 0.0;
};

// How the out-of-plane stress t33 is chosen when a stress is built from (a, b, c).
enum class OutOfPlaneStress {
  Zero,                // t33 = 0: a = 3 s11, b = 3 s22 exactly as the thesis writes (default)
  PlaneStrainElastic,  // t33 = nu (t11 + t22), the elastic plane-strain value
};

ThesisParameters thesis_parameters(const Vec4& stress);
// t11 = (2a + b)/3, t22 = (2b + a)/3, t12 = c, t33 by `rule`; returns [xx, yy, zz, xy].
Vec4 stress_from_parameters(const ThesisParameters& p, OutOfPlaneStress rule, Real poisson_ratio);

// ---- The 4x4 matrices ----------------------------------------------------------------------

enum class GradientLayout { Thesis, Navier, Gradient };
std::string to_string(GradientLayout layout);
// Accepts "thesis", "navier", "gradient"; throws InputError naming the value otherwise.
GradientLayout parse_gradient_layout(const std::string& name);

// C in the gradient ordering from a material tangent [xx, yy, zz, 2xy] -> [xx, yy, zz, xy]
// (plane strain: the zz rows and columns are dropped). shear_modulus is the elastic G that the
// thesis and navier layouts move between the shear and normal blocks.
Mat4 gradient_tangent(const Mat4& tangent, Real shear_modulus, GradientLayout layout);

// T of (3.5) from the in-plane stress [xx, yy, zz, xy].
Mat4 initial_stress_matrix(const Vec4& stress);
// lambda_min(T) in closed form (the smaller in-plane principal stress).
Real initial_stress_min_eigenvalue(const Vec4& stress);
Real initial_stress_min_eigenvalue(const ThesisParameters& p);

// The thesis's normalised split (3.9)-(3.12) of C = E/(1+nu) [S_nu - beta D S* D] with
// D = diag(a, b, c, c) (t33 = 0). S_nu has eigenvalues 1, 1/(1-2nu), 1/2, 1/2;
// S* = w w^T with w = [1/3, 1/3, 1, 1] has eigenvalues 20/9, 0, 0, 0.
Mat4 thesis_elastic_split(Real poisson_ratio);
Mat4 thesis_plastic_pattern();

// Which material tangent enters C.
enum class TangentKind {
  Elastic,        // C^E
  Continuum,      // continuum_tangent: C^EP on the yield surface, C^E inside it
  PlasticBranch,  // plastic_tangent: C^E - 2G beta s s^T whatever f is (the thesis's maps)
};

struct OperatorOptions {
  GradientLayout layout = GradientLayout::Thesis;
  TangentKind tangent = TangentKind::Continuum;
  bool initial_stress = true;  // include T
  Real mass_scale = 0.0;       // rho h^2 / dt^2 [MPa] added on the diagonal (see mass_scale())
};

// A = C + T (+ mass_scale I) at `stress` [xx, yy, zz, xy] with current yield stress
// `yield_stress` (ignored for TangentKind::Elastic; must be > 0 for PlasticBranch).
Mat4 operator_a(const MaterialParams& material, const Vec4& stress, Real yield_stress, const OperatorOptions& options);
// The same at an integration point's state: with TangentKind::Continuum, the material law's own
// C^EP (kinematic laws: the relative stress and the state's hardening modulus).
Mat4 operator_a(const MaterialParams& material, const MaterialState& state, const OperatorOptions& options);

// A with the algorithmic (consistent) tangent of the backward-Euler return: the material update
// of `strain_increment` [xx, yy, zz, 2xy] from `committed` gives the tangent and the stress that
// enters T (the second Piola-Kirchhoff stress of the increment, as in K_NL). options.tangent is
// ignored. For a zero increment this equals the continuum operator of the committed state only
// when that state is elastic: the return mapping treats a zero increment as elastic.
Mat4 operator_a_algorithmic(const MaterialParams& material, const MaterialState& committed,
                            const Vec4& strain_increment, const OperatorOptions& options);

// ---- Positive definiteness -----------------------------------------------------------------

struct Definiteness {
  Real lambda_min = 0.0;               // smallest eigenvalue
  Vec4 leading_minors = Vec4::Zero();  // det of the leading k x k blocks, k = 1..4
  bool by_eigenvalue = false;          // lambda_min > 0
  bool by_cholesky = false;            // LLT succeeds
  bool by_minors = false;              // Sylvester (Theorem 3.1): every leading minor > 0
  bool positive_definite() const { return by_eigenvalue; }
  bool consistent() const { return by_eigenvalue == by_cholesky && by_eigenvalue == by_minors; }
};

// The three tests on a symmetric 4x4 matrix. They agree except within round-off of the
// boundary (|lambda_min| ~ 1e-15 ||A||).
Definiteness definiteness(const Mat4& a);

// ---- Dynamic term and the Courant-type bound (3.15)-(3.18) -----------------------------------

// rho h^2 / dt^2 [MPa] (rho [t/mm^3], h [mm], dt [s]); 0 when dt == 0 (quasistatic) or
// rho == 0. Throws std::logic_error for negative arguments.
Real mass_scale(Real density, Real h, Real dt);

// (3.18): the largest dt for which A + rho h^2/dt^2 I is positive definite, i.e. PD iff
// dt < h sqrt(rho / -lambda_min). +infinity when lambda_min > 0 (any dt); 0 when
// lambda_min <= 0 and rho h^2 = 0 (no time step restores it).
Real restoring_time_step(Real density, Real h, Real lambda_min);

// Inverse-estimate length h of one element: int_K |grad v|^2 <= h^-2 int_K v^2 for every v in
// the element's shape-function space (v scalar; the same h serves each displacement component),
// h = lambda_max(K_lap, M)^(-1/2) with K_lap the Laplacian matrix under the element's stiffness
// quadrature and M its consistent (or row-sum lumped) mass. Square Q4 of side d: d/sqrt(24)
// (lumped: d/2); right T3 with legs d: d/6 (lumped: d/3). Throws NumericalError for inverted
// elements.
Real inverse_estimate_length(ElementType type, const std::vector<Vec2>& coordinates, bool lumped_mass);

// ---- The whole strip ----------------------------------------------------------------------

struct PointIndex {
  Index element = -1;
  int point = -1;
};

enum class InitialStressTerm {
  FollowKinematics,  // T only for finite kinematics (small kinematics has no K_NL) (default)
  Always,            // the thesis's A = C + T whatever the kinematics
  Never,
};

struct StripMonotonicityOptions {
  GradientLayout layout = GradientLayout::Thesis;
  InitialStressTerm initial_stress = InitialStressTerm::FollowKinematics;
  bool lumped_mass = false;  // the mass matrix the time integrator uses (sets h)
  // c in K_eff = K + c M/dt^2: Houbolt's effective stiffness (4.17) has c = 2 (docs/model.md,
  // Time step bound); the thesis's (3.1) writes c = 1.
  Real mass_factor = 2.0;
};

struct StripMonotonicity {
  Real dt = 0.0;                   // the time step checked (0 = quasistatic)
  Index n_points = 0;              // integration points checked
  Index n_not_pd = 0;              // points where A (+ rho h^2/dt^2 I) is not positive definite
  std::vector<PointIndex> not_pd;  // their (element, point) indices
  Real lambda_min = std::numeric_limits<Real>::infinity();  // smallest eigenvalue [MPa]
  PointIndex worst;                                         // where lambda_min occurs
  // (3.18) from the static lambda_min (without the mass term): the time step below which the
  // worst point, resp. every flagged point, becomes positive definite. +inf when nothing is
  // flagged; 0 when the density is 0 (no time step helps: quasistatic strip).
  Real dt_restore_worst = std::numeric_limits<Real>::infinity();
  Real dt_restore_all = std::numeric_limits<Real>::infinity();
  bool monotone() const { return n_not_pd == 0; }
  std::string brief_report() const;  // one line
};

// Checks A at every integration point of the committed state: stress and yield stress of the
// state, continuum tangent, h per element from the start-of-increment configuration, density
// from the material; the dynamic term is mass_factor rho h^2/dt^2 and the restoring time steps
// are h sqrt(mass_factor rho / -lambda_min). dt = 0 checks the quasistatic operator. Q4 B-bar
// replaces the volumetric strain by its element average; the pointwise A ignores that (a
// standard-Q4 view).
StripMonotonicity check_strip(const StripModel& model, Real dt, const StripMonotonicityOptions& options = {});

// ---- The assembled operator ---------------------------------------------------------------

struct SparseDefiniteness {
  bool factorized = false;  // the LDL^T factorisation succeeded (false: numerically singular)
  Index n_negative = 0;     // negative pivots of D = negative eigenvalues (Sylvester's inertia)
  Index n_zero = 0;         // null pivots (|d| <= kNullPivot ||K||): a zero-energy mode
  std::string message;      // why it did not factorise
  bool positive_definite() const { return factorized && n_negative == 0 && n_zero == 0; }
};

// Inertia of a symmetric sparse matrix (full or lower storage; the lower triangle is read) from
// MUMPS's LDL^T with pivoting (supernodal: at 2.9e5 dofs a fraction of Eigen's simplicial LDL^T).
// `solver` must be Symmetric; its analysis is reused when the pattern repeats (one solver per
// run for the run-time monitor). A pivot below 1e-12 ||K|| counts as null: round-off leaves a
// rigid-body mode a pivot of either sign near 1e-16 ||K||, while the physical pivots of the strips
// we mesh (grading ratios up to 400) stay above 1e-9 ||K||.
SparseDefiniteness sparse_definiteness(const SparseMatrix& k, MumpsSolver& solver);
SparseDefiniteness sparse_definiteness(const SparseMatrix& k);
// PD iff the sparse LDL^T factorisation succeeds and every pivot of D is > 0.
bool is_positive_definite(const SparseMatrix& k_eff);

}  // namespace roller
