#ifndef fidus_fluid_cut_element_cut_cell_block_jacobi_h
#define fidus_fluid_cut_element_cut_cell_block_jacobi_h

#include <cstddef>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/cut_element/distributed_rows.h>
#include <functional>
#include <memory>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The preconditioner of the cut element's multigrid smoother
   * (CutVelocityMultigrid): point Jacobi on the unknowns that no block
   * holds, plus an additive Schwarz sum over the blocks,
   *
   *   P^-1 = D_F^-1 + sum_K R_K^T W_K (R_K A R_K^T)^-1 W_K R_K,
   *
   * a block K being the unknowns of one cell that a particle surface
   * crosses (R_K restricts to them; where R_K A R_K^T is indefinite, the
   * inverse of its spectral absolute value stands for its inverse), W_K =
   * diag(1/sqrt(m)) with m the number of blocks that hold an unknown, and D_F
   * the diagonal of A on the unknowns of no block (zero on the others).
   *
   * Why: the Nitsche terms (eta gamma / h on the surface) and the ghost
   * penalties make the rows of a cut cell strongly coupled among
   * themselves; point Jacobi smooths those local modes poorly, so the
   * V-cycle's count grew with the level (doc/history/cut_element_solvers.md,
   * "Cut-cell blocks in the smoother"). The weights W keep the overlap
   * from stretching the top of the spectrum that Chebyshev covers. P^-1 is
   * symmetric positive definite where A is, so it serves Chebyshev and its
   * CG eigenvalue estimate.
   *
   * The inverses are kept in single precision, upper triangles only (a
   * smoother needs no more): a 3D Q2 cell's block of 81 unknowns takes
   * 13 KB.
   */
  class CutCellBlockJacobi
  {
  public:
    /**
     * Set up for the symmetric @p a with the blocks @p blocks, each a
     * list of distinct row indices of @p a. A block whose matrix is not
     * positive definite takes the inverse of its spectral absolute value
     * (n_indefinite_blocks()). With @p component (one entry per row),
     * @p a is read without its entries (i, j) whose rows hold different
     * components (neither 255), as distributed_galerkin_product() reads it.
     */
    void
    initialize(const SparseMatrix<double>                   &a,
               const std::vector<std::vector<unsigned int>> &blocks,
               const std::vector<unsigned char>             &component = {});

    /**
     * The same for this rank's rows of @p a (square, split among the
     * ranks). @p blocks are every rank's blocks, in global row numbers
     * (each rank passes the same list): a rank keeps those whose smallest
     * row it owns, with the rows other ranks own, which it fetches from
     * them, so a block across the border of two ranks' rows is the one
     * rank's block (vmult() then exchanges those rows' values). The
     * weights count every block. @p component, if not empty, has one
     * entry per global row of @p a. Collective.
     */
    void
    initialize(const DistributedRows<double>                &a,
               const std::vector<std::vector<unsigned int>> &blocks,
               const std::vector<unsigned char>             &component = {});

    /// dst = P^-1 src, in double or float (the V-cycle in single
    /// precision), on serial vectors or on this rank's rows of
    /// distributed ones.
    template <typename VectorType>
    void
    vmult(VectorType &dst, const VectorType &src) const;

    /// Number of blocks.
    unsigned int
    n_blocks() const
    {
      return block_start.size() - 1;
    }

    /// Number of blocks whose matrix is not positive definite.
    unsigned int
    n_indefinite_blocks() const
    {
      return n_indefinite;
    }

  private:
    /// The set-up from the diagonal of A and its rows: @p row(i, f)
    /// calls f(j, a_ij) for the entries of row i (columns j from
    /// @p n_rows on are ignored). Rows are local numbers: the diagonal's
    /// (this rank's) first, then the other ranks' rows the blocks hold, up
    /// to @p n_rows. @p count, if not empty, is the number of blocks
    /// (over all ranks) that hold each row; otherwise @p blocks' own.
    void
    setup(const std::vector<double> &diagonal,
          const std::function<
            void(unsigned int,
                 const std::function<void(unsigned int, double)> &)> &row,
          const std::vector<std::vector<unsigned int>>               &blocks,
          const unsigned int                                          n_rows,
          const std::vector<unsigned int> &count = {});

    /// out += the blocks' part of P^-1 in (local row numbers).
    template <typename Number>
    void
    add_blocks(const Number *in, Number *out) const;

    /// vmult() on distributed vectors whose blocks hold other ranks' rows:
    /// those rows' values imported, their results sent back and added.
    template <typename Number>
    void
    vmult_exchanging(LinearAlgebra::distributed::Vector<Number>       &dst,
                     const LinearAlgebra::distributed::Vector<Number> &src,
                     LinearAlgebra::distributed::Vector<Number>       &in,
                     LinearAlgebra::distributed::Vector<Number> &out) const;

    /// With blocks across the ranks: this rank's rows and the other
    /// ranks' that its blocks hold; whether some rank's blocks hold rows
    /// of another (then every vmult() exchanges); the vectors of the
    /// exchange.
    std::shared_ptr<const Utilities::MPI::Partitioner> block_rows;
    bool                                               exchange = false;
    mutable LinearAlgebra::distributed::Vector<double> in_double, out_double;
    mutable LinearAlgebra::distributed::Vector<float>  in_float, out_float;

    /// D_F^-1: 1/A_ii on the rows of no block, 0 on the others.
    Vector<double> inverse_diagonal;
    /// The rows of block b: rows[block_start[b]] to rows[block_start[b + 1]].
    std::vector<unsigned int> block_start{0}, rows;
    /// Where block b's inverse starts in inverses (its upper triangle, row
    /// by row).
    std::vector<std::size_t> inverse_start{0};
    std::vector<float>       inverses;
    /// Scratch of vmult: a block's part of src, and of the result.
    mutable std::vector<double> x, y;
    unsigned int                n_indefinite = 0;
  };
} // namespace Fidus

#endif
