#include "stokes_linear_solvers.h"

#include <cmath>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/block_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <deque>
#include <fidus/core/input_error.h>
#include <fidus/core/memory_usage.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fidus/mesh/canonical_cell_order.h>
#include <limits>
#include <sstream>

namespace Fidus
{



  template <int dim>
  StokesSolver<dim>::StokesSolver(
    parallel::distributed::Triangulation<dim> &triangulation,
    const Settings                            &settings)
    : mpi_communicator(triangulation.get_communicator())
    , triangulation(triangulation)
    , settings(settings)
    , fe(FE_Q<dim>(settings.degree), dim, FE_Q<dim>(settings.degree - 1), 1)
    , dof_handler(triangulation)
    , quadrature(settings.degree + 1)
    , memory_budget(settings.memory_per_rank, mpi_communicator)
  {}



  template <int dim>
  StokesSolver<dim>::~StokesSolver()
  {
    checkpoint_transfer.reset();
    linear_solver.reset();
    dof_handler.clear();
  }



  template <int dim>
  void
  StokesSolver<dim>::reset_multiplier()
  {
    multiplier_valid = false;
  }



  template <int dim>
  void
  StokesSolver<dim>::prepare_for_checkpoint()
  {
    // The multiplier is saved even when it is not a valid warm start: the
    // file layout then does not depend on the state, and the flag saved
    // with the run state decides whether it is used.
    checkpoint_transfer = std::make_unique<
      parallel::distributed::
        SolutionTransfer<dim, TrilinosWrappers::MPI::BlockVector>>(dof_handler);
    checkpoint_transfer->prepare_for_serialization(multiplier);
  }



  template <int dim>
  void
  StokesSolver<dim>::finish_checkpoint()
  {
    checkpoint_transfer.reset();
  }



  template <int dim>
  void
  StokesSolver<dim>::load_from_checkpoint(
    const std::vector<unsigned int>    &periodic,
    const std::set<types::boundary_id> &dirichlet,
    const bool                          multiplier_is_warm_start)
  {
    setup_dofs(periodic, dirichlet);
    parallel::distributed::SolutionTransfer<dim,
                                            TrilinosWrappers::MPI::BlockVector>
      transfer(dof_handler);
    transfer.deserialize(distributed_multiplier);
    multiplier       = distributed_multiplier;
    multiplier_valid = multiplier_is_warm_start;
  }



  template <int dim>
  void
  StokesSolver<dim>::setup_dofs(const std::vector<unsigned int>    &periodic,
                                const std::set<types::boundary_id> &dirichlet)
  {
    periodic_directions = periodic;
    dirichlet_ids       = dirichlet;
    linear_solver.reset();
    coupling_assembled = false;

    dof_handler.distribute_dofs(fe);
    // Number the DoFs along the forest (z-order) before splitting them by
    // block. distribute_dofs() follows the order in which cells are stored,
    // which depends on the refinement history; the forest depends only on
    // the mesh. A mesh loaded from a checkpoint then gets the numbering, the
    // AMG aggregates and therefore the numbers of the run that wrote it.
    DoFRenumbering::hierarchical(dof_handler);
    std::vector<unsigned int> block_component(dim + 1, 0);
    block_component[dim] = 1;
    DoFRenumbering::component_wise(dof_handler, block_component);
    const std::vector<types::global_dof_index> dofs_per_block =
      DoFTools::count_dofs_per_fe_block(dof_handler, block_component);
    const types::global_dof_index n_u = dofs_per_block[0],
                                  n_p = dofs_per_block[1];

    const IndexSet &owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);
    owned_partitioning    = {owned.get_view(0, n_u),
                             owned.get_view(n_u, n_u + n_p)};
    relevant_partitioning = {locally_relevant_dofs.get_view(0, n_u),
                             locally_relevant_dofs.get_view(n_u, n_u + n_p)};

