#include "roller/solver/mumps_factorization.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <dmumps_c.h>
#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

namespace {

// MUMPS orders a matrix without a Schur complement (and Ipopt's MUMPS every large one) with
// SCOTCH, whose Debian build (7.0) coarsens graphs on 2 threads by default and, so, not
// deterministically: two runs of one scene took other orderings and parted at round-off from
// the first factorisation with an empty working set (docs/stability.md, "Reproducible runs").
// On one thread SCOTCH is deterministic. Set before main, before any thread or ordering exists.
const bool kScotchOnOneThread = [] { return setenv("SCOTCH_PTHREAD_NUMBER", "1", 1) == 0; }();
constexpr int kUseCommWorld = -987654;  // MUMPS's code for MPI_COMM_WORLD (a no-op sequentially)

// Calls f(row, col, value) for each entry of `a` that MUMPS is given (the lower triangle of a
// symmetric matrix, every entry otherwise), in the order of the arrays it is given in.
template <class F>
void for_each_stored_entry(const SparseMatrix& a, bool lower_only, F&& f) {
  for (int k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it)
      if (!lower_only || it.row() >= it.col()) f(it.row(), it.col(), it.value());
}
}  // namespace

struct MumpsSolver::Impl {
  DMUMPS_STRUC_C id{};
  std::vector<MUMPS_INT> rows, cols;
  std::vector<double> values;
  std::vector<MUMPS_INT> schur_list;  // 1-based; empty = no Schur complement
  std::vector<double> schur;          // size_schur^2, by rows
  bool initialised = false;
  bool analysed = false;
  bool factorised = false;  // the arrays above hold the matrix of valid factors
  // ICNTL(14) now: percentage added to the workspace MUMPS estimates in the analysis, for
  // delayed pivots of an indefinite K; starts at options.workspace_percent. When they overrun it
  // anyway, the factorisation is retried with twice the headroom (kept for the next
  // factorisations of this solver). The headroom costs no resident memory until it is touched:
  // 20 or 50 gave the same peak on a 1.3e6-dof Hertz increment.
  int workspace_percent = 0;
  Real null_pivot_threshold = 0.0;  // CNTL(3) with ICNTL(24) = 1; 0: no null pivot detection
  bool discard_factors = false;     // ICNTL(31) = 1: inertia only
  LinearSolverOptions options;
  std::string message;

  void call(int job) {
    id.job = job;
    dmumps_c(&id);
  }
  void settings() {
    id.icntl[0] = -1;  // ICNTL(1..4): no error, diagnostic or global output
    id.icntl[1] = -1;
    id.icntl[2] = -1;
    id.icntl[3] = 0;
    id.icntl[13] = workspace_percent;            // ICNTL(14)
    id.icntl[18] = schur_list.empty() ? 0 : 1;   // ICNTL(19): centralised Schur complement, by rows
    id.icntl[25] = 0;                            // ICNTL(26): with a Schur complement, solve the interior problem only
    id.icntl[21] = options.out_of_core ? 1 : 0;  // ICNTL(22): factors on disk
    id.icntl[23] = null_pivot_threshold > 0.0 ? 1 : 0;  // ICNTL(24): null pivot detection
    id.cntl[2] = null_pivot_threshold;                  // CNTL(3): relative to the matrix's norm
    id.icntl[30] = discard_factors ? 1 : 0;             // ICNTL(31): factors discarded
    // ICNTL(7): 7 = MUMPS chooses, 0 = AMD, 5 = METIS.
    id.icntl[6] = options.ordering == "amd" ? 0 : options.ordering == "metis" ? 5 : 7;
  }
  bool factorize(const SparseMatrix& a, std::vector<MUMPS_INT> schur_vars);
  bool failed(const char* what) {
    if (id.infog[0] >= 0) return false;
    const int info = id.infog[0];
    // -7, -13: an allocation failed (INFOG(2) its size, in millions of entries when negative): the
    // machine's memory, not the matrix; the run stops (exit 3) instead of cutting the step.
    if (info == -7 || info == -13) {
      const double entries = id.infog[1] < 0 ? -1e6 * id.infog[1] : id.infog[1];
      throw SystemError(fmt::format(
          "out of memory: MUMPS's {} could not allocate {:.3g} MB (INFOG(1) = {}; the factorisation needs about "
          "{} MB in core by MUMPS's estimate, {} MB out of core); use a coarser mesh (--refine, mesh.nx, mesh.ny) "
          "or [linear_solver] out_of_core = true, or raise the memory limit (ulimit -v)",
          what, entries * (info == -7 ? 4.0 : 8.0) / 1e6, info, id.infog[16], id.infog[26]));
    }
    const char* why = info == -10   ? " (numerically singular matrix)"
                      : info == -13 ? " (out of memory: a coarser mesh, or [linear_solver] out_of_core = true)"
                      : info <= -90 ? " (out-of-core files: is [linear_solver] directory writable, with room?)"
                                    : "";
    message = fmt::format("MUMPS {} failed: INFOG(1) = {}, INFOG(2) = {}{}", what, info, id.infog[1], why);
    return true;
  }
};

