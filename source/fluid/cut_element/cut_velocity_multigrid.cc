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
#include <fidus/fluid/cut_element/galerkin_product.h>
#include <stdexcept>
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
    finest = &matrix;
    row_component.clear();
    if (settings.separate_components)
      {
        separate_components(matrix, velocity_unknowns);
        if (!settings.single_precision)
          finest = &separated;
      }
    // The finest level read without its couplings between components
    // (none once #separated holds it).
    const std::vector<unsigned char> all_entries;
    const auto                      &finest_components =
      finest == &matrix ? row_component : all_entries;
    prolongation_pattern.clear();
    prolongation.clear();
    coarse_pattern.clear();
    coarse.clear();
    smoother.clear();
    block_jacobi.clear();
    residual_f.clear();
    rhs_f.clear();
    solution_f.clear();

    // Coarsest first; the last one is the solve's mesh.
    const auto meshes =
      MGTransferGlobalCoarseningTools::create_geometric_coarsening_sequence(
        system.get_triangulation());
    const unsigned int  n_levels = meshes.size();
    const FESystem<dim> fe(FE_Q<dim>(2), dim);
    // Level l (the finest is 0) is meshes[n_levels - 1 - l].
    std::vector<std::unique_ptr<DoFHandler<dim>>> dofs(n_levels);
    std::vector<AffineConstraints<double>>        constraints(n_levels);
    for (unsigned int l = 1; l < n_levels; ++l)
      {
        dofs[l] = std::make_unique<DoFHandler<dim>>(*meshes[n_levels - 1 - l]);
        dofs[l]->distribute_dofs(fe);
        AffineConstraints<double> &c = constraints[l];
        DoFTools::make_hanging_node_constraints(*dofs[l], c);
        for (const unsigned int axis : periodic_axes)
          DoFTools::make_periodicity_constraints(*dofs[l],
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
              *dofs[l],
              face,
              Functions::ZeroFunction<dim>(dim),
              c);
        c.close();
      }

    // The finest level's rows: the system's unconstrained velocities, in
    // the caller's numbering, divided by the scaling.
    std::vector<int> local(system.n_dofs(), -1);
    for (unsigned int k = 0; k < velocity_unknowns.size(); ++k)
      local[velocity_unknowns[k]] = k;
    for (unsigned int l = 0; l + 1 < n_levels; ++l)
      {
        const DoFHandler<dim> &fine = l == 0 ? system : *dofs[l];
        std::vector<bool>      keep(fine.n_dofs());
        for (unsigned int i = 0; i < fine.n_dofs(); ++i)
          keep[i] = l == 0 ?
                      local[i] >= 0 && !system_constraints.is_constrained(i) :
                      !constraints[l].is_constrained(i);
        const std::vector<Row> rows =
          prolongation_rows<dim>(fine, keep, *dofs[l + 1], constraints[l + 1]);
        // The rigid unknowns follow the velocities on every level, the
        // same on all.
        const unsigned int n_rows =
          (l == 0 ? velocity_unknowns.size() : fine.n_dofs()) + n_rigid;
        const unsigned int     n_coarse = dofs[l + 1]->n_dofs();
        DynamicSparsityPattern dsp(n_rows, n_coarse + n_rigid);
        for (unsigned int i = 0; i < rows.size(); ++i)
          for (const auto &e : rows[i])
            dsp.add(l == 0 ? local[i] : i, e.first);
        for (unsigned int k = 0; k < n_rigid; ++k)
          dsp.add(n_rows - n_rigid + k, n_coarse + k);
        prolongation_pattern.push_back(std::make_unique<SparsityPattern>());
        prolongation_pattern.back()->copy_from(dsp);
        prolongation.push_back(
          std::make_unique<SparseMatrix<double>>(*prolongation_pattern.back()));
        for (unsigned int i = 0; i < rows.size(); ++i)
          for (const auto &e : rows[i])
            prolongation.back()->set(l == 0 ? local[i] : i,
                                     e.first,
                                     l == 0 ? e.second / scale[i] : e.second);
        for (unsigned int k = 0; k < n_rigid; ++k)
          prolongation.back()->set(n_rows - n_rigid + k, n_coarse + k, 1.);

        // A_{l+1} = P^T A_l P. Unknowns that reach no fluid (inside a
        // particle) or are constrained have empty rows: a unit diagonal
        // keeps them decoupled and zero.
        coarse_pattern.push_back(std::make_unique<RowPattern>());
        coarse.push_back(std::make_unique<SparseMatrix<double>>());
        galerkin_product(level_matrix(l),
                         *prolongation.back(),
                         *coarse_pattern.back(),
                         *coarse.back(),
                         l == 0 ? finest_components : all_entries);
        for (unsigned int i = 0; i < coarse.back()->m(); ++i)
          if (coarse.back()->diag_element(i) == 0.)
            coarse.back()->diag_element(i) = 1.;
      }

    setup_smoothers(dofs, constraints, local, finest_components);
    coarsest.initialize(level_matrix(n_levels - 1));
    if (settings.single_precision)
      {
        setup_single_precision();
        return;
      }
    residual.resize(n_levels);
    level_rhs.resize(n_levels);
    level_solution.resize(n_levels);
    for (unsigned int l = 0; l < n_levels; ++l)
      {
        residual[l].reinit(level_matrix(l).m());
        level_rhs[l].reinit(level_matrix(l).m());
        level_solution[l].reinit(level_matrix(l).m());
      }
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::setup_smoothers(
    const std::vector<std::unique_ptr<DoFHandler<dim>>> &dofs,
    const std::vector<AffineConstraints<double>>        &constraints,
    const std::vector<int>                              &local,
    const std::vector<unsigned char>                    &finest_components)
  {
    const unsigned int               n_levels = coarse.size() + 1;
    const std::vector<unsigned char> all_entries;
    for (unsigned int l = 0; l + 1 < n_levels; ++l)
      {
        const SparseMatrix<double>       &a = level_matrix(l);
        typename Smoother::AdditionalData data;
        data.degree              = settings.smoother_degree;
        data.smoothing_range     = settings.smoothing_range;
        data.eig_cg_n_iterations = 12;
        data.preconditioner      = std::make_shared<CutCellBlockJacobi>();
        data.preconditioner->initialize(
          a,
          settings.cut_cell_blocks ?
            cut_cell_blocks(l == 0 ? system : *dofs[l],
                            l == 0 ? system_constraints : constraints[l],
                            l == 0,
                            local) :
            std::vector<std::vector<unsigned int>>(),
          l == 0 ? finest_components : all_entries);
        block_jacobi.push_back(data.preconditioner);
        if (!settings.single_precision)
          {
            smoother.push_back(std::make_unique<Smoother>());
            smoother.back()->initialize(a, data);
          }
      }
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::separate_components(
    const SparseMatrix<double>      &matrix,
    const std::vector<unsigned int> &velocity_unknowns)
  {
    // Each row's velocity component (the rigid rows have none and keep
    // all their entries, so the particles stay coupled to their fluid).
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
    const unsigned int n_u = velocity_unknowns.size();
    row_component.assign(matrix.m(), 255);
    for (unsigned int k = 0; k < n_u; ++k)
      row_component[k] = dof_component[velocity_unknowns[k]];
    separated_pattern
      .fill(matrix.m(), matrix.n(), [&](const unsigned int i, const auto &f) {
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
          if (couples_within_component(row_component, i, it->column()))
            f(it->column());
      });
    if (!settings.single_precision)
      {
        separated.reinit(separated_pattern);
        copy_separated(matrix, separated);
      }
  }



  template <int dim>
  template <typename Number>
  void
  CutVelocityMultigrid<dim>::copy_separated(const SparseMatrix<double> &matrix,
                                            SparseMatrix<Number> &out) const
  {
    // Both rows hold their diagonal first and then ascending columns, and
    // the kept entries are a subsequence of the block's: copied in one
    // walk.
    on_row_ranges(
      matrix.m(),
      4,
      [&](const unsigned int first, const unsigned int last) {
        for (unsigned int i = first; i < last; ++i)
          {
            auto out_entry = out.begin(i);
            for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
              if (couples_within_component(row_component, i, it->column()))
                {
                  AssertThrow(out_entry->column() == it->column(),
                              ExcInternalError());
                  out_entry->value() = it->value();
                  ++out_entry;
                }
          }
      });
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::setup_single_precision()
  {
    // The levels, the prolongations and the smoothers in float: the
    // V-cycle is bound by the memory traffic of its products, and a
    // preconditioner needs no more digits than FGMRES takes from it (the
    // same iterations, the answers within 5e-10 of the double cycle's on
    // one sphere and the 3D pair; doc/theory/cut_element.md, "Solvers").
    // The cut-cell blocks' inverses are float already. The coarsest level
    // keeps its double factorisation.
    const unsigned int n_levels = coarse.size() + 1;
    level_float.clear();
    prolongation_float.clear();
    smoother_float.clear();
    for (unsigned int l = 0; l + 1 < n_levels; ++l)
      {
        const SparseMatrix<double> &a = level_matrix(l);
        if (l == 0 && !row_component.empty())
          {
            // The finest level separated straight from the caller's block.
            level_float.push_back(
              std::make_unique<SparseMatrix<float>>(separated_pattern));
            copy_separated(a, *level_float.back());
          }
        else
          {
            level_float.push_back(
              std::make_unique<SparseMatrix<float>>(a.get_sparsity_pattern()));
            level_float.back()->copy_from(a);
          }
        prolongation_float.push_back(
          std::make_unique<SparseMatrix<float>>(*prolongation_pattern[l]));
        prolongation_float.back()->copy_from(*prolongation[l]);
        typename FloatSmoother::AdditionalData data;
        data.degree              = settings.smoother_degree;
        data.smoothing_range     = settings.smoothing_range;
        data.eig_cg_n_iterations = 12;
        data.preconditioner      = block_jacobi[l];
        smoother_float.push_back(std::make_unique<FloatSmoother>());
        smoother_float.back()->initialize(*level_float.back(), data);
      }
    for (unsigned int l = 0; l < n_levels; ++l)
      {
        const unsigned int m = level_matrix(l).m();
        residual_f.emplace_back(m);
        rhs_f.emplace_back(m);
        solution_f.emplace_back(m);
      }
    coarse_x.reinit(level_matrix(n_levels - 1).m());
    coarse_b.reinit(coarse_x.size());
    src_f.reinit(finest->m());
    dst_f.reinit(finest->m());
    // The double copies are no longer read (the finest is the caller's).
    for (auto &p : prolongation)
      p->clear();
    for (auto &c : coarse)
      c->clear();
    // (The float finest level keeps the separated pattern.)
    separated.clear();
  }



  template <int dim>
  const SparseMatrix<double> &
  CutVelocityMultigrid<dim>::level_matrix(const unsigned int level) const
  {
    return level == 0 ? *finest : *coarse[level - 1];
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::v_cycle(const unsigned int    level,
                                     Vector<double>       &x,
                                     const Vector<double> &b) const
  {
    if (level + 1 == residual.size())
      {
        coarsest.vmult(x, b);
        return;
      }
    const SparseMatrix<double> &a = level_matrix(level);
    smoother[level]->vmult(x, b);
    a.vmult(residual[level], x);
    residual[level].sadd(-1., 1., b);
    prolongation[level]->Tvmult(level_rhs[level + 1], residual[level]);
    v_cycle(level + 1, level_solution[level + 1], level_rhs[level + 1]);
    prolongation[level]->vmult_add(x, level_solution[level + 1]);
    smoother[level]->step(x, b);
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::v_cycle_float(const unsigned int   level,
                                           Vector<float>       &x,
                                           const Vector<float> &b) const
  {
    if (level + 1 == residual_f.size())
      {
        coarse_b = b;
        coarsest.vmult(coarse_x, coarse_b);
        x = coarse_x;
        return;
      }
    const SparseMatrix<float> &a = *level_float[level];
    smoother_float[level]->vmult(x, b);
    a.vmult(residual_f[level], x);
    residual_f[level].sadd(-1.f, 1.f, b);
    prolongation_float[level]->Tvmult(rhs_f[level + 1], residual_f[level]);
    v_cycle_float(level + 1, solution_f[level + 1], rhs_f[level + 1]);
    prolongation_float[level]->vmult_add(x, solution_f[level + 1]);
    smoother_float[level]->step(x, b);
  }



  template <int dim>
  void
  CutVelocityMultigrid<dim>::vmult(Vector<double>       &dst,
                                   const Vector<double> &src) const
  {
    if (!settings.single_precision)
      {
        v_cycle(0, dst, src);
        return;
      }
    src_f = src;
    v_cycle_float(0, dst_f, src_f);
    dst = dst_f;
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
    // unknowns are left out: their rows hold the diagonal alone.
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
            block.push_back(finest ? local[i] : i);
        if (!block.empty())
          blocks.push_back(std::move(block));
      }
    return blocks;
  }



  template class CutVelocityMultigrid<2>;
  template class CutVelocityMultigrid<3>;
} // namespace Fidus