    // The linear solver first: whether the multigrid hierarchy can be
    // built on this mesh decides whether the system holds an assembled
    // velocity block.
    if (dof_handler.n_dofs() > settings.direct_max_unknowns)
      check_memory_for_mesh(owned.n_elements());
    linear_solver = choose_linear_solver();

    // The constrained DoF set does not depend on the boundary values, so
    // zero Dirichlet data give the sparsity pattern of every later solve.
    make_constraints(Functions::ZeroFunction<dim>(dim + 1));
    linear_solver->prepare_mesh();
    conforming_constraints.clear();
    conforming_constraints.reinit(locally_relevant_dofs);
    add_conforming_constraints(conforming_constraints);
    conforming_constraints.close();
    cells = canonical_cell_order(dof_handler);

    // The system couples everything but pressure with pressure; the
    // preconditioner matrix holds only the pressure mass.
    const auto make_matrix = [&](TrilinosWrappers::BlockSparseMatrix &matrix,
                                 const bool pressure_only) {
      matrix.clear();
      Table<2, DoFTools::Coupling> coupling(dim + 1, dim + 1);
      // Without an assembled velocity block (matrix-free GMG) the system
      // holds only B, B^T and the diagonal of constrained rows.
      for (unsigned int c = 0; c < dim + 1; ++c)
        for (unsigned int d = 0; d < dim + 1; ++d)
          {
            const bool pp = c == dim && d == dim;
            const bool uu = c < dim && d < dim;
            coupling[c][d] =
              pp == pressure_only && !(uu && !velocity_block_assembled()) ?
                DoFTools::always :
                DoFTools::none;
          }
      TrilinosWrappers::BlockSparsityPattern sp(owned_partitioning,
                                                owned_partitioning,
                                                relevant_partitioning,
                                                mpi_communicator);
      DoFTools::make_sparsity_pattern(dof_handler,
                                      coupling,
                                      sp,
                                      constraints,
                                      false,
                                      Utilities::MPI::this_mpi_process(
                                        mpi_communicator));
      sp.compress();
      matrix.reinit(sp);
    };
    make_matrix(system_matrix, false);
    make_matrix(preconditioner_matrix, true);
    // The sparsity patterns' scratch, freed, would stay resident.
    MemoryUsage::release_free_memory();

