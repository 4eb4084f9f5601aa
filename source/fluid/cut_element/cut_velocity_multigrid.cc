#include <algorithm>
#include <cmath>
#include <deal.II/base/function.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/multigrid/mg_transfer_global_coarsening.h>
#include <deal.II/numerics/vector_tools.h>
#include <fidus/fluid/cut_element/component_coupling.h>
#include <fidus/fluid/cut_element/cut_velocity_multigrid.h>
#include <fidus/fluid/cut_element/distributed_galerkin_product.h>
#include <fidus/fluid/cut_element/sparse_matrix_rows.h>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace Fidus
{
  namespace
  {
    /**
     * The active cell of @p coarse that covers the cell @p fine of a mesh
     * one global coarsening finer (both refine the same coarse grid), and
     * the child index of @p fine in it; -1 when it is the same cell.
     */
    template <int dim>
    std::pair<typename Triangulation<dim>::cell_iterator, int>
    covering_cell(typename Triangulation<dim>::cell_iterator fine,
                  const Triangulation<dim>                  &coarse)
    {
      std::vector<unsigned int> path; // child indices, the finest first
      while (fine->level() > 0)
        {
          const auto   parent = fine->parent();
          unsigned int k      = 0;
          while (parent->child(k) != fine)
            ++k;
          path.push_back(k);
          fine = parent;
        }
      typename Triangulation<dim>::cell_iterator cell(&coarse,
                                                      0,
                                                      fine->index());
      std::size_t                                left = path.size();
      while (left > 0 && cell->has_children())
        cell = cell->child(path[--left]);
      if (left > 1 || cell->has_children())
        throw std::logic_error("CutVelocityMultigrid: a level mesh is not "
                               "one global coarsening of the next finer one");
      return {cell, left == 1 ? int(path[0]) : -1};
    }

    using Row = std::vector<std::pair<unsigned int, double>>;

    /**
     * The prolongation from @p coarse (Q2 velocities, constraints
     * @p coarse_constraints) to the velocity unknowns of @p fine, row by
     * row in the numbering of @p fine: the value of fine unknown i is
     * sum_j w_ij x_j over the coarse unconstrained unknowns j. Rows where
     * @p keep is false stay empty.
     */
    template <int dim>
    std::vector<Row>
    prolongation_rows(const DoFHandler<dim>           &fine,
                      const std::vector<bool>         &keep,
                      const DoFHandler<dim>           &coarse,
                      const AffineConstraints<double> &coarse_constraints)
    {
      const FE_Q<dim>                 q2(2);
      const unsigned int              n_q2 = q2.n_dofs_per_cell();
      std::vector<FullMatrix<double>> embedding;
      for (unsigned int c = 0; c < GeometryInfo<dim>::max_children_per_cell;
           ++c)
        embedding.push_back(q2.get_prolongation_matrix(c));
      const auto &coarse_fe = coarse.get_fe();
      // The coarse cell's local index of (component, Q2 index).
      std::vector<std::vector<unsigned int>> coarse_local(
        dim,
        std::vector<unsigned int>(n_q2));
      for (unsigned int j = 0; j < coarse_fe.n_dofs_per_cell(); ++j)
        {
          const auto ci = coarse_fe.system_to_component_index(j);
          coarse_local[ci.first][ci.second] = j;
        }

      std::vector<Row>                     rows(fine.n_dofs());
      std::vector<bool>                    done(fine.n_dofs(), false);
      std::vector<types::global_dof_index> fine_dofs,
        coarse_dofs(coarse_fe.n_dofs_per_cell());
      for (const auto &cell : fine.active_cell_iterators())
        {
          const auto &fe = cell->get_fe();
          if (fe.n_dofs_per_cell() == 0)
            continue;
          fine_dofs.resize(fe.n_dofs_per_cell());
          cell->get_dof_indices(fine_dofs);
          // A cell none of whose rows is wanted (or left) costs no search.
          if (std::none_of(fine_dofs.begin(),
                           fine_dofs.end(),
                           [&](const auto i) { return keep[i] && !done[i]; }))
            continue;
          const auto covering =
            covering_cell<dim>(cell, coarse.get_triangulation());
          const typename DoFHandler<dim>::cell_iterator coarse_cell(
            &coarse.get_triangulation(),
            covering.first->level(),
            covering.first->index(),
            &coarse);
          coarse_cell->get_dof_indices(coarse_dofs);
          for (unsigned int i = 0; i < fine_dofs.size(); ++i)
            {
              const auto index = fine_dofs[i];
              if (done[index] || !keep[index])
                continue;
              const auto ci = fe.system_to_component_index(i);
              if (ci.first >= dim)
                continue;
              done[index]    = true;
              Row       &row = rows[index];
              const auto add = [&](const unsigned int q, const double w) {
                const auto j = coarse_dofs[coarse_local[ci.first][q]];
                if (!coarse_constraints.is_constrained(j))
                  row.emplace_back(j, w);
                else if (const auto *entries =
                           coarse_constraints.get_constraint_entries(j))
                  for (const auto &e : *entries)
                    row.emplace_back(e.first, w * e.second);
              };
              if (covering.second < 0)
                add(ci.second, 1.);
              else
                for (unsigned int q = 0; q < n_q2; ++q)
                  {
                    const double w = embedding[covering.second](ci.second, q);
                    if (std::abs(w) > 1e-14)
                      add(q, w);
                  }
              // One entry per column.
              std::sort(row.begin(), row.end());
              Row merged;
              for (const auto &e : row)
                if (!merged.empty() && merged.back().first == e.first)
                  merged.back().second += e.second;
                else
                  merged.push_back(e);
              row.swap(merged);
            }
        }
      return rows;
    }

    /// This rank's share of @p n rows split evenly among the ranks of
    /// @p comm in contiguous ranges.
    IndexSet
    even_range(const unsigned int n, const MPI_Comm comm)
    {
      const unsigned int ranks = Utilities::MPI::n_mpi_processes(comm);
      const unsigned int rank  = Utilities::MPI::this_mpi_process(comm);
      return contiguous_range(std::size_t(n) * (rank + 1) / ranks -
                                std::size_t(n) * rank / ranks,
                              comm);
    }

    /**
     * The whole matrix of which every rank holds @p rows (SparseMatrixRows
     * or DistributedRows<double>), on every rank: the coarsest level,
     * which every rank factorises.
     */
    template <typename Rows>
    void
    gather_whole(const Rows           &rows,
                 SparsityPattern      &pattern,
                 SparseMatrix<double> &matrix)
    {
      const auto                          &columns = rows.column_partitioner();
      std::vector<types::global_dof_index> packed;
      std::vector<double>                  values;
      for (unsigned int k = 0; k < rows.local_rows(); ++k)
        {
          packed.push_back(rows.first_row() + k);
          const std::size_t count_at = packed.size();
          packed.push_back(0);
          rows.for_row(k, [&](const unsigned int j, const double v) {
            packed.push_back(columns.local_to_global(j));
            values.push_back(v);
            ++packed[count_at];
          });
        }
      const auto all_packed =
        Utilities::MPI::all_gather(rows.get_mpi_communicator(), packed);
      const auto all_values =
        Utilities::MPI::all_gather(rows.get_mpi_communicator(), values);
      const unsigned int     n = columns.size();
      DynamicSparsityPattern dsp(n, n);
      const auto             walk = [&](const auto &f) {
        for (unsigned int r = 0; r < all_packed.size(); ++r)
          {
            std::size_t at = 0, value_at = 0;
            while (at < all_packed[r].size())
              {
                const auto        row   = all_packed[r][at];
                const std::size_t count = all_packed[r][at + 1];
                for (std::size_t e = 0; e < count; ++e)
                  f(row,
                    all_packed[r][at + 2 + e],
                    all_values[r][value_at + e]);
                at += 2 + count;
                value_at += count;
              }
          }
      };
      walk([&](const auto i, const auto j, const double) { dsp.add(i, j); });
      pattern.copy_from(dsp);
      matrix.reinit(pattern);
      walk([&](const auto i, const auto j, const double v) {
        matrix.set(i, j, v);
      });
    }

    /// Block Jacobi's set-up on the finest level, read in place.
    inline void
    initialize_blocks(CutCellBlockJacobi                           &jacobi,
                      const SparseMatrixRows                       &rows,
                      const std::vector<std::vector<unsigned int>> &blocks,
                      const std::vector<unsigned char>             &component)
    {
      jacobi.initialize(rows.matrix(), blocks, component);
    }
    inline void
    initialize_blocks(CutCellBlockJacobi                           &jacobi,
                      const DistributedRows<double>                &rows,
                      const std::vector<std::vector<unsigned int>> &blocks,
                      const std::vector<unsigned char>             &component)
    {
      jacobi.initialize(rows, blocks, component);
    }
  } // namespace



  template <int dim>
  CutVelocityMultigrid<dim>::CutVelocityMultigrid(
    const DoFHandler<dim>           &system,
    const AffineConstraints<double> &constraints,
    const Vector<double>            &scale,
    const std::vector<unsigned int> &periodic_axes,
    const Settings                  &settings)
    : system(system)
    , system_constraints(constraints)
    , scale(scale)
    , periodic_axes(periodic_axes)
    , settings(settings)
  {}



  template <int dim>
  void
  CutVelocityMultigrid<dim>::initialize(
    const SparseMatrix<double>      &matrix,
    const std::vector<unsigned int> &velocity_unknowns,
    const unsigned int               n_rigid)
  {
    build(SparseMatrixRows(matrix), velocity_unknowns, n_rigid);
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::initialize(
    const DistributedRows<double>   &matrix,
    const std::vector<unsigned int> &velocity_unknowns,
    const unsigned int               n_rigid)
  {
    build(matrix, velocity_unknowns, n_rigid);
  }



  template <int dim>
  template <typename Rows>
  void
  CutVelocityMultigrid<dim>::build(
    const Rows                      &finest,
    const std::vector<unsigned int> &velocity_unknowns,
    const unsigned int               n_rigid)
  {
    communicator = finest.get_mpi_communicator();
    finest_double.reset();
    coarse.clear();
    prolongation.clear();
    block_jacobi.clear();
    level_float.clear();
    prolongation_float.clear();
    row_component.clear();
    if (settings.separate_components)
      row_component = finest_components(velocity_unknowns,
                                        finest.column_partitioner().size());
    const Levels levels = make_levels(n_rigid, finest.locally_owned_rows());
    const unsigned int n_levels = owned.size();

    // The finest level's rows: the system's unconstrained velocities, in
    // the caller's numbering, divided by the scaling.
    std::vector<int> local(system.n_dofs(), -1);
    for (unsigned int k = 0; k < velocity_unknowns.size(); ++k)
      local[velocity_unknowns[k]] = k;
    // The finest level without its couplings between components, with
    // global columns (copied in float, or in double for the double cycle).
    const auto &finest_columns = finest.column_partitioner();
    const auto  finest_row     = [&](const unsigned int k, const auto &f) {
      const unsigned int i = finest.first_row() + k;
      finest.for_row(k, [&](const unsigned int j, const double v) {
        const unsigned int g = finest_columns.local_to_global(j);
        if (couples_within_component(row_component, i, g))
          f(g, v);
      });
    };

    // Level by level: P_l, A_{l+1} = P^T A_l P, level l's smoother blocks
    // (from A_l in double) and its float copies; A_l and P_l in double
    // are freed as soon as they are copied, so that the set-up never
    // holds the whole hierarchy twice.
    coarse.resize(n_levels - 1);
    prolongation.resize(n_levels - 1);
    for (unsigned int l = 0; l + 1 < n_levels; ++l)
      {
        prolongation[l] =
          make_prolongation(l, levels, local, velocity_unknowns, n_rigid);
        // Unknowns that reach no fluid (inside a particle) or are
        // constrained have empty rows: a unit diagonal keeps them
        // decoupled and zero.
        coarse[l] = std::make_unique<DistributedRows<double>>();
        if (l == 0)
          distributed_galerkin_product(finest,
                                       *prolongation[l],
                                       owned[1],
                                       *coarse[l],
                                       row_component);
        else
          distributed_galerkin_product(*coarse[l - 1],
                                       *prolongation[l],
                                       owned[l + 1],
                                       *coarse[l]);
        for (unsigned int k = 0; k < coarse[l]->local_rows(); ++k)
          if (coarse[l]->diag_element(k) == 0.)
            coarse[l]->diag_element(k) = 1.;

        const auto blocks =
          settings.cut_cell_blocks ?
            cut_cell_blocks(l == 0 ? system : *levels.dofs[l],
                            l == 0 ? system_constraints : levels.constraints[l],
                            l == 0,
                            local) :
            std::vector<std::vector<unsigned int>>();
        block_jacobi.push_back(std::make_shared<CutCellBlockJacobi>());
        if (l == 0)
          initialize_blocks(*block_jacobi.back(),
                            finest,
                            blocks,
                            row_component);
        else
          block_jacobi.back()->initialize(*coarse[l - 1], blocks);

        if (!settings.single_precision)
          continue;
        level_float.push_back(std::make_unique<DistributedRows<float>>());
        if (l == 0)
          level_float.back()->fill(owned[0],
                                   owned[0],
                                   finest_row,
                                   communicator);
        else
          {
            level_float.back()->copy_from(*coarse[l - 1]);
            coarse[l - 1].reset();
          }
        prolongation_float.push_back(
          std::make_unique<DistributedRows<float>>());
        prolongation_float.back()->copy_from(*prolongation[l]);
        prolongation[l].reset();
      }

    if (n_levels == 1)
      gather_whole(finest, coarsest_pattern, coarsest_matrix);
    else
      gather_whole(*coarse.back(), coarsest_pattern, coarsest_matrix);
    coarsest.initialize(coarsest_matrix);
    if (settings.single_precision)
      coarse.clear();
    else if (n_levels > 1)
      {
        finest_double = std::make_unique<DistributedRows<double>>();
        finest_double->fill(owned[0], owned[0], finest_row, communicator);
      }
    setup_cycle();
  }



  template <int dim>
  std::vector<unsigned char>
  CutVelocityMultigrid<dim>::finest_components(
    const std::vector<unsigned int> &velocity_unknowns,
    const unsigned int               n_rows) const
  {
    // The rigid rows have none and keep all their entries, so the
    // particles stay coupled to their fluid.
    std::vector<unsigned char>           dof_component(system.n_dofs(), 255);
    std::vector<types::global_dof_index> indices;
    for (const auto &cell : system.active_cell_iterators())
      {
        const auto &fe = cell->get_fe();
        indices.resize(fe.n_dofs_per_cell());
        cell->get_dof_indices(indices);
        for (unsigned int i = 0; i < indices.size(); ++i)
          dof_component[indices[i]] = fe.system_to_component_index(i).first;
      }
    std::vector<unsigned char> component(n_rows, 255);
    for (unsigned int k = 0; k < velocity_unknowns.size(); ++k)
      component[k] = dof_component[velocity_unknowns[k]];
    return component;
  }



  template <int dim>
  typename CutVelocityMultigrid<dim>::Levels
  CutVelocityMultigrid<dim>::make_levels(const unsigned int n_rigid,
                                         const IndexSet    &finest_rows)
  {
    Levels levels;
    // Coarsest first; the last one is the solve's mesh. Level l (the
    // finest is 0) is meshes[n_levels - 1 - l].
    levels.meshes =
      MGTransferGlobalCoarseningTools::create_geometric_coarsening_sequence(
        system.get_triangulation());
    const unsigned int  n_levels = levels.meshes.size();
    const FESystem<dim> fe(FE_Q<dim>(2), dim);
    levels.dofs.resize(n_levels);
    levels.constraints.resize(n_levels);
    owned.assign(1, finest_rows);
    for (unsigned int l = 1; l < n_levels; ++l)
      {
        auto &dofs = levels.dofs[l];
        dofs =
          std::make_unique<DoFHandler<dim>>(*levels.meshes[n_levels - 1 - l]);
        dofs->distribute_dofs(fe);
        AffineConstraints<double> &c = levels.constraints[l];
        DoFTools::make_hanging_node_constraints(*dofs, c);
        for (const unsigned int axis : periodic_axes)
          DoFTools::make_periodicity_constraints(*dofs,
                                                 2 * axis,
                                                 2 * axis + 1,
                                                 axis,
                                                 c);
        // The box faces (2d, 2d + 1 for axis d) carry the velocity: the
        // correction is zero there.
        for (unsigned int face = 0; face < 2 * dim; ++face)
          if (std::find(periodic_axes.begin(), periodic_axes.end(), face / 2) ==
              periodic_axes.end())
            VectorTools::interpolate_boundary_values(
              *dofs,
              face,
              Functions::ZeroFunction<dim>(dim),
              c);
        c.close();
        // The rigid unknowns follow the velocities on every level.
        owned.push_back(even_range(dofs->n_dofs() + n_rigid, communicator));
      }
    return levels;
  }



  template <int dim>
  std::unique_ptr<DistributedRows<double>>
  CutVelocityMultigrid<dim>::make_prolongation(
    const unsigned int               l,
    const Levels                    &levels,
    const std::vector<int>          &local,
    const std::vector<unsigned int> &velocity_unknowns,
    const unsigned int               n_rigid) const
  {
    const DoFHandler<dim> &fine = l == 0 ? system : *levels.dofs[l];
    // Only this rank's rows (a contiguous range of level l's numbering):
    // on more ranks each computes its own share of P.
    const unsigned int first =
      owned[l].n_elements() > 0 ? owned[l].nth_index_in_set(0) : 0;
    const unsigned int end = first + owned[l].n_elements();
    std::vector<bool>  keep(fine.n_dofs());
    for (unsigned int i = 0; i < fine.n_dofs(); ++i)
      {
        const long row = l == 0 ? local[i] : long(i);
        keep[i]        = row >= first && row < end &&
                  !(l == 0 ? system_constraints : levels.constraints[l])
                     .is_constrained(i);
      }
    const std::vector<Row> rows =
      prolongation_rows<dim>(fine,
                             keep,
                             *levels.dofs[l + 1],
                             levels.constraints[l + 1]);
    // This rank's rows, by their row on level l; the rigid unknowns carried
    // unchanged.
    const unsigned int n_rows =
      (l == 0 ? velocity_unknowns.size() : fine.n_dofs()) + n_rigid;
    const unsigned int       n_coarse = levels.dofs[l + 1]->n_dofs();
    std::vector<const Row *> by_row(n_rows, nullptr);
    for (unsigned int i = 0; i < rows.size(); ++i)
      if (!rows[i].empty())
        by_row[l == 0 ? local[i] : i] = &rows[i];
    std::vector<std::size_t>             start{0};
    std::vector<types::global_dof_index> columns;
    std::vector<double>                  values;
    for (unsigned int k = 0; k < owned[l].n_elements(); ++k)
      {
        const unsigned int i = first + k;
        if (i >= n_rows - n_rigid)
          {
            columns.push_back(n_coarse + i - (n_rows - n_rigid));
            values.push_back(1.);
          }
        else if (by_row[i] != nullptr)
          for (const auto &e : *by_row[i])
            {
              columns.push_back(e.first);
              values.push_back(l == 0 ? e.second / scale[velocity_unknowns[i]] :
                                        e.second);
            }
        start.push_back(columns.size());
      }
    auto p = std::make_unique<DistributedRows<double>>();
    p->reinit(owned[l], owned[l + 1], start, columns, values, communicator);
    return p;
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::setup_cycle()
  {
    const unsigned int n_levels = owned.size();
    // The smoothers: in single precision on the float levels, which the
    // V-cycle's products are bound by the memory traffic of, and a
    // preconditioner needs no more digits than FGMRES takes from it (the
    // same iterations, the answers within 5e-10 of the double cycle's on
    // one sphere and the 3D pair; doc/theory/cut_element.md, "Solvers").
    // The cut-cell blocks' inverses are float already. The coarsest level
    // keeps its double factorisation.
    smoother.clear();
    smoother_float.clear();
    for (unsigned int l = 0; l + 1 < n_levels; ++l)
      if (settings.single_precision)
        {
          typename FloatSmoother::AdditionalData data;
          data.degree              = settings.smoother_degree;
          data.smoothing_range     = settings.smoothing_range;
          data.eig_cg_n_iterations = 12;
          data.preconditioner      = block_jacobi[l];
          smoother_float.push_back(std::make_unique<FloatSmoother>());
          smoother_float.back()->initialize(*level_float[l], data);
        }
      else
        {
          typename Smoother::AdditionalData data;
          data.degree              = settings.smoother_degree;
          data.smoothing_range     = settings.smoothing_range;
          data.eig_cg_n_iterations = 12;
          data.preconditioner      = block_jacobi[l];
          smoother.push_back(std::make_unique<Smoother>());
          smoother.back()->initialize(level_matrix(l), data);
        }
    residual_f.clear();
    rhs_f.clear();
    solution_f.clear();
    residual.clear();
    level_rhs.clear();
    level_solution.clear();
    again_rhs_f.clear();
    again_f.clear();
    again_rhs.clear();
    again.clear();
    for (unsigned int l = 0; l < n_levels; ++l)
      {
        // A level visited more than once needs its own residual and
        // correction for the later visits; the others hold no rows.
        const IndexSet again_rows = l >= 2 && visits_of_next(l - 1) > 1 ?
                                      owned[l] :
                                      IndexSet(owned[l].size());
        if (settings.single_precision)
          {
            residual_f.emplace_back(owned[l], communicator);
            rhs_f.emplace_back(owned[l], communicator);
            solution_f.emplace_back(owned[l], communicator);
            again_rhs_f.emplace_back(again_rows, communicator);
            again_f.emplace_back(again_rows, communicator);
          }
        else
          {
            residual.emplace_back(owned[l], communicator);
            level_rhs.emplace_back(owned[l], communicator);
            level_solution.emplace_back(owned[l], communicator);
            again_rhs.emplace_back(again_rows, communicator);
            again.emplace_back(again_rows, communicator);
          }
      }
    coarse_x.reinit(coarsest_matrix.m());
    coarse_b.reinit(coarsest_matrix.m());
    src_f.reinit(settings.single_precision ? owned[0] : IndexSet(),
                 communicator);
    dst_f.reinit(src_f);
    src_d.reinit(owned[0], communicator);
    dst_d.reinit(src_d);
  }



  template <int dim>
  const DistributedRows<double> &
  CutVelocityMultigrid<dim>::level_matrix(const unsigned int level) const
  {
    return level == 0 ? *finest_double : *coarse[level - 1];
  }



  template <int dim>
  unsigned int
  CutVelocityMultigrid<dim>::visits_of_next(const unsigned int level) const
  {
    // Level 1 is visited once per cycle: it holds about a third of the
    // finest level's rows, and a second visit of it cost more than it
    // saved; the coarsest is solved exactly, once is enough. Below, a
    // level is visited again only where it has at most half the rows of
    // the one above, so that the visits never cost more per level than
    // level 1 does: a gap refined far below the rest of the mesh leaves
    // a chain of levels that shrink by a few per cent each (the 3D pair
    // held 0.02 a apart: 12 339, 10 311, 8 283, ... rows), which a plain
    // W-cycle would visit 2, 4, 8, ... times.
    if (level == 0 || level + 2 >= owned.size())
      return 1;
    return 2 * owned[level + 1].size() <= owned[level].size() ?
             settings.coarse_visits :
             1;
  }



  template <int dim>
  template <typename Number>
  void
  CutVelocityMultigrid<dim>::coarsest_solve(LevelVector<Number>       &x,
                                            const LevelVector<Number> &b) const
  {
    const IndexSet    &rows = b.locally_owned_elements();
    const unsigned int first =
      rows.n_elements() > 0 ? rows.nth_index_in_set(0) : 0;
    coarse_b = 0.;
    for (unsigned int k = 0; k < rows.n_elements(); ++k)
      coarse_b[first + k] = b.local_element(k);
    if (Utilities::MPI::n_mpi_processes(communicator) > 1)
      Utilities::MPI::sum(coarse_b, communicator, coarse_b);
    coarsest.vmult(coarse_x, coarse_b);
    for (unsigned int k = 0; k < rows.n_elements(); ++k)
      x.local_element(k) = coarse_x[first + k];
  }



  template <int dim>
  template <typename Number>
  void
  CutVelocityMultigrid<dim>::cycle(const unsigned int         level,
                                   LevelVector<Number>       &x,
                                   const LevelVector<Number> &b) const
  {
    if (level + 1 == owned.size())
      {
        coarsest_solve(x, b);
        return;
      }
    if constexpr (std::is_same_v<Number, float>)
      {
        const DistributedRows<float> &a = *level_float[level];
        smoother_float[level]->vmult(x, b);
        a.vmult(residual_f[level], x);
        residual_f[level].sadd(-1.f, 1.f, b);
        prolongation_float[level]->Tvmult(rhs_f[level + 1], residual_f[level]);
        cycle(level + 1, solution_f[level + 1], rhs_f[level + 1]);
        for (unsigned int visit = 1; visit < visits_of_next(level); ++visit)
          {
            level_float[level + 1]->vmult(again_rhs_f[level + 1],
                                          solution_f[level + 1]);
            again_rhs_f[level + 1].sadd(-1.f, 1.f, rhs_f[level + 1]);
            cycle(level + 1, again_f[level + 1], again_rhs_f[level + 1]);
            solution_f[level + 1] += again_f[level + 1];
          }
        prolongation_float[level]->vmult_add(x, solution_f[level + 1]);
        smoother_float[level]->step(x, b);
      }
    else
      {
        const DistributedRows<double> &a = level_matrix(level);
        smoother[level]->vmult(x, b);
        a.vmult(residual[level], x);
        residual[level].sadd(-1., 1., b);
        prolongation[level]->Tvmult(level_rhs[level + 1], residual[level]);
        cycle(level + 1, level_solution[level + 1], level_rhs[level + 1]);
        for (unsigned int visit = 1; visit < visits_of_next(level); ++visit)
          {
            level_matrix(level + 1).vmult(again_rhs[level + 1],
                                          level_solution[level + 1]);
            again_rhs[level + 1].sadd(-1., 1., level_rhs[level + 1]);
            cycle(level + 1, again[level + 1], again_rhs[level + 1]);
            level_solution[level + 1] += again[level + 1];
          }
        prolongation[level]->vmult_add(x, level_solution[level + 1]);
        smoother[level]->step(x, b);
      }
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::vmult(
    LinearAlgebra::distributed::Vector<double>       &dst,
    const LinearAlgebra::distributed::Vector<double> &src) const
  {
    if (!settings.single_precision)
      {
        cycle(0, dst, src);
        return;
      }
    std::copy(src.begin(), src.end(), src_f.begin());
    cycle(0, dst_f, src_f);
    std::copy(dst_f.begin(), dst_f.end(), dst.begin());
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::vmult(Vector<double>       &dst,
                                   const Vector<double> &src) const
  {
    // One rank: the cycle's own vectors hold all the rows.
    if (settings.single_precision)
      {
        std::copy(src.begin(), src.end(), src_f.begin());
        cycle(0, dst_f, src_f);
        std::copy(dst_f.begin(), dst_f.end(), dst.begin());
        return;
      }
    std::copy(src.begin(), src.end(), src_d.begin());
    cycle(0, dst_d, src_d);
    std::copy(dst_d.begin(), dst_d.end(), dst.begin());
  }



  template <int dim>
  template <typename Cell>
  bool
  CutVelocityMultigrid<dim>::near_surface(const Cell &cell) const
  {
    const Point<dim> centre        = cell->center();
    const double     half_diagonal = 0.5 * cell->diameter();
    for (const auto &surface : surfaces)
      if (std::abs(centre.distance(surface.first) - surface.second) <
          half_diagonal)
        return true;
    return false;
  }



  template <int dim>
  std::vector<std::vector<unsigned int>>
  CutVelocityMultigrid<dim>::cut_cell_blocks(
    const DoFHandler<dim>           &level_dofs,
    const AffineConstraints<double> &level_constraints,
    const bool                       finest,
    const std::vector<int>          &local) const
  {
    // On the finest level a row is a system velocity (local >= 0; the
    // cells inside a particle have no DoFs, pressures no row); below it,
    // every unconstrained DoF of the level is its own row. Constrained
    // unknowns are left out: their rows hold the diagonal alone. Every
    // rank's blocks, in global rows: CutCellBlockJacobi keeps on each rank
    // those whose smallest row it owns, with the other ranks' rows they
    // hold.
    std::vector<std::vector<unsigned int>> blocks;
    std::vector<types::global_dof_index>   indices;
    for (const auto &cell : level_dofs.active_cell_iterators())
      {
        const unsigned int n = cell->get_fe().n_dofs_per_cell();
        if (n == 0 || !near_surface(cell))
          continue;
        indices.resize(n);
        cell->get_dof_indices(indices);
        std::vector<unsigned int> block;
        for (const auto i : indices)
          if (!level_constraints.is_constrained(i) &&
              (!finest || local[i] >= 0))
            {
              block.push_back(finest ? local[i] : i);
            }
        if (!block.empty())
          blocks.push_back(std::move(block));
      }
    return blocks;
  }



  template class CutVelocityMultigrid<2>;
  template class CutVelocityMultigrid<3>;
} // namespace Fidus
