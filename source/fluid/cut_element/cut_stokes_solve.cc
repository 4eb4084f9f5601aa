#include "cut_stokes_solve.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <deal.II/base/multithread_info.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/non_matching/fe_immersed_values.h>
#include <deal.II/numerics/vector_tools.h>
#include <fidus/core/memory_budget.h>
#include <fidus/core/memory_usage.h>
#include <fidus/fluid/cut_element/cut_fields.h>
#include <fidus/fluid/cut_element/cut_initial_guess.h>
#include <fidus/fluid/cut_element/cut_level_set.h>
#include <fidus/fluid/cut_element/cut_saddle_point_solver.h>
#include <fidus/fluid/cut_element/element_sparsity.h>
#include <fidus/fluid/cut_element/mumps_solver.h>
#include <fidus/fluid/fictitious_domain/rigid_mode.h>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

namespace Fidus
{
  namespace
  {
    /// Throw std::invalid_argument: @p what is @p value, but must be
    /// @p allowed.
    [[noreturn]] void
    refuse(const std::string &what,
           const double       value,
           const std::string &allowed)
    {
      throw std::invalid_argument("CutStokesInclusion: " + what + " is " +
                                  std::to_string(value) +
                                  "; allowed: " + allowed);
    }
  } // namespace

  template <int dim>
  void
  CutStokesSolve<dim>::check_settings() const
  {
    if (particles.empty())
      refuse("the number of particles", 0, ">= 1");
    if (s.boundary == Boundary::exact_inclusion &&
        (particles.size() != 1 || particles[0].force.norm() > 0.))
      refuse("the number of particles of the exact inclusion",
             particles.size(),
             "one, force-free");
    if (!(eta > 0.))
      refuse("the viscosity", eta, "> 0");
    if (!(s.nitsche > 0.))
      refuse("the Nitsche parameter", s.nitsche, "> 0");
    if (!(s.ghost_velocity >= 0.) || !(s.ghost_pressure >= 0.))
      refuse("a ghost penalty",
             std::min(s.ghost_velocity, s.ghost_pressure),
             ">= 0 (0 leaves small cut pieces unstable)");
    if (n_ranks > 1 && s.linear_solver == LinearSolver::iterative &&
        s.velocity_preconditioner != VelocityPreconditioner::multigrid)
      refuse("the number of ranks of the iterative solver with the AMG",
             n_ranks,
             "1 (over ranks the iterative solver splits the multigrid)");
    if (s.quadrature_points == 0)
      refuse("the number of Gauss points", 0, ">= 1");
    if (!s.box_sides.empty() && s.box_sides.size() != dim)
      refuse("the number of box_sides", s.box_sides.size(), "dim, or none");
    for (const double L : s.box_sides)
      if (!(L >= 1.) || !std::isfinite(L))
        refuse("a side of the box",
               L,
               ">= 1 and finite (the shortest side is the length unit)");
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const auto &P = particles[k];
        if (!(P.radius > 0.))
          refuse("the radius of particle " + std::to_string(k),
                 P.radius,
                 "> 0");
        for (unsigned int d = 0; d < dim; ++d)
          if (!is_periodic(d) && (P.center[d] - P.radius <= 0. ||
                                  P.center[d] + P.radius >= side(d)))
            refuse("coordinate " + std::to_string(d) + " of particle " +
                     std::to_string(k) + "'s centre",
                   P.center[d],
                   "the particle inside the box");
      }
  }

  template <int dim>
  void
  CutStokesSolve<dim>::make_mesh()
  {
    std::vector<Point<dim>>         centers;
    std::vector<double>             radii;
    typename CutMesh<dim>::Settings mesh_settings;
    for (const auto &P : particles)
      {
        centers.push_back(P.center);
        radii.push_back(P.radius);
      }
    mesh_settings.global_level   = s.global_level;
    mesh_settings.band_levels    = s.band_levels;
    mesh_settings.band_cells     = s.band_cells;
    mesh_settings.gap_cells      = s.gap_cells;
    mesh_settings.max_gap_levels = s.max_gap_levels;
    mesh_settings.periodic_axes  = periodic_axes;
    mesh_settings.box_sides      = s.box_sides;
    mesh = std::make_unique<const CutMesh<dim>>(centers, radii, mesh_settings);
    result.n_gap_refinements      = mesh->n_gap_refinements;
    result.n_periodic_refinements = mesh->n_periodic_refinements;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::classify_cells()
  {
    dof_handler.reinit(mesh->get_triangulation());
    result.h = 1.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const Placement &here = placed(cell);
        cell->set_active_fe_index(here.solid ? 1 : 0);
        result.n_cut_cells += (!here.solid && here.n_cut > 0);
        result.h = std::min(result.h, CutMesh<dim>::shortest_side(cell));
      }
  }

  template <int dim>
  void
  CutStokesSolve<dim>::setup_dofs_and_constraints()
  {
    // The solve takes the machine's cores as threads (at most
    // DEAL_II_NUM_THREADS where that is set), shared by the ranks on the
    // machine: the assembly, the patterns and the multigrid's products
    // split among them, and deal.II's sparse products and vector
    // operations, most of an iterative solve. fidus starts with one thread
    // per rank, as the fictitious domain runs one rank per core. MUMPS
    // factorises on one core per rank. Threads sum the products in another
    // order: the answers agree with one thread's to round-off.
    MultithreadInfo::set_thread_limit(
      n_ranks == 1 ? numbers::invalid_unsigned_int :
                     std::max(1u,
                              MultithreadInfo::n_cores() /
                                ranks_on_this_machine(s.communicator)));
    // Eigen's products (product_transposed()) read cache sizes it sets up
    // once: set up here, before the threads.
    Eigen::initParallel();
    dof_handler.distribute_dofs(fe_collection);
    n_fluid        = dof_handler.n_dofs();
    n_total        = n_fluid + n_rigid * particles.size();
    result.n_dofs  = n_total;
    result.n_cells = mesh->get_triangulation().n_active_cells();

    exact =
      std::make_unique<const ExactRigidInclusion<dim>>(particles[0].center,
                                                       particles[0].radius,
                                                       g,
                                                       eta);
    const LinearShear    shear(g, 0.5 * side(1));
    const Function<dim> &box_velocity =
      s.boundary == Boundary::exact_inclusion ?
        static_cast<const Function<dim> &>(*exact) :
        static_cast<const Function<dim> &>(shear);

    // The box takes the exact velocity (the faces are numbered 2d, 2d + 1
    // for axis d), sliding walls only on y = 0, H, with the periodic faces
    // identified. With the velocity given on every wall the pressure is
    // fixed up to a constant: no pressure value is pinned, both solvers fix
    // its mean instead (solve_linear_system()).
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    for (unsigned int face = 0; face < 2 * dim; ++face)
      if (!is_periodic(face / 2))
        VectorTools::interpolate_boundary_values(dof_handler,
                                                 face,
                                                 box_velocity,
                                                 constraints,
                                                 fe_collection.component_mask(
                                                   velocity));
    mesh->make_periodicity_constraints(dof_handler, constraints);
    constraints.close();
  }

  template <int dim>
  void
  CutStokesSolve<dim>::find_ghost_penalty_faces()
  {
    // The ghost-penalty faces: between two cells with fluid, at least one
    // of them cut. Each face once: a conforming one from the cell of lower
    // index, a hanging one from its finer side (the coarser cell's values
    // are taken on the subface), a periodic one from its lower side.
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        {
          if (cell->at_boundary(f) || cell->neighbor(f)->has_children())
            continue;
          const auto neighbour = cell->neighbor(f);
          const bool coarser   = cell->neighbor_is_coarser(f);
          if (!ghost_pair(cell, neighbour) ||
              (!coarser && !(neighbour->index() > cell->index())))
            continue;
          GhostFace face{cell, neighbour, f, 0};
          if (coarser)
            {
              const auto face_and_subface =
                cell->neighbor_of_coarser_neighbor(f);
              face.neighbour_face = face_and_subface.first;
              face.subface        = face_and_subface.second;
            }
          else
            face.neighbour_face = cell->neighbor_of_neighbor(f);
          ghost_faces.push_back(face);
        }
    const Triangulation<dim> &tria = mesh->get_triangulation();
    for (const auto &pair : mesh->periodic_neighbours())
      {
        const cell_iterator lower(&tria,
                                  pair.lower_level,
                                  pair.lower_index,
                                  &dof_handler),
          upper(&tria, pair.upper_level, pair.upper_index, &dof_handler);
        if (!ghost_pair(lower, upper))
          continue;
        GhostFace face{lower, upper, 2 * pair.axis, 2 * pair.axis + 1};
        face.shift[pair.axis] = -side(pair.axis);
        ghost_faces.push_back(face);
      }
  }

  template <int dim>
  bool
  CutStokesSolve<dim>::uses_iterative_solver() const
  {
    // In 3D the iterative solver was faster than LDL^T at every size
    // measured, from 18 000 unknowns (the smallest 3D cut mesh fidus
    // builds) to 144 000, and took a half to a quarter of the memory
    // (doc/theory/cut_element.md, "Solvers"); below, the factorisation
    // costs next to nothing and cannot stall.
    return s.linear_solver == LinearSolver::iterative ||
           (s.linear_solver == LinearSolver::automatic && dim == 3 &&
            n_total > 15000);
  }

  template <int dim>
  typename CutStokesSolve<dim>::MemoryNeed
  CutStokesSolve<dim>::memory_need(const bool with_pattern) const
  {
    // Peak bytes of a whole solve (the system, its pattern, the scaled
    // copies, the solver and its vectors), measured on one rank
    // (doc/theory/cut_element.md, "Memory"). The iterative solver's peak
    // follows the pattern's entries: the blocks it assembles into, the
    // multigrid's levels and FGMRES's basis, 20-28 bytes per entry from a
    // dense suspension (600-740 entries per unknown) to one sphere (240;
    // per unknown 6.7 to 15 KB and more). Before the pattern, a bound per
    // unknown below all of them. The direct solver's factor fills in: as LU
    // 8-11 KB per unknown in 2D, 56-68 KB in 3D; as LDL^T 4.1 KB in 2D, 32 KB
    // in 3D. The lower ends, so that a solve is stopped only when it would
    // clearly not fit.
    const bool iterate = uses_iterative_solver();
    const bool ldlt    = !iterate && system_is_symmetric();
    MemoryNeed need;
    need.per_unit      = with_pattern ? 20. :
                         iterate      ? 6e3 :
                         dim == 2     ? (ldlt ? 4e3 : 7e3) :
                                        (ldlt ? 28e3 : 50e3);
    const double units = with_pattern ? double(result.n_entries) : n_total;
    // On more ranks, about half of the direct solver's peak is held by
    // every rank (the mesh, the system and its copies) and the factor,
    // the other half, is shared (2D and 3D, 1 to 3 ranks: 0.43-0.56); the
    // iterative solver's ranks share every block, the multigrid and
    // FGMRES's basis, and hold the mesh, the pattern's whole parts and the
    // coarsest level whole (2 ranks: 0.64 of one rank's peak for one
    // sphere, 0.67 for 37 spheres; a quarter held whole is below both).
    const double held_whole = iterate ? 0.25 : 0.5;
    need.bytes              = need.per_unit * units *
                 (n_ranks == 1 ? 1. : held_whole + (1. - held_whole) / n_ranks);
    return need;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::release_free_memory_if_short() const
  {
    // Memory handed back to the system is taken again by the next solve,
    // page by page, each cleared by the kernel: in the dense 3D scene
    // (rheology_steady_shear_3d_cut.prm) that made the later steps 19-28 s
    // instead of 18.5-19.6 s, for a peak 5-28 % lower. So the freed
    // memory goes back only when the machine has less than twice what the
    // solve needs. Without MPI there is no budget (MemoryBudget asks the
    // ranks of the machine): always.
    int mpi_started = 0;
    MPI_Initialized(&mpi_started);
    if (!mpi_started)
      MemoryUsage::release_free_memory();
    else
      MemoryBudget(s.memory_limit, s.communicator)
        .release_freed_memory_if_short(
          memory_need(uses_iterative_solver()).bytes,
          s.communicator);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::check_memory(const bool with_pattern) const
  {
    // The budget counts the ranks of the machine; without MPI (a caller
    // that did not start it) there is no budget to keep.
    int mpi_started = 0;
    MPI_Initialized(&mpi_started);
    const bool iterate = uses_iterative_solver();
    if (!mpi_started || (with_pattern && !iterate))
      return;
    const MemoryNeed   need     = memory_need(with_pattern);
    const double       needed   = need.bytes;
    const double       per_unit = need.per_unit;
    const MemoryBudget budget(s.memory_limit, s.communicator);
    // The least any rank has: the ranks decide together.
    const double free =
      dealii::Utilities::MPI::min(budget.free_bytes(), s.communicator);
    if (needed <= free)
      return;
    std::ostringstream m;
    m << "the cut mesh has " << n_total << " unknowns";
    if (with_pattern)
      m << " and " << result.n_entries << " matrix entries";
    m << "; its " << (iterate ? "iterative" : "direct") << " solve needs about "
      << MemoryUsage::format(needed)
      << (n_ranks > 1 ?
            " on each of its " + std::to_string(n_ranks) + " ranks" :
            std::string())
      << " ("
      << (with_pattern ? std::to_string(int(per_unit)) + " B per entry" :
                         MemoryUsage::format(per_unit) + " per unknown")
      << "), but this rank has " << MemoryUsage::format(free) << " left ("
      << budget.source()
      << "): raise 'Fluid/Cut minimum gap', lower 'Fluid/Cut gap cells' or "
         "'Mesh refinement/Maximum level', or set 'Fluid/Linear "
         "solver/Memory per rank' if the machine's figure is not what the "
         "run may use";
    throw std::runtime_error(m.str());
  }

  template <int dim>
  void
  CutStokesSolve<dim>::make_sparsity_pattern()
  {
    const auto &balls = mesh->get_balls();
    // The fluid cells' couplings, and a cut cell's with the rigid unknowns
    // of its particle, in one pattern of all unknowns (what
    // DoFTools::make_sparsity_pattern does for the fluid alone; a second
    // pattern copied into this one doubled the set-up's time and memory).
    // Through the constraints: a hanging DoF of a cell passes its couplings
    // on to the DoFs it hangs from, and a matrix entry missing from the
    // pattern would be dropped without an error.
    ElementSparsity                      elements(n_total, constraints);
    std::vector<types::global_dof_index> coupled;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (cell->active_fe_index() != 0)
          continue;
        const Placement &here = placed(cell);
        cell->get_dof_indices(dofs);
        coupled = dofs;
        if (here.n_cut > 0)
          for (unsigned int k = 0; k < n_rigid; ++k)
            coupled.push_back(n_fluid + balls[here.ball].owner * n_rigid + k);
        elements.add_element(coupled);
      }
    for (const GhostFace &face : ghost_faces)
      {
        face.cell->get_dof_indices(dofs);
        face.neighbour->get_dof_indices(neighbour_dofs);
        coupled = dofs;
        for (const auto j : neighbour_dofs)
          if (std::find(dofs.begin(), dofs.end(), j) == dofs.end())
            coupled.push_back(j);
        elements.add_element(coupled);
      }
    // Each particle's rigid unknowns together, and those of the particles
    // a rigid coupling joins.
    const auto add_rigid = [&](const std::vector<unsigned int> &owners) {
      coupled.clear();
      for (const unsigned int p : owners)
        for (unsigned int k = 0; k < n_rigid; ++k)
          coupled.push_back(n_fluid + p * n_rigid + k);
      elements.add_element(coupled);
    };
    for (unsigned int p = 0; p < particles.size(); ++p)
      add_rigid({p});
    for (const auto &c : s.couplings)
      add_rigid(c.owners);
    // With the system as blocks, the pressure rows keep their pressure
    // columns only (B is Bᵀ's transpose); with K's and Bᵀ's rows split, a
    // rank keeps of the velocity rows it does not hold their diagonal
    // alone: their entries, most of the system, are not built.
    if (split_rows)
      split_velocity_rows(elements.row_weights());
    elements.build(sparsity, rows_kept(), is_pressure);
    count_entries();
  }

  template <int dim>
  void
  CutStokesSolve<dim>::choose_solver()
  {
    const IndexSet pressure_dofs =
      DoFTools::extract_dofs(dof_handler,
                             fe_collection.component_mask(pressure));
    is_pressure.assign(n_total, false);
    for (const auto i : pressure_dofs)
      is_pressure[i] = true;
    iterative = uses_iterative_solver();
    // Between sliding walls, the unconstrained rows of the walls too: the
    // walls' stress is the residual of their DoFs' rows, which the
    // constrained matrix no longer has.
    if (periodic)
      make_wall_rows();
    // On more ranks the iterative solver with the multigrid splits K's and
    // Bᵀ's rows among them, each rank holding a range (K numbers the
    // velocities in the system's order, then the rigid unknowns), and the
    // rigid rows and P whole (summed over the ranks); the ranges are chosen
    // with the pattern (split_velocity_rows()).
    as_blocks = iterative &&
                s.velocity_preconditioner == VelocityPreconditioner::multigrid;
    split_rows = as_blocks && n_ranks > 1;
  }

  template <int dim>
  std::vector<ElementSparsity::Keep>
  CutStokesSolve<dim>::rows_kept() const
  {
    using Keep = ElementSparsity::Keep;
    std::vector<Keep> keep;
    if (!as_blocks)
      return keep;
    keep.assign(n_total, Keep::all);
    // The walls' rows are read whole (make_wall_pattern()).
    for (unsigned int i = 0; i < n_fluid; ++i)
      if (is_pressure[i])
        keep[i] = Keep::flagged;
      else if (split_rows && !held_velocity_rows[i] &&
               !(periodic && wall_rows[i]))
        keep[i] = Keep::diagonal;
    return keep;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::count_entries()
  {
    result.n_entries = sparsity.n_nonzero_elements();
    if (!as_blocks)
      return;
    // The whole system's entries, as one rank would hold them: those of
    // this rank's velocity rows, summed over the ranks, and those of the
    // pressure and rigid rows, which every rank holds alike; B's, which
    // the pattern leaves out, counted as their transposes in Bᵀ.
    std::uint64_t own = 0, shared = 0;
    for (unsigned int i = 0; i < n_total; ++i)
      {
        const bool velocity = i < n_fluid && !is_pressure[i];
        if (velocity && split_rows && !held_velocity_rows[i])
          continue;
        for (auto it = sparsity.begin(i); it != sparsity.end(i); ++it)
          {
            const unsigned int in_b =
              i < n_fluid && is_pressure[i] ? 0 : is_pressure[it->column()];
            (velocity ? own : shared) += 1 + in_b;
          }
      }
    result.n_entries = Utilities::MPI::sum(own, s.communicator) + shared;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::setup_system()
  {
    // Between sliding walls, the walls' unconstrained rows
    // (choose_solver()).
    if (periodic)
      {
        make_wall_pattern();
        unconstrained.reinit(wall_sparsity);
      }
    // The iterative solver with the multigrid keeps the system as its
    // blocks: assembled into them, it is never held whole (the system and
    // its blocks side by side were the solve's peak).
    if (as_blocks)
      {
        std::vector<unsigned char> kind(n_total, 2);
        for (unsigned int i = 0; i < n_fluid; ++i)
          kind[i] = is_pressure[i] ? 1 : 0;
        blocks = std::make_unique<CutSystemBlocks>();
        if (split_rows)
          blocks->reinit(sparsity, kind, k_first, k_end);
        else
          blocks->reinit(sparsity, kind);
        sparsity.reinit(0, 0, 0);
      }
    else
      matrix.reinit(sparsity);
    // The iterative solver's pressure preconditioner takes the pressure
    // mass matrix over the fluid, on the pressures' own pattern; in the
    // order the volume kernel writes the cells' pressure mass in.
    pressure_shapes = TaylorHoodLayout<dim>(taylor_hood).pressure;
    pressure_dof_indices.resize(pressure_shapes.size());
    pressure_mean.reinit(n_total);
    if (iterative)
      {
        // The pressures of each fluid cell, coupled all with all.
        ElementSparsity elements(n_fluid, constraints);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->active_fe_index() == 0)
            {
              cell->get_dof_indices(dofs);
              for (unsigned int a = 0; a < pressure_shapes.size(); ++a)
                pressure_dof_indices[a] = dofs[pressure_shapes[a]];
              elements.add_element(pressure_dof_indices);
            }
        elements.build(mass_sparsity);
        pressure_mass.reinit(mass_sparsity);
      }
    rhs.reinit(n_total);
    solution.reinit(n_total);

    n_ext = n_local + n_rigid;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::scale_system()
  {
    // f(j, value) on row i's entries, whether the system is one matrix
    // or its blocks.
    const auto for_row = [this](const unsigned int i, const auto &f) {
      if (blocks)
        blocks->for_row(i, f);
      else
        for (auto it = matrix.begin(i), end = matrix.end(i); it != end; ++it)
          f(it->column(), it->value());
    };
    scale.reinit(n_total);
    for (unsigned int i = 0; i < n_total; ++i)
      if (!is_pressure[i])
        {
          const double d = std::abs(system_diagonal(i));
          scale[i]       = d > 0. ? 1. / std::sqrt(d) : 1.;
        }
    // A pressure's: its diagonal and its row of B weighed by the velocity
    // scales, read from the matrix's row, or as Bᵀ's column from the
    // blocks (over the ranks' rows of Bᵀ with the split; the diagonal and
    // the rigid rows, which every rank holds, counted once).
    Vector<double> schur(n_total);
    for (unsigned int i = 0; i < n_total; ++i)
      if (is_pressure[i] && (!split_rows || this_rank == 0))
        schur[i] = std::abs(system_diagonal(i));
    if (as_blocks)
      {
        const SparseMatrix<double> &bt = blocks->bt;
        for (unsigned int r = 0; r < bt.m(); ++r)
          {
            const unsigned int i = blocks->k_rows[r];
            if (i >= n_fluid && split_rows && this_rank != 0)
              continue;
            for (auto it = bt.begin(r), end = bt.end(r); it != end; ++it)
              schur[blocks->p_rows[it->column()]] +=
                it->value() * it->value() * scale[i] * scale[i];
          }
        if (split_rows)
          Utilities::MPI::sum(schur, s.communicator, schur);
      }
    else
      for (unsigned int i = 0; i < n_total; ++i)
        if (is_pressure[i])
          for_row(i, [&](const unsigned int j, const double value) {
            if (!is_pressure[j])
              schur[i] += value * value * scale[j] * scale[j];
          });
    for (unsigned int i = 0; i < n_total; ++i)
      if (is_pressure[i])
        scale[i] = schur[i] > 0. ? 1. / std::sqrt(schur[i]) : 1.;
    if (split_rows)
      for (unsigned int i = 0; i < n_total; ++i)
        velocity_diagonal[i] *= scale[i] * scale[i];
    // Every row on its own: on the threads (a 3D system has tens of
    // millions of entries).
    on_row_ranges(n_total,
                  1,
                  [&](const unsigned int first, const unsigned int last) {
                    for (unsigned int i = first; i < last; ++i)
                      for_row(i, [&](const unsigned int j, auto &&value) {
                        value *= scale[i] * scale[j];
                      });
                  });
  }

  template <int dim>
  void
  CutStokesSolve<dim>::solve_linear_system()
  {
    // The saddle-point system is solved directly with MUMPS (UMFPACK,
    // tried first, returned wrong solutions without an error above about
    // 1.5e5 unknowns), or iteratively. The residual is measured, since a
    // factorisation that lost accuracy gives no error.
    //
    // A refined gap puts cells 1e-4 times smaller than the box's next to
    // its coarse ones, and the pressure of a cell of size h couples with
    // weight h^(dim-1) against viscous entries of order h^(dim-2): without
    // scaling, the closing speed of a pair 1e-3 a apart (1e-3 of the
    // particles' own speeds) was lost in round-off (sign changes between
    // refinements, doc/cut_element.md). So the system is scaled
    // symmetrically before the factorisation, velocity and rigid unknowns
    // by their diagonal, pressures by the diagonal of B diag(A)^-1 B^T,
    // and two steps of iterative refinement take the residual to round-off.
    scale_system();

    // Scaled: A' = D A D, b' = D b, x = D x'; A' r' = D (b - A x).
    Vector<double> scaled_rhs(n_total), scaled_solution(n_total),
      residual(n_total);
    for (unsigned int i = 0; i < n_total; ++i)
      scaled_rhs[i] = scale[i] * rhs[i];

    // The pressure's constant is fixed by its mean over the fluid: both
    // solvers solve A' x' - m' m'^T x' = b', where m_i = int phi_i / eta
    // over the fluid (the pressure mass of the constant), normalised by
    // the square root of 1^T m, and m' = D m. This keeps every continuity
    // row (pinning one pressure value dropped one, which then held the cut
    // quadratures' small miss of the divergence theorem), and gives the
    // Schur complement on the constant what the iterative solver's
    // pressure mass gives it (doc/history/cut_element.md, "The pinned
    // pressure").
    {
      double volume = 0.;
      for (unsigned int i = 0; i < n_fluid; ++i)
        volume += pressure_mean[i];
      if (!(volume > 0.))
        throw std::runtime_error("CutStokesInclusion: the fluid has no volume");
      scaled_mean.reinit(n_total);
      for (unsigned int i = 0; i < n_fluid; ++i)
        scaled_mean[i] = scale[i] * pressure_mean[i] / std::sqrt(volume);
    }
    if (iterative)
      solve_iterative(scaled_rhs, scaled_solution, residual);
    else
      solve_direct(scaled_rhs, scaled_solution, residual);
    double r2 = 0., b2 = 0.;
    for (unsigned int i = 0; i < n_total; ++i)
      {
        solution[i] = scale[i] * scaled_solution[i];
        r2 += std::pow(residual[i] / scale[i], 2);
        b2 += rhs[i] * rhs[i];
      }
    result.residual = std::sqrt(r2 / b2);
    constraints.distribute(solution);
  }

  template <int dim>
  bool
  CutStokesSolve<dim>::in_thin_gap(const Point<dim> &x) const
  {
    // The two nearest surfaces: the gap's width at x is the sum of the
    // distances to them, its lateral scale set by their reduced radius.
    // A brute-force search over the balls (with their periodic images):
    // a few hundred distances per pressure even for the dense scenes,
    // small beside the pressure's share of the assembly.
    double     d1 = std::numeric_limits<double>::infinity(), d2 = d1;
    double     r1 = d1, r2 = d1;
    const auto nearer = [&](const double d, const double r) {
      if (d < d1)
        {
          d2 = d1;
          r2 = r1;
          d1 = d;
          r1 = r;
        }
      else if (d < d2)
        {
          d2 = d;
          r2 = r;
        }
    };
    for (const auto &b : mesh->get_balls())
      nearer(std::max(0., x.distance(b.center) - b.radius), b.radius);
    const double infinite = std::numeric_limits<double>::infinity();
    for (unsigned int d = 0; d < dim; ++d)
      if (!is_periodic(d))
        {
          nearer(std::max(0., x[d]), infinite);
          nearer(std::max(0., mesh->side(d) - x[d]), infinite);
        }
    const double reduced = std::isinf(r1) ? r2 :
                           std::isinf(r2) ? r1 :
                                            r1 * r2 / (r1 + r2);
    return !std::isinf(reduced) && d1 + d2 < s.gap_threshold * reduced;
  }



  template <int dim>
  void
  CutStokesSolve<dim>::solve_iterative(const Vector<double> &scaled_rhs,
                                       Vector<double>       &scaled_solution,
                                       Vector<double>       &residual)
  {
    typename CutSaddlePointSolver<dim>::Layout layout;
    layout.kind.assign(n_total, 2);
    layout.constrained.assign(n_total, false);
    layout.support_point.resize(n_total);
    layout.component.assign(n_total, 0);
    layout.pressure_mean = scaled_mean;
    layout.communicator  = s.communicator;
    if (split_rows)
      {
        layout.k_first = k_first;
        layout.k_end   = k_end;
        layout.p_first = p_bounds[this_rank];
        layout.p_end   = p_bounds[this_rank + 1];
      }
    for (unsigned int i = 0; i < n_fluid; ++i)
      {
        layout.kind[i]        = is_pressure[i] ? 1 : 0;
        layout.constrained[i] = constraints.is_constrained(i);
      }
    const auto &unit_points = taylor_hood.get_unit_support_points();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->active_fe_index() == 0)
        {
          cell->get_dof_indices(dofs);
          const Point<dim>     lower = cell->vertex(0);
          const Tensor<1, dim> h =
            cell->vertex(GeometryInfo<dim>::vertices_per_cell - 1) - lower;
          for (unsigned int k = 0; k < n_local; ++k)
            {
              Point<dim> x = lower;
              for (unsigned int d = 0; d < dim; ++d)
                x[d] += h[d] * unit_points[k][d];
              layout.support_point[dofs[k]] = x;
              layout.component[dofs[k]] =
                taylor_hood.system_to_component_index(k).first;
            }
        }
    if (s.gap_laplacian > 0.)
      {
        layout.gap_laplacian = s.gap_laplacian;
        layout.in_gap.assign(n_total, false);
        for (unsigned int i = 0; i < n_fluid; ++i)
          if (is_pressure[i])
            layout.in_gap[i] = in_thin_gap(layout.support_point[i]);
      }
    for (unsigned int i = 0; i < n_fluid; ++i)
      for (auto it = pressure_mass.begin(i); it != pressure_mass.end(i); ++it)
        it->value() *= scale[i] * scale[it->column()];
    std::unique_ptr<CutVelocityMultigrid<dim>>   multigrid;
    typename CutVelocityMultigrid<dim>::Settings multigrid_settings;
    multigrid_settings.cut_cell_blocks     = s.cut_cell_blocks;
    multigrid_settings.smoother_degree     = s.smoother_degree;
    multigrid_settings.single_precision    = s.single_precision_cycle;
    multigrid_settings.separate_components = s.separate_components;
    if (!s.cut_cell_blocks)
      multigrid_settings.smoothing_range = 15.;
    if (s.velocity_preconditioner == VelocityPreconditioner::multigrid)
      {
        multigrid =
          std::make_unique<CutVelocityMultigrid<dim>>(dof_handler,
                                                      constraints,
                                                      scale,
                                                      periodic_axes,
                                                      multigrid_settings);
        std::vector<std::pair<Point<dim>, double>> surfaces;
        for (const auto &b : mesh->get_balls())
          surfaces.emplace_back(b.center, b.radius);
        multigrid->set_surfaces(surfaces);
      }
    // The start reads the constrained rows' diagonal, before the system
    // goes.
    const bool guessed = initial_guess(layout, scaled_rhs, scaled_solution);
    // With the multigrid, the solver takes the system's blocks over, and
    // the pressure mass is freed before the multigrid's levels are built;
    // without, the solver copies the blocks it needs from the system.
    const auto release = [this]() {
      matrix.clear();
      sparsity.reinit(0, 0, 0);
      pressure_mass.clear();
      mass_sparsity.reinit(0, 0, 0);
      release_free_memory_if_short();
    };
    std::unique_ptr<CutSaddlePointSolver<dim>> solver =
      blocks ? std::make_unique<CutSaddlePointSolver<dim>>(std::move(blocks),
                                                           pressure_mass,
                                                           layout,
                                                           *multigrid,
                                                           release) :
               std::make_unique<CutSaddlePointSolver<dim>>(matrix,
                                                           pressure_mass,
                                                           layout,
                                                           multigrid.get(),
                                                           release);
    release_free_memory_if_short();
    const auto statistics         = solver->solve(scaled_solution,
                                          scaled_rhs,
                                          s.iterative_tolerance,
                                          s.iterative_max_iterations,
                                          guessed);
    result.initial_residual       = statistics.initial_residual;
    result.iterative              = true;
    result.n_iterations           = statistics.iterations;
    result.n_setup_iterations     = statistics.setup_iterations;
    result.stage_seconds.fgmres   = statistics.solve_seconds;
    result.stage_seconds.blocks   = statistics.blocks_seconds;
    result.stage_seconds.pressure = statistics.pressure_seconds;
    result.stage_seconds.velocity = statistics.velocity_seconds;
    solver->system_vmult(residual, scaled_solution);
    residual.sadd(-1., scaled_rhs);
  }

  template <int dim>
  bool
  CutStokesSolve<dim>::initial_guess(
    const typename CutSaddlePointSolver<dim>::Layout &layout,
    const Vector<double>                             &scaled_rhs,
    Vector<double>                                   &scaled_solution) const
  {
    std::vector<double> sides(dim);
    for (unsigned int d = 0; d < dim; ++d)
      sides[d] = side(d);
    if (!s.initial_guess || !CutInitialGuess<dim>::applies(*s.initial_guess,
                                                           sides,
                                                           particles.size()))
      return false;
    // The flow is proportional to the shear rate when no force drives a
    // particle: a changed rate (oscillatory shear, a reversal) scales the
    // previous field.
    const CutFields<dim> &previous = *s.initial_guess;
    bool                  forced   = false;
    for (const auto &P : particles)
      forced = forced || P.force.norm() > 0.;
    const double factor =
      !forced && previous.proportional && previous.shear_rate != 0. ?
        g / previous.shear_rate :
        1.;
    CutInitialGuess<dim> guess(previous, factor);
    // Each particle's displacement since, the shortest across periodic
    // axes.
    std::vector<Tensor<1, dim>> moved(particles.size());
    std::vector<bool>           periodic_axis(dim);
    for (unsigned int d = 0; d < dim; ++d)
      periodic_axis[d] = is_periodic(d);
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        moved[p] = particles[p].center - previous.centers[p];
        for (unsigned int d = 0; d < dim; ++d)
          if (is_periodic(d))
            moved[p][d] -= side(d) * std::round(moved[p][d] / side(d));
      }
    guess.follow(mesh->get_balls(), moved, periodic_axis);
    // A constrained row holds its diagonal alone: its value is known. The
    // unknowns are scaled, x' = x / D.
    for (unsigned int i = 0; i < n_fluid; ++i)
      scaled_solution[i] =
        constraints.is_constrained(i) ?
          scaled_rhs[i] / system_diagonal(i) :
          guess.value(layout.support_point[i], layout.component[i]) / scale[i];
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        const std::vector<double> v = guess.rigid(p);
        for (unsigned int k = 0; k < n_rigid; ++k)
          scaled_solution[n_fluid + p * n_rigid + k] =
            v[k] / scale[n_fluid + p * n_rigid + k];
      }
    return true;
  }

  template <int dim>
  bool
  CutStokesSolve<dim>::system_is_symmetric() const
  {
    if (!s.symmetric_factorisation)
      return false;
    // The fluid's terms are symmetric by construction (tested by
    // fluid/cut_symmetric: LDL^T and LU agree); a rigid coupling is
    // whatever its model gives.
    for (const auto &c : s.couplings)
      {
        double largest = 0., asymmetry = 0.;
        for (unsigned int k = 0; k < c.matrix.size(); ++k)
          for (unsigned int l = 0; l < c.matrix.size(); ++l)
            {
              largest = std::max(largest, std::abs(c.matrix[k][l]));
              asymmetry =
                std::max(asymmetry, std::abs(c.matrix[k][l] - c.matrix[l][k]));
            }
        if (asymmetry > 1e-12 * largest)
          return false;
      }
    return true;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::solve_direct(const Vector<double> &scaled_rhs,
                                    Vector<double>       &scaled_solution,
                                    Vector<double>       &residual)
  {
    // The bordered system [A' m'; m'^T 1] [x'; y] = [b'; 0], whose first
    // rows are A' x' - m' m'^T x' = b' (y = -m'^T x'), handed to MUMPS as
    // its entries: each rank its own range of rows, from the whole system
    // every rank holds; of a symmetric system the upper triangle only.
    const unsigned int n     = n_total + 1;
    const unsigned int first = std::uint64_t(n) * this_rank / n_ranks,
                       last  = std::uint64_t(n) * (this_rank + 1) / n_ranks;
    const bool symmetric     = system_is_symmetric();
    result.symmetric_factorisation = symmetric;
    std::vector<int>    rows, columns;
    std::vector<double> values;
    const auto          add =
      [&](const unsigned int i, const unsigned int j, const double value) {
        if (symmetric && j < i)
          return;
        rows.push_back(i);
        columns.push_back(j);
        values.push_back(value);
      };
    for (unsigned int i = first; i < std::min(last, n_total); ++i)
      {
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
          add(i, it->column(), it->value());
        if (scaled_mean[i] != 0.)
          add(i, n_total, scaled_mean[i]);
      }
    if (last == n)
      {
        for (unsigned int j = 0; j < n_total; ++j)
          if (scaled_mean[j] != 0.)
            add(n_total, j, scaled_mean[j]);
        add(n_total, n_total, 1.);
      }
    // MUMPS's fill-reducing ordering: approximate minimum degree in 2D,
    // 11-12 % less time per dense 2D step than the automatic choice (PORD,
    // where MUMPS is built without METIS and SCOTCH, as Debian's is); in
    // 3D the automatic choice, PORD, against which AMD took 40 % longer
    // (doc/history/cut_element_solvers.md, "The direct solver's ordering").
    MumpsSolver::Settings settings;
    settings.symmetric = symmetric;
    settings.ordering  = dim == 2 ? 0 : 7;
    MumpsSolver direct(s.communicator, settings);
    try
      {
        direct.factorize(n,
                         std::move(rows),
                         std::move(columns),
                         std::move(values));
      }
    catch (const std::exception &e)
      {
        throw std::runtime_error(
          std::string("CutStokesInclusion: ") + e.what() +
          "; is the system singular (are the ghost penalties zero?)");
      }
    // Two steps of iterative refinement take the residual to round-off.
    // Every rank ends with the whole solution.
    Vector<double> x(n);
    residual = scaled_rhs;
    for (unsigned int step = 0; step < 3; ++step)
      {
        for (unsigned int i = 0; i < n_total; ++i)
          x[i] = residual[i];
        x[n_total] = 0.;
        direct.solve(x);
        for (unsigned int i = 0; i < n_total; ++i)
          scaled_solution[i] += x[i];
        apply_system(residual, scaled_solution);
        residual.sadd(-1., scaled_rhs);
      }
  }

  template class CutStokesSolve<2>;
  template class CutStokesSolve<3>;
} // namespace Fidus
