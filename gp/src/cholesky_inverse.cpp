#include "touchcloud/gp/cholesky_inverse.hpp"

#include <Eigen/Dense>

#ifdef TOUCHCLOUD_GP_OPENBLAS
// LAPACK's dpotri (= dtrtri + dlauum, in libopenblas), gfortran calling convention.
extern "C" void dpotri_(const char* uplo, const int* n, double* a, const int* lda, int* info, std::size_t uplo_len);
#endif

namespace touchcloud::gp {

namespace {
// Below this size the recursion stops and Eigen does the block directly.
constexpr Eigen::Index kLeaf = 64;
}

// With m = [A 0; B C]: m^-1 = [A^-1 0; -C^-1 B A^-1  C^-1]; the two
// triangular products keep the cost at n^3/3.
void invert_lower_triangular(Eigen::Ref<Eigen::MatrixXd> m) {
  const Eigen::Index n = m.rows();
  if (n <= kLeaf) {
    Eigen::MatrixXd inverse = Eigen::MatrixXd::Identity(n, n);
    m.triangularView<Eigen::Lower>().solveInPlace(inverse);
    m.triangularView<Eigen::Lower>() = inverse;
    return;
  }
  const Eigen::Index n1 = n / 2, n2 = n - n1;
  invert_lower_triangular(m.topLeftCorner(n1, n1));
  invert_lower_triangular(m.bottomRightCorner(n2, n2));
  auto b = m.bottomLeftCorner(n2, n1);
  Eigen::MatrixXd b_ainv = b * m.topLeftCorner(n1, n1).triangularView<Eigen::Lower>();
  b.noalias() = m.bottomRightCorner(n2, n2).triangularView<Eigen::Lower>() * b_ainv;
  b = -b;
}

// With W = [A 0; B C]: W^T W = [A^T A + B^T B, .; C^T B, C^T C].
void lower_gram_in_place(Eigen::Ref<Eigen::MatrixXd> m) {
  const Eigen::Index n = m.rows();
  if (n <= kLeaf) {
    Eigen::MatrixXd w = m.triangularView<Eigen::Lower>();
    Eigen::MatrixXd gram = w.transpose() * w;
    m.triangularView<Eigen::Lower>() = gram;
    return;
  }
  const Eigen::Index n1 = n / 2, n2 = n - n1;
  auto a = m.topLeftCorner(n1, n1);
  auto b = m.bottomLeftCorner(n2, n1);
  auto c = m.bottomRightCorner(n2, n2);
  lower_gram_in_place(a);
  a.selfadjointView<Eigen::Lower>().rankUpdate(b.transpose());
  Eigen::MatrixXd ct_b = c.transpose().triangularView<Eigen::Upper>() * b;
  b = ct_b;
  lower_gram_in_place(c);
}

void cholesky_inverse_in_place(Eigen::Ref<Eigen::MatrixXd> m) {
#ifdef TOUCHCLOUD_GP_OPENBLAS
  if (m.rows() >= 256) {  // as in factor_algebra.cpp: small factors stay on Eigen
    const int n = static_cast<int>(m.rows()), lda = static_cast<int>(m.outerStride());
    int info = 0;
    dpotri_("L", &n, m.data(), &lda, &info, 1);
    if (info == 0) return;
    // info > 0: a zero pivot (dtrtri checks before writing, so m is intact);
    // the recursion below then behaves as without OpenBLAS.
  }
#endif
  invert_lower_triangular(m);
  lower_gram_in_place(m);
}

}  // namespace touchcloud::gp
