#ifndef fidus_fluid_cut_element_product_transposed_h
#define fidus_fluid_cut_element_product_transposed_h

#include <Eigen/Core>
#include <deal.II/lac/full_matrix.h>

namespace Fidus
{
  /**
   * @p product = @p left @p right^T, for two matrices with the same number
   * of columns, computed by Eigen (header-only, vectorised, blocked).
   *
   * The cut element's cell and face kernels run on several threads at once
   * (WorkStream). deal.II's FullMatrix::mTmult hands products of this size
   * to the BLAS, and the serial OpenBLAS that Debian's alternatives select
   * (libopenblas0-serial, installed for MUMPS) is not safe to call from two
   * threads at once: its work buffers are shared without a lock, and
   * concurrent calls return wrong products now and then (a program calling
   * dgemm from two threads, 22 x 1500 times 1500 x 22, gave 2774 wrong
   * products in 40 000 on this project's machine). Eigen's product keeps
   * its buffers on the calling thread's stack or heap, so the kernels give
   * the same matrices, to the bit, on any number of threads.
   */
  inline void
  product_transposed(const dealii::FullMatrix<double> &left,
                     const dealii::FullMatrix<double> &right,
                     dealii::FullMatrix<double>       &product)
  {
    using RowMajor =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    AssertDimension(left.n(), right.n());
    product.reinit(left.m(), right.m());
    if (left.m() == 0 || right.m() == 0 || left.n() == 0)
      return; // reinit() left the product zero
    const Eigen::Map<const RowMajor> l(&left(0, 0), left.m(), left.n());
    const Eigen::Map<const RowMajor> r(&right(0, 0), right.m(), right.n());
    Eigen::Map<RowMajor>             p(&product(0, 0), left.m(), right.m());
    p.noalias() = l * r.transpose();
  }
} // namespace Fidus

#endif
