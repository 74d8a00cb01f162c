#include "roller/solver/mumps_factorization.hpp"

#include <vector>

#include <dmumps_c.h>
#include <fmt/format.h>

namespace roller {

namespace {
constexpr int kUseCommWorld = -987654;  // MUMPS's code for MPI_COMM_WORLD (a no-op sequentially)
}

struct MumpsSolver::Impl {
  DMUMPS_STRUC_C id{};
  std::vector<MUMPS_INT> rows, cols;
  std::vector<double> values;
  bool initialised = false;
  bool analysed = false;
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
    id.icntl[13] = 50;  // ICNTL(14): 50 % workspace headroom for delayed pivots
  }
  bool failed(const char* what) {
    if (id.infog[0] >= 0) return false;
    message = fmt::format("MUMPS {} failed: INFOG(1) = {}, INFOG(2) = {}{}", what, id.infog[0], id.infog[1],
                          id.infog[0] == -10 ? " (numerically singular matrix)" : "");
    return true;
  }
};

MumpsSolver::MumpsSolver(Symmetry symmetry) : impl_(std::make_unique<Impl>()) {
  impl_->id.comm_fortran = kUseCommWorld;
  impl_->id.par = 1;
  impl_->id.sym = symmetry == Symmetry::Symmetric ? 2 : 0;
  impl_->call(-1);
  impl_->settings();
  impl_->initialised = impl_->id.infog[0] >= 0;
}

MumpsSolver::~MumpsSolver() {
  if (impl_->initialised) impl_->call(-2);
}

bool MumpsSolver::factorize(const SparseMatrix& a) {
  Impl& m = *impl_;
  if (!m.initialised) {
    m.message = "MUMPS could not be initialised";
    return false;
  }
  std::vector<MUMPS_INT> rows, cols;
  std::vector<double> values;
  rows.reserve(a.nonZeros());
  cols.reserve(a.nonZeros());
  values.reserve(a.nonZeros());
  const bool lower_only = m.id.sym != 0;
  for (int k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it)
      if (!lower_only || it.row() >= it.col()) {
        rows.push_back(static_cast<MUMPS_INT>(it.row() + 1));
        cols.push_back(static_cast<MUMPS_INT>(it.col() + 1));
        values.push_back(it.value());
      }
  const bool same_pattern = m.analysed && rows == m.rows && cols == m.cols && m.id.n == a.rows();
  m.rows = std::move(rows);
  m.cols = std::move(cols);
  m.values = std::move(values);
  m.id.n = static_cast<MUMPS_INT>(a.rows());
  m.id.nnz = static_cast<int64_t>(m.values.size());
  m.id.irn = m.rows.data();
  m.id.jcn = m.cols.data();
  m.id.a = m.values.data();
  m.settings();
  if (!same_pattern) {
    m.analysed = false;
    m.call(1);
    if (m.failed("analysis")) return false;
    m.analysed = true;
  }
  m.call(2);
  return !m.failed("factorisation");
}

VecX MumpsSolver::solve(const VecX& b) {
  VecX x = b;
  impl_->id.rhs = x.data();
  impl_->id.nrhs = 1;
  impl_->id.lrhs = static_cast<MUMPS_INT>(x.size());
  impl_->call(3);
  return x;
}

Index MumpsSolver::negative_pivots() const { return impl_->id.infog[11]; }

const std::string& MumpsSolver::message() const { return impl_->message; }

}  // namespace roller
