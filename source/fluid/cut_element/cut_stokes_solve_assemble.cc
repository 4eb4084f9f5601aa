#include "cut_stokes_solve.h"

#include <algorithm>
#include <array>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
#include <cmath>
#include <cstdint>
#include <deal.II/base/work_stream.h>
#include <deal.II/lac/affine_constraints.templates.h>
#include <deal.II/non_matching/fe_immersed_values.h>
#include <fidus/fluid/cut_element/cut_level_set.h>
#include <fidus/fluid/cut_element/product_transposed.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <fidus/fluid/fictitious_domain/rigid_mode.h>
#include <map>
#include <stdexcept>

// The assembly stages of CutStokesSolve: the fluid cells (volume and
// Nitsche terms), the ghost penalties and the rigid couplings. Cells and
// faces are computed on the machine's cores (WorkStream: one scratch per
// thread) and added to the global matrices by one thread in the cells'
// order, so that the system is the same, to the bit, on any number of
// threads. The kernels' matrix products do not call the BLAS
// (product_transposed()).

namespace Fidus
{
  namespace
  {
    /// matrix(dofs[i], dofs[j]) += local(i, j) for every entry of the rows
    /// dofs[i] that @p rows marks, with the columns of each row in
    /// ascending order: SparseMatrix::add then walks the row once instead
    /// of searching it for every entry (a tenth of a dense 3D suspension's
    /// solve). Zeros are added too, as SparseMatrix::add(indices,
    /// full_matrix) does.
    void
    add_sorted(SparseMatrix<double>                       &matrix,
               const std::vector<types::global_dof_index> &dofs,
               const FullMatrix<double>                   &local,
               const std::vector<bool>                    &rows)
    {
      const unsigned int n = dofs.size();
      if (std::none_of(dofs.begin(), dofs.end(), [&](const auto i) {
            return rows[i];
          }))
        return;
      std::vector<unsigned int> order(n);
      for (unsigned int k = 0; k < n; ++k)
        order[k] = k;
      std::sort(order.begin(), order.end(), [&](const auto a, const auto b) {
        return dofs[a] < dofs[b];
      });
      std::vector<types::global_dof_index> columns(n);
      std::vector<double>                  values(n);
      for (unsigned int k = 0; k < n; ++k)
        columns[k] = dofs[order[k]];
      for (unsigned int i = 0; i < n; ++i)
        if (rows[dofs[i]])
          {
            for (unsigned int k = 0; k < n; ++k)
              values[k] = local(i, order[k]);
            matrix.add(dofs[i], n, columns.data(), values.data(), false, true);
          }
    }

    /**
     * Colours for @p n_items items, each writing the rows that
     * @p rows_of(k) lists (of @p n_rows): items of one colour write no
     * common row. Greedy, in order: each item takes the lowest colour that
     * none of its rows has had. Beyond 64 colours (a row's colours are a
     * bit mask), an item gets a colour of its own.
     */
    template <typename RowsOf>
    std::vector<std::vector<unsigned int>>
    colour_greedily(const unsigned int n_items,
                    const unsigned int n_rows,
                    const RowsOf      &rows_of)
    {
      std::vector<std::uint64_t>             taken(n_rows, 0);
      std::vector<std::vector<unsigned int>> colours(64);
      for (unsigned int k = 0; k < n_items; ++k)
        {
          const auto    rows = rows_of(k);
          std::uint64_t used = 0;
          for (const auto r : rows)
            used |= taken[r];
          if (~used == 0)
            {
              colours.push_back({k});
              continue;
            }
          const unsigned int colour = __builtin_ctzll(~used);
          colours[colour].push_back(k);
          for (const auto r : rows)
            taken[r] |= std::uint64_t(1) << colour;
        }
      colours.erase(std::remove_if(colours.begin(),
                                   colours.end(),
                                   [](const auto &c) { return c.empty(); }),
                    colours.end());
      return colours;
    }
  } // namespace

  template <int dim>
  CutStokesSolve<dim>::CellScratch::CellScratch(const CutStokesSolve &solve)
    : solve(solve)
    , q1d(QGauss<1>(solve.s.quadrature_points))
    , generator(q1d)
    , fe_fluid(solve.mapping,
               solve.taylor_hood,
               solve.q_cell,
               update_gradients | update_values | update_JxW_values)
    , dofs(solve.n_local)
    , volume(solve.taylor_hood)
  {}

