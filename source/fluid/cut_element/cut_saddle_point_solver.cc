#include <Teuchos_ParameterList.hpp>
#include <deal.II/base/timer.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <fidus/fluid/cut_element/cut_saddle_point_solver.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <fidus/fluid/cut_element/transposed_vmult.h>
#include <fidus/fluid/fictitious_domain/rigid_mode.h>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace Fidus
{
  namespace
  {
    /// A block of the system that extract_blocks() fills: the map from a
    /// system column to the block's (-1: not one of the block's), its
    /// number of columns, its pattern and its matrix.
    template <typename Column>
    struct Block
    {
      Column                column;
      unsigned int          n_columns;
      RowPattern           &pattern;
      SparseMatrix<double> &matrix;
    };

    /**
     * Copy the rows @p rows of the square @p matrix (numbered in that
     * order) into the @p blocks at once, each taking the entries its column
     * map keeps. Each row is read three times (its lengths, its columns,
     * its values) whatever the number of blocks, on the threads. The
     * matrix's rows hold the diagonal first, then ascending columns; the
     * column maps must keep that order (the caller's do), so each block's
     * row comes out in order and nothing is sorted. Copying one block at
     * a time, with a sort and a row of scratch values each, took a tenth
     * of a 3D step of the cut element.
     */
    template <typename... Blocks>
    void
    copy_rows(const SparseMatrix<double>      &matrix,
              const std::vector<unsigned int> &rows,
              const Blocks &...blocks)
    {
      const unsigned int n_rows = rows.size();
      // f(column, value) on row k's entries, its diagonal first.
      const auto for_row = [&](const unsigned int k, const auto &f) {
        for (auto entry = matrix.begin(rows[k]), end = matrix.end(rows[k]);
             entry != end;
             ++entry)
          f(entry->column(), entry->value());
      };
      // Each block's row lengths; a square pattern stores its diagonal in
      // any case (as SparsityPattern does, first in its row).
      std::vector<unsigned int> lengths[sizeof...(blocks)];
      for (auto &l : lengths)
        l.assign(n_rows, 0);
      on_row_ranges(n_rows,
                    4,
                    [&](const unsigned int first, const unsigned int last) {
                      for (unsigned int k = first; k < last; ++k)
                        {
                          unsigned int b = 0;
                          (
                            [&](const auto &block) {
                              unsigned int &length = lengths[b++][k];
                              bool diagonal        = block.n_columns != n_rows;
                              for_row(k, [&](const unsigned int j, double) {
                                const int c = block.column(j);
                                length += c >= 0;
                                diagonal = diagonal || c == int(k);
                              });
                              length += !diagonal;
                            }(blocks),
                            ...);
                        }
                    });
      unsigned int b = 0;
      (
        [&](const auto &block) {
          const bool square = block.n_columns == n_rows;
          block.pattern.fill_ordered(
            n_rows,
            block.n_columns,
            lengths[b++],
            [&](const unsigned int k, unsigned int *columns) {
              int last = -1;
              for_row(k, [&](const unsigned int j, double) {
                const int c = block.column(j);
                if (c >= 0 && !(square && c == int(k)))
                  {
                    Assert(c > last, ExcInternalError());
                    *columns++ = last = c;
                  }
              });
            });
          block.matrix.reinit(block.pattern);
          on_row_ranges(n_rows,
                        1,
                        [&](const unsigned int first, const unsigned int last) {
                          for (unsigned int k = first; k < last; ++k)
                            {
                              auto entry = block.matrix.begin(k);
                              if (square)
                                ++entry;
                              for_row(k,
                                      [&](const unsigned int j,
                                          const double       v) {
                                        const int c = block.column(j);
                                        if (square && c == int(k))
                                          block.matrix.diag_element(k) = v;
                                        else if (c >= 0)
                                          (entry++)->value() = v;
                                      });
                            }
                        });
        }(blocks),
        ...);
    }
  } // namespace



  template <int dim>
  void
  CutSaddlePointSolver<dim>::extract_blocks(const Layout &layout)
  {
    const unsigned int n_u = velocity.size(), n_p = pressure.size(),
                       n_v = rigid.size();

    // The copies go through copy_rows(), below: the rigid unknowns must
    // follow the fluid's for K's column map to keep the system's order.
    const auto block = [](const auto           &column,
                          const unsigned int    n_columns,
                          RowPattern           &pattern,
                          SparseMatrix<double> &matrix) {
      return Block<std::decay_t<decltype(column)>>{column,
                                                   n_columns,
                                                   pattern,
                                                   matrix};
    };
    AssertThrow(rigid.empty() || velocity.empty() ||
                  rigid.front() > velocity.back(),
                ExcMessage("The cut element's iterative solver needs the "
                           "rigid unknowns numbered after the fluid's."));
    const auto of_kind = [&](const unsigned char kind) {
      return [&, kind](const unsigned int j) {
        return layout.kind[j] == kind ? int(local[j]) : -1;
      };
    };
    std::vector<unsigned int> velocity_and_rigid = velocity;
    velocity_and_rigid.insert(velocity_and_rigid.end(),
                              rigid.begin(),
                              rigid.end());
    // K's numbering: velocities first, then the rigid unknowns.
    const auto of_k = [&](const unsigned int j) {
      return layout.kind[j] == 0 ? int(local[j]) :
             layout.kind[j] == 2 ? int(n_u + local[j]) :
                                   -1;
    };
    // With the multigrid, K = [A_uu A_uV; A_Vu A_VV] is its finest level,
    // and the blocks hold all of the system (which can then go): K and B^T
    // (rows: velocities, then rigid unknowns), B and the pressure block.
    // Otherwise A_uu goes to the AMG, with B^T and A_Vu beside it.
    const auto transposed_divergence =
      block(of_kind(1), n_p, blocks->bt_pattern, coupling);
    const auto pressures =
      block(of_kind(1), n_p, blocks->p_pattern, pressure_block);
    if (multigrid)
      {
        copy_rows(*matrix,
                  velocity_and_rigid,
                  block(of_k, n_u + n_v, blocks->k_pattern, velocity_matrix),
                  transposed_divergence);
        // B is read as B^T's transpose.
        copy_rows(*matrix, pressure, pressures);
      }
    else
      {
        copy_rows(*matrix,
                  velocity,
                  block(of_kind(0), n_u, blocks->k_pattern, velocity_matrix));
        copy_rows(*matrix, velocity_and_rigid, transposed_divergence);
        copy_rows(*matrix,
                  rigid,
                  block(of_kind(0), n_u, rigid_sparsity, rigid_coupling));
        copy_rows(*matrix, pressure, pressures);
      }
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::build_pressure_schur(
    const SparseMatrix<double> &pressure_mass,
    const Layout               &layout)
  {
    const unsigned int n_p = pressure.size();

    // S = M / eta + C on the pressures: the system holds -C in its pressure
    // block. A constrained pressure (hanging, or pinned) has its diagonal
    // alone in the system; S holds 1 there, so that CG sees a positive
    // definite matrix, and apply_pressure_inverse() inverts the system's
    // diagonal instead.
    DynamicSparsityPattern dsp(n_p, n_p);
    for (const unsigned int i : pressure)
      {
        dsp.add(local[i], local[i]);
        if (layout.constrained[i])
          continue;
        for (auto it = pressure_block.begin(local[i]);
             it != pressure_block.end(local[i]);
             ++it)
          if (!layout.constrained[pressure[it->column()]])
            dsp.add(local[i], it->column());
        for (auto it = pressure_mass.begin(i); it != pressure_mass.end(i); ++it)
          if (layout.kind[it->column()] == 1 &&
              !layout.constrained[it->column()])
            dsp.add(local[i], local[it->column()]);
      }
    pressure_sparsity.copy_from(dsp);
    pressure_schur.reinit(pressure_sparsity);
    for (const unsigned int i : pressure)
      {
        if (layout.constrained[i])
          {
            pressure_schur.set(local[i], local[i], 1.);
            constrained_pressures.push_back(local[i]);
            constrained_diagonal.push_back(
              pressure_block.diag_element(local[i]));
            continue;
          }
        for (auto it = pressure_block.begin(local[i]);
             it != pressure_block.end(local[i]);
             ++it)
          if (!layout.constrained[pressure[it->column()]])
            pressure_schur.add(local[i], it->column(), -it->value());
        for (auto it = pressure_mass.begin(i); it != pressure_mass.end(i); ++it)
          if (layout.kind[it->column()] == 1 &&
              !layout.constrained[it->column()])
            pressure_schur.add(local[i], local[it->column()], it->value());
      }
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::apply_pressure_inverse(
    Vector<double>       &z,
    const Vector<double> &r) const
  {
    // The pressure mass is well conditioned under point Jacobi on any
    // grading of the mesh; 1e-2 gives FGMRES the iterations of an exact
    // inverse (3D pair at 0.1 a: 36 at 1e-1, 1e-2 and 1e-8) in about 9 CG
    // iterations per application. A CG that stops short leaves its
    // iterate, which FGMRES takes as any other preconditioner's output.
    z = 0.;
    SolverControl            control(200, 1e-2 * r.l2_norm(), false, false);
    SolverCG<Vector<double>> cg(control);
    try
      {
        cg.solve(pressure_schur, z, r, pressure_jacobi);
      }
    catch (const SolverControl::NoConvergence &)
      {}
    // The thin gaps' lubrication modes (build_gap_laplacian()).
    if (!gap_pressures.empty())
      {
        for (unsigned int k = 0; k < gap_pressures.size(); ++k)
          r_g[k] = r[gap_pressures[k]];
        gap_amg.vmult(z_g, r_g);
        for (unsigned int k = 0; k < gap_pressures.size(); ++k)
          z[gap_pressures[k]] += gap_weight * z_g[k];
      }
    // -S^-1, and a constrained pressure's row, the system's diagonal alone,
    // inverted exactly.
    z *= -1.;
    for (unsigned int k = 0; k < constrained_pressures.size(); ++k)
      z[constrained_pressures[k]] =
        r[constrained_pressures[k]] / constrained_diagonal[k];
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::setup_velocity_amg(const Layout &layout)
  {
    const unsigned int n_u = velocity.size();

    velocity_trilinos.reinit(velocity_matrix);
    const unsigned int n_modes = dim * (dim + 1) / 2;
    null_space                 = std::make_unique<Epetra_MultiVector>(
      velocity_trilinos.trilinos_matrix().RowMap(),
      n_modes);
    Tensor<1, dim> centre;
    for (unsigned int d = 0; d < dim; ++d)
      centre[d] = 0.5;
    for (unsigned int k = 0; k < n_u; ++k)
      {
        const unsigned int   i = velocity[k];
        const Tensor<1, dim> r = layout.support_point[i] - centre;
        for (unsigned int m = 0; m < n_modes; ++m)
          (*null_space)[m][k] = rigid_mode<dim>(m, r)[layout.component[i]];
      }
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = true;
    // Four Chebyshev sweeps: against two, they took the FGMRES
    // iterations of a 3D sphere at h = a/3.2 from 174 to 95, and the
    // time from 42 s to 31 s; an aggregation threshold of 0.02 or 0.05
    // saved a few iterations and cost more in setup (41 s, 46 s).
    data.smoother_sweeps       = 4;
    data.aggregation_threshold = 0.;
    Teuchos::ParameterList              parameters;
    std::unique_ptr<Epetra_MultiVector> unused;
    data.set_parameters(parameters, unused, velocity_trilinos);
    parameters.set("null space: type", "pre-computed");
    parameters.set("null space: dimension", int(n_modes));
    parameters.set("null space: vectors", null_space->Values());
    velocity_amg.initialize(velocity_trilinos, parameters);
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::compute_rigid_schur()
  {
    const unsigned int n_u = velocity.size(), n_v = rigid.size();

    // Without the multigrid: W = A_uu^-1 A_uV column by column (A_uV =
    // A_Vu^T, the system being symmetric), and S_V = A_VV - A_Vu W.
    w.assign(n_v, Vector<double>(n_u));
    Vector<double>     column(n_u), product(n_v);
    FullMatrix<double> schur(n_v, n_v);
    for (unsigned int k = 0; k < n_v; ++k)
      {
        column = 0.;
        for (auto it = rigid_coupling.begin(k); it != rigid_coupling.end(k);
             ++it)
          column[it->column()] = it->value();
        // W only enters the preconditioner: 1e-4 is enough (the FGMRES
        // iterations are the same as with 1e-10, the setup is three times
        // shorter).
        SolverControl            control(1000, 1e-4 * column.l2_norm());
        SolverCG<Vector<double>> cg(control);
        try
          {
            cg.solve(velocity_matrix, w[k], column, velocity_amg);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            std::ostringstream message;
            message << "CutSaddlePointSolver: CG on the velocity block "
                       "(for the rigid unknowns' Schur complement) did not "
                       "reach 1e-4 in 1000 iterations (reached "
                    << e.last_residual / column.l2_norm()
                    << "); is the Nitsche parameter too small?";
            throw std::runtime_error(message.str());
          }
        statistics.setup_iterations += control.last_step();
        rigid_coupling.vmult(product, w[k]);
        for (unsigned int l = 0; l < n_v; ++l)
          schur(l, k) = matrix->el(rigid[l], rigid[k]) - product[l];
      }
    rigid_schur_inverse.reinit(n_v, n_v);
    rigid_schur_inverse.invert(schur);
  }



  template <int dim>
  std::vector<int>
  CutSaddlePointSolver<dim>::select_gap_pressures(const Layout &layout)
  {
    const unsigned int n_p = pressure.size();
    std::vector<int>   gap_index(n_p, -1);
    for (unsigned int k = 0; k < n_p; ++k)
      if (layout.in_gap[pressure[k]] && !layout.constrained[pressure[k]])
        {
          gap_index[k] = gap_pressures.size();
          gap_pressures.push_back(k);
        }
    if (!gap_pressures.empty())
      gap_weight = layout.gap_laplacian;
    return gap_index;
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::build_gap_laplacian(const Layout &layout)
  {
    if (layout.gap_laplacian <= 0. || layout.in_gap.empty())
      return;
    const unsigned int     n_u       = velocity.size();
    const std::vector<int> gap_index = select_gap_pressures(layout);
    const unsigned int     n_g       = gap_pressures.size();
    if (n_g == 0)
      return;

    // Each fluid velocity's column of B^T, its gap pressures only (the
    // rigid unknowns, which couple to every pressure of their particle's
    // cut cells, are left out).
    std::vector<std::pair<unsigned int, double>> column;
    const auto gap_column = [&](const unsigned int k) {
      column.clear();
      for (auto it = coupling.begin(k); it != coupling.end(k); ++it)
        if (gap_index[it->column()] >= 0 && it->value() != 0.)
          column.emplace_back(gap_index[it->column()], it->value());
    };
    // The ghost penalty's entries among the gap pressures (the system
    // holds -C).
    const auto for_ghost_penalty = [&](const auto &f) {
      for (unsigned int g = 0; g < n_g; ++g)
        {
          const unsigned int i = gap_pressures[g];
          for (auto it = pressure_block.begin(i); it != pressure_block.end(i);
               ++it)
            if (gap_index[it->column()] >= 0)
              f(g, gap_index[it->column()], -it->value());
        }
    };
    DynamicSparsityPattern dsp(n_g, n_g);
    for (unsigned int k = 0; k < n_u; ++k)
      {
        gap_column(k);
        for (const auto &i : column)
          for (const auto &j : column)
            dsp.add(i.first, j.first);
      }
    for_ghost_penalty([&](const unsigned int i, const unsigned int j, double) {
      dsp.add(i, j);
    });
    // Assembled here, then copied into Trilinos's matrix for the AMG: this
    // copy is freed on return.
    SparsityPattern gap_sparsity;
    gap_sparsity.copy_from(dsp);
    SparseMatrix<double> gap_matrix(gap_sparsity);
    for (unsigned int k = 0; k < n_u; ++k)
      {
        gap_column(k);
        const double d = k_diagonal[k];
        for (const auto &i : column)
          for (const auto &j : column)
            gap_matrix.add(i.first, j.first, i.second * j.second / d);
      }
    for_ghost_penalty([&](const unsigned int i,
                          const unsigned int j,
                          const double value) { gap_matrix.add(i, j, value); });
    // One AMG cycle stands for L_gap^-1: FGMRES took the same iterations
    // as with L_gap factorised, in 2D, at less cost (and a 3D factor is
    // dear).
    gap_trilinos.reinit(gap_matrix);
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic        = true;
    data.smoother_sweeps = 2;
    gap_amg.initialize(gap_trilinos, data);
    r_g.reinit(n_g);
    z_g.reinit(n_g);
  }



  template <int dim>
  CutSaddlePointSolver<dim>::CutSaddlePointSolver(
    const SparseMatrix<double>  &matrix,
    const SparseMatrix<double>  &pressure_mass,
    const Layout                &layout,
    CutVelocityMultigrid<dim>   *multigrid,
    const std::function<void()> &release)
    : matrix(&matrix)
    , blocks(std::make_unique<CutSystemBlocks>())
    , velocity_matrix(blocks->k)
    , coupling(blocks->bt)
    , pressure_block(blocks->p)
    , multigrid(multigrid)
  {
    Timer timer;
    number_unknowns(layout);
    extract_blocks(layout);
    statistics.blocks_seconds = timer.wall_time();
    setup(pressure_mass, layout, release);
    statistics.setup_seconds = timer.wall_time();
  }



  template <int dim>
  CutSaddlePointSolver<dim>::CutSaddlePointSolver(
    std::unique_ptr<CutSystemBlocks> system_blocks,
    const SparseMatrix<double>      &pressure_mass,
    const Layout                    &layout,
    CutVelocityMultigrid<dim>       &multigrid,
    const std::function<void()>     &release)
    : matrix(nullptr)
    , blocks(std::move(system_blocks))
    , velocity_matrix(blocks->k)
    , coupling(blocks->bt)
    , pressure_block(blocks->p)
    , multigrid(&multigrid)
  {
    Timer timer;
    number_unknowns(layout);
    AssertThrow(blocks->kind == layout.kind,
                ExcMessage("The cut element's blocks and its layout differ "
                           "in the kinds of the unknowns."));
    setup(pressure_mass, layout, release);
    statistics.setup_seconds = timer.wall_time();
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::number_unknowns(const Layout &layout)
  {
    const unsigned int n = layout.kind.size();
    local.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        auto &list = layout.kind[i] == 0 ? velocity :
                     layout.kind[i] == 1 ? pressure :
                                           rigid;
        local[i]   = list.size();
        list.push_back(i);
      }
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::setup(const SparseMatrix<double>  &pressure_mass,
                                   const Layout                &layout,
                                   const std::function<void()> &release)
  {
    const unsigned int n_u = velocity.size(), n_p = pressure.size(),
                       n_v = rigid.size();

    // The set-up's parts, for the verbose output.
    Timer      timer;
    double     last = 0.;
    const auto lap  = [&]() {
      const double now = timer.wall_time(), spent = now - last;
      last = now;
      return spent;
    };
    // K's diagonal, which the gap Laplacian reads: with the split every
    // rank holds its own velocity rows only.
    k_diagonal.reinit(velocity_matrix.m());
    const bool split = Utilities::MPI::n_mpi_processes(layout.communicator) > 1;
    for (unsigned int k = 0; k < velocity_matrix.m(); ++k)
      if (!split || (k >= layout.k_first && k < layout.k_end))
        k_diagonal[k] = velocity_matrix.diag_element(k);
    if (split)
      Utilities::MPI::sum(k_diagonal, layout.communicator, k_diagonal);
    build_pressure_schur(pressure_mass, layout);
    mean = layout.pressure_mean;
    const bool split_all =
      multigrid && Utilities::MPI::n_mpi_processes(layout.communicator) > 1;
    if (split_all)
      {
        split_blocks(layout);
        split_gap_laplacian(layout);
      }
    else
      {
        pressure_jacobi.initialize(pressure_schur);
        build_gap_laplacian(layout);
      }
    statistics.pressure_seconds = lap();
    // Everything read from the system is in the blocks now.
    if (multigrid && release)
      release();

    // The multigrid on K; or the AMG of the velocity block, with the rigid
    // motions about the box's centre as near-null space: the viscous
    // operator does not see them, and translations alone leave the coarse
    // spaces without rotations.
    if (split_all)
      split_velocity_block(layout);
    else if (multigrid)
      multigrid->initialize(velocity_matrix, velocity, n_v);
    else
      setup_velocity_amg(layout);
    statistics.velocity_seconds = lap();

    if (!multigrid)
      compute_rigid_schur();

    // The whole vectors of system_vmult() and vmult(); with the split they
    // work on the ranks' parts instead.
    if (split_all)
      return;
    r_u.reinit(multigrid ? n_u + n_v : n_u);
    y_u.reinit(multigrid ? n_u + n_v : n_u);
    r_p.reinit(n_p);
    z_p.reinit(n_p);
    coupling_product.reinit(n_u + n_v);
    r_v.reinit(n_v);
    z_v.reinit(n_v);
    if (multigrid)
      {
        x_k.reinit(n_u + n_v);
        y_k.reinit(n_u + n_v);
        x_p.reinit(n_p);
        y_p.reinit(n_p);
      }
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::system_vmult(Vector<double>       &dst,
                                          const Vector<double> &src) const
  {
    if (bt_rows)
      {
        through_parts(dst, src, &CutSaddlePointSolver::split_system_vmult);
        return;
      }
    if (!multigrid)
      matrix->vmult(dst, src);
    else
      {
        // [K B^T; B P] [x_K; x_p] by the blocks, in the system's numbering.
        const unsigned int n_u = velocity.size();
        for (unsigned int k = 0; k < n_u; ++k)
          x_k[k] = src[velocity[k]];
        for (unsigned int k = 0; k < rigid.size(); ++k)
          x_k[n_u + k] = src[rigid[k]];
        for (unsigned int k = 0; k < pressure.size(); ++k)
          x_p[k] = src[pressure[k]];
        velocity_matrix.vmult(y_k, x_k);
        coupling.vmult_add(y_k, x_p);
        pressure_block.vmult(y_p, x_p);
        transposed_vmult_add(
          coupling.m(),
          coupling.n(),
          [this](const unsigned int k, const auto &f) {
            for (auto it = coupling.begin(k), end = coupling.end(k); it != end;
                 ++it)
              f(it->column(), it->value());
          },
          x_k.begin(),
          y_p.begin(),
          transposed_scratch);
        for (unsigned int k = 0; k < n_u; ++k)
          dst[velocity[k]] = y_k[k];
        for (unsigned int k = 0; k < rigid.size(); ++k)
          dst[rigid[k]] = y_k[n_u + k];
        for (unsigned int k = 0; k < pressure.size(); ++k)
          dst[pressure[k]] = y_p[k];
      }
    // The rank-one term that fixes the pressure's mean.
    if (mean.size() > 0)
      dst.add(-(mean * src), mean);
  }



  template <int dim>
  void
  CutSaddlePointSolver<dim>::vmult(Vector<double>       &dst,
                                   const Vector<double> &src) const
  {
    if (bt_rows)
      {
        through_parts(dst, src, &CutSaddlePointSolver::split_vmult);
        return;
      }
    // z_p = -S^-1 r_p, then r_K - B^T z_p.
    for (unsigned int k = 0; k < pressure.size(); ++k)
      r_p[k] = src[pressure[k]];
    apply_pressure_inverse(z_p, r_p);
    coupling.vmult(coupling_product, z_p);
    const unsigned int n_u = velocity.size();
    // K^-1 by its rigid Schur complement: y_u = A_uu^-1 r_u, z_V = S_V^-1
    // (r_V - A_Vu y_u), z_u = y_u - W z_V.
    for (unsigned int k = 0; k < velocity.size(); ++k)
      r_u[k] = src[velocity[k]] - coupling_product[k];
    if (multigrid)
      {
        // K^-1 by one multigrid cycle on K.
        for (unsigned int k = 0; k < rigid.size(); ++k)
          r_u[n_u + k] = src[rigid[k]] - coupling_product[n_u + k];
        multigrid->vmult(y_u, r_u);
        for (unsigned int k = 0; k < velocity.size(); ++k)
          dst[velocity[k]] = y_u[k];
        for (unsigned int k = 0; k < rigid.size(); ++k)
          dst[rigid[k]] = y_u[n_u + k];
        for (unsigned int k = 0; k < pressure.size(); ++k)
          dst[pressure[k]] = z_p[k];
        return;
      }
    velocity_amg.vmult(y_u, r_u);
    rigid_coupling.vmult(r_v, y_u);
    for (unsigned int k = 0; k < rigid.size(); ++k)
      r_v[k] = src[rigid[k]] - coupling_product[n_u + k] - r_v[k];
    rigid_schur_inverse.vmult(z_v, r_v);
    for (unsigned int l = 0; l < rigid.size(); ++l)
      y_u.add(-z_v[l], w[l]);
    for (unsigned int k = 0; k < velocity.size(); ++k)
      dst[velocity[k]] = y_u[k];
    for (unsigned int k = 0; k < rigid.size(); ++k)
      dst[rigid[k]] = z_v[k];
    for (unsigned int k = 0; k < pressure.size(); ++k)
      dst[pressure[k]] = z_p[k];
  }



  template <int dim>
  typename CutSaddlePointSolver<dim>::Statistics
  CutSaddlePointSolver<dim>::solve(Vector<double>       &x,
                                   const Vector<double> &b,
                                   const double          tolerance,
                                   const unsigned int    max_iterations,
                                   const bool            from_x)
  {
    if (bt_rows)
      return solve_split(x, b, tolerance, max_iterations, from_x);
    run_fgmres(System{*this}, *this, x, b, tolerance, max_iterations, from_x);
    return statistics;
  }

  template class CutSaddlePointSolver<2>;
  template class CutSaddlePointSolver<3>;
} // namespace Fidus