MumpsSolver::MumpsSolver(Symmetry symmetry, const LinearSolverOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->workspace_percent = options.workspace_percent;
  impl_->id.comm_fortran = kUseCommWorld;
  impl_->id.par = 1;
  impl_->id.sym = symmetry == Symmetry::Symmetric ? 2 : 0;
  impl_->call(-1);
  if (!options.directory.empty())
    std::snprintf(impl_->id.ooc_tmpdir, sizeof impl_->id.ooc_tmpdir, "%s", options.directory.c_str());
  impl_->settings();
  impl_->initialised = impl_->id.infog[0] >= 0;
}

MumpsSolver::~MumpsSolver() {
  if (impl_->initialised) impl_->call(-2);
}

bool MumpsSolver::Impl::factorize(const SparseMatrix& a, std::vector<MUMPS_INT> schur_vars) {
  Impl& m = *this;
  if (!m.initialised) {
    m.message = "MUMPS could not be initialised";
    return false;
  }
  // The matrix in MUMPS's 1-based coordinates, written over the previous one's arrays while
  // comparing, so the pattern check costs no second copy (at 1.3e6 dofs a copy is 190 MB).
  const bool lower_only = m.id.sym != 0;
  std::size_t count = 0;
  for_each_stored_entry(a, lower_only, [&count](Index, Index, Real) { ++count; });
  bool same_pattern = m.analysed && count == m.rows.size() && m.id.n == a.rows() && schur_vars == m.schur_list;
  m.rows.resize(count);
  m.cols.resize(count);
  m.values.resize(count);
  std::size_t e = 0;
  for_each_stored_entry(a, lower_only, [&](Index row, Index col, Real value) {
    const auto r = static_cast<MUMPS_INT>(row + 1), c = static_cast<MUMPS_INT>(col + 1);
    same_pattern = same_pattern && m.rows[e] == r && m.cols[e] == c;
    m.rows[e] = r;
    m.cols[e] = c;
    m.values[e++] = value;
  });
  m.factorised = false;
  m.rows.shrink_to_fit();
  m.cols.shrink_to_fit();
  m.values.shrink_to_fit();
  m.schur_list = std::move(schur_vars);
  m.id.n = static_cast<MUMPS_INT>(a.rows());
  m.id.nnz = static_cast<int64_t>(m.values.size());
  m.id.irn = m.rows.data();
  m.id.jcn = m.cols.data();
  m.id.a = m.values.data();
  const auto ns = static_cast<MUMPS_INT>(m.schur_list.size());
  m.schur.assign(static_cast<std::size_t>(ns) * ns, 0.0);
  m.id.size_schur = ns;
  m.id.listvar_schur = ns > 0 ? m.schur_list.data() : nullptr;
  m.id.schur = ns > 0 ? m.schur.data() : nullptr;
  m.id.schur_lld = ns;
  m.settings();
  if (!same_pattern) {
    m.analysed = false;
    m.call(1);
    if (m.failed("analysis")) return false;
    m.analysed = true;
  }
  m.call(2);
  // Workspace overrun (INFOG(1) = -8, -9: integer/real work arrays; -14, -15 their 64-bit
  // counterparts): more headroom and factorise again, up to 16x MUMPS's estimate.
  while ((m.id.infog[0] == -8 || m.id.infog[0] == -9 || m.id.infog[0] == -14 || m.id.infog[0] == -15) &&
         m.workspace_percent < 1600) {
    m.workspace_percent = std::max(2 * m.workspace_percent, 20);
    m.id.icntl[13] = m.workspace_percent;
    m.call(2);
  }
  const bool ok = !m.failed("factorisation");
  m.factorised = ok && !m.discard_factors;
  return ok;
}