  template <int dim>
  CutStokesSolve<dim>::CellCopy::CellCopy(const CutStokesSolve &solve)
    : local(solve.n_ext, solve.n_ext)
    , local_pressure(solve.pressure_shapes.size(), solve.pressure_shapes.size())
    , ext_dofs(solve.n_ext)
  {}

  template <int dim>
  void
  CutStokesSolve<dim>::add_volume(const FEValues<dim> &fe_values,
                                  CellScratch         &scratch,
                                  CellCopy            &copy) const
  {
    // local is n_ext x n_ext; the volume terms fill its first n_local rows
    // and columns.
    scratch.volume.add(fe_values, eta, copy.local, copy.local_pressure);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::add_nitsche(const cell_iterator &cell,
                                   const Ball          &P,
                                   const double         h,
                                   CellScratch         &scratch,
                                   CellCopy            &copy) const
  {
    const auto &q_surface = scratch.generator.get_surface_quadrature();
    NonMatching::FEImmersedSurfaceValues<dim> fe_surface(mapping,
                                                         taylor_hood,
                                                         q_surface,
                                                         surface_flags);
    fe_surface.reinit(cell);
    const double gamma = s.nitsche * eta / h;
    // Per extended index i and point: the trace v_i of v - w_v and
    // g_i = -2 eta eps(v_i) n + p_i n + gamma/2 v_i, so that the terms
    // -t_j.v_i + p_j v_i.n - t_i.v_j + p_i v_j.n + gamma v_i.v_j are
    // v_i.g_j + g_i.v_j: the matrix is L R^T with the rows of L holding
    // (v_i, g_i) and those of R (g_i, v_i), times sqrt(JxW) (one product
    // instead of a double loop over the shape functions per point).
    const unsigned int n_q = q_surface.size();
    auto              &L = scratch.surface_left, &R = scratch.surface_right;
    L.reinit(n_ext, n_q * 2 * dim);
    R.reinit(n_ext, n_q * 2 * dim);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        // The fluid's outward normal points into the particle.
        const Tensor<1, dim> n    = -fe_surface.normal_vector(q);
        const Tensor<1, dim> r    = fe_surface.quadrature_point(q) - P.center;
        const double         w    = std::sqrt(fe_surface.JxW(q));
        const unsigned int   v_at = 2 * dim * q, g_at = v_at + dim;
        const auto           set = [&](const unsigned int    i,
                             const Tensor<1, dim> &v,
                             const Tensor<1, dim> &g) {
          for (unsigned int c = 0; c < dim; ++c)
            {
              L(i, v_at + c) = R(i, g_at + c) = w * v[c];
              L(i, g_at + c) = R(i, v_at + c) = w * g[c];
            }
        };
        for (unsigned int i = 0; i < n_local; ++i)
          {
            const Tensor<1, dim> v = fe_surface[velocity].value(i, q);
            set(i,
                v,
                -2. * eta *
                    (fe_surface[velocity].symmetric_gradient(i, q) * n) +
                  fe_surface[pressure].value(i, q) * n + 0.5 * gamma * v);
          }
        for (unsigned int k = 0; k < n_rigid; ++k)
          {
            const Tensor<1, dim> v = -rigid_mode<dim>(k, r);
            set(n_local + k, v, 0.5 * gamma * v);
          }
      }
    auto &product = scratch.product;
    product_transposed(L, R, product);
    copy.local.add(1., product);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::assemble_cell(const cell_iterator &cell,
                                     CellScratch         &scratch,
                                     CellCopy            &copy) const
  {
    copy.fluid = cell->active_fe_index() == 0;
    if (!copy.fluid)
      return;
    cell->get_dof_indices(scratch.dofs);
    std::copy(scratch.dofs.begin(), scratch.dofs.end(), copy.ext_dofs.begin());
    const Placement &here = placed(cell);
    const auto      &P    = mesh->get_balls()[here.ball];
    for (unsigned int k = 0; k < n_rigid; ++k)
      copy.ext_dofs[n_local + k] = n_fluid + P.owner * n_rigid + k;
    copy.local          = 0.;
    copy.local_pressure = 0.;
    const double h      = CutMesh<dim>::shortest_side(cell);
    scratch.generator.generate(
      CutLevelSet<dim>(cell->vertex(0),
                       cell->vertex(GeometryInfo<dim>::vertices_per_cell - 1),
                       P.center,
                       P.radius),
      unit_box);
    const Quadrature<dim> &q_outside =
      scratch.generator.get_outside_quadrature();
    if (q_outside.size() > 0)
      {
        FEValues<dim> fe_cut(mapping,
                             taylor_hood,
                             q_outside,
                             update_gradients | update_values |
                               update_JxW_values);
        fe_cut.reinit(cell);
        add_volume(fe_cut, scratch, copy);
      }
    if (scratch.generator.get_surface_quadrature().size() > 0)
      add_nitsche(cell, P, h, scratch, copy);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::distribute_cell(const CellCopy &copy)
  {
    if (copy.fluid)
      distribute(copy.local, copy.local_pressure, copy.ext_dofs, copy.share);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::distribute(
    const FullMatrix<double>                   &local,
    const FullMatrix<double>                   &local_pressure,
    const std::vector<types::global_dof_index> &dofs,
    const bool                                  share)
  {
    if (!share)
      {
        add_to_held_rows(local, dofs);
        return;
      }
    // The cell's pressures and its part of the constant's mass: local, as
    // full cells are added from several threads at once.
    const unsigned int                   n_p = pressure_shapes.size();
    std::vector<types::global_dof_index> pressures(n_p);
    Vector<double>                       mean(n_p);
    for (unsigned int a = 0; a < n_p; ++a)
      {
        pressures[a] = dofs[pressure_shapes[a]];
        for (unsigned int b = 0; b < n_p; ++b)
          mean[a] += local_pressure(a, b);
      }
    constraints.distribute_local_to_global(mean, pressures, pressure_mean);
    if (iterative)
      constraints.distribute_local_to_global(local_pressure,
                                             pressures,
                                             pressure_mass);
    if (periodic)
      add_sorted(unconstrained, dofs, local, wall_rows);
    // The cells carry no load: the right-hand side comes from the
    // constraints' inhomogeneities (the imposed velocities).
    const Vector<double> zero(dofs.size());
    add_to_system(local, zero, dofs);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::add_to_system(
    const FullMatrix<double>                   &local,
    const Vector<double>                       &local_rhs,
    const std::vector<types::global_dof_index> &dofs)
  {
    if (split_rows)
      {
        CutSystemBlocks::Part part(*blocks, true);
        constraints.distribute_local_to_global(local,
                                               local_rhs,
                                               dofs,
                                               part,
                                               rhs);
      }
    else if (blocks)
      constraints.distribute_local_to_global(local,
                                             local_rhs,
                                             dofs,
                                             *blocks,
                                             rhs);
    else
      constraints.distribute_local_to_global(local,
                                             local_rhs,
                                             dofs,
                                             matrix,
                                             rhs);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::add_to_held_rows(
    const FullMatrix<double>                   &local,
    const std::vector<types::global_dof_index> &dofs)
  {
    // The matrix alone: what the cell moves to the right-hand side is its
    // share owner's to add.
    CutSystemBlocks::Part part(*blocks, false);
    constraints.distribute_local_to_global(local, dofs, part);
  }

  template <int dim>
  bool
  CutStokesSolve<dim>::writes_held_rows(
    const std::vector<types::global_dof_index> &dofs) const
  {
    for (const auto i : dofs)
      {
        if (i >= n_fluid)
          continue;
        if (blocks->owns_velocity_row(i))
          return true;
        if (const auto *entries = constraints.get_constraint_entries(i))
          for (const auto &entry : *entries)
            if (blocks->owns_velocity_row(entry.first))
              return true;
      }
    return false;
  }

  template <int dim>
  std::vector<unsigned int>
  CutStokesSolve<dim>::border_destinations(const cell_iterator &cell) const
  {
    std::vector<unsigned int> ranks;
    for (const auto i : rows_written(cell))
      if (blocks->kind[i] == 0 && !blocks->owns_velocity_row(i))
        ranks.push_back(velocity_row_rank(i));
    std::sort(ranks.begin(), ranks.end());
    ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
    return ranks;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::add_cells_of_other_ranks(
    const std::map<unsigned int, PackedCells> &outgoing)
  {
    // The other ranks' cut cells that write this rank's rows. Collective.
    FullMatrix<double>                   local(n_ext, n_ext);
    std::vector<types::global_dof_index> dofs(n_ext);
    for (const auto &incoming :
         Utilities::MPI::some_to_some(s.communicator, outgoing))
      {
        const PackedCells &packed = incoming.second;
        for (std::size_t c = 0; c * n_ext < packed.first.size(); ++c)
          {
            std::copy(packed.second.begin() + c * n_ext * n_ext,
                      packed.second.begin() + (c + 1) * n_ext * n_ext,
                      &local(0, 0));
            std::copy(packed.first.begin() + c * n_ext,
                      packed.first.begin() + (c + 1) * n_ext,
                      dofs.begin());
            add_to_held_rows(local, dofs);
          }
      }
  }

  template <int dim>
  void
  CutStokesSolve<dim>::gather_velocity_diagonal()
  {
    velocity_diagonal.reinit(n_total);
    for (unsigned int i = 0; i < n_fluid; ++i)
      if (blocks->owns_velocity_row(i))
        velocity_diagonal[i] = blocks->diag_element(i);
    Utilities::MPI::sum(velocity_diagonal, s.communicator, velocity_diagonal);
  }

  template <int dim>
  std::vector<types::global_dof_index>
  CutStokesSolve<dim>::rows_written(const cell_iterator &cell) const
  {
    std::vector<types::global_dof_index> dofs(n_local), rows;
    cell->get_dof_indices(dofs);
    // A constrained DoF's own row gets a diagonal entry, and the rows of
    // those it stands for its couplings.
    for (const auto i : dofs)
      {
        rows.push_back(i);
        if (const auto *entries = constraints.get_constraint_entries(i))
          for (const auto &entry : *entries)
            rows.push_back(entry.first);
      }
    return rows;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::assemble_cells()
  {
    // The generator of the stages after the solve (the stresslets).
    q1d = std::make_unique<const hp::QCollection<1>>(
      QGauss<1>(s.quadrature_points));
    generator = std::make_unique<NonMatching::QuadratureGenerator<dim>>(*q1d);

    CellScratch scratch(*this);
    CellCopy    copy(*this);
    // A cell without a surface is a full square of its level's size: its
    // matrices (on its own DoFs: it reaches no rigid unknown) are computed
    // once per level, before the threads read them.
    full_cells.clear();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->active_fe_index() == 0 && placed(cell).n_cut == 0 &&
          full_cells.count(cell->level()) == 0)
        {
          copy.local          = 0.;
          copy.local_pressure = 0.;
          scratch.fe_fluid.reinit(cell);
          add_volume(scratch.fe_fluid, scratch, copy);
          FullMatrix<double> local(n_local, n_local);
          for (unsigned int i = 0; i < n_local; ++i)
            for (unsigned int j = 0; j < n_local; ++j)
              local(i, j) = copy.local(i, j);
          full_cells.emplace(cell->level(),
                             std::make_pair(local, copy.local_pressure));
        }
    // This rank's share of the fluid cells (all of them on one rank): with
    // K's velocity rows split among the ranks, the full cells whose first
    // unknown (a velocity: the element numbers a vertex's velocities
    // first) has its row here, and besides them the full cells that write
    // this rank's rows (for those only; their matrices are cached, so
    // adding is all their work); a cut cell, whose integration is the
    // assembly's cost, is integrated once, by one rank (its first
    // unknown's, as far as the ranks' loads stay even:
    // balance_cut_cells()), which sends its matrix to the other ranks
    // whose rows it writes (border_destinations()). Without the split (the
    // direct solver), cut and full cells each dealt round robin.
    struct CutCell
    {
      cell_iterator             cell;
      bool                      share;
      std::vector<unsigned int> destinations;
    };
    std::vector<CutCell>                 cut;
    std::vector<cell_iterator>           full;
    std::vector<bool>                    full_share;
    std::vector<cell_iterator>           split_cut;
    std::vector<unsigned int>            home;
    unsigned int                         n_cut = 0, n_full = 0;
    std::vector<types::global_dof_index> cell_dofs(n_local);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->active_fe_index() == 0)
        {
          const bool         is_cut = placed(cell).n_cut > 0;
          const unsigned int k      = is_cut ? n_cut++ : n_full++;
          bool               share = !split_rows && mine(k), held = false;
          if (split_rows)
            {
              cell->get_dof_indices(cell_dofs);
              if (is_cut)
                {
                  split_cut.push_back(cell);
                  home.push_back(velocity_row_rank(cell_dofs[0]));
                  continue;
                }
              share = blocks->owns_velocity_row(cell_dofs[0]);
              held  = share || writes_held_rows(cell_dofs);
            }
          if (!share && !held)
            continue;
          if (is_cut)
            cut.push_back({cell, share, std::vector<unsigned int>()});
          else
            {
              full.push_back(cell);
              full_share.push_back(share);
            }
        }
    if (split_rows)
      {
        const std::vector<unsigned int> rank = balance_cut_cells(home);
        for (unsigned int k = 0; k < split_cut.size(); ++k)
          if (rank[k] == this_rank)
            cut.push_back(
              {split_cut[k], true, border_destinations(split_cut[k])});
      }
    // The cut cells are integrated on the threads and added one at a time
    // (those of a particle share its rigid unknowns' rows); the matrices
    // other ranks' rows need are packed as they are added: the cells' DoFs,
    // then their matrices.
    std::map<unsigned int, PackedCells> outgoing;
    WorkStream::run(
      cut.begin(),
      cut.end(),
      [this](const typename std::vector<CutCell>::iterator &cell,
             CellScratch                                   &sc,
             CellCopy                                      &cp) {
        assemble_cell(cell->cell, sc, cp);
        cp.share        = cell->share;
        cp.destinations = &cell->destinations;
      },
      [this, &outgoing](const CellCopy &cp) {
        distribute_cell(cp);
        if (!cp.fluid)
          return;
        for (const unsigned int rank : *cp.destinations)
          {
            PackedCells &packed = outgoing[rank];
            packed.first.insert(packed.first.end(),
                                cp.ext_dofs.begin(),
                                cp.ext_dofs.end());
            packed.second.insert(packed.second.end(),
                                 &cp.local(0, 0),
                                 &cp.local(0, 0) + cp.local.n_elements());
          }
      },
      scratch,
      copy);
    if (split_rows)
      add_cells_of_other_ranks(outgoing);
    // Adding a full cell's cached matrices is all its work, and one thread
    // adding them all was a third of the 3D assembly: cells that write no
    // common row (rows_written()) are added on the threads, colour by
    // colour, each entry's sum in the colours' order whatever the threads.
    // (deal.II's GraphColoring took as long as the additions it saved.)
    const std::vector<std::vector<unsigned int>> colours =
      colour_greedily(full.size(), n_total, [&](const unsigned int k) {
        return rows_written(full[k]);
      });
    for (const auto &colour : colours)
      on_row_ranges(colour.size(),
                    4,
                    [&](const unsigned int first, const unsigned int last) {
                      std::vector<types::global_dof_index> dofs(n_local);
                      for (unsigned int k = first; k < last; ++k)
                        {
                          const cell_iterator &cell = full[colour[k]];
                          cell->get_dof_indices(dofs);
                          const auto &cached = full_cells.at(cell->level());
                          distribute(cached.first,
                                     cached.second,
                                     dofs,
                                     full_share[colour[k]]);
                        }
                    });
  }

  template <int dim>
  void
  CutStokesSolve<dim>::sum_over_ranks()
  {
    // Every rank built the same patterns, so the shares add entry by entry.
    if (n_ranks == 1)
      return;
    if (split_rows)
      {
        // K's and Bᵀ's velocity rows are each held whole by one rank; their
        // rigid rows (last, on the same pattern on every rank) are summed,
        // and P.
        Utilities::MPI::sum(blocks->p, s.communicator, blocks->p);
        const unsigned int  n_v = particles.size() * n_rigid;
        const unsigned int  n_k = blocks->k.m();
        std::vector<double> rigid_values;
        const auto          for_rigid_entries = [&](const auto &f) {
          for (SparseMatrix<double> *block : {&blocks->k, &blocks->bt})
            for (unsigned int r = n_k - n_v; r < n_k; ++r)
              for (auto it = block->begin(r); it != block->end(r); ++it)
                f(it->value());
        };
        for_rigid_entries([&](double v) { rigid_values.push_back(v); });
        Utilities::MPI::sum(rigid_values, s.communicator, rigid_values);
        std::size_t at = 0;
        for_rigid_entries([&](auto &&v) { v = rigid_values[at++]; });
      }
    else
      Utilities::MPI::sum(matrix, s.communicator, matrix);
    if (iterative)
      Utilities::MPI::sum(pressure_mass, s.communicator, pressure_mass);
    Utilities::MPI::sum(rhs, s.communicator, rhs);
    Utilities::MPI::sum(pressure_mean, s.communicator, pressure_mean);
    if (periodic)
      Utilities::MPI::sum(unconstrained, s.communicator, unconstrained);
    if (split_rows)
      gather_velocity_diagonal();
  }

  template <int dim>
  void
  CutStokesSolve<dim>::assemble_couplings()
  {
    // The rigid rows read A x = F: the fluid's traction and the external
    // force. A resistance whose load on the particles is -M x + l joins
    // them as (A + M) x = F + l.
    for (unsigned int p = 0; p < particles.size(); ++p)
      for (unsigned int d = 0; d < dim; ++d)
        rhs(n_fluid + p * n_rigid + d) += particles[p].force[d];
    for (const auto &c : s.couplings)
      {
        const unsigned int m = c.owners.size() * n_rigid;
        AssertThrow(c.matrix.size() == m && c.load.size() == m,
                    ExcMessage("a rigid coupling of the wrong size"));
        const auto row = [&](const unsigned int k) {
          return n_fluid + c.owners[k / n_rigid] * n_rigid + k % n_rigid;
        };
        for (unsigned int k = 0; k < m; ++k)
          {
            AssertThrow(c.owners[k / n_rigid] < particles.size(),
                        ExcMessage("a rigid coupling of a particle that "
                                   "is not there"));
            rhs(row(k)) += c.load[k];
            for (unsigned int l = 0; l < m; ++l)
              {
                if (blocks)
                  blocks->add(row(k), row(l), c.matrix[k][l]);
                else
                  matrix.add(row(k), row(l), c.matrix[k][l]);
              }
          }
      }
  }


  template <int dim>
  CutStokesSolve<dim>::FaceScratch::FaceScratch(const CutStokesSolve &solve)
    : solve(solve)
    , q_face(3)
    , fe_face(solve.mapping, solve.taylor_hood, q_face, flags())
    , fe_neighbour(solve.mapping, solve.taylor_hood, q_face, flags())
    , fe_coarser(solve.mapping, solve.taylor_hood, q_face, flags())
    , dofs(solve.n_local)
    , neighbour_dofs(solve.n_local)
    , local_of(solve.n_local)
    , layout(solve.taylor_hood)
    , scalar_of(solve.n_local)
    , pressure_rank(solve.n_local)
  {
    const unsigned int n_s = layout.velocity[0].size();
    for (auto &ids : scalar_id)
      ids.resize(n_s);
    for (auto &ids : pressure_id)
      ids.resize(layout.pressure.size());
    for (unsigned int k = 0; k < n_s; ++k)
      scalar_of[layout.velocity[0][k]] = k;
    for (unsigned int a = 0; a < layout.pressure.size(); ++a)
      pressure_rank[layout.pressure[a]] = a;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::assemble_face(const GhostFace &ghost,
                                     FaceScratch     &scratch,
                                     FaceCopy        &copy) const
  {
    // The two cells share the DoFs of their common face, so the face's
    // unknowns are the union of both cells' (as FEInterfaceValues numbers
    // them): a shared DoF's jump takes the contributions of both sides.
    const auto &cell      = ghost.cell;
    const auto &neighbour = ghost.neighbour;
    const bool  coarser   = ghost.subface != numbers::invalid_unsigned_int;
    auto       &fe_face   = scratch.fe_face;
    auto       &q_face    = scratch.q_face;
    fe_face.reinit(cell, ghost.face);
    if (coarser)
      scratch.fe_coarser.reinit(neighbour, ghost.neighbour_face, ghost.subface);
    else
      scratch.fe_neighbour.reinit(neighbour, ghost.neighbour_face);
    const FEFaceValuesBase<dim> &fe_other =
      coarser ?
        static_cast<const FEFaceValuesBase<dim> &>(scratch.fe_coarser) :
        static_cast<const FEFaceValuesBase<dim> &>(scratch.fe_neighbour);
    auto &dofs = scratch.dofs, &neighbour_dofs = scratch.neighbour_dofs;
    auto &local_of  = scratch.local_of;
    auto &face_dofs = copy.face_dofs;
    cell->get_dof_indices(dofs);
    neighbour->get_dof_indices(neighbour_dofs);
    face_dofs = dofs;
    for (unsigned int i = 0; i < n_local; ++i)
      {
        local_of[i][0] = i;
        const auto it  = std::find(dofs.begin(), dofs.end(), neighbour_dofs[i]);
        if (it != dofs.end())
          local_of[i][1] = it - dofs.begin();
        else
          {
            local_of[i][1] = face_dofs.size();
            face_dofs.push_back(neighbour_dofs[i]);
          }
      }
    const unsigned int n_face = face_dofs.size();
    // The face matrix is sum_q JxW (w_v h d1 d1^T + w_v h^3 d2 d2^T -
    // w_p h^3 dp dp^T), d1 and d2 the jumps of the velocity's first and
    // second normal derivatives, dp the pressure gradient's normal jump.
    // A velocity function phi_k e_c jumps in its component c only, by the
    // jump of its scalar phi_k, so the velocity part is one matrix of the
    // face's scalar Q2 functions, repeated on each component: its product
    // has the scalar functions as rows (a third of the velocity ones) and
    // two columns per point (instead of 2 dim + 1 for all of them).
    const auto        &layout = scratch.layout;
    const unsigned int n_s    = layout.velocity[0].size(),
                       n_p    = layout.pressure.size();
    // The face's scalar and pressure functions: each side's, a shared one
    // once; scalar S is the face unknowns velocity_of[S][c] for c < dim.
    auto &scalar_id = scratch.scalar_id, &pressure_id = scratch.pressure_id;
    auto &velocity_of = scratch.velocity_of;
    auto &pressure_of = scratch.pressure_of;
    velocity_of.clear();
    pressure_of.clear();
    for (unsigned int side = 0; side < 2; ++side)
      {
        for (unsigned int k = 0; k < n_s; ++k)
          {
            const unsigned int first = local_of[layout.velocity[0][k]][side];
            if (first < n_local && side == 1)
              {
                // Shared with the cell: its scalar is the cell's one there.
                scalar_id[1][k] = scalar_id[0][scratch.scalar_of[first]];
                continue;
              }
            scalar_id[side][k] = velocity_of.size();
            std::array<unsigned int, dim> at;
            for (unsigned int c = 0; c < dim; ++c)
              at[c] = local_of[layout.velocity[c][k]][side];
            velocity_of.push_back(at);
          }
        for (unsigned int a = 0; a < n_p; ++a)
          {
            const unsigned int at = local_of[layout.pressure[a]][side];
            if (at < n_local && side == 1)
              {
                pressure_id[1][a] = pressure_id[0][scratch.pressure_rank[at]];
                continue;
              }
            pressure_id[side][a] = pressure_of.size();
            pressure_of.push_back(at);
          }
      }
    const unsigned int n_scalar = velocity_of.size(), n_pf = pressure_of.size();
    auto              &A = scratch.velocity_jumps, &B = scratch.pressure_jumps;
    A.reinit(n_scalar, 2 * q_face.size());
    B.reinit(n_pf, q_face.size());
    // The cells' sizes across the face (the derivatives jumped are normal
    // to it); across a hanging face, the mean of the two.
    const unsigned int axis = ghost.face / 2;
    const double       h    = 0.5 * (cell->extent_in_direction(axis) +
                            neighbour->extent_in_direction(axis));
    for (unsigned int q = 0; q < q_face.size(); ++q)
      {
        if ((fe_face.quadrature_point(q) - fe_other.quadrature_point(q) -
             ghost.shift)
              .norm() > 1e-12 * h)
          throw std::logic_error("CutStokesInclusion: face quadrature "
                                 "points do not match");
        const Tensor<1, dim> n   = fe_face.normal_vector(q);
        const double         JxW = fe_face.JxW(q);
        const double         w1  = std::sqrt(s.ghost_velocity * eta * h * JxW),
                     w2 = std::sqrt(s.ghost_velocity * eta * h * h * h * JxW),
                     wp = std::sqrt(s.ghost_pressure / eta * h * h * h * JxW);
        for (unsigned int side = 0; side < 2; ++side)
          {
            const FEFaceValuesBase<dim> &fv   = side == 0 ? fe_face : fe_other;
            const double                 sign = side == 0 ? 1. : -1.;
            for (unsigned int k = 0; k < n_s; ++k)
              {
                const unsigned int i = layout.velocity[0][k];
                const unsigned int S = scalar_id[side][k];
                A(S, 2 * q) += sign * w1 * (fv.shape_grad(i, q) * n);
                A(S, 2 * q + 1) +=
                  sign * w2 * (n * (fv.shape_hessian(i, q) * n));
              }
            for (unsigned int a = 0; a < n_p; ++a)
              B(pressure_id[side][a], q) +=
                sign * wp * (fv.shape_grad(layout.pressure[a], q) * n);
          }
      }
    auto &velocity_part = scratch.velocity_part,
         &pressure_part = scratch.pressure_part;
    product_transposed(A, A, velocity_part);
    product_transposed(B, B, pressure_part);
    copy.face_matrix.reinit(n_face, n_face);
    for (unsigned int S = 0; S < n_scalar; ++S)
      for (unsigned int T = 0; T < n_scalar; ++T)
        for (unsigned int c = 0; c < dim; ++c)
          copy.face_matrix(velocity_of[S][c], velocity_of[T][c]) =
            velocity_part(S, T);
    for (unsigned int P = 0; P < n_pf; ++P)
      for (unsigned int Q = 0; Q < n_pf; ++Q)
        copy.face_matrix(pressure_of[P], pressure_of[Q]) = -pressure_part(P, Q);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::assemble_ghost_penalties()
  {
    FaceScratch    scratch(*this);
    FaceCopy       copy;
    Vector<double> face_rhs;
    // This rank's share of the faces, as of the cells (assemble_cells()):
    // with K's velocity rows split, the faces whose first cell's first
    // unknown has its row here, and besides them the faces that write this
    // rank's rows (for those only); without the split, dealt round robin.
    std::vector<std::pair<const GhostFace *, bool>> share;
    std::vector<types::global_dof_index>            dofs(n_local), both;
    for (unsigned int k = 0; k < ghost_faces.size(); ++k)
      {
        bool in_share = !split_rows && mine(k), held = false;
        if (split_rows)
          {
            both.clear();
            for (const auto &cell :
                 {ghost_faces[k].cell, ghost_faces[k].neighbour})
              {
                cell->get_dof_indices(dofs);
                both.insert(both.end(), dofs.begin(), dofs.end());
              }
            in_share = blocks->owns_velocity_row(both[0]);
            held     = !in_share && writes_held_rows(both);
          }
        if (in_share || held)
          share.emplace_back(&ghost_faces[k], in_share);
      }
    WorkStream::run(
      share.begin(),
      share.end(),
      [this](const typename std::vector<
               std::pair<const GhostFace *, bool>>::iterator &ghost,
             FaceScratch                                     &sc,
             FaceCopy                                        &cp) {
        assemble_face(*ghost->first, sc, cp);
        cp.share = ghost->second;
      },
      [this, &face_rhs](const FaceCopy &cp) {
        if (!cp.share)
          {
            add_to_held_rows(cp.face_matrix, cp.face_dofs);
            return;
          }
        if (periodic)
          add_sorted(unconstrained, cp.face_dofs, cp.face_matrix, wall_rows);
        // With the right-hand side: a face next to the box's boundary
        // couples to DoFs with imposed velocity, whose values move to it.
        face_rhs.reinit(cp.face_dofs.size());
        add_to_system(cp.face_matrix, face_rhs, cp.face_dofs);
      },
      scratch,
      copy);
  }

  template struct CutStokesSolve<2>::CellScratch;
  template struct CutStokesSolve<2>::CellCopy;
  template struct CutStokesSolve<2>::FaceScratch;
  template void
  CutStokesSolve<2>::assemble_cells();
  template void
  CutStokesSolve<2>::assemble_ghost_penalties();
  template void
  CutStokesSolve<2>::sum_over_ranks();
  template void
  CutStokesSolve<2>::assemble_couplings();
  template struct CutStokesSolve<3>::CellScratch;
  template struct CutStokesSolve<3>::CellCopy;
  template struct CutStokesSolve<3>::FaceScratch;
  template void
  CutStokesSolve<3>::assemble_cells();
  template void
  CutStokesSolve<3>::assemble_ghost_penalties();
  template void
  CutStokesSolve<3>::sum_over_ranks();
  template void
  CutStokesSolve<3>::assemble_couplings();
} // namespace Fidus
