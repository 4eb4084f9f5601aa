#ifndef fidus_fluid_direct_stokes_solver_h
#define fidus_fluid_direct_stokes_solver_h

#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>
#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <memory>
#include <string>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * A sparse direct solve of the fictitious domain's penalised Stokes system
   * (`Fluid/Linear solver/Method = direct`), for the meshes where a
   * factorisation is cheaper than FGMRES: every 2D scene fidus ships
   * (doc/fluid.md, "A direct solver for 2D").
   *
   * Within one solve of StokesSolver the matrix stays the same for all
   * Uzawa iterations (the penalised viscosity is also the augmentation;
   * only the multiplier's load changes), so it is factorised once and each
   * Uzawa iteration costs one forward and backward substitution, where
   * FGMRES needed 40 to 400 iterations.
   *
   * The block system [A B^T; B 0] (hanging-node, periodic and boundary
   * rows reduced to their diagonal by the assembly) is copied into one
   * distributed Trilinos matrix. Its pattern and the factorisation's
   * analysis (ordering, symbolic factorisation) are kept for as long as the
   * mesh is: a later time step only copies the values and factorises
   * again (refactorise()). With velocity imposed on the whole
   * boundary the pressure is fixed up to a constant, so the row of one
   * unconstrained pressure unknown is replaced by p_pin = 0; the
   * right-hand side is consistent (StokesSolver removes its
   * constant-pressure part), so the dropped equation holds anyway, and
   * StokesSolver shifts the pressure to zero mean afterwards. The matrix is
   * factorised with MUMPS through Trilinos' Amesos, or KLU where MUMPS is
   * not available. Each solve measures the residual of the block system
   * and refines iteratively until it is below the requested fraction of
   * the right-hand side; a solve that cannot get there is reported, not
   * passed on.
   */
  class DirectStokesSolver
  {
  public:
    /**
     * Copy and factorise @p matrix. @p owned: the locally owned rows of
     * each block (velocity, pressure), numbered within the block;
     * @p pinned_pressure: the pressure unknown (numbered within the
     * pressure block) whose row becomes p = 0, or numbers::invalid_dof_index
     * when the pressure is not fixed up to a constant (some boundary without
     * imposed velocity).
     */
    DirectStokesSolver(const TrilinosWrappers::BlockSparseMatrix &matrix,
                       const std::vector<IndexSet>               &owned,
                       types::global_dof_index pinned_pressure,
                       MPI_Comm                communicator);

    /**
     * Factorise again after the values of the block matrix changed on the
     * same mesh (its sparsity, and so the analysis, are kept).
     */
    void
    refactorise();

    /**
     * Solve matrix x = b to a residual below @p tolerance times |b| (at
     * most four refinement passes; RunError otherwise). Returns the
     * number of substitutions it took.
     */
    unsigned int
    solve(TrilinosWrappers::MPI::BlockVector       &x,
          const TrilinosWrappers::MPI::BlockVector &b,
          double                                    tolerance);

  private:
    /// Call @p f(row, columns, values) for each owned row of the
    /// monolithic system (the diagonal first; the pinned row reduced).
    template <class RowFunction>
    void
    read_rows(const RowFunction &f) const;
    /// Copy the block matrix's values into the monolithic one.
    void
    copy_values();
    /// Numeric factorisation (the analysis is made once per mesh).
    void
    factorise();
    void
    gather(const TrilinosWrappers::MPI::BlockVector &source,
           TrilinosWrappers::MPI::Vector            &target) const;
    void
    scatter(const TrilinosWrappers::MPI::Vector &source,
            TrilinosWrappers::MPI::BlockVector  &target) const;

    const TrilinosWrappers::BlockSparseMatrix &block_matrix;
    std::vector<IndexSet>                      owned;
    /// First global index of each block in the monolithic numbering.
    std::vector<types::global_dof_index> offset;
    /// The pinned pressure in the monolithic numbering, if this rank owns
    /// it; numbers::invalid_dof_index otherwise.
    types::global_dof_index pinned_here;

    /// The monolithic pattern: per owned row, its columns.
    std::vector<std::vector<types::global_dof_index>> columns;
    TrilinosWrappers::SparseMatrix                    matrix;
    TrilinosWrappers::MPI::Vector                     x_flat, b_flat;
    std::unique_ptr<Epetra_LinearProblem>             problem;
    std::unique_ptr<Amesos_BaseSolver>                solver;
    /// The Amesos solver in use: "Amesos_Mumps" or "Amesos_Klu".
    std::string package_name;
  };
} // namespace Fidus

#endif