bool MumpsSolver::factorize(const SparseMatrix& a) { return impl_->factorize(a, {}); }

bool MumpsSolver::factorize_with_schur(const SparseMatrix& a, const std::vector<Index>& schur, MatX* s) {
  std::vector<MUMPS_INT> list;
  list.reserve(schur.size());
  for (const Index i : schur) list.push_back(static_cast<MUMPS_INT>(i + 1));
  if (!impl_->factorize(a, std::move(list))) return false;
  const Index n = static_cast<Index>(schur.size());
  s->resize(n, n);
  const std::vector<double>& v = impl_->schur;
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) (*s)(i, j) = v[static_cast<std::size_t>(i) * n + j];
  // Symmetric matrices: MUMPS fills one triangle only (the lower one by rows = the upper one
  // by columns); mirror it.
  if (impl_->id.sym != 0)
    for (Index i = 0; i < n; ++i)
      for (Index j = i + 1; j < n; ++j) (*s)(i, j) = (*s)(j, i);
  return true;
}

VecX MumpsSolver::solve_interior(const VecX& b) {
  VecX x = b;
  for (const MUMPS_INT i : impl_->schur_list) x(i - 1) = 0.0;
  x = solve(x);
  for (const MUMPS_INT i : impl_->schur_list) x(i - 1) = 0.0;
  return x;
}

VecX MumpsSolver::solve_with_schur(const VecX& b, const std::function<VecX(const VecX&)>& schur_solve) {
  Impl& m = *impl_;
  const auto ns = static_cast<Index>(m.schur_list.size());
  VecX x = b;
  VecX reduced = VecX::Zero(ns);
  m.id.rhs = x.data();
  m.id.nrhs = 1;
  m.id.lrhs = static_cast<MUMPS_INT>(x.size());
  m.id.redrhs = reduced.data();
  m.id.lredrhs = static_cast<MUMPS_INT>(ns);
  m.id.icntl[25] = 1;  // ICNTL(26) = 1: forward elimination, reduced right-hand side in REDRHS
  m.call(3);
  if (m.id.infog[0] >= 0) {
    reduced = schur_solve(reduced);
    m.id.redrhs = reduced.data();
    m.id.icntl[25] = 2;  // ICNTL(26) = 2: expansion of the Schur variables' values in REDRHS
    m.call(3);
  }
  m.id.icntl[25] = 0;
  m.id.redrhs = nullptr;
  m.id.lredrhs = 0;
  if (m.id.infog[0] < 0)
    throw std::runtime_error(fmt::format("MUMPS reduced solve failed: INFOG(1) = {}", m.id.infog[0]));
  for (Index s = 0; s < ns; ++s) x(m.schur_list[s] - 1) = reduced(s);
  return x;
}

bool MumpsSolver::holds_factors_of(const SparseMatrix& a, const std::vector<Index>& schur) const {
  const Impl& m = *impl_;
  if (!m.factorised || a.rows() != m.id.n || schur.size() != m.schur_list.size()) return false;
  for (std::size_t i = 0; i < schur.size(); ++i)
    if (schur[i] + 1 != m.schur_list[i]) return false;
  std::size_t e = 0;
  bool same = true;
  for_each_stored_entry(a, m.id.sym != 0, [&](Index row, Index col, Real value) {
    same = same && e < m.values.size() && m.rows[e] == row + 1 && m.cols[e] == col + 1 && m.values[e] == value;
    ++e;
  });
  return same && e == m.values.size();
}

VecX MumpsSolver::solve(const VecX& b) {
  VecX x = b;
  impl_->id.rhs = x.data();
  impl_->id.nrhs = 1;
  impl_->id.lrhs = static_cast<MUMPS_INT>(x.size());
  impl_->call(3);
  return x;
}

void MumpsSolver::detect_null_pivots(Real relative_threshold) { impl_->null_pivot_threshold = relative_threshold; }

void MumpsSolver::discard_factors() { impl_->discard_factors = true; }

Index MumpsSolver::negative_pivots() const { return impl_->id.infog[11]; }

Index MumpsSolver::null_pivots() const { return impl_->id.infog[27]; }

Index MumpsSolver::memory_mb() const { return impl_->id.infog[18]; }

int MumpsSolver::workspace_percent() const { return impl_->workspace_percent; }

const std::string& MumpsSolver::message() const { return impl_->message; }

}  // namespace roller
