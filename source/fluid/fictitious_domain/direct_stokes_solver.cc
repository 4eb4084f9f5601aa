#include <Amesos.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <algorithm>
#include <cmath>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/fictitious_domain/direct_stokes_solver.h>
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

    // The pattern: each owned row with monolithic column numbers, the
    // diagonal first (read_rows()).
    DynamicSparsityPattern pattern(n, n, owned_rows);
    read_rows([&](const types::global_dof_index         row,
                  std::vector<types::global_dof_index> &c,
                  const std::vector<double> &) {
      pattern.add_entries(row, c.begin(), c.end());
      columns.push_back(c);
    });
    matrix.reinit(owned_rows, owned_rows, pattern, communicator);
    copy_values();
    x_flat.reinit(owned_rows, communicator);
    b_flat.reinit(owned_rows, communicator);
    problem =
      std::make_unique<Epetra_LinearProblem>(const_cast<Epetra_CrsMatrix *>(
                                               &matrix.trilinos_matrix()),
                                             &x_flat.trilinos_vector(),
                                             &b_flat.trilinos_vector());

    // MUMPS first: on the 2D meshes of the paper scene it factorises
    // faster than KLU, whose ordering is meant for circuit matrices; KLU
    // where the Trilinos build has no MUMPS.
    Amesos factory;
    for (const char *name : {"Amesos_Mumps", "Amesos_Klu"})
      if (factory.Query(name))
        {
          solver.reset(factory.Create(name, *problem));
          if (solver)
            {
              package_name = name;
              break;
            }
        }
    if (!solver)
      throw RunError("the direct Stokes solver (Fluid/Linear solver/Method "
                     "= direct) found neither MUMPS nor KLU in Trilinos' "
                     "Amesos; use Method = iterative");
    if (solver->SymbolicFactorization() != 0)
      throw RunError("the direct Stokes solver (" + package_name +
                     ") could not analyse the system of " + std::to_string(n) +
                     " unknowns; use Method = iterative");
    factorise();
  }



  template <class RowFunction>
  void
  DirectStokesSolver::read_rows(const RowFunction &f) const
  {
    // Straight from the Epetra rows: deal.II's element iterators cost ten
    // times the factorisation on a 2D mesh of 4000 unknowns.
    std::vector<types::global_dof_index> c;
    std::vector<double>                  v;
    const unsigned int                   n_blocks = owned.size();
    for (unsigned int i = 0; i < n_blocks; ++i)
      for (const auto r : owned[i])
        {
          const types::global_dof_index row = offset[i] + r;
          c.assign(1, row);
          v.assign(1, 0.);
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
          f(row, c, v);
        }
  }



  void
  DirectStokesSolver::copy_values()
  {
    // The block matrix's pattern is fixed for one mesh, so each row comes
    // in the order in which the pattern was built.
    unsigned int k = 0;
    read_rows([&](const types::global_dof_index         row,
                  std::vector<types::global_dof_index> &c,
                  const std::vector<double>            &v) {
      Assert(c == columns[k], ExcInternalError());
      (void)c;
      matrix.set(row, columns[k].size(), columns[k].data(), v.data());
      ++k;
    });
    matrix.compress(VectorOperation::insert);
  }



  void
  DirectStokesSolver::factorise()
  {
    if (solver->NumericFactorization() != 0)
      throw RunError("the direct Stokes solver (" + package_name +
                     ") could not factorise the system of " +
                     std::to_string(matrix.m()) +
                     " unknowns (numerically singular); use Method = "
                     "iterative or a smaller Penalty factor");
  }



  void
  DirectStokesSolver::refactorise()
  {
    copy_values();
    factorise();
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
        if (solver->Solve() != 0)
          throw RunError("the direct Stokes solver (" + package_name +
                         ") failed in its substitution");
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
