#include <algorithm>
#include <cmath>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/multigrid/mg_coarse.h>
#include <deal.II/multigrid/mg_constrained_dofs.h>
#include <deal.II/multigrid/mg_matrix.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/mg_transfer_global_coarsening.h>
#include <deal.II/multigrid/multigrid.h>
#include <deal.II/numerics/vector_tools.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/fictitious_domain/cell_block_preconditioner.h>
#include <fidus/fluid/fictitious_domain/velocity_multigrid.h>
#include <fidus/fluid/fictitious_domain/velocity_operator.h>
#include <limits>

namespace Fidus
{
  /// The degree-independent face of the hierarchy (the degree is a template
  /// argument of the matrix-free kernels).
  template <int dim>
  class VelocityMultigrid<dim>::Implementation
  {
  public:
    virtual ~Implementation() = default;
    virtual void
    setup(const DoFHandler<dim>              &system,
          const std::vector<unsigned int>    &periodic_directions,
          const std::set<types::boundary_id> &dirichlet_ids) = 0;
    virtual void
    update(const ViscosityFunction              &viscosity,
           const TrilinosWrappers::SparseMatrix *velocity_block,
           const AffineConstraints<double>      &system_constraints) = 0;
    virtual void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const = 0;
    virtual void
    apply_velocity_block(TrilinosWrappers::MPI::Vector       &dst,
                         const TrilinosWrappers::MPI::Vector &src) const = 0;
    virtual void
    subtract_constraint_load(TrilinosWrappers::MPI::Vector       &rhs,
                             const TrilinosWrappers::MPI::Vector &g) const = 0;
    virtual double
    galerkin_defect() const = 0;

    Info info;
  };



  namespace
  {
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    template <int dim, int degree>
    class Hierarchy : public VelocityMultigrid<dim>::Implementation
    {
    public:
      using Settings  = typename VelocityMultigrid<dim>::Settings;
      using Averaging = typename VelocityMultigrid<dim>::Averaging;
      using ViscosityFunction =
        typename VelocityMultigrid<dim>::ViscosityFunction;
      using Operator               = VelocityOperator<dim, degree>;
      using SmootherPreconditioner = CellBlockPreconditioner<dim, degree>;
      using Smoother =
        PreconditionChebyshev<Operator, VectorType, SmootherPreconditioner>;

      Hierarchy(const parallel::distributed::Triangulation<dim> &tria,
                const Settings                                  &settings)
        : triangulation(tria)
        , settings(settings)
        , fe(FE_Q<dim>(degree), dim)
        , moment_fe(2 * degree)
      {}

