// The cut element's iterative solve over more than one MPI rank: each rank
// holds its range of K's rows (velocities, then rigid unknowns) with B^T's,
// and a range of the pressures with B's, the pressure block's and the
// pressure preconditioner's; FGMRES and the pressure side's CG run on
// vectors of those ranges (doc/developer/architecture.md, "The cut element
// over ranks").

#include <algorithm>
#include <deal.II/base/timer.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <fidus/fluid/cut_element/cut_saddle_point_solver.h>
#include <fidus/fluid/cut_element/distributed_galerkin_product.h>
#include <sstream>
#include <stdexcept>

namespace Fidus
{
  template <int dim>
  void
  CutSaddlePointSolver<dim>::split_velocity_block(const Layout &layout)
  {
    // K's rows this rank holds (the rigid rows go with the last range):
    // split_blocks() set k_owned.
    const MPI_Comm communicator = layout.communicator;
    // Read in place: K holds these rows only (the other velocity rows an
    // empty diagonal), so the rank keeps no second copy of them.
    k_rows = std::make_unique<DistributedRows<double>>();
    k_rows->borrow(k_owned, velocity_matrix, communicator);
    k_in.reinit(k_owned, communicator);
    multigrid->initialize(*k_rows, velocity, rigid.size());
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::split_blocks(const Layout &layout)
  {
    const MPI_Comm     communicator = layout.communicator;
    const unsigned int n_p          = pressure.size();
    k_owned = contiguous_range(layout.k_end - layout.k_first, communicator);
    AssertThrow(k_owned.n_elements() == 0 ||
                  k_owned.nth_index_in_set(0) == layout.k_first,
                ExcMessage("The ranks' rows of K are not consecutive."));
    // The pressures where the system's split of K's rows falls among them
    // (CutStokesSolve splits both at the same system index), so that a
    // rank's pressures lie where its velocities do.
    const unsigned int p_first = layout.p_first, p_end = layout.p_end;
    AssertThrow(p_end <= n_p, ExcIndexRange(p_end, 0, n_p + 1));
    p_owned = contiguous_range(p_end - p_first, communicator);
    AssertThrow(p_owned.n_elements() == 0 ||
                  p_owned.nth_index_in_set(0) == p_first,
                ExcMessage("The ranks' pressures are not consecutive."));

    // Each block's rows here, from the whole block (its columns already in
    // the block's numbering; a square block's diagonal first, as fill()
    // keeps it).
    const auto rows_of = [&](const SparseMatrix<double> &whole,
                             const unsigned int          first) {
      return [&whole, first](const unsigned int k, const auto &f) {
        for (auto it = whole.begin(first + k), end = whole.end(first + k);
             it != end;
             ++it)
          f(it->column(), it->value());
      };
    };
    const unsigned int k_first = layout.k_first;
    bt_rows                    = std::make_unique<DistributedRows<double>>();
    bt_rows->fill(k_owned, p_owned, rows_of(coupling, k_first), communicator);
    p_rows = std::make_unique<DistributedRows<double>>();
    p_rows->fill(p_owned,
                 p_owned,
                 rows_of(pressure_block, p_first),
                 communicator);
    s_rows = std::make_unique<DistributedRows<double>>();
    s_rows->fill(p_owned,
                 p_owned,
                 rows_of(pressure_schur, p_first),
                 communicator);

    s_inverse_diagonal.reinit(p_owned, communicator);
    for (unsigned int k = 0; k < p_end - p_first; ++k)
      s_inverse_diagonal.local_element(k) = 1. / s_rows->diag_element(k);
    for (unsigned int c = 0; c < constrained_pressures.size(); ++c)
      if (constrained_pressures[c] >= p_first &&
          constrained_pressures[c] < p_end)
        {
          own_constrained.push_back(constrained_pressures[c] - p_first);
          own_constrained_diagonal.push_back(constrained_diagonal[c]);
        }
    if (mean.size() > 0)
      {
        // m lies on the pressures (the pressure mass's rows).
        for (const unsigned int i : velocity)
          AssertThrow(mean[i] == 0., ExcInternalError());
        mean_part.reinit(p_owned, communicator);
        for (unsigned int k = 0; k < p_end - p_first; ++k)
          mean_part.local_element(k) = mean[pressure[p_first + k]];
      }

    // The whole blocks are read no more (split_gap_laplacian() reads the
    // rows).
    coupling.clear();
    pressure_block.clear();
    blocks->bt_pattern.reinit(0, 0, 0);
    blocks->p_pattern.reinit(0, 0, 0);
    pressure_schur.clear();
    pressure_sparsity.reinit(0, 0, 0);
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::split_gap_laplacian(const Layout &layout)
  {
    if (layout.gap_laplacian <= 0. || layout.in_gap.empty())
      return;
    const std::vector<int> gap_index = select_gap_pressures(layout);
    if (gap_pressures.empty())
      return;
    const MPI_Comm     communicator = layout.communicator;
    const unsigned int n_u          = velocity.size();
    const unsigned int k_first      = bt_rows->first_row(),
                       p_first      = p_rows->first_row();
    // This rank's gap pressures are those of its range of the pressures:
    // consecutive among them, in the ranks' order.
    const unsigned int g_first =
      std::lower_bound(gap_pressures.begin(), gap_pressures.end(), p_first) -
      gap_pressures.begin();
    const unsigned int g_end =
      std::lower_bound(gap_pressures.begin(),
                       gap_pressures.end(),
                       p_first + p_owned.n_elements()) -
      gap_pressures.begin();
    gap_owned = contiguous_range(g_end - g_first, communicator);

    // B D^-1 B^T = P^T A P with P B^T's fluid rows on the gap pressures'
    // columns (the rigid rows left out, as in build_gap_laplacian()) and
    // A = D^-1 on K's rows.
    const Utilities::MPI::Partitioner &bt_columns =
      bt_rows->column_partitioner();
    DistributedRows<double> p, d_inverse, product;
    p.fill(
      k_owned,
      gap_owned,
      [&](const unsigned int k, const auto &f) {
        if (k_first + k < n_u)
          bt_rows->for_row(k, [&](const unsigned int c, const double v) {
            const int g = gap_index[bt_columns.local_to_global(c)];
            if (g >= 0 && v != 0.)
              f(g, v);
          });
      },
      communicator);
    d_inverse.fill(
      k_owned,
      k_owned,
      [&](const unsigned int k, const auto &f) {
        const double d = k_diagonal[k_first + k];
        f(k_first + k, d > 0. ? 1. / d : 0.);
      },
      communicator);
    distributed_galerkin_product(d_inverse, p, gap_owned, product);

    // Plus C among the gap pressures (the system holds -C), into Trilinos's
    // matrix over the ranks.
    const Utilities::MPI::Partitioner &product_columns =
                                        product.column_partitioner(),
                                      &p_columns = p_rows->column_partitioner();
    const auto for_entries                       = [&](const auto &f) {
      for (unsigned int k = 0; k < g_end - g_first; ++k)
        {
          const unsigned int row = g_first + k;
          product.for_row(k, [&](const unsigned int c, const double v) {
            f(row, product_columns.local_to_global(c), v);
          });
          p_rows->for_row(gap_pressures[row] - p_first,
                          [&](const unsigned int c, const double v) {
                            const int g =
                              gap_index[p_columns.local_to_global(c)];
                            if (g >= 0)
                              f(row, g, -v);
                          });
        }
    };
    TrilinosWrappers::SparsityPattern pattern(gap_owned, communicator);
    for_entries([&](const unsigned int i, const unsigned int j, double) {
      pattern.add(i, j);
    });
    pattern.compress();
    gap_rows.reinit(pattern);
    for_entries([&](const unsigned int i,
                    const unsigned int j,
                    const double       v) { gap_rows.add(i, j, v); });
    gap_rows.compress(VectorOperation::add);
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic        = true;
    data.smoother_sweeps = 2;
    gap_amg.initialize(gap_rows, data);
    r_gap.reinit(gap_owned, communicator);
    z_gap.reinit(gap_owned, communicator);
  }



  template <int dim>
  typename CutSaddlePointSolver<dim>::PartsVector
  CutSaddlePointSolver<dim>::make_parts() const
  {
    PartsVector parts(2);
    parts.block(0).reinit(k_owned, k_rows->get_mpi_communicator());
    parts.block(1).reinit(p_owned, k_rows->get_mpi_communicator());
    parts.collect_sizes();
    return parts;
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::to_parts(const Vector<double> &whole,
                                      PartsVector          &parts) const
  {
    const unsigned int n_u     = velocity.size();
    const unsigned int k_first = bt_rows->first_row(),
                       p_first = p_rows->first_row();
    for (unsigned int k = 0; k < k_owned.n_elements(); ++k)
      {
        const unsigned int j = k_first + k;
        parts.block(0).local_element(k) =
          whole[j < n_u ? velocity[j] : rigid[j - n_u]];
      }
    for (unsigned int k = 0; k < p_owned.n_elements(); ++k)
      parts.block(1).local_element(k) = whole[pressure[p_first + k]];
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::from_parts(const PartsVector &parts,
                                        Vector<double>    &whole) const
  {
    const unsigned int n_u     = velocity.size();
    const unsigned int k_first = bt_rows->first_row(),
                       p_first = p_rows->first_row();
    whole                      = 0.;
    for (unsigned int k = 0; k < k_owned.n_elements(); ++k)
      {
        const unsigned int j = k_first + k;
        whole[j < n_u ? velocity[j] : rigid[j - n_u]] =
          parts.block(0).local_element(k);
      }
    for (unsigned int k = 0; k < p_owned.n_elements(); ++k)
      whole[pressure[p_first + k]] = parts.block(1).local_element(k);
    Utilities::MPI::sum(whole, k_rows->get_mpi_communicator(), whole);
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::through_parts(
    Vector<double>       &dst,
    const Vector<double> &src,
    void (CutSaddlePointSolver::*op)(PartsVector &, const PartsVector &)
      const) const
  {
    PartsVector parts = make_parts(), product = make_parts();
    to_parts(src, parts);
    (this->*op)(product, parts);
    from_parts(product, dst);
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::split_system_vmult(PartsVector       &dst,
                                                const PartsVector &src) const
  {
    // [K B^T; B P] [x_K; x_p] (B as B^T's transpose), and the rank-one
    // term that fixes the pressure's mean.
    k_rows->vmult(dst.block(0), src.block(0));
    bt_rows->vmult_add(dst.block(0), src.block(1));
    p_rows->vmult(dst.block(1), src.block(1));
    bt_rows->Tvmult_add(dst.block(1), src.block(0));
    if (mean_part.size() > 0)
      dst.block(1).add(-(mean_part * src.block(1)), mean_part);
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::split_pressure_inverse(PartVector       &z,
                                                    const PartVector &r) const
  {
    // As apply_pressure_inverse(): CG with point Jacobi on S to 1e-2, the
    // gap Laplacian's AMG, the constrained pressures exactly.
    struct Jacobi
    {
      const PartVector &inverse_diagonal;
      void
      vmult(PartVector &dst, const PartVector &src) const
      {
        dst = src;
        dst.scale(inverse_diagonal);
      }
    };
    z = 0.;
    SolverControl        control(200, 1e-2 * r.l2_norm(), false, false);
    SolverCG<PartVector> cg(control);
    try
      {
        cg.solve(*s_rows, z, r, Jacobi{s_inverse_diagonal});
      }
    catch (const SolverControl::NoConvergence &)
      {}
    if (!gap_pressures.empty())
      {
        const unsigned int p_first = r.get_partitioner()->local_range().first,
                           g_first =
                             z_gap.get_partitioner()->local_range().first;
        for (unsigned int k = 0; k < r_gap.locally_owned_size(); ++k)
          r_gap.local_element(k) =
            r.local_element(gap_pressures[g_first + k] - p_first);
        gap_amg.vmult(z_gap, r_gap);
        for (unsigned int k = 0; k < z_gap.locally_owned_size(); ++k)
          z.local_element(gap_pressures[g_first + k] - p_first) +=
            gap_weight * z_gap.local_element(k);
      }
    z *= -1.;
    for (unsigned int c = 0; c < own_constrained.size(); ++c)
      z.local_element(own_constrained[c]) =
        r.local_element(own_constrained[c]) / own_constrained_diagonal[c];
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::split_vmult(PartsVector       &dst,
                                         const PartsVector &src) const
  {
    // z_p = -S^-1 r_p, then one multigrid cycle on r_K - B^T z_p.
    split_pressure_inverse(dst.block(1), src.block(1));
    bt_rows->vmult(k_in, dst.block(1));
    k_in.sadd(-1., 1., src.block(0));
    multigrid->vmult(dst.block(0), k_in);
  }



  template <int dim>
  typename CutSaddlePointSolver<dim>::Statistics
  CutSaddlePointSolver<dim>::solve_split(Vector<double>       &x,
                                         const Vector<double> &b,
                                         const double          tolerance,
                                         const unsigned int    max_iterations,
                                         const bool            from_x)
  {
    // The system and the preconditioner as FGMRES multiplies by them.
    struct Operator
    {
      const CutSaddlePointSolver &solver;
      const bool                  system;
      void
      vmult(PartsVector &dst, const PartsVector &src) const
      {
        if (system)
          solver.split_system_vmult(dst, src);
        else
          solver.split_vmult(dst, src);
      }
    };
    const Operator system{*this, true}, preconditioner{*this, false};
    PartsVector    x_parts = make_parts(), b_parts = make_parts();
    to_parts(b, b_parts);
    if (from_x)
      to_parts(x, x_parts);
    run_fgmres(system,
               preconditioner,
               x_parts,
               b_parts,
               tolerance,
               max_iterations,
               from_x);
    from_parts(x_parts, x);
    return statistics;
  }

  // The members defined here, for both dimensions (the class itself is
  // instantiated in cut_saddle_point_solver.cc).
  template void
  CutSaddlePointSolver<2>::split_velocity_block(const Layout &);
  template void
  CutSaddlePointSolver<2>::split_blocks(const Layout &);
  template void
  CutSaddlePointSolver<2>::split_gap_laplacian(const Layout &);
  template CutSaddlePointSolver<2>::PartsVector
  CutSaddlePointSolver<2>::make_parts() const;
  template void
  CutSaddlePointSolver<2>::to_parts(const Vector<double> &,
                                    PartsVector &) const;
  template void
  CutSaddlePointSolver<2>::from_parts(const PartsVector &,
                                      Vector<double> &) const;
  template void
  CutSaddlePointSolver<2>::through_parts(
    Vector<double> &,
    const Vector<double> &,
    void (CutSaddlePointSolver<2>::*)(PartsVector &, const PartsVector &)
      const) const;
  template void
  CutSaddlePointSolver<2>::split_system_vmult(PartsVector &,
                                              const PartsVector &) const;
  template void
  CutSaddlePointSolver<2>::split_pressure_inverse(PartVector &,
                                                  const PartVector &) const;
  template void
  CutSaddlePointSolver<2>::split_vmult(PartsVector &,
                                       const PartsVector &) const;
  template CutSaddlePointSolver<2>::Statistics
  CutSaddlePointSolver<2>::solve_split(Vector<double> &,
                                       const Vector<double> &,
                                       const double,
                                       const unsigned int,
                                       const bool);
  template void
  CutSaddlePointSolver<3>::split_velocity_block(const Layout &);
  template void
  CutSaddlePointSolver<3>::split_blocks(const Layout &);
  template void
  CutSaddlePointSolver<3>::split_gap_laplacian(const Layout &);
  template CutSaddlePointSolver<3>::PartsVector
  CutSaddlePointSolver<3>::make_parts() const;
  template void
  CutSaddlePointSolver<3>::to_parts(const Vector<double> &,
                                    PartsVector &) const;
  template void
  CutSaddlePointSolver<3>::from_parts(const PartsVector &,
                                      Vector<double> &) const;
  template void
  CutSaddlePointSolver<3>::through_parts(
    Vector<double> &,
    const Vector<double> &,
    void (CutSaddlePointSolver<3>::*)(PartsVector &, const PartsVector &)
      const) const;
  template void
  CutSaddlePointSolver<3>::split_system_vmult(PartsVector &,
                                              const PartsVector &) const;
  template void
  CutSaddlePointSolver<3>::split_pressure_inverse(PartVector &,
                                                  const PartVector &) const;
  template void
  CutSaddlePointSolver<3>::split_vmult(PartsVector &,
                                       const PartsVector &) const;
  template CutSaddlePointSolver<3>::Statistics
  CutSaddlePointSolver<3>::solve_split(Vector<double> &,
                                       const Vector<double> &,
                                       const double,
                                       const unsigned int,
                                       const bool);
} // namespace Fidus
