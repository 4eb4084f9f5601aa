#ifndef fidus_fluid_rigid_mode_correction_h
#define fidus_fluid_rigid_mode_correction_h

#include <deal.II/base/index_set.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <fidus/fluid/fictitious_domain/velocity_block.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * Coarse space of the rigid motions of each particle for the velocity
   * block A of the penalised Stokes system.
   *
   * Why: in the solid the viscosity is r eta_f, so every particle adds
   * dim (dim + 1) / 2 rigid motions whose energy is only that of the fluid
   * around it: eigenvalues of A that are r times smaller than the strain
   * modes of the solid. One V-cycle (AMG or geometric) does not see those
   * local modes; with 120 discs the cheap preconditioner needed about 390
   * FGMRES iterations per solve, against 31 with exact inner solves of the
   * same blocks (doc/preconditioners.md). The correction Q = Z (Z^T A Z)^{-1}
   * Z^T removes them: Z holds, for each particle, its rigid motions on the
   * velocity DoFs of the cells that meet its solid, zero elsewhere.
   *
   * Used multiplicatively around the V-cycle P
   * (DeflatedVelocityPreconditioner): x = Q r, then x += P (r - A x), then x +=
   * Q (r - A x).
   */
  class RigidModeCorrection
  {
  public:
    /**
     * Build Z^T A Z. @p rows: positions in the rank's part of the velocity
     * block of the DoFs in a particle's support; @p particles: the particle
     * of each (0 ... @p n_particles - 1, the same numbering on every rank);
     * @p values: the @p n_modes rigid-motion values of each row, row after
     * row; @p owned: the velocity DoFs of this rank. Costs n_particles *
     * n_modes products with A.
     */
    void
    reinit(const VelocityBlock        &A,
           const IndexSet             &owned,
           MPI_Comm                    communicator,
           unsigned int                n_particles,
           unsigned int                n_modes,
           std::vector<unsigned int> &&rows,
           std::vector<unsigned int> &&particles,
           std::vector<double>       &&values);

    /// Whether there is a coarse space (at least one particle).
    bool
    empty() const
    {
      return n_columns == 0;
    }

    /// dst = Z (Z^T A Z)^{-1} Z^T src.
    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

    /// Wall seconds of the last reinit().
    double setup_seconds = 0.;

  private:
    /// y = Z^T v, summed over ranks.
    void
    restrict_to_modes(const TrilinosWrappers::MPI::Vector &v,
                      dealii::Vector<double>              &y) const;

    unsigned int                     n_columns = 0, n_modes = 0;
    std::vector<unsigned int>        rows, particles;
    std::vector<double>              values;
    MPI_Comm                         communicator = MPI_COMM_SELF;
    mutable LAPACKFullMatrix<double> coarse;
    mutable dealii::Vector<double>   y;
  };
} // namespace Fidus

#endif
