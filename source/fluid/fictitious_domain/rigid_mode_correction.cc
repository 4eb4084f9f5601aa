#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <fidus/fluid/fictitious_domain/rigid_mode_correction.h>

namespace Fidus
{
  void
  RigidModeCorrection::reinit(const VelocityBlock        &A,
                              const IndexSet             &owned,
                              const MPI_Comm              comm,
                              const unsigned int          n_particles,
                              const unsigned int          modes,
                              std::vector<unsigned int> &&rows_in,
                              std::vector<unsigned int> &&particles_in,
                              std::vector<double>       &&values_in)
  {
    Timer timer;
    n_modes      = modes;
    n_columns    = n_particles * n_modes;
    rows         = std::move(rows_in);
    particles    = std::move(particles_in);
    values       = std::move(values_in);
    communicator = comm;
    if (n_columns == 0)
      return;

    // Z^T A Z column by column: z_j, then A z_j, then Z^T (A z_j). The
    // supports of different particles are disjoint, so z_j is cheap to set
    // and to clear; the product with A is the cost.
    TrilinosWrappers::MPI::Vector z(owned, communicator),
      Az(owned, communicator);
    FullMatrix<double>     E(n_columns, n_columns);
    dealii::Vector<double> column(n_columns);
    // The rows of each particle, so that z_j is set without a full pass.
    std::vector<std::vector<unsigned int>> rows_of(n_particles);
    for (unsigned int i = 0; i < rows.size(); ++i)
      rows_of[particles[i]].push_back(i);
    for (unsigned int p = 0; p < n_particles; ++p)
      for (unsigned int t = 0; t < n_modes; ++t)
        {
          double *zl = z.begin();
          for (const unsigned int i : rows_of[p])
            zl[rows[i]] = values[i * n_modes + t];
          A.vmult(Az, z);
          for (const unsigned int i : rows_of[p])
            zl[rows[i]] = 0.;
          restrict_to_modes(Az, column);
          for (unsigned int k = 0; k < n_columns; ++k)
            E(k, p * n_modes + t) = column(k);
        }
    // A particle with no DoF of its own (all its cells shared) gives an
    // empty column: make it the identity, which leaves that mode alone.
    // A small shift keeps modes that a tiny support makes dependent
    // solvable.
    double trace = 0.;
    for (unsigned int k = 0; k < n_columns; ++k)
      trace += E(k, k);
    for (unsigned int k = 0; k < n_columns; ++k)
      E(k, k) = E(k, k) > 0. ? E(k, k) + 1e-12 * trace / n_columns : 1.;
    coarse.reinit(n_columns);
    coarse = E;
    coarse.compute_lu_factorization();
    y.reinit(n_columns);
    setup_seconds = timer.wall_time();
  }



  void
  RigidModeCorrection::restrict_to_modes(const TrilinosWrappers::MPI::Vector &v,
                                         dealii::Vector<double> &out) const
  {
    out              = 0.;
    const double *vl = v.begin();
    for (unsigned int i = 0; i < rows.size(); ++i)
      for (unsigned int t = 0; t < n_modes; ++t)
        out(particles[i] * n_modes + t) +=
          values[i * n_modes + t] * vl[rows[i]];
    Utilities::MPI::sum(out, communicator, out);
  }



  void
  RigidModeCorrection::vmult(TrilinosWrappers::MPI::Vector       &dst,
                             const TrilinosWrappers::MPI::Vector &src) const
  {
    dst = 0.;
    if (n_columns == 0)
      return;
    restrict_to_modes(src, y);
    coarse.solve(y);
    double *dl = dst.begin();
    for (unsigned int i = 0; i < rows.size(); ++i)
      for (unsigned int t = 0; t < n_modes; ++t)
        dl[rows[i]] += values[i * n_modes + t] * y(particles[i] * n_modes + t);
  }
} // namespace Fidus
