#ifndef fidus_fluid_cut_element_galerkin_product_h
#define fidus_fluid_cut_element_galerkin_product_h

#include <deal.II/lac/sparse_matrix.h>
#include <fidus/fluid/cut_element/row_pattern.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The Galerkin coarse operator C = P^T A P of a square sparse @p a
   * (n × n) and a prolongation @p p (n × m): @p pattern becomes C's
   * sparsity pattern (with every diagonal entry) and @p c is reinitialised
   * on it.
   *
   * Both products are formed row by row with a dense accumulator over the
   * columns (Gustavson's algorithm): A P first, then P^T (A P) from the
   * transpose of P. deal.II's SparseMatrix::mmult and Tmmult build their
   * patterns through a DynamicSparsityPattern, which was half of a 3D cut
   * element solve's time and most of its peak memory
   * (doc/history/cut_element_solvers.md, "The multigrid's set-up"). The rows
   * are split among the threads (MultithreadInfo::n_threads()); the result does
   * not depend on their number.
   *
   * With @p component (one entry per row of @p a), A is read without its
   * entries (i, j) whose rows hold different components (component[i] !=
   * component[j], neither 255): the product of the block without its
   * couplings between components, without a copy of it
   * (CutVelocityMultigrid::Settings::separate_components).
   */
  void
  galerkin_product(const SparseMatrix<double>       &a,
                   const SparseMatrix<double>       &p,
                   RowPattern                       &pattern,
                   SparseMatrix<double>             &c,
                   const std::vector<unsigned char> &component = {});
} // namespace Fidus

#endif