      void
      setup(const DoFHandler<dim>              &system,
            const std::vector<unsigned int>    &periodic_directions,
            const std::set<types::boundary_id> &dirichlet_ids) override
      {
        Timer timer;
        clear();
        level_meshes =
          MGTransferGlobalCoarseningTools::create_geometric_coarsening_sequence(
            triangulation);
        const unsigned int n_levels = level_meshes.size();
        dof_handlers.resize(0, n_levels - 1);
        constraints.resize(0, n_levels - 1);
        operators.resize(0, n_levels - 1);
        transfers.resize(0, n_levels - 1);
        for (unsigned int l = 0; l < n_levels; ++l)
          {
            dof_handlers[l].reinit(*level_meshes[l]);
            dof_handlers[l].distribute_dofs(fe);
            // As the system: numbered along the forest, so that the finest
            // level lines up with the system's velocity block.
            DoFRenumbering::hierarchical(dof_handlers[l]);

            IndexSet relevant;
            DoFTools::extract_locally_relevant_dofs(dof_handlers[l], relevant);
            constraints[l].reinit(relevant);
            DoFTools::make_hanging_node_constraints(dof_handlers[l],
                                                    constraints[l]);
            for (const unsigned int d : periodic_directions)
              DoFTools::make_periodicity_constraints(dof_handlers[l],
                                                     2 * d,
                                                     2 * d + 1,
                                                     d,
                                                     constraints[l]);
            for (const types::boundary_id id : dirichlet_ids)
              VectorTools::interpolate_boundary_values(
                mapping,
                dof_handlers[l],
                id,
                Functions::ZeroFunction<dim>(dim),
                constraints[l]);
            constraints[l].close();

            typename MatrixFree<dim, double>::AdditionalData data;
            data.tasks_parallel_scheme =
              MatrixFree<dim, double>::AdditionalData::none;
            data.mapping_update_flags =
              update_gradients | update_JxW_values | update_quadrature_points;
            auto matrix_free = std::make_shared<MatrixFree<dim, double>>();
            matrix_free->reinit(
              mapping,
              std::vector<const DoFHandler<dim> *>{&dof_handlers[l]},
              std::vector<const AffineConstraints<double> *>{&constraints[l]},
              level_quadratures(l, n_levels),
              data);
            operators[l]                 = std::make_unique<Operator>();
            operators[l]->galerkin_level = galerkin_level(l, n_levels);
            operators[l]->initialize(matrix_free);
          }
        for (unsigned int l = 0; l + 1 < n_levels; ++l)
          transfers[l + 1].reinit(dof_handlers[l + 1],
                                  dof_handlers[l],
                                  constraints[l + 1],
                                  constraints[l]);
        if (galerkin())
          {
            // The moments' space on every level and its transfers.
            moment_dofs.resize(0, n_levels - 1);
            moment_transfers.resize(0, n_levels - 1);
            moments.resize(0, n_levels - 1);
            for (unsigned int l = 0; l < n_levels; ++l)
              {
                moment_dofs[l].reinit(*level_meshes[l]);
                moment_dofs[l].distribute_dofs(moment_fe);
                moments[l].reinit(moment_dofs[l].locally_owned_dofs(),
                                  moment_dofs[l].get_communicator());
              }
            for (unsigned int l = 0; l + 1 < n_levels; ++l)
              moment_transfers[l + 1].reinit(moment_dofs[l + 1],
                                             moment_dofs[l]);
          }
        transfer =
          std::make_unique<MGTransferGlobalCoarsening<dim, VectorType>>(
            transfers,
            [this](const unsigned int l, VectorType &v) {
              operators[l]->initialize_dof_vector(v);
            });

        map_system_velocities(system);
        this->info.n_levels      = n_levels;
        this->info.coarse_dofs   = dof_handlers[0].n_dofs();
        this->info.setup_seconds = timer.wall_time();
      }

