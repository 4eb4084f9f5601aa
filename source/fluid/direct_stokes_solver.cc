#include <Epetra_CrsMatrix.h>
#include <algorithm>
#include <cmath>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/direct_stokes_solver.h>
#include <sstream>

namespace Fidus
{
  DirectStokesSolver::DirectStokesSolver(
    const TrilinosWrappers::BlockSparseMatrix &block_matrix,
    const std::vector<IndexSet>               &owned,
    const types::global_dof_index              pinned_pressure,
    const MPI_Comm                             communicator)
    : block_matrix(block_matrix)
    , owned(owned)
    , pinned_here(numbers::invalid_dof_index)
  {
    Timer              timer;
    const unsigned int n_blocks = owned.size();
    offset.assign(n_blocks + 1, 0);
    for (unsigned int k = 0; k < n_blocks; ++k)
      offset[k + 1] = offset[k] + owned[k].size();
    const types::global_dof_index n = offset[n_blocks];

    // The monolithic numbering keeps the blocks one after the other, so a
    // rank owns its velocity rows and then its pressure rows, and its local
    // entries are those of the blocks concatenated (gather(), scatter()).
    IndexSet owned_rows(n);
    for (unsigned int k = 0; k < n_blocks; ++k)
      owned_rows.add_indices(owned[k], offset[k]);
    owned_rows.compress();
    if (pinned_pressure != numbers::invalid_dof_index &&
        owned[1].is_element(pinned_pressure))
      pinned_here = offset[1] + pinned_pressure;

    // Each owned row of the block system, with monolithic column numbers,
    // read straight from the Epetra rows (deal.II's element iterators cost
    // ten times the factorisation on a 2D mesh of 4000 unknowns).
    std::vector<std::vector<types::global_dof_index>> columns;
    std::vector<std::vector<double>>                  values;
    columns.reserve(owned_rows.n_elements());
    values.reserve(owned_rows.n_elements());
    DynamicSparsityPattern pattern(n, n, owned_rows);
    for (unsigned int i = 0; i < n_blocks; ++i)
      for (const auto r : owned[i])
        {
          const types::global_dof_index row = offset[i] + r;
          columns.emplace_back(1, row);
          values.emplace_back(1, 0.);
          auto &c = columns.back();
          auto &v = values.back();
          for (unsigned int j = 0; j < n_blocks; ++j)
            {
              const Epetra_CrsMatrix &block =
                block_matrix.block(i, j).trilinos_matrix();
              const int local_row = block.LRID(static_cast<int>(r));
              if (local_row < 0)
                continue;
              int     n_entries = 0;
              double *entries   = nullptr;
              int    *indices   = nullptr;
              block.ExtractMyRowView(local_row, n_entries, entries, indices);
              for (int k = 0; k < n_entries; ++k)
                {
                  const types::global_dof_index column =
                    offset[j] + block.ColMap().GID(indices[k]);
                  if (column == row)
                    v[0] += entries[k];
                  else
                    {
                      c.push_back(column);
                      v.push_back(entries[k]);
                    }
                }
            }
          // The pinned row keeps only its diagonal, as large as the row's
          // largest entry, so that it does not spoil the pivots' scale.
          if (row == pinned_here)
            {
              double scale = 0.;
              for (const double x : v)
                scale = std::max(scale, std::abs(x));
              c.resize(1);
              v.assign(1, scale > 0. ? scale : 1.);
            }
          pattern.add_entries(row, c.begin(), c.end());
        }
    matrix.reinit(owned_rows, owned_rows, pattern, communicator);
    {
      unsigned int k = 0;
      for (const auto row : owned_rows)
        {
          matrix.set(row,
                     columns[k].size(),
                     columns[k].data(),
                     values[k].data());
          ++k;
        }
    }
    matrix.compress(VectorOperation::insert);
    x_flat.reinit(owned_rows, communicator);
    b_flat.reinit(owned_rows, communicator);

    // MUMPS first: on the 2D meshes of the paper scene it factorises
    // several times faster than KLU, whose ordering is meant for circuit
    // matrices; KLU where the Trilinos build has no MUMPS.
    std::string failures;
    for (const char *name : {"Amesos_Mumps", "Amesos_Klu"})
      try
        {
          direct = std::make_unique<TrilinosWrappers::SolverDirect>(
            control,
            TrilinosWrappers::SolverDirect::AdditionalData(false, name));
          direct->initialize(matrix);
          package_name = name;
          break;
        }
      catch (const ExceptionBase &e)
        {
          failures += std::string(" ") + name + ": " + e.get_exc_name() + ";";
          direct.reset();
        }
    if (!direct)
      throw RunError("the direct Stokes solver (Fluid/Linear solver/Method = "
                     "direct) could not factorise the system of " +
                     std::to_string(n) + " unknowns (" + failures +
                     "); use Method = iterative");
    setup_time = timer.wall_time();
  }



  void
  DirectStokesSolver::gather(const TrilinosWrappers::MPI::BlockVector &source,
                             TrilinosWrappers::MPI::Vector &target) const
  {
    auto out = target.begin();
    for (unsigned int k = 0; k < owned.size(); ++k)
      out = std::copy(source.block(k).begin(), source.block(k).end(), out);
    Assert(out == target.end(), ExcInternalError());
    if (pinned_here != numbers::invalid_dof_index)
      target[pinned_here] = 0.;
  }



  void
  DirectStokesSolver::scatter(const TrilinosWrappers::MPI::Vector &source,
                              TrilinosWrappers::MPI::BlockVector  &target) const
  {
    auto in = source.begin();
    for (unsigned int k = 0; k < owned.size(); ++k)
      {
        std::copy(in,
                  in + target.block(k).locally_owned_size(),
                  target.block(k).begin());
        in += target.block(k).locally_owned_size();
      }
  }



  unsigned int
  DirectStokesSolver::solve(TrilinosWrappers::MPI::BlockVector       &x,
                            const TrilinosWrappers::MPI::BlockVector &b,
                            const double                              tolerance)
  {
    x                   = 0.;
    const double b_norm = b.l2_norm();
    if (b_norm == 0.)
      return 0;
    // Iterative refinement: the factorisation of a matrix with the solid's
    // viscosity r times the fluid's can lose digits; the residual shows
    // it, and a pass on the residual gets them back.
    TrilinosWrappers::MPI::BlockVector residual(b), correction(x);
    double                             r_norm = b_norm;
    unsigned int                       passes = 0;
    for (; passes < 4 && r_norm > tolerance * b_norm; ++passes)
      {
        gather(residual, b_flat);
        direct->solve(x_flat, b_flat);
        scatter(x_flat, correction);
        x += correction;
        block_matrix.vmult(residual, x);
        residual.sadd(-1., 1., b);
        // The pinned row's own equation was replaced; with a consistent
        // right-hand side it holds to round-off, and it is not what the
        // factorisation solved.
        if (pinned_here != numbers::invalid_dof_index)
          residual.block(1)[pinned_here - offset[1]] = 0.;
        residual.compress(VectorOperation::insert);
        r_norm = residual.l2_norm();
      }
    if (!(r_norm <= tolerance * b_norm))
      {
        std::ostringstream s;
        s << "the direct Stokes solver (" << package_name
          << ") left a residual of " << r_norm / b_norm
          << " of the right-hand side after " << passes
          << " refinement passes, above the tolerance " << tolerance
          << " (Fluid/Linear solver/Tolerance); the system is close to "
             "singular: try Method = iterative or a smaller Penalty factor";
        throw RunError(s.str());
      }
    return passes;
  }
} // namespace Fidus
