#include "roller/solver/mumps_factorization.hpp"

#include <string>
#include <vector>

#include <dmumps_c.h>
#include <fmt/format.h>

namespace roller {

namespace {
constexpr int kUseCommWorld = -987654;  // MUMPS's code for MPI_COMM_WORLD (a no-op sequentially)
}

struct MumpsLdlt::Impl {
  DMUMPS_STRUC_C id{};
  std::vector<MUMPS_INT> rows, cols;
  std::vector<double> values;
  bool initialised = false;
  std::string message;

  void call(int job) {
    id.job = job;
    dmumps_c(&id);
  }
  void silence() {
    id.icntl[0] = -1;  // ICNTL(1..4): no error, diagnostic or global output
    id.icntl[1] = -1;
    id.icntl[2] = -1;
    id.icntl[3] = 0;
  }
};

MumpsLdlt::MumpsLdlt() : impl_(std::make_unique<Impl>()) {
  impl_->id.comm_fortran = kUseCommWorld;
  impl_->id.par = 1;
  impl_->id.sym = 2;  // general symmetric (indefinite allowed)
  impl_->call(-1);
  impl_->silence();
  impl_->initialised = impl_->id.infog[0] >= 0;
}

MumpsLdlt::~MumpsLdlt() {
  if (impl_->initialised) impl_->call(-2);
}

bool MumpsLdlt::factorize(const SparseMatrix& a) {
  Impl& m = *impl_;
  m.rows.clear();
  m.cols.clear();
  m.values.clear();
  for (int k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it)
      if (it.row() >= it.col()) {
        m.rows.push_back(static_cast<MUMPS_INT>(it.row() + 1));
        m.cols.push_back(static_cast<MUMPS_INT>(it.col() + 1));
        m.values.push_back(it.value());
      }
  m.id.n = static_cast<MUMPS_INT>(a.rows());
  m.id.nnz = static_cast<int64_t>(m.values.size());
  m.id.irn = m.rows.data();
  m.id.jcn = m.cols.data();
  m.id.a = m.values.data();
  m.silence();
  m.id.icntl[13] = 50;  // ICNTL(14): 50 % workspace headroom for delayed pivots
  m.call(4);            // analysis + factorisation
  if (m.id.infog[0] < 0) {
    m.message = fmt::format("MUMPS failed: INFOG(1) = {}, INFOG(2) = {}", m.id.infog[0], m.id.infog[1]);
    return false;
  }
  return true;
}

VecX MumpsLdlt::solve(const VecX& b) {
  VecX x = b;
  impl_->id.rhs = x.data();
  impl_->id.nrhs = 1;
  impl_->id.lrhs = static_cast<MUMPS_INT>(x.size());
  impl_->call(3);
  return x;
}

Index MumpsLdlt::negative_pivots() const { return impl_->id.infog[11]; }

const std::string& MumpsLdlt::message() const { return impl_->message; }

}  // namespace roller