      void
      update(const ViscosityFunction              &viscosity,
             const TrilinosWrappers::SparseMatrix *velocity_block,
             const AffineConstraints<double>      &system_constraints) override
      {
        Timer              timer;
        const unsigned int max_level = operators.max_level();
        MGLevelObject<typename Smoother::AdditionalData> smoother_data(
          0,
          max_level);
        Timer part;
        this->info.blocks_seconds = this->info.diagonal_seconds = 0.;
        if (galerkin())
          compute_moments(viscosity);
        this->info.viscosity_seconds = part.wall_time();
        this->info.smoother_blocks   = 0;
        for (unsigned int l = 0; l <= max_level; ++l)
          {
            part.restart();
            if (galerkin() && l < max_level)
              fill_galerkin_viscosity(l);
            else
              fill_viscosity(l, viscosity);
            this->info.viscosity_seconds += part.wall_time();
            part.restart();
            operators[l]->compute_diagonal();
            this->info.diagonal_seconds += part.wall_time();
            part.restart();
            // Level 0 is solved, not smoothed: no blocks there.
            auto preconditioner = std::make_shared<SmootherPreconditioner>();
            preconditioner->initialize(*operators[l],
                                       dof_handlers[l],
                                       constraints[l],
                                       l > 0 ? settings.smoother_blocks :
                                               SmootherBlocks::none,
                                       ghost_viscosity(l, viscosity));
            this->info.blocks_seconds += part.wall_time();
            this->info.smoother_blocks += preconditioner->n_blocks();
            smoother_data[l].preconditioner = preconditioner;
            smoother_data[l].degree         = settings.smoother_degree;
            // Blocks shorten the spectrum's top: a narrower range then
            // smooths more of it (3D level 4, r = 1e4: 44 FGMRES per solve
            // with 8 against 47 with 15).
            smoother_data[l].smoothing_range =
              settings.smoother_blocks == SmootherBlocks::none ?
                settings.smoothing_range :
                settings.smoothing_range_with_blocks;
            smoother_data[l].eig_cg_n_iterations = settings.eigenvalue_cg_steps;
          }
        smoother = std::make_unique<
          MGSmootherPrecondition<Operator, Smoother, VectorType>>();
        smoother->initialize(operators, smoother_data);

        // Coarse level: assembled from the matrix-free operator, CG with AMG.
        part.restart();
        coarse_matrix.clear();
        {
          const DoFHandler<dim>            &dof0 = dof_handlers[0];
          TrilinosWrappers::SparsityPattern sp(dof0.locally_owned_dofs(),
                                               dof0.get_communicator());
          DoFTools::make_sparsity_pattern(dof0, sp, constraints[0]);
          sp.compress();
          coarse_matrix.reinit(sp);
          operators[0]->compute_matrix(constraints[0], coarse_matrix);
        }
        TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
        amg_data.elliptic              = true;
        amg_data.higher_order_elements = true;
        amg_data.smoother_sweeps       = 2;
        DoFTools::extract_constant_modes(dof_handlers[0],
                                         ComponentMask(dim, true),
                                         amg_data.constant_modes);
        coarse_amg.initialize(coarse_matrix, amg_data);
        coarse_control =
          std::make_unique<ReductionControl>(1000,
                                             1e-14,
                                             settings.coarse_tolerance,
                                             false,
                                             false);
        coarse_cg = std::make_unique<SolverCG<VectorType>>(*coarse_control);
        this->info.coarse_seconds = part.wall_time();
        coarse                    = std::make_unique<
          MGCoarseGridIterativeSolver<VectorType,
                                      SolverCG<VectorType>,
                                      Operator,
                                      TrilinosWrappers::PreconditionAMG>>(
          *coarse_cg,
          *operators[0],
          coarse_amg);

        level_matrices = std::make_unique<mg::Matrix<VectorType>>(operators);
        multigrid = std::make_unique<Multigrid<VectorType>>(*level_matrices,
                                                            *coarse,
                                                            *transfer,
                                                            *smoother,
                                                            *smoother);
        preconditioner = std::make_unique<
          PreconditionMG<dim,
                         VectorType,
                         MGTransferGlobalCoarsening<dim, VectorType>>>(
          dof_handlers[max_level],
          *multigrid,
          *transfer);

        // Rows with a constraint in the system (Dirichlet, hanging, periodic)
        // hold only their diagonal there: invert it exactly instead. The
        // system numbers velocities first, so the rank's velocity DoFs are
        // the first to_level.size() of its owned system DoFs.
        constrained_rows.clear();
        const types::global_dof_index first =
          system_owned_dofs.n_elements() > 0 ? *system_owned_dofs.begin() : 0;
        for (unsigned int i = 0; i < to_level.size(); ++i)
          if (system_constraints.is_constrained(first + i))
            constrained_rows.emplace_back(i,
                                          velocity_block ?
                                            1. / velocity_block->diag_element(
                                                   first + i) :
                                            1.);

        operators[max_level]->initialize_dof_vector(mg_src);
        operators[max_level]->initialize_dof_vector(mg_dst);
        this->info.update_seconds = timer.wall_time();
      }

      void
      vmult(TrilinosWrappers::MPI::Vector       &dst,
            const TrilinosWrappers::MPI::Vector &src) const override
      {
        const double *s = src.begin();
        for (unsigned int i = 0; i < to_level.size(); ++i)
          mg_src.local_element(to_level[i]) = s[i];
        for (const auto &[i, inverse] : constrained_rows)
          mg_src.local_element(to_level[i]) = 0.;
        preconditioner->vmult(mg_dst, mg_src);
        double *d = dst.begin();
        for (unsigned int i = 0; i < to_level.size(); ++i)
          d[i] = mg_dst.local_element(to_level[i]);
        for (const auto &[i, inverse] : constrained_rows)
          d[i] = inverse * s[i];
      }

