#ifndef fidus_fluid_cut_element_sparse_matrix_rows_h
#define fidus_fluid_cut_element_sparse_matrix_rows_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/lac/sparse_matrix.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * A deal.II SparseMatrix<double> read the way DistributedRows is read
   * (local_rows(), for_row(), column_partitioner(), ...), as the only rank
   * of MPI_COMM_SELF owning every row and column: the one-rank solver hands
   * its velocity block to the multigrid (CutVelocityMultigrid) and the
   * Galerkin product (distributed_galerkin_product()) through it, without a
   * copy.
   */
  class SparseMatrixRows
  {
  public:
    explicit SparseMatrixRows(const SparseMatrix<double> &matrix)
      : m(matrix)
      , rows(complete_index_set(matrix.m()))
      , partitioner(matrix.n())
    {}

    unsigned int
    local_rows() const
    {
      return m.m();
    }
    types::global_dof_index
    first_row() const
    {
      return 0;
    }
    const IndexSet &
    locally_owned_rows() const
    {
      return rows;
    }
    const Utilities::MPI::Partitioner &
    column_partitioner() const
    {
      return partitioner;
    }
    MPI_Comm
    get_mpi_communicator() const
    {
      return MPI_COMM_SELF;
    }
    /// f(column, value) for each entry of row @p k, the diagonal first.
    template <typename F>
    void
    for_row(const unsigned int k, const F &f) const
    {
      for (auto e = m.begin(k); e != m.end(k); ++e)
        f(e->column(), e->value());
    }

    /// The matrix read.
    const SparseMatrix<double> &
    matrix() const
    {
      return m;
    }

  private:
    const SparseMatrix<double>       &m;
    const IndexSet                    rows;
    const Utilities::MPI::Partitioner partitioner;
  };
} // namespace Fidus

#endif
