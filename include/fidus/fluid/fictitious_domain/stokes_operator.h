#ifndef fidus_fluid_stokes_operator_h
#define fidus_fluid_stokes_operator_h

#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <fidus/fluid/fictitious_domain/velocity_block.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * The penalised Stokes operator
   *
   *     [ A  B^T ]
   *     [ B  C   ]
   *
   * with the velocity block A given as a VelocityBlock (assembled or
   * matrix-free) and B, B^T and C (zero, but for the diagonal entries of
   * constrained pressure rows) taken from the assembled block matrix. This
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
      stokes.block(0, 1).vmult_add(dst.block(0), src.block(1));
      stokes.block(1, 0).vmult(dst.block(1), src.block(0));
      stokes.block(1, 1).vmult_add(dst.block(1), src.block(1));
    }

  private:
    const TrilinosWrappers::BlockSparseMatrix &stokes;
    const VelocityBlock                       &A;
  };
} // namespace Fidus

#endif