      void
      apply_velocity_block(
        TrilinosWrappers::MPI::Vector       &dst,
        const TrilinosWrappers::MPI::Vector &src) const override
      {
        const double *s = src.begin();
        for (unsigned int i = 0; i < to_level.size(); ++i)
          mg_src.local_element(to_level[i]) = s[i];
        for (const auto &[i, inverse] : constrained_rows)
          mg_src.local_element(to_level[i]) = 0.;
        operators[operators.max_level()]->vmult(mg_dst, mg_src);
        double *d = dst.begin();
        for (unsigned int i = 0; i < to_level.size(); ++i)
          d[i] = mg_dst.local_element(to_level[i]);
        for (const auto &[i, inverse] : constrained_rows)
          d[i] = s[i] / inverse;
      }

      void
      subtract_constraint_load(
        TrilinosWrappers::MPI::Vector       &rhs,
        const TrilinosWrappers::MPI::Vector &g) const override
      {
        // g is read as it stands (its constrained entries are the point),
        // so every entry, owned or ghost, must be there: the ghosts come
        // from the level's partitioner.
        const double *gl = g.begin();
        for (unsigned int i = 0; i < to_level.size(); ++i)
          mg_src.local_element(to_level[i]) = gl[i];
        mg_src.update_ghost_values();
        operators[operators.max_level()]->compute_load(mg_dst, mg_src);
        mg_src.zero_out_ghost_values();
        double *r = rhs.begin();
        for (unsigned int i = 0; i < to_level.size(); ++i)
          r[i] -= mg_dst.local_element(to_level[i]);
      }

      double
      galerkin_defect() const override
      {
        double worst = 0.;
        for (unsigned int l = 0; l < operators.max_level(); ++l)
          {
            VectorType v, w, Av, Aw;
            operators[l]->initialize_dof_vector(v);
            operators[l]->initialize_dof_vector(Av);
            operators[l + 1]->initialize_dof_vector(w);
            operators[l + 1]->initialize_dof_vector(Aw);
            // The same pseudo-random vector on any number of ranks.
            const IndexSet &owned = dof_handlers[l].locally_owned_dofs();
            for (const auto i : owned)
              v[i] = constraints[l].is_constrained(i) ?
                       0. :
                       std::sin(1.3 * i + 0.7) + 0.5 * std::cos(0.37 * i);
            transfers[l + 1].prolongate_and_add(w, v);
            operators[l]->vmult(Av, v);
            operators[l + 1]->vmult(Aw, w);
            const double coarse = v * Av, fine = w * Aw;
            worst = std::max(worst, std::abs(coarse - fine) / fine);
          }
        return worst;
      }

    private:
      bool
      galerkin() const
      {
        return settings.averaging == Averaging::galerkin;
      }

      /// Whether level @p l of @p n_levels is a Galerkin level.
      bool
      galerkin_level(const unsigned int l, const unsigned int n_levels) const
      {
        return galerkin() && l + 1 < n_levels;
      }

      /// The quadratures of level @p l of @p n_levels: Gauss as the
      /// assembly, and on a Galerkin level also the support points of
      /// FE_DGQ(2 degree) (VelocityOperator).
      std::vector<Quadrature<1>>
      level_quadratures(const unsigned int l, const unsigned int n_levels) const
      {
        std::vector<Quadrature<1>> q{QGauss<1>(Operator::gauss_points)};
        if (galerkin_level(l, n_levels))
          q.push_back(QGaussLobatto<1>(Operator::galerkin_points));
        return q;
      }

