#ifndef fidus_fluid_cut_element_distributed_galerkin_product_h
#define fidus_fluid_cut_element_distributed_galerkin_product_h

#include <deal.II/base/index_set.h>
#include <fidus/fluid/cut_element/distributed_rows.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The Galerkin coarse operator C = P^T A P over MPI ranks: galerkin_product()
   * for DistributedRows. @p a is square over the fine space, @p p has the
   * same rows (the same split) and columns in the coarse space, of which
   * this rank owns @p coarse_owned (a contiguous range, the ranks' ranges
   * in their order); @p c becomes C on those rows, with every diagonal
   * entry.
   *
   * Each rank forms the rows of A P it owns, from its rows of P and the
   * rows of P that A's ghost columns need (fetched from their owners), then
   * P^T (A P) from its own fine rows: a coarse row gets contributions from
   * every rank whose fine rows its coarse functions reach, and those from
   * other ranks are sent to its owner and added there. The result is the
   * serial product's to round-off (the sums run in another order).
   *
   * With @p component (one entry per global row of @p a, on every rank),
   * A is read without its entries (i, j) whose rows hold different
   * components, as galerkin_product() reads it. Collective.
   *
   * @p a is a DistributedRows<double> or a SparseMatrixRows (a serial
   * matrix on MPI_COMM_SELF, read in place).
   */
  template <typename RowsOfA>
  void
  distributed_galerkin_product(
    const RowsOfA                    &a,
    const DistributedRows<double>    &p,
    const IndexSet                   &coarse_owned,
    DistributedRows<double>          &c,
    const std::vector<unsigned char> &component = {});
} // namespace Fidus

#endif
