#include "roller/solver/dense_kkt_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <vector>

extern "C" {
// LAPACK: Bunch-Kaufman factorisation of a symmetric indefinite matrix, and its solve.
void dsytrf_(const char* uplo, const int* n, double* a, const int* lda, int* ipiv, double* work, const int* lwork,
             int* info, std::size_t uplo_len);
void dsytrs_(const char* uplo, const int* n, const int* nrhs, const double* a, const int* lda, const int* ipiv,
             double* b, const int* ldb, int* info, std::size_t uplo_len);
}

namespace roller::dense_kkt {

namespace {

// IW layout: IW(1) = the offset of the factor in A (= NZ), IW(2..N+1) = dsytrf's pivots.
constexpr int kIwHeader = 1;

std::int64_t real_workspace(ipfint n, ipfint nz) {
  return static_cast<std::int64_t>(nz) + static_cast<std::int64_t>(n) * n;
}

// Counts the negative and the zero eigenvalues of D (dsytrf's 1x1 and 2x2 blocks); a block's
// eigenvalue at or below `zero` in magnitude counts as zero.
void inertia_of_d(int n, const double* f, const int* ipiv, double zero, int* negative, int* zeros) {
  *negative = 0;
  *zeros = 0;
  const auto at = [&](int r, int c) { return f[r + static_cast<std::int64_t>(c) * n]; };
  const auto count = [&](double lambda) {
    if (std::abs(lambda) <= zero)
      ++*zeros;
    else if (lambda < 0.0)
      ++*negative;
  };
  for (int k = 0; k < n; ++k) {
    if (ipiv[k] > 0) {
      count(at(k, k));
      continue;
    }
    // A 2x2 block in rows k, k+1 (lower storage: ipiv(k) = ipiv(k+1) < 0).
    const double a = at(k, k), b = at(k + 1, k), c = at(k + 1, k + 1);
    const double mean = 0.5 * (a + c), radius = std::hypot(0.5 * (a - c), b);
    count(mean + radius);
    count(mean - radius);
    ++k;
  }
}

}  // namespace

namespace dense_ma27 {

void init(ipfint* icntl, double* cntl) {
  std::fill(icntl, icntl + 30, 0);
  std::fill(cntl, cntl + 5, 0.0);
  cntl[0] = 0.1;  // MA27's default pivot tolerance, reported back unused
}

void analyse(ipfint* n, ipfint* nz, const ipfint* irn, const ipfint* icn, ipfint* /*iw*/, ipfint* /*liw*/,
             ipfint* /*ikeep*/, ipfint* /*iw1*/, ipfint* nsteps, ipfint* iflag, ipfint* /*icntl*/, double* /*cntl*/,
             ipfint* info, double* ops) {
  std::fill(info, info + 20, 0);
  *nsteps = 1;
  *ops = static_cast<double>(*n) * (*n) * (*n) / 3.0;
  const std::int64_t la = real_workspace(*n, *nz);
  if (*n < 1 || *nz < 0 || la > std::numeric_limits<ipfint>::max()) {
    *iflag = info[0] = -1;
    return;
  }
  for (ipfint k = 0; k < *nz; ++k)
    if (irn[k] < 1 || irn[k] > *n || icn[k] < 1 || icn[k] > *n) {
      *iflag = info[0] = 1;  // MA27's warning for an entry out of range (Ipopt treats it as fatal)
      info[1] = k + 1;
      return;
    }
  *iflag = 0;
  // LA needed. Ipopt allocates ma27_la_init_factor (default 5) times INFO(5): ask for a fifth, so
  // that the default gives LA = NZ + N^2 and not five times that; with another factor the first
  // factorisation reports IFLAG = -4 and Ipopt grows LA to what it needs.
  info[4] = static_cast<ipfint>((la + 4) / 5);
  info[5] = (*n + kIwHeader + 4) / 5;  // LIW needed, likewise
}

void factorise(ipfint* n, ipfint* nz, const ipfint* irn, const ipfint* icn, double* a, ipfint* la, ipfint* iw,
               ipfint* liw, ipfint* /*ikeep*/, ipfint* /*nsteps*/, ipfint* maxfrt, ipfint* /*iw1*/, ipfint* /*icntl*/,
               double* /*cntl*/, ipfint* info) {
  std::fill(info, info + 20, 0);
  const int dim = *n;
  *maxfrt = 1;
  if (*liw < dim + kIwHeader) {
    info[0] = -3;
    info[1] = dim + kIwHeader;
    return;
  }
  const std::int64_t need = real_workspace(dim, *nz);
  if (*la < need) {
    info[0] = -4;
    info[1] = static_cast<ipfint>(need);
    return;
  }
  double* f = a + *nz;
  std::fill(f, f + static_cast<std::int64_t>(dim) * dim, 0.0);
  double a_max = 0.0;
  for (ipfint k = 0; k < *nz; ++k) {
    const int r = std::max(irn[k], icn[k]) - 1, c = std::min(irn[k], icn[k]) - 1;
    f[r + static_cast<std::int64_t>(c) * dim] += a[k];
  }
  for (std::int64_t k = 0; k < static_cast<std::int64_t>(dim) * dim; ++k) {
    if (!std::isfinite(f[k])) {
      info[0] = -5;  // no factorisation of a matrix with NaN or Inf (Ipopt: singular, it perturbs)
      return;
    }
    a_max = std::max(a_max, std::abs(f[k]));
  }
  int* ipiv = iw + kIwHeader;
  iw[0] = *nz;
  int lwork = -1, status = 0;
  double query = 0.0;
  dsytrf_("L", &dim, f, &dim, ipiv, &query, &lwork, &status, 1);
  lwork = std::max(1, static_cast<int>(query));
  std::vector<double> work(static_cast<std::size_t>(lwork));
  dsytrf_("L", &dim, f, &dim, ipiv, work.data(), &lwork, &status, 1);
  if (status < 0) {
    info[0] = -1;
    return;
  }
  int negative = 0, zeros = 0;
  // MUMPS's null-pivot threshold in Ipopt (CNTL(3) = 0: 1e-5 eps |A|). A looser one (n eps |A|)
  // called a Z3 KKT matrix singular 15 times in 1371, where MUMPS did not: Ipopt then perturbed
  // it, took 21 iterations more and restarted a warm start cold (docs/benchmarks.md).
  const double zero = 1e-5 * std::numeric_limits<double>::epsilon() * a_max;
  inertia_of_d(dim, f, ipiv, zero, &negative, &zeros);
  info[14] = negative;
  if (zeros > 0 || status > 0) {
    info[0] = 3;
    info[1] = dim - std::max(zeros, 1);  // the rank
  }
}

void solve(ipfint* n, double* a, ipfint* /*la*/, ipfint* iw, ipfint* /*liw*/, double* /*w*/, ipfint* /*maxfrt*/,
           double* rhs, ipfint* /*iw1*/, ipfint* /*nsteps*/, ipfint* /*icntl*/, double* /*cntl*/) {
  const int dim = *n, one = 1;
  int status = 0;
  dsytrs_("L", &dim, &one, a + iw[0], &dim, iw + kIwHeader, rhs, &dim, &status, 1);
}

}  // namespace dense_ma27

void register_dense_kkt_solver() {
  static std::once_flag once;
  std::call_once(
      once, [] { LSL_setMA27(&dense_ma27::analyse, &dense_ma27::factorise, &dense_ma27::solve, &dense_ma27::init); });
}

}  // namespace roller::dense_kkt