      /// The moments L(l_Q) = sum over the finest Gauss points of eta JxW
      /// l_Q, on the finest level, then restricted to every level below.
      void
      compute_moments(const ViscosityFunction &viscosity)
      {
        const unsigned int                   top = operators.max_level();
        const QGauss<dim>                    quadrature(Operator::gauss_points);
        FEValues<dim>                        fe_values(mapping,
                                moment_fe,
                                quadrature,
                                update_values | update_quadrature_points |
                                  update_JxW_values);
        std::vector<types::global_dof_index> dofs(moment_fe.n_dofs_per_cell());
        std::vector<double>                  eta(quadrature.size());
        moments[top] = 0.;
        for (const auto &cell : moment_dofs[top].active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              viscosity(cell, true, fe_values.get_quadrature_points(), eta);
              cell->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                {
                  double sum = 0.;
                  for (unsigned int q = 0; q < quadrature.size(); ++q)
                    sum +=
                      eta[q] * fe_values.JxW(q) * fe_values.shape_value(i, q);
                  moments[top][dofs[i]] = sum;
                }
            }
        for (unsigned int l = top; l > 0; --l)
          {
            moments[l - 1] = 0.;
            moment_transfers[l].restrict_and_add(moments[l - 1], moments[l]);
          }
      }

      /// The viscosity of level @p l on a ghost cell, as fill_viscosity()
      /// and fill_galerkin_viscosity() would put it in the operator's table
      /// (for the smoother's blocks at the partition boundary).
      typename SmootherPreconditioner::GhostViscosity
      ghost_viscosity(const unsigned int l, const ViscosityFunction &viscosity)
      {
        if (Utilities::MPI::n_mpi_processes(
              dof_handlers[l].get_communicator()) == 1)
          return {};
        const bool finest = l == operators.max_level();
        if (galerkin() && !finest)
          {
            // The moments of the ghost cells.
            IndexSet relevant;
            DoFTools::extract_locally_relevant_dofs(moment_dofs[l], relevant);
            auto ghosted =
              std::make_shared<VectorType>(moment_dofs[l].locally_owned_dofs(),
                                           relevant,
                                           moment_dofs[l].get_communicator());
            ghosted->copy_locally_owned_data_from(moments[l]);
            ghosted->update_ghost_values();
            return [this, l, ghosted](
                     const typename DoFHandler<dim>::active_cell_iterator &cell,
                     const FEValues<dim> &fe_values,
                     std::vector<double> &eta) {
              typename DoFHandler<dim>::active_cell_iterator moment_cell(
                &cell->get_triangulation(),
                cell->level(),
                cell->index(),
                &moment_dofs[l]);
              std::vector<types::global_dof_index> dofs(
                moment_fe.n_dofs_per_cell());
              moment_cell->get_dof_indices(dofs);
              eta.resize(fe_values.n_quadrature_points);
              for (unsigned int q = 0; q < eta.size(); ++q)
                eta[q] = (*ghosted)[dofs[q]] / fe_values.JxW(q);
              const auto [low, high] =
                std::minmax_element(eta.begin(), eta.end());
              if (Operator::same_viscosity(*low, *high))
                std::fill(eta.begin(), eta.end(), eta[0]);
            };
          }
        return [this, finest, &viscosity](
                 const typename DoFHandler<dim>::active_cell_iterator &cell,
                 const FEValues<dim> &fe_values,
                 std::vector<double> &eta) {
          eta.resize(fe_values.n_quadrature_points);
          viscosity(cell, finest, fe_values.get_quadrature_points(), eta);
          if (!finest)
            average(eta);
        };
      }

