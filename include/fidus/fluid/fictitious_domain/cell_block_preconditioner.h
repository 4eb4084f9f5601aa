#ifndef fidus_fluid_cell_block_preconditioner_h
#define fidus_fluid_cell_block_preconditioner_h

#include <algorithm>
#include <cmath>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <fidus/fluid/fictitious_domain/velocity_operator.h>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /// Which cells of a multigrid level get a block in its smoother.
  enum class SmootherBlocks
  {
    /// None: point Jacobi.
    none,
    /// Cells whose viscosity is not the same at all their points.
    cut_cells
  };

  /**
   * The preconditioner inside the Chebyshev smoother of one multigrid level:
   * point Jacobi, except on the DoFs of cut cells (cells whose viscosity is
   * not the same at all their points), where it is additive Schwarz with one
   * block per cut cell:
   *
   *   P^{-1} = D_F^{-1} + sum over cut cells K of
   *            R_K^T W_K (R_K A R_K^T)^{-1} W_K R_K,
   *
   * with R_K the restriction to the free DoFs of K (its DoFs after hanging
   * node and periodic constraints are resolved) and D_F the diagonal of A on
   * the DoFs in no block, W_K the diagonal of 1/sqrt(m), m the number of
   * blocks that hold a DoF. Both terms are symmetric positive definite, so
   * Chebyshev (and its CG eigenvalue estimate) may use the sum.
   *
   * Why: in a cut cell the penalty r eta_f e(u):e(u) acts at a few of the
   * cell's quadrature points only. Its near-kernel there (velocities whose
   * strain vanishes at those points but not elsewhere in the cell) is local
   * and oscillatory, so the coarse levels cannot correct it, and a point
   * smoother, which scales every DoF of the cell by r, barely moves it: the
   * V-cycle's count grows like r (doc/preconditioners.md). The exact solve on
   * the cell's block contains that near-kernel.
   *
   * The block R_K A R_K^T is the assembled matrix restricted to K's DoFs: the
   * element matrices (from the operator's own cell integrand, so it is the
   * level's operator exactly) of every cell that shares a DoF with a block
   * are summed into it. With several MPI ranks a block keeps only the DoFs
   * the rank owns whose rows are complete on it (no ghost cell touches
   * them); the others stay with the point Jacobi part.
   */
  template <int dim, int degree>
  class CellBlockPreconditioner
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;
    using Operator   = VelocityOperator<dim, degree>;

    /**
     * The viscosity of the level at the quadrature points of @p fe_values
     * (reinitialised on @p cell, a ghost cell), as the operator's table
     * would hold it there.
     */
    using GhostViscosity = std::function<
      void(const typename DoFHandler<dim>::active_cell_iterator &cell,
           const FEValues<dim>                                  &fe_values,
           std::vector<double>                                  &eta)>;

    /**
     * Build the blocks of @p op (after its viscosity and inverse diagonal
     * are set): @p dofs and @p constraints are the level's DoF handler and
     * constraints, the ones its MatrixFree object was built with. With
     * @p use_blocks none this is point Jacobi. With @p ghost_viscosity the
     * element matrices of the ghost cells complete the rows at the
     * partition boundary, and ghost cut cells get blocks (on this rank's
     * DoFs); without it, DoFs that a ghost cell touches stay in no block.
     */
    void
    initialize(const Operator                  &op,
               const DoFHandler<dim>           &dofs,
               const AffineConstraints<double> &constraints,
               const SmootherBlocks             use_blocks,
               const GhostViscosity            &ghost_viscosity = {})
    {
      op.get_matrix_free()->initialize_dof_vector(point_inverse);
      point_inverse = op.get_matrix_diagonal_inverse()->get_vector();
      block_start.assign(1, 0);
      block_dofs.clear();
      inverses.clear();
      holder_count.assign(point_inverse.locally_owned_size(), 0);
      if (use_blocks == SmootherBlocks::none)
        return;

      const MatrixFree<dim, double> &mf = *op.get_matrix_free();
      const auto        &partitioner    = point_inverse.get_partitioner();
      const IndexSet    &owned          = dofs.locally_owned_dofs();
      const unsigned int n_owned        = point_inverse.locally_owned_size();
      const unsigned int dofs_per_cell  = dofs.get_fe().n_dofs_per_cell();

      // A DoF's free DoFs and weights after the constraints are resolved.
      std::vector<std::pair<types::global_dof_index, double>> resolved_one;
      auto resolve = [&](const types::global_dof_index g) {
        resolved_one.clear();
        if (constraints.is_constrained(g))
          {
            const auto *entries = constraints.get_constraint_entries(g);
            if (entries != nullptr)
              resolved_one.assign(entries->begin(), entries->end());
          }
        else
          resolved_one.emplace_back(g, 1.);
      };

      // The ghost cells: with their viscosity, their element matrices
      // complete the rows here; without it, the owned rows that they touch
      // are incomplete here.
      std::vector<unsigned char>           complete(n_owned, 1);
      std::vector<types::global_dof_index> indices(dofs_per_cell);
      std::unique_ptr<FEValues<dim>>       ghost_values;
      op.with_points([&](auto n, const unsigned int quadrature) {
        const QGauss<1>        gauss(decltype(n)::value);
        const QGaussLobatto<1> lobatto(decltype(n)::value);
        const Quadrature<dim>  points(quadrature == 0 ?
                                       static_cast<Quadrature<1>>(gauss) :
                                       static_cast<Quadrature<1>>(lobatto));
        ghost_values =
          std::make_unique<FEValues<dim>>(dofs.get_fe(),
                                          points,
                                          update_gradients | update_JxW_values |
                                            update_quadrature_points);
      });
      struct GhostCell
      {
        typename DoFHandler<dim>::active_cell_iterator cell;
        std::vector<double>                            eta;
        bool                                           cut;
      };
      std::vector<GhostCell> ghosts;
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_ghost())
          {
            if (ghost_viscosity)
              {
                GhostCell ghost{cell, {}, false};
                ghost_values->reinit(cell);
                ghost_viscosity(cell, *ghost_values, ghost.eta);
                const auto [low, high] =
                  std::minmax_element(ghost.eta.begin(), ghost.eta.end());
                ghost.cut = !Operator::same_viscosity(*low, *high);
                ghosts.push_back(std::move(ghost));
                continue;
              }
            cell->get_dof_indices(indices);
            for (const auto g : indices)
              {
                resolve(g);
                for (const auto &[free, weight] : resolved_one)
                  if (owned.is_element(free))
                    complete[partitioner->global_to_local(free)] = 0;
              }
          }

      // The blocks: the usable free DoFs of each cut cell. (Blocks on the
      // cells wholly in the solid as well were tried: the same count, 30 %
      // dearer set-up; doc/preconditioners.md.)
      const unsigned int        n_points = op.viscosity.size(1);
      std::vector<unsigned int> local;
      auto add_block = [&](const std::vector<types::global_dof_index> &cell) {
        local.clear();
        for (const auto g : cell)
          {
            resolve(g);
            for (const auto &[free, weight] : resolved_one)
              if (owned.is_element(free))
                {
                  const unsigned int i = partitioner->global_to_local(free);
                  if (complete[i])
                    local.push_back(i);
                }
          }
        std::sort(local.begin(), local.end());
        local.erase(std::unique(local.begin(), local.end()), local.end());
        if (local.empty())
          return;
        block_dofs.insert(block_dofs.end(), local.begin(), local.end());
        block_start.push_back(block_dofs.size());
      };
      for (unsigned int batch = 0; batch < mf.n_cell_batches(); ++batch)
        for (unsigned int lane = 0;
             lane < mf.n_active_entries_per_cell_batch(batch);
             ++lane)
          {
            double low = op.viscosity(batch, 0)[lane], high = low;
            for (unsigned int q = 1; q < n_points; ++q)
              {
                low  = std::min(low, op.viscosity(batch, q)[lane]);
                high = std::max(high, op.viscosity(batch, q)[lane]);
              }
            if (Operator::same_viscosity(low, high))
              continue;
            mf.get_cell_iterator(batch, lane)->get_dof_indices(indices);
            add_block(indices);
          }
      for (const GhostCell &ghost : ghosts)
        if (ghost.cut)
          {
            ghost.cell->get_dof_indices(indices);
            add_block(indices);
          }
      const unsigned int n_blocks = block_start.size() - 1;

      // Which blocks hold each owned DoF (compressed rows).
      std::vector<unsigned int> holder_start(n_owned + 1, 0);
      for (const unsigned int i : block_dofs)
        ++holder_start[i + 1];
      for (unsigned int i = 0; i < n_owned; ++i)
        holder_start[i + 1] += holder_start[i];
      std::vector<unsigned int> holders(block_dofs.size());
      {
        std::vector<unsigned int> next(holder_start.begin(),
                                       holder_start.end() - 1);
        for (unsigned int b = 0; b < n_blocks; ++b)
          for (unsigned int k = block_start[b]; k < block_start[b + 1]; ++k)
            holders[next[block_dofs[k]]++] = b;
      }

      std::vector<FullMatrix<double>> blocks(n_blocks);
      for (unsigned int b = 0; b < n_blocks; ++b)
        blocks[b].reinit(block_start[b + 1] - block_start[b],
                         block_start[b + 1] - block_start[b]);

      // Sum the element matrices of every cell that touches a block.
      op.with_points([&](auto n, const unsigned int quadrature) {
        constexpr int n_1d = decltype(n)::value;
        typename Operator::template EvaluatorWith<n_1d> phi(mf, 0, quadrature);
        // On a Galerkin level a cell of uniform viscosity is exact with the
        // Gauss points too, at a fifth of the cost in 3D Q2 (most cells
        // next to a cut cell are such cells).
        typename Operator::Evaluator gauss(mf, 0, 0);
        const auto                  &lexicographic =
          mf.get_shape_info(0, quadrature, 0, 0, 0).lexicographic_numbering;
        std::vector<types::global_dof_index> cell_dofs(dofs_per_cell);
        // Per cell DoF: its (owned local index, weight) after resolution.
        std::vector<std::vector<std::pair<unsigned int, double>>> free(
          dofs_per_cell);
        std::vector<FullMatrix<double>> element(
          VectorizedArray<double>::size(),
          FullMatrix<double>(dofs_per_cell, dofs_per_cell));
        std::vector<unsigned char> touches(VectorizedArray<double>::size());
        // Each lane's resolved DoFs, kept from the test for touching blocks
        // to the scatter.
        std::vector<decltype(free)> lane_free(VectorizedArray<double>::size(),
                                              decltype(free)(dofs_per_cell));
        std::vector<unsigned int>   cell_blocks;
        // Per cell DoF, its (position in the block, weight).
        std::vector<std::vector<std::pair<unsigned int, double>>> in_block(
          dofs_per_cell);
        std::vector<int> position(n_owned, -1);

        // The free DoFs of a cell whose element matrix numbers its DoFs as
        // cell_dofs; whether any is in a block.
        auto resolve_cell = [&]() {
          bool any = false;
          for (unsigned int a = 0; a < dofs_per_cell; ++a)
            {
              free[a].clear();
              resolve(cell_dofs[a]);
              for (const auto &[g, weight] : resolved_one)
                if (owned.is_element(g))
                  {
                    const unsigned int i = partitioner->global_to_local(g);
                    free[a].emplace_back(i, weight);
                    any = any || holder_start[i + 1] > holder_start[i];
                  }
            }
          return any;
        };
        auto free_dofs_of = [&](const unsigned int batch,
                                const unsigned int lane) {
          mf.get_cell_iterator(batch, lane)->get_dof_indices(indices);
          for (unsigned int a = 0; a < dofs_per_cell; ++a)
            cell_dofs[a] = indices[lexicographic[a]];
          return resolve_cell();
        };
        // Add the element matrix of the cell last resolved to the blocks
        // that share its DoFs.
        auto scatter = [&](const FullMatrix<double> &matrix) {
          cell_blocks.clear();
          for (unsigned int a = 0; a < dofs_per_cell; ++a)
            for (const auto &[i, weight] : free[a])
              for (unsigned int h = holder_start[i]; h < holder_start[i + 1];
                   ++h)
                cell_blocks.push_back(holders[h]);
          std::sort(cell_blocks.begin(), cell_blocks.end());
          cell_blocks.erase(std::unique(cell_blocks.begin(), cell_blocks.end()),
                            cell_blocks.end());
          for (const unsigned int b : cell_blocks)
            {
              for (unsigned int k = block_start[b]; k < block_start[b + 1]; ++k)
                position[block_dofs[k]] = k - block_start[b];
              for (unsigned int a = 0; a < dofs_per_cell; ++a)
                {
                  in_block[a].clear();
                  for (const auto &[i, weight] : free[a])
                    if (position[i] >= 0)
                      in_block[a].emplace_back(position[i], weight);
                }
              FullMatrix<double> &block = blocks[b];
              for (unsigned int a = 0; a < dofs_per_cell; ++a)
                for (const auto &[p, wp] : in_block[a])
                  for (unsigned int c = 0; c < dofs_per_cell; ++c)
                    for (const auto &[q, wq] : in_block[c])
                      block(p, q) += wp * wq * matrix(a, c);
              for (unsigned int k = block_start[b]; k < block_start[b + 1]; ++k)
                position[block_dofs[k]] = -1;
            }
        };

        for (unsigned int batch = 0; batch < mf.n_cell_batches(); ++batch)
          {
            const unsigned int n_lanes =
              mf.n_active_entries_per_cell_batch(batch);
            bool any = false;
            for (unsigned int lane = 0; lane < n_lanes; ++lane)
              {
                touches[lane] = free_dofs_of(batch, lane);
                lane_free[lane].swap(free);
                any = any || touches[lane];
              }
            if (!any)
              continue;
            auto compute = [&](auto &evaluator) {
              evaluator.reinit(batch);
              for (unsigned int j = 0; j < dofs_per_cell; ++j)
                {
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    evaluator.begin_dof_values()[i] =
                      static_cast<double>(i == j);
                  op.cell_term(evaluator);
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    for (unsigned int lane = 0; lane < n_lanes; ++lane)
                      element[lane](i, j) =
                        evaluator.begin_dof_values()[i][lane];
                }
            };
            if (op.galerkin_level && op.uniform_viscosity[batch])
              compute(gauss);
            else
              compute(phi);
            for (unsigned int lane = 0; lane < n_lanes; ++lane)
              {
                if (!touches[lane])
                  continue;
                free.swap(lane_free[lane]);
                scatter(element[lane]);
              }
          }

        // The ghost cells, with FEValues on the same points: 2 eta e(u):e(v).
        const FEValuesExtractors::Vector     velocity(0);
        std::vector<SymmetricTensor<2, dim>> strain(dofs_per_cell);
        for (const GhostCell &ghost : ghosts)
          {
            ghost.cell->get_dof_indices(cell_dofs);
            if (!resolve_cell())
              continue;
            ghost_values->reinit(ghost.cell);
            FullMatrix<double> &matrix = element[0];
            matrix                     = 0.;
            for (unsigned int q = 0; q < ghost.eta.size(); ++q)
              {
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  strain[i] =
                    (*ghost_values)[velocity].symmetric_gradient(i, q);
                const double factor = 2. * ghost.eta[q] * ghost_values->JxW(q);
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  for (unsigned int j = 0; j < dofs_per_cell; ++j)
                    matrix(i, j) += factor * (strain[i] * strain[j]);
              }
            scatter(matrix);
          }
      });

      // Invert the blocks; the point part leaves their DoFs alone.
      block_inverse_start.assign(1, 0);
      for (unsigned int b = 0; b < n_blocks; ++b)
        {
          blocks[b].gauss_jordan();
          // Scaled by 1/sqrt(m_p m_q), m the number of blocks holding a
          // DoF: still symmetric, and the overlap no longer stretches the
          // top of the spectrum that Chebyshev must cover (at 3D level 4,
          // r = 1e4: 47 FGMRES per solve against 54 unscaled).
          {
            const unsigned int first = block_start[b];
            for (unsigned int p = 0; p < blocks[b].m(); ++p)
              for (unsigned int q = 0; q < blocks[b].n(); ++q)
                {
                  const unsigned int ip = block_dofs[first + p],
                                     iq = block_dofs[first + q];
                  blocks[b](p, q) /=
                    std::sqrt(double(holder_start[ip + 1] - holder_start[ip]) *
                              double(holder_start[iq + 1] - holder_start[iq]));
                }
          }
          // Exactly symmetric, as add_block_solves assumes.
          for (unsigned int p = 0; p < blocks[b].m(); ++p)
            for (unsigned int q = 0; q < p; ++q)
              blocks[b](p, q) = blocks[b](q, p) =
                0.5 * (blocks[b](p, q) + blocks[b](q, p));
          for (const double v : blocks[b])
            AssertThrow(std::isfinite(v),
                        ExcMessage("A cut-cell block of the multigrid "
                                   "smoother is singular."));
          // The upper triangle, row by row: the inverses are the largest
          // data a smoothing step streams (24 spheres: 100 MB), and
          // symmetry halves it.
          for (unsigned int p = 0; p < blocks[b].m(); ++p)
            for (unsigned int q = p; q < blocks[b].n(); ++q)
              inverses.push_back(blocks[b](p, q));
          block_inverse_start.push_back(inverses.size());
        }
      for (const unsigned int i : block_dofs)
        point_inverse.local_element(i) = 0.;
      holder_count.resize(n_owned);
      for (unsigned int i = 0; i < n_owned; ++i)
        holder_count[i] = holder_start[i + 1] - holder_start[i];
    }

    /// dst = P^{-1} src.
    void
    vmult(VectorType &dst, const VectorType &src) const
    {
      const unsigned int n_owned = point_inverse.locally_owned_size();
      for (unsigned int i = 0; i < n_owned; ++i)
        dst.local_element(i) =
          point_inverse.local_element(i) * src.local_element(i);
      add_block_solves(dst, src);
    }

    /// dst += the block solves alone (no point Jacobi part).
    void
    add_block_solves(VectorType &dst, const VectorType &src) const
    {
      std::vector<double> &x = scratch, &y = scratch_result;
      for (unsigned int b = 0; b + 1 < block_start.size(); ++b)
        {
          const unsigned int  first = block_start[b];
          const unsigned int  n     = block_start[b + 1] - first;
          const double *const inverse =
            inverses.data() + block_inverse_start[b];
          x.resize(n);
          for (unsigned int k = 0; k < n; ++k)
            x[k] = src.local_element(block_dofs[first + k]);
          // y = B x with B symmetric, from its upper triangle: row k
          // gives y_k its part on and right of the diagonal (a dot
          // product) and, by symmetry, adds x_k times the row to the y_p
          // with p > k (an axpy).
          y.assign(n, 0.);
          double *const       out   = y.data();
          const double *const in    = x.data();
          const double       *entry = inverse;
          for (unsigned int k = 0; k < n; ++k)
            {
              const double        xk  = in[k];
              const double *const row = entry - k;
              // Four partial sums: one would chain every addition to the
              // last (the compiler may not reorder them).
              double       s0 = row[k] * xk, s1 = 0., s2 = 0., s3 = 0.;
              unsigned int p = k + 1;
              for (; p + 3 < n; p += 4)
                {
                  s0 += row[p] * in[p];
                  s1 += row[p + 1] * in[p + 1];
                  s2 += row[p + 2] * in[p + 2];
                  s3 += row[p + 3] * in[p + 3];
                  out[p] += row[p] * xk;
                  out[p + 1] += row[p + 1] * xk;
                  out[p + 2] += row[p + 2] * xk;
                  out[p + 3] += row[p + 3] * xk;
                }
              for (; p < n; ++p)
                {
                  s0 += row[p] * in[p];
                  out[p] += row[p] * xk;
                }
              out[k] += (s0 + s1) + (s2 + s3);
              entry += n - k;
            }
          for (unsigned int p = 0; p < n; ++p)
            dst.local_element(block_dofs[first + p]) += y[p];
        }
    }

    /// Number of cut-cell blocks on this rank.
    unsigned int
    n_blocks() const
    {
      return block_start.size() - 1;
    }

    /// The owned local indices of block @p b (for checks).
    std::vector<unsigned int>
    block_indices(const unsigned int b) const
    {
      return {block_dofs.begin() + block_start[b],
              block_dofs.begin() + block_start[b + 1]};
    }

    /// The weighted inverse W_K (R_K A R_K^T)^{-1} W_K of block @p b.
    FullMatrix<double>
    block_inverse(const unsigned int b) const
    {
      const unsigned int n = block_start[b + 1] - block_start[b];
      FullMatrix<double> inverse(n, n);
      const double      *entry = inverses.data() + block_inverse_start[b];
      for (unsigned int p = 0; p < n; ++p)
        for (unsigned int q = p; q < n; ++q, ++entry)
          inverse(p, q) = inverse(q, p) = *entry;
      return inverse;
    }

    /// How many blocks hold each owned DoF (local index), 0 for none.
    const std::vector<unsigned int> &
    multiplicity() const
    {
      return holder_count;
    }

  private:
    /// D^{-1} on the DoFs of no block, zero on theirs.
    VectorType point_inverse;
    /// The owned local indices of block b: block_dofs[block_start[b]] to
    /// block_dofs[block_start[b + 1] - 1].
    std::vector<unsigned int> block_start{0};
    std::vector<unsigned int> block_dofs;
    /// The blocks' inverses, the upper triangle row by row, one after the
    /// other.
    std::vector<std::size_t>    block_inverse_start{0};
    std::vector<double>         inverses;
    mutable std::vector<double> scratch, scratch_result;
    std::vector<unsigned int>   holder_count;
  };
} // namespace Fidus

#endif
