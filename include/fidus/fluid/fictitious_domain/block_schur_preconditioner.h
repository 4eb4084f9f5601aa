#ifndef fidus_fluid_block_schur_preconditioner_h
#define fidus_fluid_block_schur_preconditioner_h

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <fidus/fluid/fictitious_domain/stokes_operator.h>
#include <fidus/fluid/fictitious_domain/velocity_block.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * Block upper-triangular preconditioner for the penalised Stokes system
   *
   *     P = [ A  B^T ]      P^{-1} r:  p = -S^{-1} r_p,
   *         [ 0  -S  ]                 u =  A^{-1} (r_u - B^T p),
   *
   * with A^{-1} approximated by @p VelocityPreconditioner (the ML AMG or the
   * geometric multigrid) and S^{-1} by the inverse of
   * the pressure mass matrix weighted by 1/eta, which is spectrally
   * equivalent to the Schur complement B A^{-1} B^T even across large
   * viscosity jumps (the solid has r times the fluid viscosity).
   *
   * "Cheap" mode applies one V-cycle and CG with Jacobi on the pressure
   * mass to 1e-2; "expensive" mode solves both blocks with CG to a
   * relative tolerance (1e-2 on the velocities, 1e-6 on the pressures). FGMRES
   * is used outside because either mode is a nonlinear (or inexact) operator.
   */
  template <class VelocityPreconditioner>
  class BlockSchurPreconditioner : public Subscriptor
  {
  public:
    /// @p stokes: the system matrix (for B^T); @p A: its velocity block
    /// (assembled or matrix-free); @p mass: the 1/eta pressure mass;
    /// @p expensive selects inner solves.
    BlockSchurPreconditioner(const TrilinosWrappers::BlockSparseMatrix &stokes,
                             const VelocityBlock                       &A,
                             const TrilinosWrappers::SparseMatrix      &mass,
                             const VelocityPreconditioner &velocity,
                             const TrilinosWrappers::PreconditionJacobi &jacobi,
                             const bool expensive)
      : stokes(stokes)
      , A(A)
      , mass(mass)
      , velocity(velocity)
      , jacobi(jacobi)
      , expensive(expensive)
    {}

    /// Apply the preconditioner: dst = P^{-1} src.
    void
    vmult(TrilinosWrappers::MPI::BlockVector       &dst,
          const TrilinosWrappers::MPI::BlockVector &src) const
    {
      if (expensive)
        {
          SolverControl control(1000, 1e-6 * src.block(1).l2_norm());
          SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
          dst.block(1) = 0;
          cg.solve(mass, dst.block(1), src.block(1), jacobi);
          inner_iterations += control.last_step();
        }
      else
        {
          // CG with Jacobi to 1e-2, a few matrix products on the pressures:
          // one Jacobi sweep alone, used before, left FGMRES 17-29 % more
          // iterations on the bulk 3D scene (doc/theory/fictitious_domain.md,
          // "Linear solvers"). FGMRES takes the varying operator.
          SolverControl                           control(100,
                                1e-2 * src.block(1).l2_norm(),
                                false,
                                false);
          SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
          dst.block(1) = 0;
          try
            {
              cg.solve(mass, dst.block(1), src.block(1), jacobi);
            }
          catch (const SolverControl::NoConvergence &)
            {}
        }
      dst.block(1) *= -1.;

      if (tmp.size() != src.block(0).size())
        tmp.reinit(src.block(0), true);
      apply_coupling_transpose(stokes, tmp, dst.block(1), false);
      tmp *= -1.;
      tmp += src.block(0);

      if (expensive)
        {
          SolverControl control(10000, 1e-2 * tmp.l2_norm());
          SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
          dst.block(0) = 0;
          cg.solve(A, dst.block(0), tmp, velocity);
          inner_iterations += control.last_step();
        }
      else
        velocity.vmult(dst.block(0), tmp);
    }

    /// Inner CG iterations done so far (expensive mode).
    mutable unsigned int inner_iterations = 0;

  private:
    const TrilinosWrappers::BlockSparseMatrix  &stokes;
    const VelocityBlock                        &A;
    const TrilinosWrappers::SparseMatrix       &mass;
    const VelocityPreconditioner               &velocity;
    const TrilinosWrappers::PreconditionJacobi &jacobi;
    const bool                                  expensive;
    mutable TrilinosWrappers::MPI::Vector       tmp;
  };
} // namespace Fidus

#endif