      /// Viscosity table of a Galerkin level: eta_Q = L(l_Q) / JxW_Q (the
      /// FE_DGQ DoFs and the points are both lexicographic), and which cell
      /// batches have a uniform viscosity.
      void
      fill_galerkin_viscosity(const unsigned int l)
      {
        const MatrixFree<dim, double> &mf = *operators[l]->get_matrix_free();
        typename Operator::template EvaluatorWith<Operator::galerkin_points>
              phi(mf, 0, 1);
        auto &table   = operators[l]->viscosity;
        auto &uniform = operators[l]->uniform_viscosity;
        uniform.assign(mf.n_cell_batches(), 1);
        std::vector<types::global_dof_index> dofs(moment_fe.n_dofs_per_cell());
        AssertDimension(dofs.size(), phi.n_q_points);
        table.reinit(mf.n_cell_batches(), phi.n_q_points);
        for (unsigned int batch = 0; batch < mf.n_cell_batches(); ++batch)
          {
            phi.reinit(batch);
            for (unsigned int q = 0; q < phi.n_q_points; ++q)
              table(batch, q) = 0.;
            for (unsigned int lane = 0;
                 lane < mf.n_active_entries_per_cell_batch(batch);
                 ++lane)
              {
                const auto cell = mf.get_cell_iterator(batch, lane);
                typename DoFHandler<dim>::active_cell_iterator moment_cell(
                  &cell->get_triangulation(),
                  cell->level(),
                  cell->index(),
                  &moment_dofs[l]);
                moment_cell->get_dof_indices(dofs);
                double low = std::numeric_limits<double>::max(), high = 0.;
                for (unsigned int q = 0; q < phi.n_q_points; ++q)
                  {
                    const double eta = moments[l][dofs[q]] / phi.JxW(q)[lane];
                    table(batch, q)[lane] = eta;
                    low                   = std::min(low, eta);
                    high                  = std::max(high, eta);
                  }
                // A cell wholly in the fluid or wholly in the solid: its
                // values agree to round-off. Make them equal, so that the
                // Gauss and the Gauss-Lobatto paths give the same operator.
                if (Operator::same_viscosity(low, high))
                  for (unsigned int q = 0; q < phi.n_q_points; ++q)
                    table(batch, q)[lane] = table(batch, 0)[lane];
                else
                  uniform[batch] = 0;
              }
          }
      }

      void
      clear()
      {
        preconditioner.reset();
        multigrid.reset();
        level_matrices.reset();
        coarse.reset();
        smoother.reset();
        transfer.reset();
        transfers.resize(0, 0);
        moment_transfers.resize(0, 0);
        moments.resize(0, 0);
        moment_dofs.resize(0, 0);
        operators.resize(0, 0);
        constraints.resize(0, 0);
        dof_handlers.resize(0, 0);
        level_meshes.clear();
      }

      /// to_level[i]: the finest-level local index of the i-th locally owned
      /// velocity DoF of the system.
      void
      map_system_velocities(const DoFHandler<dim> &system)
      {
        const DoFHandler<dim> &fine  = dof_handlers[dof_handlers.max_level()];
        const IndexSet        &owned = fine.locally_owned_dofs();
        const types::global_dof_index n_owned = owned.n_elements();
        // The system numbers velocities first: its velocity DoFs on this
        // rank are a contiguous range of the same length.
        const IndexSet system_owned = system.locally_owned_dofs();
        system_owned_dofs           = system_owned;
        to_level.assign(n_owned, numbers::invalid_unsigned_int);
        const FiniteElement<dim>            &system_fe = system.get_fe();
        std::vector<types::global_dof_index> system_dofs(
          system_fe.n_dofs_per_cell()),
          level_dofs(fe.n_dofs_per_cell());
        for (const auto &cell : system.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(system_dofs);
              typename DoFHandler<dim>::active_cell_iterator level_cell(
                &fine.get_triangulation(),
                cell->level(),
                cell->index(),
                &fine);
              level_cell->get_dof_indices(level_dofs);
              for (unsigned int k = 0; k < system_dofs.size(); ++k)
                {
                  const auto [c, i] = system_fe.system_to_component_index(k);
                  if (c >= dim || !system_owned.is_element(system_dofs[k]))
                    continue;
                  const types::global_dof_index local =
                    system_owned.index_within_set(system_dofs[k]);
                  const types::global_dof_index g =
                    level_dofs[fe.component_to_system_index(c, i)];
                  if (!(local < n_owned && owned.is_element(g)))
                    throw RunError("the multigrid velocity DoFs are not "
                                   "owned as the system's (internal "
                                   "error)");
                  to_level[local] = owned.index_within_set(g);
                }
            }
        for (const unsigned int j : to_level)
          if (!(j != numbers::invalid_unsigned_int))
            throw RunError("a velocity DoF of the system has no "
                           "multigrid counterpart (internal error)");
      }

