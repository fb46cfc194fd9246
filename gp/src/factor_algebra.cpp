#include "touchcloud/gp/factor_algebra.hpp"

#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#ifdef TOUCHCLOUD_GP_OPENBLAS
#include <cblas.h>

// LAPACK's Fortran entry point (in libopenblas), with gfortran's hidden
// string-length argument.
extern "C" void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info, std::size_t uplo_len);
#endif

namespace touchcloud::gp {

namespace {

// Eigen's code, the reference for every operation and the only path without
// OpenBLAS.
bool eigen_cholesky(Eigen::Ref<Eigen::MatrixXd> a) {
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(a);
  return llt.info() == Eigen::Success;
}
void eigen_solve(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::MatrixXd> b) {
  l.triangularView<Eigen::Lower>().solveInPlace(b);
}
void eigen_solve_transposed(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::VectorXd> b) {
  l.triangularView<Eigen::Lower>().transpose().solveInPlace(b);
}
void eigen_solve_right_transposed(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::MatrixXd> b) {
  l.triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(b);
}
void eigen_subtract_gram(Eigen::Ref<Eigen::MatrixXd> c, const Eigen::Ref<const Eigen::MatrixXd>& a) {
  c.selfadjointView<Eigen::Lower>().rankUpdate(a, -1.0);
}

#ifdef TOUCHCLOUD_GP_OPENBLAS
// Small factors stay on Eigen: they fit in cache, OpenBLAS gains nothing
// there, and the stability suite's tolerances (hard cases 1 and 3 sit within
// a few units of rounding of their bounds) were set against Eigen's rounding.
constexpr Eigen::Index kOpenBlasFromRows = 256;
// A Gram matrix of candidates (the next-touch choice's V^T V) goes to
// OpenBLAS from this many columns: at 196 cells and a 60-row touch its
// dsyrk takes 40 us with Cooperlake kernels and 63 us with Haswell's,
// against Eigen's 133 us (one thread).
constexpr Eigen::Index kOpenBlasFromGramColumns = 64;

int as_int(Eigen::Index i) { return static_cast<int>(i); }

// Lower triangle of c += alpha a a^T (a_rows_are_terms false: a is m x k) or
// c += alpha a^T a (true: a is k x m), one dsyrk.
void openblas_gram_lower(Eigen::Ref<Eigen::MatrixXd> c, const Eigen::Ref<const Eigen::MatrixXd>& a,
                         bool a_rows_are_terms, double alpha) {
  cblas_dsyrk(CblasColMajor, CblasLower, a_rows_are_terms ? CblasTrans : CblasNoTrans, as_int(c.rows()),
              as_int(a_rows_are_terms ? a.rows() : a.cols()), alpha, a.data(), as_int(a.outerStride()), 1.0,
              c.data(), as_int(c.outerStride()));
}
#endif

}  // namespace

bool cholesky_lower_in_place(Eigen::Ref<Eigen::MatrixXd> a) {
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (a.rows() >= kOpenBlasFromRows) {
    const int n = as_int(a.rows()), lda = as_int(a.outerStride());
    int info = 0;
    dpotrf_("L", &n, a.data(), &lda, &info, 1);
    return info == 0;
  }
#endif
  return eigen_cholesky(a);
}

void solve_lower_in_place(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::MatrixXd> b) {
  if (b.rows() == 0 || b.cols() == 0) return;
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (l.rows() >= kOpenBlasFromRows) {
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, as_int(b.rows()), as_int(b.cols()),
                1.0, l.data(), as_int(l.outerStride()), b.data(), as_int(b.outerStride()));
    return;
  }
#endif
  eigen_solve(l, b);
}

void solve_lower_transposed_in_place(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::VectorXd> b) {
  if (b.size() == 0) return;
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (l.rows() >= kOpenBlasFromRows) {
    cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, as_int(b.size()), l.data(),
                as_int(l.outerStride()), b.data(), 1);
    return;
  }
#endif
  eigen_solve_transposed(l, b);
}

void solve_right_lower_transposed_in_place(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::MatrixXd> b) {
  if (b.rows() == 0 || b.cols() == 0) return;
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (l.rows() >= kOpenBlasFromRows) {
    cblas_dtrsm(CblasColMajor, CblasRight, CblasLower, CblasTrans, CblasNonUnit, as_int(b.rows()), as_int(b.cols()),
                1.0, l.data(), as_int(l.outerStride()), b.data(), as_int(b.outerStride()));
    return;
  }
#endif
  eigen_solve_right_transposed(l, b);
}

