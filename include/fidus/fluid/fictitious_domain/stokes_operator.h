#ifndef fidus_fluid_stokes_operator_h
#define fidus_fluid_stokes_operator_h

#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <fidus/fluid/fictitious_domain/velocity_block.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * dst (+)= B^T src. The matrix-free GMG keeps no B^T block (it is
   * cleared once B is assembled, StokesSolver::assemble_system(), saving
   * the memory of a second copy of B): then B^T is applied as the
   * transpose of the B block. Where the block is kept, it is used.
   */
  inline void
  apply_coupling_transpose(const TrilinosWrappers::BlockSparseMatrix &stokes,
                           TrilinosWrappers::MPI::Vector             &dst,
                           const TrilinosWrappers::MPI::Vector       &src,
                           const bool                                 add)
  {
    const bool stored = stokes.block(0, 1).m() > 0;
    if (stored && add)
      stokes.block(0, 1).vmult_add(dst, src);
    else if (stored)
      stokes.block(0, 1).vmult(dst, src);
    else if (add)
      stokes.block(1, 0).Tvmult_add(dst, src);
    else
      stokes.block(1, 0).Tvmult(dst, src);
  }

  /**
   * The penalised Stokes operator
   *
   *     [ A  B^T ]
   *     [ B  C   ]
   *
   * with the velocity block A given as a VelocityBlock (assembled or
   * matrix-free) and B, B^T and C (zero, but for the diagonal entries of
   * constrained pressure rows) taken from the assembled block matrix (B^T
   * as the transpose of B where its block is not kept). This
   * is what the outer FGMRES multiplies by.
   */
  class StokesOperator
  {
  public:
    StokesOperator(const TrilinosWrappers::BlockSparseMatrix &stokes,
                   const VelocityBlock                       &A)
      : stokes(stokes)
      , A(A)
    {}

    /// dst = [A B^T; B C] src.
    void
    vmult(TrilinosWrappers::MPI::BlockVector       &dst,
          const TrilinosWrappers::MPI::BlockVector &src) const
    {
      A.vmult(dst.block(0), src.block(0));
      apply_coupling_transpose(stokes, dst.block(0), src.block(1), true);
      stokes.block(1, 0).vmult(dst.block(1), src.block(0));
      stokes.block(1, 1).vmult_add(dst.block(1), src.block(1));
    }

  private:
    const TrilinosWrappers::BlockSparseMatrix &stokes;
    const VelocityBlock                       &A;
  };
} // namespace Fidus

#endif