      /// Viscosity table of level @p l: point values, averaged per cell
      /// below the finest level.
      void
      fill_viscosity(const unsigned int l, const ViscosityFunction &viscosity)
      {
        const MatrixFree<dim, double> &mf = *operators[l]->get_matrix_free();
        const bool                     finest    = l == operators.max_level();
        const unsigned int             n_batches = mf.n_cell_batches();
        typename Operator::Evaluator   phi(mf);
        auto                          &table = operators[l]->viscosity;
        table.reinit(n_batches, phi.n_q_points);
        std::vector<Point<dim>> points(phi.n_q_points);
        std::vector<double>     eta(phi.n_q_points);
        for (unsigned int batch = 0; batch < n_batches; ++batch)
          {
            phi.reinit(batch);
            const unsigned int n_lanes =
              mf.n_active_entries_per_cell_batch(batch);
            for (unsigned int q = 0; q < phi.n_q_points; ++q)
              table(batch, q) = 0.;
            for (unsigned int lane = 0; lane < n_lanes; ++lane)
              {
                for (unsigned int q = 0; q < phi.n_q_points; ++q)
                  for (unsigned int d = 0; d < dim; ++d)
                    points[q][d] = phi.quadrature_point(q)[d][lane];
                viscosity(mf.get_cell_iterator(batch, lane),
                          finest,
                          points,
                          eta);
                if (!finest)
                  average(eta);
                for (unsigned int q = 0; q < phi.n_q_points; ++q)
                  table(batch, q)[lane] = eta[q];
              }
          }
      }

      void
      average(std::vector<double> &eta) const
      {
        if (settings.averaging == Averaging::none)
          return;
        double mean = 0.;
        for (const double e : eta)
          switch (settings.averaging)
            {
              case Averaging::arithmetic:
                mean += e;
                break;
              case Averaging::harmonic:
                mean += 1. / e;
                break;
              default:
                mean += std::log(e);
            }
        mean /= eta.size();
        if (settings.averaging == Averaging::harmonic)
          mean = 1. / mean;
        else if (settings.averaging == Averaging::geometric)
          mean = std::exp(mean);
        std::fill(eta.begin(), eta.end(), mean);
      }

      const parallel::distributed::Triangulation<dim> &triangulation;
      const Settings                                   settings;
      const FESystem<dim>                              fe;
      /// The space of the Galerkin levels' viscosity moments.
      const FE_DGQ<dim>    moment_fe;
      const MappingQ1<dim> mapping;

      std::vector<std::shared_ptr<const Triangulation<dim>>>       level_meshes;
      MGLevelObject<DoFHandler<dim>>                               dof_handlers;
      MGLevelObject<AffineConstraints<double>>                     constraints;
      MGLevelObject<std::unique_ptr<Operator>>                     operators;
      MGLevelObject<MGTwoLevelTransfer<dim, VectorType>>           transfers;
      std::unique_ptr<MGTransferGlobalCoarsening<dim, VectorType>> transfer;
      MGLevelObject<DoFHandler<dim>>                               moment_dofs;
      MGLevelObject<MGTwoLevelTransfer<dim, VectorType>> moment_transfers;
      MGLevelObject<VectorType>                          moments;

      std::unique_ptr<MGSmootherPrecondition<Operator, Smoother, VectorType>>
                                                    smoother;
      TrilinosWrappers::SparseMatrix                coarse_matrix;
      TrilinosWrappers::PreconditionAMG             coarse_amg;
      std::unique_ptr<ReductionControl>             coarse_control;
      std::unique_ptr<SolverCG<VectorType>>         coarse_cg;
      std::unique_ptr<MGCoarseGridBase<VectorType>> coarse;
      std::unique_ptr<mg::Matrix<VectorType>>       level_matrices;
      std::unique_ptr<Multigrid<VectorType>>        multigrid;
      std::unique_ptr<
        PreconditionMG<dim,
                       VectorType,
                       MGTransferGlobalCoarsening<dim, VectorType>>>
        preconditioner;