void multiply_lower_in_place(const Eigen::Ref<const Eigen::MatrixXd>& l, Eigen::Ref<Eigen::MatrixXd> b) {
  if (b.rows() == 0 || b.cols() == 0) return;
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (l.rows() >= kOpenBlasFromRows) {
    cblas_dtrmm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, as_int(b.rows()), as_int(b.cols()),
                1.0, l.data(), as_int(l.outerStride()), b.data(), as_int(b.outerStride()));
    return;
  }
#endif
  b = l.triangularView<Eigen::Lower>() * b;
}

bool left_side_solve_preferred(Eigen::Index factor_rows) {
#ifdef TOUCHCLOUD_GP_OPENBLAS
  static const bool avx512_kernels = [] {
    const std::string core = openblas_get_corename();
    return core == "SkylakeX" || core == "Cooperlake";
  }();
  return avx512_kernels && factor_rows >= kOpenBlasFromRows;
#else
  (void)factor_rows;
  return false;
#endif
}

void subtract_gram_lower(Eigen::Ref<Eigen::MatrixXd> c, const Eigen::Ref<const Eigen::MatrixXd>& a) {
  if (c.rows() == 0 || a.cols() == 0) return;
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (a.cols() >= kOpenBlasFromRows) {
    openblas_gram_lower(c, a, false, -1.0);
    return;
  }
#endif
  eigen_subtract_gram(c, a);
}

void add_row_gram_lower(Eigen::Ref<Eigen::MatrixXd> c, const Eigen::Ref<const Eigen::MatrixXd>& rows) {
  if (c.rows() == 0 || rows.rows() == 0) return;
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (c.rows() >= kOpenBlasFromGramColumns) {
    openblas_gram_lower(c, rows, true, 1.0);
    return;
  }
#endif
  c.selfadjointView<Eigen::Lower>().rankUpdate(rows.transpose());
}

void subtract_product(Eigen::Ref<Eigen::MatrixXd> c, const Eigen::Ref<const Eigen::MatrixXd>& a,
                      const Eigen::Ref<const Eigen::MatrixXd>& b) {
  if (c.size() == 0 || a.cols() == 0) return;
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (a.cols() >= kOpenBlasFromRows) {
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, as_int(c.rows()), as_int(c.cols()), as_int(a.cols()), -1.0,
                a.data(), as_int(a.outerStride()), b.data(), as_int(b.outerStride()), 1.0, c.data(),
                as_int(c.outerStride()));
    return;
  }
#endif
  c.noalias() -= a * b;
}

Eigen::MatrixXd product_transposed(const Eigen::Ref<const Eigen::MatrixXd>& a,
                                   const Eigen::Ref<const Eigen::MatrixXd>& b) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(a.rows(), b.rows());
  if (c.size() == 0 || a.cols() == 0) return c;
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (a.cols() >= kOpenBlasFromRows) {
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, as_int(a.rows()), as_int(b.rows()), as_int(a.cols()), 1.0,
                a.data(), as_int(a.outerStride()), b.data(), as_int(b.outerStride()), 0.0, c.data(),
                as_int(c.outerStride()));
    return c;
  }
#endif
  c.noalias() = a * b.transpose();
  return c;
}

void set_factor_algebra_threads(int threads) {
#ifdef TOUCHCLOUD_GP_OPENBLAS
  static const int initial = openblas_get_num_threads();
  openblas_set_num_threads(threads > 0 ? threads : initial);
#else
  (void)threads;
#endif
}

bool factor_algebra_threads_settable() {
#ifdef TOUCHCLOUD_GP_OPENBLAS
  return true;
#else
  return false;
#endif
}

int factor_algebra_threads() {
#ifdef TOUCHCLOUD_GP_OPENBLAS
  return openblas_get_num_threads();
#else
  return 1;
#endif
}

const char* factor_algebra_backend() {
#ifdef TOUCHCLOUD_GP_OPENBLAS
  static const std::string name = std::string(openblas_get_config()) + " (" +
                                  std::to_string(openblas_get_num_threads()) + " threads) from " +
                                  std::to_string(kOpenBlasFromRows) + " rows, Eigen below";
  return name.c_str();
#else
  return "Eigen";
#endif
}

}  // namespace touchcloud::gp
