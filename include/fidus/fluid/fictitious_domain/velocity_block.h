#ifndef fidus_fluid_velocity_block_h
#define fidus_fluid_velocity_block_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <functional>

namespace Fidus
{
  using namespace dealii;

  /**
   * The velocity block A of the penalised Stokes system, as an operator on
   * the system's velocity vectors: either the assembled Trilinos matrix or
   * the matrix-free operator of the finest multigrid level
   * (VelocityMultigrid::apply_velocity_block). Everything that multiplies
   * by A (the outer FGMRES, the inner CG of expensive mode, the rigid-body
   * correction, Anderson's energy products) goes through this class, so
   * that the matrix need not be assembled when the geometric multigrid is
   * on: for Q2 in 3D the assembled block is the largest object of a run
   * and its product the largest cost of an FGMRES iteration.
   */
  class VelocityBlock
  {
  public:
    using Vector = TrilinosWrappers::MPI::Vector;

    /// The assembled matrix @p A (kept by reference).
    explicit VelocityBlock(const TrilinosWrappers::SparseMatrix &A)
      : apply([&A](Vector &dst, const Vector &src) { A.vmult(dst, src); })
    {}

    /// Any operator with the same action: dst = A src.
    explicit VelocityBlock(std::function<void(Vector &, const Vector &)> f)
      : apply(std::move(f))
    {}

    /// dst = A src.
    void
    vmult(Vector &dst, const Vector &src) const
    {
      apply(dst, src);
    }

  private:
    std::function<void(Vector &, const Vector &)> apply;
  };
} // namespace Fidus

#endif
