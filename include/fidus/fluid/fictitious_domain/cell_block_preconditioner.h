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

      SetupData data(op, dofs, constraints, point_inverse);
      find_ghost_cells(data, ghost_viscosity);
      collect_blocks(data);
      const unsigned int n_blocks = block_start.size() - 1;
      find_holders(data);

      // The blocks are summed in their upper triangles, row by row, one
      // after the other (half the memory of full matrices: this is the
      // set-up's largest scratch, 0.9 GB on a rank of the 3D bulk box at
      // level 6), and their inverses are stored in the same layout.
      block_inverse_start.assign(1, 0);
      for (unsigned int b = 0; b < n_blocks; ++b)
        {
          const std::size_t n = block_start[b + 1] - block_start[b];
          block_inverse_start.push_back(block_inverse_start.back() +
                                        n * (n + 1) / 2);
        }
      std::vector<double> blocks(block_inverse_start.back(), 0.);

      // Sum the element matrices of every cell that touches a block.
      op.with_points([&](auto n, const unsigned int quadrature) {
        constexpr int  n_1d = decltype(n)::value;
        ElementScratch scratch(data, quadrature);
        add_cell_matrices<n_1d>(data, quadrature, scratch, blocks);
        add_ghost_cell_matrices(data, scratch, blocks);
      });

      invert_blocks(data, blocks);
      const unsigned int n_owned = data.n_owned;
      for (const unsigned int i : block_dofs)
        point_inverse.local_element(i) = 0.;
      holder_count.resize(n_owned);
      for (unsigned int i = 0; i < n_owned; ++i)
        holder_count[i] = data.holder_start[i + 1] - data.holder_start[i];
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
          const unsigned int first   = block_start[b];
          const unsigned int n       = block_start[b + 1] - first;
          const float *const inverse = inverses.data() + block_inverse_start[b];
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
          const float        *entry = inverse;
          for (unsigned int k = 0; k < n; ++k)
            {
              const double       xk  = in[k];
              const float *const row = entry - k;
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
      const float       *entry = inverses.data() + block_inverse_start[b];
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
    /// A ghost cell, with the viscosity at its points and whether it is cut.
    struct GhostCell
    {
      typename DoFHandler<dim>::active_cell_iterator cell;
      std::vector<double>                            eta;
      bool                                           cut;
    };

    /// What the stages of initialize() share: the level, the resolution of
    /// a DoF's constraints, which owned rows are complete here, the ghost
    /// cells and which blocks hold each owned DoF.
    struct SetupData
    {
      SetupData(const Operator                  &op,
                const DoFHandler<dim>           &dofs,
                const AffineConstraints<double> &constraints,
                const VectorType                &point_inverse)
        : op(op)
        , dofs(dofs)
        , constraints(constraints)
        , mf(*op.get_matrix_free())
        , partitioner(point_inverse.get_partitioner())
        , owned(dofs.locally_owned_dofs())
        , n_owned(point_inverse.locally_owned_size())
        , dofs_per_cell(dofs.get_fe().n_dofs_per_cell())
        , complete(n_owned, 1)
        , indices(dofs_per_cell)
      {}

      /// Sets resolved_one to the free DoFs and weights of @p g.
      void
      resolve(const types::global_dof_index g)
      {
        resolved_one.clear();
        if (constraints.is_constrained(g))
          {
            const auto *entries = constraints.get_constraint_entries(g);
            if (entries != nullptr)
              resolved_one.assign(entries->begin(), entries->end());
          }
        else
          resolved_one.emplace_back(g, 1.);
      }

      const Operator                                           &op;
      const DoFHandler<dim>                                    &dofs;
      const AffineConstraints<double>                          &constraints;
      const MatrixFree<dim, double>                            &mf;
      const std::shared_ptr<const Utilities::MPI::Partitioner> &partitioner;
      const IndexSet                                           &owned;
      const unsigned int                                        n_owned;
      const unsigned int                                        dofs_per_cell;

      // A DoF's free DoFs and weights after the constraints are resolved.
      std::vector<std::pair<types::global_dof_index, double>> resolved_one;
      // Whether the row of each owned DoF is complete on this rank.
      std::vector<unsigned char>           complete;
      std::vector<types::global_dof_index> indices;
      std::unique_ptr<FEValues<dim>>       ghost_values;
      std::vector<GhostCell>               ghosts;
      /// Which blocks hold each owned DoF (compressed rows).
      std::vector<unsigned int> holder_start, holders;
    };

    /// The work arrays of the summation of the element matrices into the
    /// blocks.
    struct ElementScratch
    {
      ElementScratch(const SetupData &data, const unsigned int quadrature)
        : lexicographic(data.mf.get_shape_info(0, quadrature, 0, 0, 0)
                          .lexicographic_numbering)
        , cell_dofs(data.dofs_per_cell)
        , free(data.dofs_per_cell)
        , element(VectorizedArray<double>::size(),
                  FullMatrix<double>(data.dofs_per_cell, data.dofs_per_cell))
        , touches(VectorizedArray<double>::size())
        , lane_free(VectorizedArray<double>::size(),
                    std::vector<std::vector<std::pair<unsigned int, double>>>(
                      data.dofs_per_cell))
        , in_block(data.dofs_per_cell)
        , position(data.n_owned, -1)
      {}

      const std::vector<unsigned int>     &lexicographic;
      std::vector<types::global_dof_index> cell_dofs;
      // Per cell DoF: its (owned local index, weight) after resolution.
      std::vector<std::vector<std::pair<unsigned int, double>>> free;
      std::vector<FullMatrix<double>>                           element;
      std::vector<unsigned char>                                touches;
      // Each lane's resolved DoFs, kept from the test for touching blocks
      // to the scatter.
      std::vector<std::vector<std::vector<std::pair<unsigned int, double>>>>
                                lane_free;
      std::vector<unsigned int> cell_blocks;
      // Per cell DoF, its (position in the block, weight).
      std::vector<std::vector<std::pair<unsigned int, double>>> in_block;
      std::vector<int>                                          position;
    };

    /// Collects the ghost cells with their viscosity (with
    /// @p ghost_viscosity), or marks the owned rows they touch incomplete
    /// (without it).
    void
    find_ghost_cells(SetupData &data, const GhostViscosity &ghost_viscosity)
    {
      const Operator                       &op       = data.op;
      const DoFHandler<dim>                &dofs     = data.dofs;
      std::vector<unsigned char>           &complete = data.complete;
      std::vector<types::global_dof_index> &indices  = data.indices;

      // The ghost cells: with their viscosity, their element matrices
      // complete the rows here; without it, the owned rows that they touch
      // are incomplete here.
      op.with_points([&](auto n, const unsigned int quadrature) {
        const QGauss<1>        gauss(decltype(n)::value);
        const QGaussLobatto<1> lobatto(decltype(n)::value);
        const Quadrature<dim>  points(quadrature == 0 ?
                                       static_cast<Quadrature<1>>(gauss) :
                                       static_cast<Quadrature<1>>(lobatto));
        data.ghost_values =
          std::make_unique<FEValues<dim>>(dofs.get_fe(),
                                          points,
                                          update_gradients | update_JxW_values |
                                            update_quadrature_points);
      });
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_ghost())
          {
            if (ghost_viscosity)
              {
                GhostCell ghost{cell, {}, false};
                data.ghost_values->reinit(cell);
                ghost_viscosity(cell, *data.ghost_values, ghost.eta);
                const auto [low, high] =
                  std::minmax_element(ghost.eta.begin(), ghost.eta.end());
                ghost.cut = !Operator::same_viscosity(*low, *high);
                data.ghosts.push_back(std::move(ghost));
                continue;
              }
            cell->get_dof_indices(indices);
            for (const auto g : indices)
              {
                data.resolve(g);
                for (const auto &[free, weight] : data.resolved_one)
                  if (data.owned.is_element(free))
                    complete[data.partitioner->global_to_local(free)] = 0;
              }
          }
    }

    /// Appends to block_dofs and block_start a block for each cut cell,
    /// owned or ghost, with its usable free DoFs.
    void
    collect_blocks(SetupData &data)
    {
      const Operator                       &op      = data.op;
      const MatrixFree<dim, double>        &mf      = *op.get_matrix_free();
      std::vector<types::global_dof_index> &indices = data.indices;

      // The blocks: the usable free DoFs of each cut cell. (Blocks on the
      // cells wholly in the solid as well were tried: the same count, 30 %
      // dearer set-up; doc/preconditioners.md.)
      const unsigned int        n_points = op.viscosity.size(1);
      std::vector<unsigned int> local;
      auto add_block = [&](const std::vector<types::global_dof_index> &cell) {
        local.clear();
        for (const auto g : cell)
          {
            data.resolve(g);
            for (const auto &[free, weight] : data.resolved_one)
              if (data.owned.is_element(free))
                {
                  const unsigned int i =
                    data.partitioner->global_to_local(free);
                  if (data.complete[i])
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
      for (const GhostCell &ghost : data.ghosts)
        if (ghost.cut)
          {
            ghost.cell->get_dof_indices(indices);
            add_block(indices);
          }
    }

    /// Sets data.holder_start and data.holders: which blocks hold each
    /// owned DoF.
    void
    find_holders(SetupData &data) const
    {
      const unsigned int         n_owned      = data.n_owned;
      const unsigned int         n_blocks     = block_start.size() - 1;
      std::vector<unsigned int> &holder_start = data.holder_start;
      std::vector<unsigned int> &holders      = data.holders;

      // Which blocks hold each owned DoF (compressed rows).
      holder_start.assign(n_owned + 1, 0);
      for (const unsigned int i : block_dofs)
        ++holder_start[i + 1];
      for (unsigned int i = 0; i < n_owned; ++i)
        holder_start[i + 1] += holder_start[i];
      holders.assign(block_dofs.size(), 0);
      {
        std::vector<unsigned int> next(holder_start.begin(),
                                       holder_start.end() - 1);
        for (unsigned int b = 0; b < n_blocks; ++b)
          for (unsigned int k = block_start[b]; k < block_start[b + 1]; ++k)
            holders[next[block_dofs[k]]++] = b;
      }
    }

    /// The free DoFs of a cell whose element matrix numbers its DoFs as
    /// s.cell_dofs, into s.free; whether any is in a block.
    bool
    resolve_cell(SetupData &data, ElementScratch &s) const
    {
      bool any = false;
      for (unsigned int a = 0; a < data.dofs_per_cell; ++a)
        {
          s.free[a].clear();
          data.resolve(s.cell_dofs[a]);
          for (const auto &[g, weight] : data.resolved_one)
            if (data.owned.is_element(g))
              {
                const unsigned int i = data.partitioner->global_to_local(g);
                s.free[a].emplace_back(i, weight);
                any = any || data.holder_start[i + 1] > data.holder_start[i];
              }
        }
      return any;
    }

    /// resolve_cell() for the cell of lane @p lane of batch @p batch.
    bool
    free_dofs_of(SetupData         &data,
                 ElementScratch    &s,
                 const unsigned int batch,
                 const unsigned int lane) const
    {
      data.mf.get_cell_iterator(batch, lane)->get_dof_indices(data.indices);
      for (unsigned int a = 0; a < data.dofs_per_cell; ++a)
        s.cell_dofs[a] = data.indices[s.lexicographic[a]];
      return resolve_cell(data, s);
    }

    /// Add the element matrix of the cell last resolved to the blocks that
    /// share its DoFs.
    void
    scatter(const SetupData          &data,
            ElementScratch           &s,
            const FullMatrix<double> &matrix,
            std::vector<double>      &blocks) const
    {
      const unsigned int dofs_per_cell = data.dofs_per_cell;
      const auto        &holder_start  = data.holder_start;
      s.cell_blocks.clear();
      for (unsigned int a = 0; a < dofs_per_cell; ++a)
        for (const auto &[i, weight] : s.free[a])
          for (unsigned int h = holder_start[i]; h < holder_start[i + 1]; ++h)
            s.cell_blocks.push_back(data.holders[h]);
      std::sort(s.cell_blocks.begin(), s.cell_blocks.end());
      s.cell_blocks.erase(std::unique(s.cell_blocks.begin(),
                                      s.cell_blocks.end()),
                          s.cell_blocks.end());
      for (const unsigned int b : s.cell_blocks)
        {
          for (unsigned int k = block_start[b]; k < block_start[b + 1]; ++k)
            s.position[block_dofs[k]] = k - block_start[b];
          for (unsigned int a = 0; a < dofs_per_cell; ++a)
            {
              s.in_block[a].clear();
              for (const auto &[i, weight] : s.free[a])
                if (s.position[i] >= 0)
                  s.in_block[a].emplace_back(s.position[i], weight);
            }
          // The upper triangle: (a, c) with p > q is the mirror of (c, a),
          // which the element matrix's symmetry makes the same entry.
          double *const      block = blocks.data() + block_inverse_start[b];
          const unsigned int n     = block_start[b + 1] - block_start[b];
          for (unsigned int a = 0; a < dofs_per_cell; ++a)
            for (const auto &[p, wp] : s.in_block[a])
              for (unsigned int c = 0; c < dofs_per_cell; ++c)
                for (const auto &[q, wq] : s.in_block[c])
                  if (p <= q)
                    block[packed_index(p, q, n)] += wp * wq * matrix(a, c);
          for (unsigned int k = block_start[b]; k < block_start[b + 1]; ++k)
            s.position[block_dofs[k]] = -1;
        }
    }

    /// Adds the element matrices of the locally owned cells that touch a
    /// block, from the operator's own cell integrand on @p n_1d points.
    template <int n_1d>
    void
    add_cell_matrices(SetupData           &data,
                      const unsigned int   quadrature,
                      ElementScratch      &s,
                      std::vector<double> &blocks) const
    {
      const Operator                &op            = data.op;
      const MatrixFree<dim, double> &mf            = data.mf;
      const unsigned int             dofs_per_cell = data.dofs_per_cell;

      typename Operator::template EvaluatorWith<n_1d> phi(mf, 0, quadrature);
      // On a Galerkin level a cell of uniform viscosity is exact with the
      // Gauss points too, at a fifth of the cost in 3D Q2 (most cells
      // next to a cut cell are such cells).
      typename Operator::Evaluator gauss(mf, 0, 0);

      for (unsigned int batch = 0; batch < mf.n_cell_batches(); ++batch)
        {
          const unsigned int n_lanes =
            mf.n_active_entries_per_cell_batch(batch);
          bool any = false;
          for (unsigned int lane = 0; lane < n_lanes; ++lane)
            {
              s.touches[lane] = free_dofs_of(data, s, batch, lane);
              s.lane_free[lane].swap(s.free);
              any = any || s.touches[lane];
            }
          if (!any)
            continue;
          auto compute = [&](auto &evaluator) {
            evaluator.reinit(batch);
            for (unsigned int j = 0; j < dofs_per_cell; ++j)
              {
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  evaluator.begin_dof_values()[i] = static_cast<double>(i == j);
                op.cell_term(evaluator);
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  for (unsigned int lane = 0; lane < n_lanes; ++lane)
                    s.element[lane](i, j) =
                      evaluator.begin_dof_values()[i][lane];
              }
          };
          if (op.galerkin_level && op.uniform_viscosity[batch])
            compute(gauss);
          else
            compute(phi);
          for (unsigned int lane = 0; lane < n_lanes; ++lane)
            {
              if (!s.touches[lane])
                continue;
              s.free.swap(s.lane_free[lane]);
              scatter(data, s, s.element[lane], blocks);
            }
        }
    }

    /// Adds the element matrices of the ghost cells that touch a block.
    void
    add_ghost_cell_matrices(SetupData           &data,
                            ElementScratch      &s,
                            std::vector<double> &blocks) const
    {
      const unsigned int dofs_per_cell = data.dofs_per_cell;
      FEValues<dim>     &ghost_values  = *data.ghost_values;

      // The ghost cells, with FEValues on the same points: 2 eta e(u):e(v).
      const FEValuesExtractors::Vector     velocity(0);
      std::vector<SymmetricTensor<2, dim>> strain(dofs_per_cell);
      for (const GhostCell &ghost : data.ghosts)
        {
          ghost.cell->get_dof_indices(s.cell_dofs);
          if (!resolve_cell(data, s))
            continue;
          ghost_values.reinit(ghost.cell);
          FullMatrix<double> &matrix = s.element[0];
          matrix                     = 0.;
          for (unsigned int q = 0; q < ghost.eta.size(); ++q)
            {
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                strain[i] = ghost_values[velocity].symmetric_gradient(i, q);
              const double factor = 2. * ghost.eta[q] * ghost_values.JxW(q);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                for (unsigned int j = 0; j < dofs_per_cell; ++j)
                  matrix(i, j) += factor * (strain[i] * strain[j]);
            }
          scatter(data, s, matrix, blocks);
        }
    }

    /// Index of entry (p, q), p <= q, of an n x n upper triangle stored
    /// row by row.
    static std::size_t
    packed_index(const std::size_t p, const std::size_t q, const std::size_t n)
    {
      return p * (2 * n - p + 1) / 2 + (q - p);
    }

    /// Inverts the blocks (upper triangles in @p sums), scales the
    /// inverses and stores their upper triangles in inverses.
    void
    invert_blocks(const SetupData &data, const std::vector<double> &sums)
    {
      const unsigned int n_blocks     = block_start.size() - 1;
      const auto        &holder_start = data.holder_start;

      // In single precision: a smoother's block solve does not need more,
      // and the inverses are the largest data a smoothing step streams
      // (symmetry halves them, single precision halves them again).
      inverses.resize(sums.size());
      for (unsigned int b = 0; b < n_blocks; ++b)
        {
          const unsigned int first = block_start[b];
          const unsigned int n     = block_start[b + 1] - first;
          const double      *sum   = sums.data() + block_inverse_start[b];
          FullMatrix<double> block(n, n);
          for (unsigned int p = 0; p < n; ++p)
            for (unsigned int q = p; q < n; ++q)
              block(p, q) = block(q, p) = sum[packed_index(p, q, n)];
          block.gauss_jordan();
          // Scaled by 1/sqrt(m_p m_q), m the number of blocks holding a
          // DoF: still symmetric, and the overlap no longer stretches the
          // top of the spectrum that Chebyshev must cover (at 3D level 4,
          // r = 1e4: 47 FGMRES per solve against 54 unscaled). The upper
          // triangle of the mean of the inverse and its transpose, exactly
          // symmetric as add_block_solves assumes.
          float *const inverse = inverses.data() + block_inverse_start[b];
          for (unsigned int p = 0; p < n; ++p)
            for (unsigned int q = p; q < n; ++q)
              {
                const unsigned int ip = block_dofs[first + p],
                                   iq = block_dofs[first + q];
                const double value =
                  0.5 * (block(p, q) + block(q, p)) /
                  std::sqrt(double(holder_start[ip + 1] - holder_start[ip]) *
                            double(holder_start[iq + 1] - holder_start[iq]));
                AssertThrow(std::isfinite(value),
                            ExcMessage("A cut-cell block of the multigrid "
                                       "smoother is singular."));
                inverse[packed_index(p, q, n)] = static_cast<float>(value);
              }
        }
    }
    /// D^{-1} on the DoFs of no block, zero on theirs.
    VectorType point_inverse;
    /// The owned local indices of block b: block_dofs[block_start[b]] to
    /// block_dofs[block_start[b + 1] - 1].
    std::vector<unsigned int> block_start{0};
    std::vector<unsigned int> block_dofs;
    /// The blocks' inverses, the upper triangle row by row, one after the
    /// other.
    std::vector<std::size_t>    block_inverse_start{0};
    std::vector<float>          inverses;
    mutable std::vector<double> scratch, scratch_result;
    std::vector<unsigned int>   holder_count;
  };
} // namespace Fidus

#endif
