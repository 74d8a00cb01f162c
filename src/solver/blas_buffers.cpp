#include "roller/solver/blas_buffers.hpp"

#include <vector>

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
                       const double* beta, double* c, const int* ldc);

namespace roller {

void map_blas_buffers() {
  // 256^3 multiply-adds: above OpenBLAS's threshold for splitting a product over its threads.
  const int n = 256;
  const double one = 1.0, zero = 0.0;
  const std::vector<double> a(static_cast<std::size_t>(n) * n, 1.0);
  std::vector<double> c(a.size(), 0.0);
  dgemm_("N", "N", &n, &n, &n, &one, a.data(), &n, a.data(), &n, &zero, c.data(), &n);
}

}  // namespace roller
