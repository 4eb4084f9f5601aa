#ifndef fidus_fluid_stokes_solver_h
#define fidus_fluid_stokes_solver_h

#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <fidus/core/memory_budget.h>
#include <fidus/fluid/fictitious_domain/direct_stokes_solver.h>
#include <fidus/fluid/fictitious_domain/fictitious_domain_parameters.h>
#include <fidus/fluid/fictitious_domain/rigid_motion.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <fidus/fluid/fictitious_domain/uzawa_loop.h>
#include <fidus/fluid/fictitious_domain/velocity_block.h>
#include <memory>
#include <set>
#include <utility>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The fluid predictor of fidus (numerics section 1): Stokes flow on the
   * whole box, the solid given the viscosity r * eta_f, and a Lagrange
   * multiplier lambda that enforces rigidity (epsilon(u) = 0 on the solid),
   * found by the augmented-Lagrangian Uzawa loop
   *
   *   (2 eta e(u^k), e(v)) - (p^k, div v) = -(e(lambda^k), e(v))_solid,
   *   (q, div u^k) = 0,
   *   lambda^{k+1} = lambda^k + rho u^k,   rho = 2 (eta_s - eta_f).
   *
   * The penalised viscosity is the augmentation, so the matrix and its
   * preconditioner are built once per solve and every Uzawa iteration is one
   * FGMRES solve with a new right-hand side (warm-started from the previous
   * iterate). Taylor-Hood Q(k)/Q(k-1) on a p4est mesh, Trilinos linear
   * algebra, MPI parallel.
   */
  template <int dim>
  class StokesSolver
  {
  public:
    /**
     * Solver settings: the fictitious domain's entries
     * (FictitiousDomainParameters, where each is documented) and what the
     * rest of the scene decides.
     */
    struct Settings : public FictitiousDomainParameters
    {
      unsigned int degree    = 2;
      double       viscosity = 1.;
      /// A velocity scale of the particles' forced motion (external
      /// forces; 0: none). The rigid velocity change is measured against
      /// the larger of it and the box's shear: a scene driven by forces
      /// alone has a small rms shear rate that would make the measure
      /// unreachably strict.
      double forced_velocity_scale = 0.;
      /// Print one line per Uzawa iteration (rank 0).
      bool verbose = false;
    };

    /// What one solve() did.
    struct Statistics
    {
      unsigned int uzawa_iterations  = 0;
      unsigned int linear_iterations = 0; ///< outer FGMRES, summed
      unsigned int inner_iterations  = 0; ///< inner CG of expensive mode
      unsigned int expensive_solves  = 0;
      /// The rigidity residual in the measure the Uzawa loop stops on
      /// (Settings::rigidity_per_particle): UzawaProblem::Residual::held
      /// or UzawaProblem::Residual::particle.
      double rigidity_residual = 0.;
      /// UzawaProblem::Residual::particle of the last iteration, whatever the
      /// measure.
      double particle_rigidity_residual = 0.;
      /// Largest change of a particle's rigid velocity in the last Uzawa
      /// iteration, |dU|/(g a) or |d omega|/g with g the box's rms shear
      /// rate sqrt(2 <e(u):e(u)>); NaN after a single iteration.
      double rigid_velocity_change = 0.;
      /// Cells whose solid was released (Settings::release_shared_cells),
      /// and the rigidity residual of the solid in them (reported only).
      unsigned int shared_cells    = 0;
      double       shared_residual = 0.;
      bool         uzawa_converged = true;
      /// The Uzawa loop stopped early: no progress (see solve()).
      bool   uzawa_stalled    = false;
      double assemble_seconds = 0.;
      double setup_seconds    = 0.; ///< AMG and Jacobi set-up
      double solve_seconds    = 0.;
      /// Part of solve_seconds spent in the Uzawa loop's passes over the
      /// solid (multiplier load, rigidity residual, rigid motions).
      double solid_pass_seconds = 0.;
      /// The GMRES restart the solves used (Settings::gmres_restart, or
      /// less where its basis would not fit in memory); 0 with the direct
      /// solver.
      unsigned int gmres_restart = 0;
    };

    /// Error norms against an exact solution.
    struct Errors
    {
      double u_l2 = 0., u_h1 = 0., p_l2 = 0.;
      /// L2 norm of the exact velocity on the same region (for relative
      /// errors).
      double u_l2_norm = 0.;
    };

    /// Work on @p triangulation (owned by the caller).
    StokesSolver(parallel::distributed::Triangulation<dim> &triangulation,
                 const Settings                            &settings);
    ~StokesSolver();

    /**
     * Distribute DoFs and build sparsity patterns for the current mesh.
     * @p periodic_directions: axes whose faces (boundary ids 2k, 2k+1) are
     * periodic; @p dirichlet_ids: boundary ids with imposed velocity.
     */
    void
    setup_dofs(const std::vector<unsigned int>    &periodic_directions,
               const std::set<types::boundary_id> &dirichlet_ids);

    /**
     * Solve for the given solid region and boundary velocity (a function of
     * dim+1 components). Optional: a body force (dim+1 components) and a
     * variable fluid viscosity (scalar) used by verification tests, and
     * a linear tolerance for the loop's solves above Linear
     * solver/Tolerance (a solve whose velocities only start an iteration:
     * 0 keeps Tolerance).
     */
    Statistics
    solve(const SolidIndicator<dim> &solid,
          const Function<dim>       &boundary_velocity,
          const Function<dim>       *body_force       = nullptr,
          const Function<dim>       *fluid_viscosity  = nullptr,
          double                     linear_tolerance = 0.);

    /**
     * Solve again with the system of the last solve() (the same solid,
     * boundary values and preconditioner: for the 2D direct solver its
     * factorisation) and its right-hand side plus the body force
     * @p extra_force (dim+1 components, the pressure's zero), from the last
     * multiplier: for solves that differ in their loads only (the
     * sub-grid lubrication solved with the flow). Needs
     * keep_right_hand_side(true) before that solve().
     *
     * @p linear_tolerance, if positive, replaces the linear tolerance for
     * every solve of this Uzawa loop, the last one included (an inexact
     * solve of an outer iteration that checks its own convergence); it is
     * never taken below the settings' linear tolerance.
     */
    Statistics
    resolve(const SolidIndicator<dim> &solid,
            const Function<dim>       &extra_force,
            double                     linear_tolerance = 0.);

    /// Keep a copy of each solve()'s right-hand side for resolve() (one
    /// vector of the unknowns' size).
    void
    keep_right_hand_side(const bool keep)
    {
      keep_rhs_for_resolve = keep;
    }

    /**
     * Errors of the current solution against @p exact (dim+1 components):
     * L2 and H1-seminorm of u and L2 of p (both pressures with zero mean),
     * integrated on the fluid part only when @p fluid_only is set.
     */
    Errors
    compute_errors(const Function<dim>       &exact,
                   const SolidIndicator<dim> &solid,
                   const bool                 fluid_only) const;

    /// The DoF handler (velocity components first, then pressure).
    const DoFHandler<dim> &
    get_dof_handler() const
    {
      return dof_handler;
    }

    /// The settings in use.
    const Settings &
    get_settings() const
    {
      return settings;
    }

    /**
     * The viscosity at a point of solid fraction @p phi (SolidIndicator::
     * fraction()) where the fluid's is @p eta_f: eta_f outside, r eta_f
     * inside, and between them, in a smoothed solid's layer, the
     * arithmetic mix eta_f (1 + (r - 1) phi), as the multiplier's load is
     * weighted by phi: the penalty and the multiplier then act on the same
     * weighted strain. The assembly, the multigrid levels and the stress
     * all use it.
     */
    double
    solid_viscosity(const double eta_f, const double phi) const
    {
      return phi == 0. ? eta_f :
             phi == 1. ? settings.penalty_factor * eta_f :
                         eta_f * (1. + (settings.penalty_factor - 1.) * phi);
    }

    /**
     * The hanging-node and periodicity constraints of the current mesh,
     * without the imposed velocity (closed, on the locally relevant DoFs):
     * the conforming space, for residuals at DoFs with imposed velocity.
     * Built by setup_dofs().
     */
    const AffineConstraints<double> &
    get_conforming_constraints() const
    {
      return conforming_constraints;
    }

    /// The finite element.
    const FESystem<dim> &
    get_fe() const
    {
      return fe;
    }

    /// The solution with ghost entries (block 0: u, block 1: p).
    const TrilinosWrappers::MPI::BlockVector &
    get_solution() const
    {
      return solution;
    }

    /// The rigidity multiplier with ghost entries (block 0).
    const TrilinosWrappers::MPI::BlockVector &
    get_multiplier() const
    {
      return multiplier;
    }

    /// Quadrature used for assembly, the indicator and particle integrals.
    const QGauss<dim> &
    get_quadrature() const
    {
      return quadrature;
    }

    /// Whether the linear solves are exact whatever tolerance they are
    /// given (the direct solver), so that an inexact one saves nothing.
    bool
    solves_exactly() const;

    /// Total number of DoFs.
    types::global_dof_index
    n_dofs() const
    {
      return dof_handler.n_dofs();
    }

    /**
     * With Preconditioner = GMG: the largest
     * VelocityMultigrid::galerkin_defect() of any preconditioner set-up so
     * far (round-off with Multigrid viscosity averaging = galerkin); else 0.
     */
    double
    multigrid_galerkin_defect() const
    {
      return worst_galerkin_defect;
    }

    /// Locally owned and ghost cells in mesh order (canonical_cell_order),
    /// for sums over cells that must not depend on the refinement history.
    const std::vector<typename DoFHandler<dim>::active_cell_iterator> &
    get_cells() const
    {
      return cells;
    }

    /// Per active cell (active_cell_index): whether the last solve treated
    /// its solid part as fluid (a shared cell).
    const std::vector<bool> &
    get_shared_cells() const
    {
      return shared;
    }

    /// Invalidate the multiplier warm start (the solid moved).
    void
    reset_multiplier();

    /// Whether the multiplier is the warm start of the next solve.
    bool
    multiplier_is_valid() const
    {
      return multiplier_valid;
    }

    /**
     * Attach the multiplier to the triangulation, so that the next
     * triangulation.save() stores it with the mesh (a checkpoint). Call
     * finish_checkpoint() after the save.
     */
    void
    prepare_for_checkpoint();

    /// Release what prepare_for_checkpoint() attached.
    void
    finish_checkpoint();

    /**
     * After triangulation.load() of a checkpoint: distribute DoFs as
     * setup_dofs() does and read the multiplier back. It is the next
     * solve's warm start if @p multiplier_is_warm_start (as it was when
     * saved). On the same number of ranks the DoF numbering, and therefore
     * every later number, is the same as in the run that wrote it.
     */
    void
    load_from_checkpoint(const std::vector<unsigned int> &periodic_directions,
                         const std::set<types::boundary_id> &dirichlet_ids,
                         bool multiplier_is_warm_start);

  private:
    /// Add the hanging-node and periodicity constraints to @p c.
    void
    add_conforming_constraints(AffineConstraints<double> &c) const;
    /// Hanging nodes, periodicity and the boundary velocity.
    void
    make_constraints(const Function<dim> &boundary_velocity);
    void
    assemble_system(const SolidIndicator<dim> &solid,
                    const Function<dim>       *body_force,
                    const Function<dim>       *fluid_viscosity);
    /// Add the load of @p body_force, which vanishes outside the particles
    /// of @p solid, to base_rhs (the matrix unchanged).
    void
    add_body_force_rhs(const SolidIndicator<dim> &solid,
                       const Function<dim>       &body_force);
    /// The Uzawa loop on the assembled system and its set-up
    /// preconditioner, from a zero multiplier if @p start_from_zero (or no
    /// valid one), else from the last; fills the loop's part of @p stats.
    /// A positive @p linear_tolerance replaces the settings' (resolve()).
    void
    run_uzawa_loop(const SolidIndicator<dim> &solid,
                   bool                       start_from_zero,
                   Statistics                &stats,
                   double                     linear_tolerance = 0.);
    void
    assemble_multiplier_rhs(const SolidIndicator<dim> &solid);
    /// The strain the current solution leaves in the solid
    /// (UzawaProblem::Residual).
    UzawaProblem::Residual
    rigidity_residual(const SolidIndicator<dim> &solid) const;
    /// The products int phi e(v):e(w_i) over the held solid (the inner
    /// product behind Residual::held) of @p v with each @p w_i, then of
    /// @p v with itself; all with ghost entries.
    std::vector<double>
    held_strain_products(
      const SolidIndicator<dim>                                     &solid,
      const TrilinosWrappers::MPI::BlockVector                      &v,
      const std::vector<const TrilinosWrappers::MPI::BlockVector *> &w) const;
    /// The solver seen as the problem UzawaLoop iterates on
    /// (stokes_solver_uzawa.cc).
    class Uzawa;
    /// The linear solvers, one class per choice of Fluid/Linear solver
    /// (stokes_linear_solvers.h).
    class LinearSolver;
    class DirectLinearSolver;
    class IterativeLinearSolver;
    class AmgLinearSolver;
    class GmgLinearSolver;
    /// The linear solver of a new mesh: direct on meshes of at most
    /// Settings::direct_max_unknowns unknowns, else FGMRES with the GMG
    /// (Settings::geometric_multigrid) or the AMG, which also stands in
    /// where the multigrid hierarchy cannot be built.
    std::unique_ptr<LinearSolver>
    choose_linear_solver();
    /// Before this mesh's system is built: stop the run (RunError) if the
    /// estimate of what the iterative solvers need for @p n_owned owned
    /// unknowns exceeds the memory budget of some rank
    /// (stokes_solver_memory.cc).
    void
    check_memory_for_mesh(types::global_dof_index n_owned) const;
    /// Whether FGMRES's basis at the configured restart would not fit in
    /// what some rank has left (then assemble_system() frees B^T, and
    /// B^T is applied as the transpose of B: slower, by about 6 % per
    /// dense 3D step, but the size of B less).
    bool
    basis_is_short() const;
    /// One solve of the current system, from zero, to @p tolerance
    /// (relative to the right-hand side), by the linear solver of this mesh.
    unsigned int
    solve_linear(Statistics &stats, double tolerance);
    /// Whether the solid of @p cell is released
    /// (Settings::release_shared_cells): within half a cell diameter of two
    /// particles (@p candidates: the particles near the cell), or touching a
    /// face with imposed velocity.
    bool
    is_shared_cell(const SolidIndicator<dim>                        &solid,
                   const typename Triangulation<dim>::cell_iterator &cell,
                   const std::vector<unsigned int> &candidates) const;
    /// The viscosity at @p points of a cell (of any mesh) near the
    /// particles @p candidates: r eta_f in the solid unless the cell is
    /// shared, eta_f elsewhere. Returns whether a point is in the solid.
    /// The assembly and the multigrid levels both use it.
    bool
    viscosity_at(const SolidIndicator<dim>       &solid,
                 const Function<dim>             *fluid_viscosity,
                 const std::vector<unsigned int> &candidates,
                 bool                             shared_cell,
                 const std::vector<Point<dim>>   &points,
                 std::vector<double>             &eta) const;
    void
    make_pressure_rhs_consistent();
    /// Whether the velocity block is assembled into system_matrix (not
    /// when the geometric multigrid applies it without a matrix).
    bool
    velocity_block_assembled() const;
    /// Scratch of one cell's assembly (stokes_solver.cc).
    struct CellAssembly;
    /// The local matrices of one cell of assemble_system(): the velocity
    /// block (@p with_a), the coupling B (@p with_b), the pressure mass
    /// weighted by 1/eta, the body force.
    void
    integrate_cell(CellAssembly        &cell,
                   bool                 with_a,
                   bool                 with_b,
                   const Function<dim> *body_force) const;
    /// Add one cell's local matrices to the system, or with the coupling
    /// kept (@p keep_coupling) only the load of its boundary values.
    void
    distribute_cell(CellAssembly &cell, bool keep_coupling, bool with_b);

    MPI_Comm                                   mpi_communicator;
    parallel::distributed::Triangulation<dim> &triangulation;
    const Settings                             settings;
    FESystem<dim>                              fe;
    DoFHandler<dim>                            dof_handler;
    QGauss<dim>                                quadrature;

    /// Locally owned and ghost cells in mesh order (canonical_cell_order):
    /// every loop that adds up over cells runs in this order.
    std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;

    /// Per locally owned velocity DoF: the solid entry (SolidIndicator) of
    /// the cells that hold it rigid, or -1.
    std::vector<int> solid_entry_of_dof;
    /// See multigrid_galerkin_defect().
    double worst_galerkin_defect = 0.;

    /// Shared cells of the last assembly, and how many (all ranks).
    std::vector<bool> shared;
    /// Per active cell: its solid is a sliver (a share of its quadrature
    /// points below Settings::sliver_threshold), held by the penalty alone,
    /// without the multiplier.
    std::vector<bool> sliver;
    unsigned int      n_shared_cells = 0;
    /// Whether system_matrix holds B and B^T of the current mesh, to be
    /// kept (the velocity block is matrix-free, so nothing else in it
    /// moves with the particles); reset by setup_dofs().
    bool coupling_assembled = false;

    std::vector<unsigned int>    periodic_directions;
    std::set<types::boundary_id> dirichlet_ids;
    std::vector<IndexSet>        owned_partitioning, relevant_partitioning;
    IndexSet                     locally_relevant_dofs;
    AffineConstraints<double>    constraints;
    /// Hanging nodes and periodicity only (get_conforming_constraints()).
    AffineConstraints<double> conforming_constraints;

    TrilinosWrappers::BlockSparseMatrix system_matrix;
    TrilinosWrappers::BlockSparseMatrix preconditioner_matrix;
    TrilinosWrappers::MPI::BlockVector  base_rhs, rhs;
    TrilinosWrappers::MPI::BlockVector  distributed_solution;
    TrilinosWrappers::MPI::BlockVector  solution;
    TrilinosWrappers::MPI::BlockVector  distributed_multiplier, multiplier;
    TrilinosWrappers::MPI::BlockVector  solid_mask;
    bool                                multiplier_valid = false;
    /// See keep_right_hand_side(): base_rhs as solve() assembled it.
    bool                               keep_rhs_for_resolve = false;
    TrilinosWrappers::MPI::BlockVector saved_base_rhs;
    /// Meshes on which the geometric multigrid could not be built and the
    /// AMG stood in.
    unsigned int multigrid_fallbacks = 0;
    /// How this mesh's systems are solved (choose_linear_solver()).
    std::unique_ptr<LinearSolver> linear_solver;
    /// What each rank may still allocate (Settings::memory_per_rank).
    MemoryBudget memory_budget;

    /// Holds the multiplier between prepare_for_checkpoint() and the save.
    std::unique_ptr<parallel::distributed::
                      SolutionTransfer<dim, TrilinosWrappers::MPI::BlockVector>>
      checkpoint_transfer;
  };
} // namespace Fidus

#endif