      std::vector<unsigned int> to_level;
      /// The system's locally owned DoFs (velocities first).
      IndexSet                                     system_owned_dofs;
      std::vector<std::pair<unsigned int, double>> constrained_rows;
      mutable VectorType                           mg_src, mg_dst;
    };
  } // namespace



  template <int dim>
  typename VelocityMultigrid<dim>::Averaging
  VelocityMultigrid<dim>::parse_averaging(const std::string &name)
  {
    if (name == "none")
      return Averaging::none;
    if (name == "arithmetic")
      return Averaging::arithmetic;
    if (name == "geometric")
      return Averaging::geometric;
    if (name == "galerkin")
      return Averaging::galerkin;
    if (!(name == "harmonic"))
      throw InputError("Fluid/Linear solver/Multigrid viscosity averaging "
                       "= '" +
                       name +
                       "': allowed are none, arithmetic, harmonic, "
                       "geometric, galerkin");
    return Averaging::harmonic;
  }



  template <int dim>
  VelocityMultigrid<dim>::VelocityMultigrid(
    const parallel::distributed::Triangulation<dim> &tria,
    const Settings                                  &settings)
    : triangulation(tria)
    , settings(settings)
  {
    switch (settings.degree)
      {
        case 2:
          implementation = std::make_unique<Hierarchy<dim, 2>>(tria, settings);
          break;
        case 3:
          implementation = std::make_unique<Hierarchy<dim, 3>>(tria, settings);
          break;
        default:
          if (!(false))
            throw InputError(
              "Fluid/Velocity degree = " + std::to_string(settings.degree) +
              " with Preconditioner = GMG: allowed are 2 "
              "and 3");
      }
  }



  template <int dim>
  VelocityMultigrid<dim>::~VelocityMultigrid() = default;



  template <int dim>
  void
  VelocityMultigrid<dim>::setup(
    const DoFHandler<dim>              &system,
    const std::vector<unsigned int>    &periodic_directions,
    const std::set<types::boundary_id> &dirichlet_ids)
  {
    implementation->setup(system, periodic_directions, dirichlet_ids);
  }



  template <int dim>
  void
  VelocityMultigrid<dim>::update(
    const ViscosityFunction              &viscosity,
    const TrilinosWrappers::SparseMatrix *velocity_block,
    const AffineConstraints<double>      &system_constraints)
  {
    implementation->update(viscosity, velocity_block, system_constraints);
  }



  template <int dim>
  void
  VelocityMultigrid<dim>::vmult(TrilinosWrappers::MPI::Vector       &dst,
                                const TrilinosWrappers::MPI::Vector &src) const
  {
    implementation->vmult(dst, src);
  }



  template <int dim>
  void
  VelocityMultigrid<dim>::apply_velocity_block(
    TrilinosWrappers::MPI::Vector       &dst,
    const TrilinosWrappers::MPI::Vector &src) const
  {
    implementation->apply_velocity_block(dst, src);
  }



  template <int dim>
  void
  VelocityMultigrid<dim>::subtract_constraint_load(
    TrilinosWrappers::MPI::Vector       &rhs,
    const TrilinosWrappers::MPI::Vector &g) const
  {
    implementation->subtract_constraint_load(rhs, g);
  }



  template <int dim>
  double
  VelocityMultigrid<dim>::galerkin_defect() const
  {
    return implementation->galerkin_defect();
  }



  template <int dim>
  const typename VelocityMultigrid<dim>::Info &
  VelocityMultigrid<dim>::get_info() const
  {
    return implementation->info;
  }



  template class VelocityMultigrid<2>;
  template class VelocityMultigrid<3>;
} // namespace Fidus