    base_rhs.reinit(owned_partitioning,
                    relevant_partitioning,
                    mpi_communicator,
                    true);
    rhs.reinit(owned_partitioning,
               relevant_partitioning,
               mpi_communicator,
               true);
    distributed_solution.reinit(owned_partitioning, mpi_communicator);
    solution.reinit(owned_partitioning,
                    relevant_partitioning,
                    mpi_communicator);
    distributed_multiplier.reinit(owned_partitioning, mpi_communicator);
    multiplier.reinit(owned_partitioning,
                      relevant_partitioning,
                      mpi_communicator);
    solid_mask.reinit(owned_partitioning, mpi_communicator);
    multiplier_valid = false;
  }



  template <int dim>
  void
  StokesSolver<dim>::add_conforming_constraints(
    AffineConstraints<double> &c) const
  {
    DoFTools::make_hanging_node_constraints(dof_handler, c);
    for (const unsigned int d : periodic_directions)
      DoFTools::make_periodicity_constraints(dof_handler,
                                             2 * d,
                                             2 * d + 1,
                                             d,
                                             c);
  }



  template <int dim>
  void
  StokesSolver<dim>::make_constraints(const Function<dim> &boundary_velocity)
  {
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    add_conforming_constraints(constraints);
    const FEValuesExtractors::Vector velocities(0);
    for (const types::boundary_id id : dirichlet_ids)
      VectorTools::interpolate_boundary_values(dof_handler,
                                               id,
                                               boundary_velocity,
                                               constraints,
                                               fe.component_mask(velocities));
    constraints.close();
  }



  template <int dim>
  bool
  StokesSolver<dim>::is_shared_cell(
    const SolidIndicator<dim>                        &solid,
    const typename Triangulation<dim>::cell_iterator &cell,
    const std::vector<unsigned int>                  &candidates) const
  {
    // A cell whose solid lies within half a cell diameter of another
    // particle (its bounding ball grown by half a diameter, about the reach
    // of the cells that share DoFs with it; two particles closer than a
    // cell), or that touches a face with imposed velocity: one velocity
    // polynomial cannot be two rigid motions there. With
    // 'Shared cells = fluid' its solid part is treated as fluid (no penalty,
    // no multiplier, not in the rigidity residual), and each particle keeps
    // its rigid motion from the rest of its solid.
    if (!settings.release_shared_cells || candidates.empty())
      return false;
    std::vector<unsigned int> near;
    solid.candidates(cell->center(), cell->diameter(), near);
    for (const unsigned int k : near)
      if (solid.owner(k) != solid.owner(near[0]))
        return true;
    // A face with imposed velocity is the other motion of a particle
    // that touches a wall.
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary() &&
          dirichlet_ids.count(cell->face(f)->boundary_id()) > 0)
        return true;
    return false;
  }



  template <int dim>
  bool
  StokesSolver<dim>::viscosity_at(const SolidIndicator<dim> &solid,
                                  const Function<dim>       *fluid_viscosity,
                                  const std::vector<unsigned int> &candidates,
                                  const bool                       shared_cell,
                                  const std::vector<Point<dim>>   &points,
                                  std::vector<double>             &eta) const
  {
    bool meets_solid = false;
    for (unsigned int q = 0; q < points.size(); ++q)
      {
        const double eta_f = fluid_viscosity ?
                               fluid_viscosity->value(points[q]) :
                               settings.viscosity;
        int          entry = -1;
        const double phi   = candidates.empty() ?
                               0. :
                               solid.fraction(points[q], candidates, entry);
        meets_solid |= phi > 0.;
        eta[q] = shared_cell ? eta_f : solid_viscosity(eta_f, phi);
      }
    return meets_solid;
  }



  /// Scratch of the assembly of one cell: its values, its local matrices
  /// and right-hand side, and which of its DoFs are velocities.
  template <int dim>
  struct StokesSolver<dim>::CellAssembly
  {
    CellAssembly(const FESystem<dim> &fe, const QGauss<dim> &quadrature)
      : fe_values(fe,
                  quadrature,
                  update_values | update_gradients | update_quadrature_points |
                    update_JxW_values)
      , n_q(quadrature.size())
      , cell_matrix(fe.n_dofs_per_cell(), fe.n_dofs_per_cell())
      , cell_prec(fe.n_dofs_per_cell(), fe.n_dofs_per_cell())
      , cell_rhs(fe.n_dofs_per_cell())
      , dofs(fe.n_dofs_per_cell())
      , symgrad(fe.n_dofs_per_cell())
      , div(fe.n_dofs_per_cell())
      , phi_p(fe.n_dofs_per_cell())
      , eta(quadrature.size())
      , force(dim + 1)
      , is_velocity(fe.n_dofs_per_cell())
      , points(quadrature.size())
    {
      // The cell's velocity and pressure DoFs, so that each coupling is
      // visited once (the pairs of a Q2-Q1 cell in 3D are 95 % velocity).
      for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
        {
          is_velocity[k] = fe.system_to_component_index(k).first < dim;
          (is_velocity[k] ? u_dofs : p_dofs).push_back(k);
        }
    }

    FEValues<dim>                        fe_values;
    const unsigned int                   n_q;
    FullMatrix<double>                   cell_matrix;
    FullMatrix<double>                   cell_prec;
    dealii::Vector<double>               cell_rhs;
    std::vector<types::global_dof_index> dofs;
    std::vector<SymmetricTensor<2, dim>> symgrad;
    std::vector<double>                  div;
    std::vector<double>                  phi_p;
    std::vector<double>                  eta;
    dealii::Vector<double>               force;
    std::vector<bool>                    is_velocity;
    std::vector<unsigned int>            u_dofs, p_dofs;
    std::vector<Point<dim>>              points;
  };



  template <int dim>
  void
  StokesSolver<dim>::assemble_system(const SolidIndicator<dim> &solid,
                                     const Function<dim>       *body_force,
                                     const Function<dim>       *fluid_viscosity)
  {
    const bool with_a = velocity_block_assembled();
    // Without the velocity block, system_matrix holds only B (B^T until
    // the first assembly is done, below) and the diagonal of constrained
    // rows: the same for every step on one mesh.
    // Then it is assembled once per mesh; the load that the boundary values
    // put on the pressure rows through B (it follows the shear rate) is
    // added to the right-hand side by hand on the cells with such values.
    const bool keep_coupling = !with_a && coupling_assembled;
    if (!keep_coupling)
      system_matrix = 0;
    preconditioner_matrix = 0;
    base_rhs              = 0;
    solid_mask            = 0;

    CellAssembly              c(fe, quadrature);
    FEValues<dim>            &fe_values     = c.fe_values;
    const unsigned int        dofs_per_cell = fe.n_dofs_per_cell();
    const unsigned int        n_q           = c.n_q;
    std::vector<unsigned int> cands;

    shared.assign(triangulation.n_active_cells(), false);
    sliver.assign(triangulation.n_active_cells(), false);
    n_shared_cells = 0;
    solid_entry_of_dof.assign(owned_partitioning[0].n_elements(), -1);
    // The velocity DoFs of a cell that meets the solid (outside shared
    // cells) are held rigid by the multiplier (solid mask), and belong to
    // that particle's rigid motions in the preconditioner's coarse space
    // (the first particle seen, in mesh order, where two meet).
    const auto mark_solid_dofs = [&](const auto &cell) {
      int    entry    = -1;
      double n_inside = 0.;
      for (unsigned int q = 0; q < n_q; ++q)
        {
          int          e = -1;
          const double phi =
            solid.fraction(fe_values.quadrature_point(q), cands, e);
          if (phi > 0.)
            {
              n_inside += phi;
              if (entry < 0)
                entry = e;
            }
        }
      if (entry < 0)
        return;
      if (n_inside < settings.sliver_threshold * n_q)
        {
          sliver[cell->active_cell_index()] = true;
          return;
        }
      cell->get_dof_indices(c.dofs);
      for (unsigned int k = 0; k < dofs_per_cell; ++k)
        if (c.is_velocity[k] && solid_mask.in_local_range(c.dofs[k]))
          {
            solid_mask(c.dofs[k]) = 1.;
            int &e = solid_entry_of_dof[owned_partitioning[0].index_within_set(
              c.dofs[k])];
            if (e < 0)
              e = entry;
          }
    };
    for (const auto &cell : cells)
      {
        solid.candidates(cell->center(), 0.5 * cell->diameter(), cands);
        const bool shared_cell = is_shared_cell(solid, cell, cands);
        if (!cell->is_locally_owned())
          {
            // Ghost cells only mark the locally owned DoFs.
            if (cands.empty() || shared_cell)
              continue;
            fe_values.reinit(cell);
            mark_solid_dofs(cell);
            continue;
          }

        fe_values.reinit(cell);
        cell->get_dof_indices(c.dofs);
        for (unsigned int q = 0; q < n_q; ++q)
          c.points[q] = fe_values.quadrature_point(q);
        const bool meets_solid = viscosity_at(solid,
                                              fluid_viscosity,
                                              cands,
                                              shared_cell,
                                              c.points,
                                              c.eta);
        if (meets_solid && shared_cell)
          {
            shared[cell->active_cell_index()] = true;
            ++n_shared_cells;
          }
        if (meets_solid && !shared_cell)
          mark_solid_dofs(cell);

        // With B kept, the cell's B is needed only for the load of its
        // boundary values.
        bool with_b = !keep_coupling;
        for (unsigned int i = 0; i < c.u_dofs.size() && !with_b; ++i)
          with_b =
            constraints.is_inhomogeneously_constrained(c.dofs[c.u_dofs[i]]);

        integrate_cell(c, with_a, with_b, body_force);
        distribute_cell(c, keep_coupling, with_b);
      }
    if (!with_a)
      coupling_assembled = true;
    n_shared_cells = Utilities::MPI::sum(n_shared_cells, mpi_communicator);
    if (!keep_coupling)
      system_matrix.compress(VectorOperation::add);
    // Without the velocity block the coupling is kept for the whole mesh.
    // Where FGMRES's basis would not fit, B^T is applied as the transpose
    // of B and its own block, a second copy of B, is freed (5 % of a dense
    // 3D box's peak, for 6 % more time per step: doc/cookbooks/cluster.md).
    if (!with_a && !keep_coupling && basis_is_short())
      {
        system_matrix.block(0, 1).clear();
        MemoryUsage::release_free_memory();
      }
    preconditioner_matrix.compress(VectorOperation::add);
    base_rhs.compress(VectorOperation::add);
    solid_mask.compress(VectorOperation::insert);
    make_pressure_rhs_consistent();
  }



  template <int dim>
  void
  StokesSolver<dim>::integrate_cell(CellAssembly        &c,
                                    const bool           with_a,
                                    const bool           with_b,
                                    const Function<dim> *body_force) const
  {
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(dim);
    const FEValues<dim>             &fe_values   = c.fe_values;
    const std::vector<unsigned int> &u_dofs      = c.u_dofs;
    const std::vector<unsigned int> &p_dofs      = c.p_dofs;
    FullMatrix<double>              &cell_matrix = c.cell_matrix;
    FullMatrix<double>              &cell_prec   = c.cell_prec;

    cell_matrix = 0;
    cell_prec   = 0;
    c.cell_rhs  = 0;
    for (unsigned int q = 0; q < c.n_q; ++q)
      {
        const double JxW = fe_values.JxW(q);
        // (with_a implies with_b: the velocity block is assembled with
        // the rest every step.)
        if (with_b)
          for (const unsigned int k : u_dofs)
            {
              if (with_a)
                c.symgrad[k] = fe_values[velocities].symmetric_gradient(k, q);
              c.div[k] = fe_values[velocities].divergence(k, q) * JxW;
            }
        for (const unsigned int k : p_dofs)
          c.phi_p[k] = fe_values[pressure].value(k, q);
        if (with_a)
          {
            const double w = 2. * c.eta[q] * JxW;
            for (unsigned int i = 0; i < u_dofs.size(); ++i)
              for (unsigned int j = 0; j <= i; ++j)
                cell_matrix(u_dofs[i], u_dofs[j]) +=
                  w * (c.symgrad[u_dofs[i]] * c.symgrad[u_dofs[j]]);
          }
        if (with_b)
          for (const unsigned int k : u_dofs)
            for (const unsigned int l : p_dofs)
              {
                const double b = c.div[k] * c.phi_p[l];
                cell_matrix(k, l) -= b;
                cell_matrix(l, k) -= b;
              }
        const double w = JxW / c.eta[q];
        for (unsigned int i = 0; i < p_dofs.size(); ++i)
          for (unsigned int j = 0; j <= i; ++j)
            cell_prec(p_dofs[i], p_dofs[j]) +=
              w * c.phi_p[p_dofs[i]] * c.phi_p[p_dofs[j]];
        if (body_force)
          {
            body_force->vector_value(fe_values.quadrature_point(q), c.force);
            for (const unsigned int k : u_dofs)
              {
                const unsigned int comp = fe.system_to_component_index(k).first;
                c.cell_rhs(k) +=
                  c.force[comp] * fe_values[velocities].value(k, q)[comp] * JxW;
              }
          }
      }
    // The velocity-velocity and pressure-pressure parts were summed in
    // one triangle (in the order of u_dofs and p_dofs, which is the
    // cell's order): copy it to the other.
    for (unsigned int i = 0; i < u_dofs.size(); ++i)
      for (unsigned int j = 0; j < i; ++j)
        cell_matrix(u_dofs[j], u_dofs[i]) = cell_matrix(u_dofs[i], u_dofs[j]);
    for (unsigned int i = 0; i < p_dofs.size(); ++i)
      for (unsigned int j = 0; j < i; ++j)
        cell_prec(p_dofs[j], p_dofs[i]) = cell_prec(p_dofs[i], p_dofs[j]);
  }



  template <int dim>
  void
  StokesSolver<dim>::distribute_cell(CellAssembly &c,
                                     const bool    keep_coupling,
                                     const bool    with_b)
  {
    if (!keep_coupling)
      constraints.distribute_local_to_global(c.cell_matrix,
                                             c.cell_rhs,
                                             c.dofs,
                                             system_matrix,
                                             base_rhs);
    else
      {
        // What the distribution above adds to the right-hand side: the
        // local rows times the constrained values (inhomogeneities), with
        // the sign of a move to the other side; only a cell with such
        // values (with_b) has any.
        for (const unsigned int k : c.u_dofs)
          if (with_b && constraints.is_inhomogeneously_constrained(c.dofs[k]))
            {
              const double g = constraints.get_inhomogeneity(c.dofs[k]);
              for (const unsigned int l : c.p_dofs)
                c.cell_rhs(l) -= c.cell_matrix(l, k) * g;
            }
        constraints.distribute_local_to_global(c.cell_rhs, c.dofs, base_rhs);
      }
    constraints.distribute_local_to_global(c.cell_prec,
                                           c.dofs,
                                           preconditioner_matrix);
  }



  template <int dim>
  void
  StokesSolver<dim>::add_body_force_rhs(const SolidIndicator<dim> &solid,
                                        const Function<dim>       &body_force)
  {
    // Only the velocity rows of the cells the force reaches; a linear
    // load, so the constraints only condense it (no inhomogeneity).
    const FEValuesExtractors::Vector velocities(0);
    CellAssembly                     c(fe, quadrature);
    FEValues<dim>                   &fe_values = c.fe_values;
    std::vector<unsigned int>        cands;
    for (const auto &cell : cells)
      {
        if (!cell->is_locally_owned())
          continue;
        // The loads live in the particles (ParticleForceDensity).
        solid.candidates(cell->center(), 0.5 * cell->diameter(), cands);
        if (cands.empty())
          continue;
        fe_values.reinit(cell);
        cell->get_dof_indices(c.dofs);
        c.cell_rhs  = 0;
        bool loaded = false;
        for (unsigned int q = 0; q < c.n_q; ++q)
          {
            body_force.vector_value(fe_values.quadrature_point(q), c.force);
            if (c.force.l2_norm() == 0.)
              continue;
            loaded           = true;
            const double JxW = fe_values.JxW(q);
            for (const unsigned int k : c.u_dofs)
              {
                const unsigned int comp = fe.system_to_component_index(k).first;
                c.cell_rhs(k) +=
                  c.force[comp] * fe_values[velocities].value(k, q)[comp] * JxW;
              }
          }
        if (loaded)
          constraints.distribute_local_to_global(c.cell_rhs, c.dofs, base_rhs);
      }
    base_rhs.compress(VectorOperation::add);
  }



  template <int dim>
  bool
  StokesSolver<dim>::velocity_block_assembled() const
  {
    return !linear_solver || linear_solver->assembles_velocity_block();
  }



  template <int dim>
  std::unique_ptr<typename StokesSolver<dim>::LinearSolver>
  StokesSolver<dim>::choose_linear_solver()
  {
    if (dof_handler.n_dofs() <= settings.direct_max_unknowns)
      return std::make_unique<DirectLinearSolver>(*this);
    if (settings.geometric_multigrid)
      try
        {
          return std::make_unique<GmgLinearSolver>(*this);
        }
      catch (const ExceptionBase &e)
        {
          // deal.II 9.4's global-coarsening transfer refuses some adaptive
          // meshes (a coarsened copy that is finer than the mesh above it
          // somewhere; seen in 2D at maximum level 9 with a disc a tenth of
          // its radius from a wall). This mesh is solved with the AMG
          // instead, and the run says so.
          ++multigrid_fallbacks;
          if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
            std::cerr << "fidus: warning: the geometric multigrid could not "
                         "be built on this mesh ("
                      << triangulation.n_global_active_cells()
                      << " cells, mesh " << multigrid_fallbacks
                      << " of this run where that happened); it is solved "
                         "with the AMG preconditioner instead. deal.II "
                         "said: "
                      << e.get_exc_name() << std::endl;
        }
    return std::make_unique<AmgLinearSolver>(*this);
  }



  template <int dim>
  void
  StokesSolver<dim>::make_pressure_rhs_consistent()
  {
    // With velocity imposed on the whole boundary the pressure is fixed up to
    // a constant, and the discrete system is solvable only if the imposed
    // velocity has zero discrete net flux. Interpolated boundary data (as for
    // the exact rigid inclusion) miss that by a truncation error; removing
    // the constant-pressure component of the right-hand side makes the
    // system consistent without changing the velocity at the order of the
    // scheme.
    TrilinosWrappers::MPI::Vector ones(owned_partitioning[1], mpi_communicator);
    // Indices of the block view are block-local: shift by the number of
    // velocity DoFs to ask the constraints.
    const types::global_dof_index n_u = owned_partitioning[0].size();
    for (const auto i : owned_partitioning[1])
      if (!constraints.is_constrained(n_u + i))
        ones(i) = 1.;
    ones.compress(VectorOperation::insert);
    const double n_free = ones * ones;
    if (n_free > 0)
      {
        const double mean = (base_rhs.block(1) * ones) / n_free;
        base_rhs.block(1).add(-mean, ones);
      }
  }



  template <int dim>
  void
  StokesSolver<dim>::assemble_multiplier_rhs(const SolidIndicator<dim> &solid)
  {
    rhs = base_rhs;
    if (solid.n_particles() == 0)
      return;

    TrilinosWrappers::MPI::BlockVector   load(owned_partitioning,
                                            relevant_partitioning,
                                            mpi_communicator,
                                            true);
    FEValues<dim>                        fe_values(fe,
                            quadrature,
                            update_gradients | update_quadrature_points |
                              update_JxW_values);
    const unsigned int                   dofs_per_cell = fe.n_dofs_per_cell();
    const unsigned int                   n_q           = quadrature.size();
    const FEValuesExtractors::Vector     velocities(0);
    dealii::Vector<double>               cell_rhs(dofs_per_cell);
    std::vector<types::global_dof_index> dofs(dofs_per_cell);
    std::vector<SymmetricTensor<2, dim>> eps_lambda(n_q);
    std::vector<unsigned int>            cands;

    for (const auto &cell : cells)
      if (cell->is_locally_owned() && !shared[cell->active_cell_index()] &&
          !sliver[cell->active_cell_index()])
        {
          solid.candidates(cell->center(), 0.5 * cell->diameter(), cands);
          if (cands.empty())
            continue;
          fe_values.reinit(cell);
          fe_values[velocities].get_function_symmetric_gradients(multiplier,
                                                                 eps_lambda);
          cell_rhs   = 0;
          bool touch = false;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              int          entry = -1;
              const double phi =
                solid.fraction(fe_values.quadrature_point(q), cands, entry);
              if (phi == 0.)
                continue;
              touch = true;
              for (unsigned int k = 0; k < dofs_per_cell; ++k)
                cell_rhs(k) -=
                  (eps_lambda[q] *
                   fe_values[velocities].symmetric_gradient(k, q)) *
                  phi * fe_values.JxW(q);
            }
          if (!touch)
            continue;
          cell->get_dof_indices(dofs);
          constraints.distribute_local_to_global(cell_rhs, dofs, load);
        }
    load.compress(VectorOperation::add);
    rhs += load;
  }



  template <int dim>
  typename StokesSolver<dim>::Errors
  StokesSolver<dim>::compute_errors(const Function<dim>       &exact,
                                    const SolidIndicator<dim> &solid,
                                    const bool                 fluid_only) const
  {
    QGauss<dim>                      q_error(fe.degree + 2);
    FEValues<dim>                    fe_values(fe,
                            q_error,
                            update_values | update_gradients |
                              update_quadrature_points | update_JxW_values);
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(dim);
    const unsigned int               n_q = q_error.size();
    std::vector<Tensor<1, dim>>      u(n_q);
    std::vector<Tensor<2, dim>>      grad_u(n_q);
    std::vector<double>              p(n_q);
    dealii::Vector<double>           exact_value(dim + 1);
    std::vector<Tensor<1, dim>>      exact_grad(dim + 1);
    std::vector<unsigned int>        cands;

    // Pass 0: pressure means on the integration region; pass 1: errors.
    // |region|, int p_h, int p, eu, egu, ep, |u exact|^2
    double sums[7] = {0, 0, 0, 0, 0, 0, 0};
    for (unsigned int pass = 0; pass < 2; ++pass)
      {
        const double mean_h = pass ? sums[1] / sums[0] : 0.;
        const double mean_e = pass ? sums[2] / sums[0] : 0.;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              fe_values[velocities].get_function_values(solution, u);
              fe_values[velocities].get_function_gradients(solution, grad_u);
              fe_values[pressure].get_function_values(solution, p);
              solid.candidates(cell->center(), 0.5 * cell->diameter(), cands);
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  const Point<dim> &x = fe_values.quadrature_point(q);
                  if (fluid_only && !cands.empty() &&
                      solid.particle_containing(x, cands) >= 0)
                    continue;
                  const double JxW = fe_values.JxW(q);
                  exact.vector_value(x, exact_value);
                  if (pass == 0)
                    {
                      sums[0] += JxW;
                      sums[1] += p[q] * JxW;
                      sums[2] += exact_value[dim] * JxW;
                      continue;
                    }
                  exact.vector_gradient(x, exact_grad);
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      sums[3] += std::pow(u[q][d] - exact_value[d], 2) * JxW;
                      sums[6] += std::pow(exact_value[d], 2) * JxW;
                      sums[4] +=
                        (grad_u[q][d] - exact_grad[d]).norm_square() * JxW;
                    }
                  sums[5] +=
                    std::pow((p[q] - mean_h) - (exact_value[dim] - mean_e), 2) *
                    JxW;
                }
            }
        if (pass == 0)
          Utilities::MPI::sum(ArrayView<const double>(sums, 3),
                              mpi_communicator,
                              ArrayView<double>(sums, 3));
      }
    Utilities::MPI::sum(ArrayView<const double>(sums + 3, 4),
                        mpi_communicator,
                        ArrayView<double>(sums + 3, 4));
    Errors e;
    e.u_l2      = std::sqrt(sums[3]);
    e.u_h1      = std::sqrt(sums[4]);
    e.p_l2      = std::sqrt(sums[5]);
    e.u_l2_norm = std::sqrt(sums[6]);
    return e;
  }

  template <int dim>
  bool
  StokesSolver<dim>::solves_exactly() const
  {
    return linear_solver && linear_solver->solves_exactly();
  }



  template class StokesSolver<2>;
  template class StokesSolver<3>;
} // namespace Fidus
