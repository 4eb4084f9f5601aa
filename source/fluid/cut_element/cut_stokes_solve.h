#ifndef fidus_fluid_cut_element_cut_stokes_solve_h
#define fidus_fluid_cut_element_cut_stokes_solve_h

#include <algorithm>
#include <array>
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/fe_values_extractors.h>
#include <deal.II/fe/mapping_cartesian.h>
#include <deal.II/hp/fe_collection.h>
#include <deal.II/hp/q_collection.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/non_matching/quadrature_generator.h>
#include <fidus/core/memory_usage.h>
#include <fidus/fluid/cut_element/cut_mesh.h>
#include <fidus/fluid/cut_element/cut_saddle_point_solver.h>
#include <fidus/fluid/cut_element/cut_stokes_inclusion.h>
#include <fidus/fluid/cut_element/cut_system_blocks.h>
#include <fidus/fluid/cut_element/element_sparsity.h>
#include <fidus/fluid/cut_element/stokes_volume_kernel.h>
#include <fidus/fluid/cut_element/taylor_hood_layout.h>
#include <fidus/verification/exact_rigid_inclusion.h>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * One solve of CutStokesInclusion, in named stages: the settings
   * checked, the cut mesh built, its cells classified and the DoFs and
   * constraints set up, the ghost-penalty faces found, the sparsity
   * pattern and the matrices set up, the cells and the ghost penalties
   * assembled, the scaled system solved (directly or iteratively), and the
   * solution measured (the particles' motions, the mean pressure, the
   * stresslets, the walls' stress and the exact inclusion's errors).
   *
   * What the stages share (mesh, DoFs, constraints, matrices, vectors,
   * quadratures) is held as members; run() calls the stages in order and
   * returns the Result. An object serves one solve: construct, run(),
   * discard. The Settings passed to the constructor must outlive it.
   */
  template <int dim>
  class CutStokesSolve
  {
  public:
    using Settings = typename CutStokesInclusion<dim>::Settings;
    using Result   = typename CutStokesInclusion<dim>::Result;

    /// Start the clock and take the scene from @p settings (checked by
    /// run(), not here).
    explicit CutStokesSolve(const Settings &settings)
      : s(settings)
      , particles(settings.particles)
      , eta(settings.viscosity)
      , g(settings.shear_rate)
      , periodic(settings.boundary == Boundary::sliding_walls)
      , exact_case(settings.boundary == Boundary::exact_inclusion)
      , taylor_hood(FE_Q<dim>(2), dim, FE_Q<dim>(1), 1)
      , nothing(FE_Nothing<dim>(), dim, FE_Nothing<dim>(), 1)
      , fe_collection(taylor_hood, nothing)
      , n_local(taylor_hood.n_dofs_per_cell())
      , velocity(0)
      , pressure(dim)
      , mapping()
      , dofs(n_local)
      , neighbour_dofs(n_local)
      , unit_box(create_unit_bounding_box<dim>())
      , q_cell(3)
      , surface_flags(update_values | update_gradients | update_JxW_values |
                      update_quadrature_points | update_normal_vectors)
    {
      // Sliding walls: y has the walls, every other axis is periodic.
      for (unsigned int d = 0; d < dim; ++d)
        if (periodic && d != 1)
          periodic_axes.push_back(d);
      int mpi_started = 0;
      MPI_Initialized(&mpi_started);
      if (mpi_started)
        {
          n_ranks   = Utilities::MPI::n_mpi_processes(s.communicator);
          this_rank = Utilities::MPI::this_mpi_process(s.communicator);
        }
    }

    /// Check the settings, build the mesh, assemble, solve and measure:
    /// the stages below, in order. Call once.
    Result
    run()
    {
      auto &stage = result.stage_seconds;
      // The wall time since the last call: each stage's share of the solve.
      double     last = 0.;
      const auto lap  = [&]() {
        const double now = timer.wall_time(), spent = now - last;
        last = now;
        return spent;
      };
      check_settings();
      lap();
      make_mesh();
      classify_cells();
      stage.mesh = lap();
      setup_dofs_and_constraints();
      check_memory(false);
      find_ghost_penalty_faces();
      choose_solver();
      make_sparsity_pattern();
      // The pattern's scratch is freed in many small blocks.
      release_free_memory_if_short();
      check_memory(true);
      setup_system();
      stage.dofs = lap();
      assemble_cells();
      assemble_ghost_penalties();
      sum_over_ranks();
      assemble_couplings();
      stage.assembly = lap();
      solve_linear_system();
      stage.solve = lap();
      read_rigid_motion();
      measure_solution();
      wall_stress();
      exact_inclusion_errors();
      if (s.keep_fields)
        keep_fields();
      stage.measure  = lap();
      result.seconds = timer.wall_time();
      return result;
    }

  private:
    /// The box's velocity for a linear shear and sliding walls:
    /// u = g (y - y_mid) e_x, p = 0.
    class LinearShear : public Function<dim>
    {
    public:
      LinearShear(const double g, const double y_mid)
        : Function<dim>(dim + 1)
        , g(g)
        , y_mid(y_mid)
      {}

      double
      value(const Point<dim> &x, const unsigned int component) const override
      {
        return component == 0 ? g * (x[1] - y_mid) : 0.;
      }

    private:
      const double g, y_mid;
    };

    using Particle     = typename CutStokesInclusion<dim>::Particle;
    using Boundary     = typename CutStokesInclusion<dim>::Boundary;
    using LinearSolver = typename CutStokesInclusion<dim>::LinearSolver;
    using VelocityPreconditioner =
      typename CutStokesInclusion<dim>::VelocityPreconditioner;
    using Placement     = typename CutMesh<dim>::Placement;
    using Ball          = typename CutMesh<dim>::Ball;
    using cell_iterator = typename DoFHandler<dim>::active_cell_iterator;

    /// A face that carries a ghost penalty: between two cells with fluid,
    /// at least one of them cut.
    struct GhostFace
    {
      cell_iterator  cell, neighbour;
      unsigned int   face, neighbour_face;
      unsigned int   subface = numbers::invalid_unsigned_int;
      Tensor<1, dim> shift   = Tensor<1, dim>();
    };

    /// Rigid unknowns of a particle: dim translations and the rotations.
    static constexpr unsigned int n_rigid = dim * (dim + 1) / 2;

    /// @name The stages, in the order run() calls them.
    /// @{

    /// Throw std::invalid_argument, naming the value, for settings the
    /// solver cannot take.
    void
    check_settings() const;

    /// Build the cut mesh for the particles.
    void
    make_mesh();

    /// Give the cells inside a particle no unknowns, and count the cut
    /// cells and the finest cell size.
    void
    classify_cells();

    /// Take the machine's cores as threads, distribute the DoFs and set
    /// up the hanging-node, boundary, periodicity and pressure
    /// constraints.
    void
    setup_dofs_and_constraints();

    /// Whether the system goes to the iterative solver (Settings::
    /// linear_solver; automatic: 3D above 15 000 unknowns, one rank).
    bool
    uses_iterative_solver() const;

    /// Throw, naming the unknowns, the estimate and what to change, if the
    /// system, its solver and their work space would not fit in
    /// Settings::memory_limit (or what the machine has available): before
    /// the sparsity pattern from the unknowns alone (a bound below every
    /// measured peak, so that only a mesh far too large stops there), and
    /// with @p with_pattern, for the iterative solver, from the pattern's
    /// entries, which set its peak.
    void
    check_memory(const bool with_pattern) const;

    /// A solve's expected peak on each rank, and the bytes per unit
    /// (matrix entry or unknown) it is counted in (check_memory()).
    struct MemoryNeed
    {
      double bytes    = 0.;
      double per_unit = 0.;
    };

    /// The peak check_memory() expects: from the pattern's entries with
    /// @p with_pattern, else from the unknowns.
    MemoryNeed
    memory_need(const bool with_pattern) const;

    /// Hand the memory freed so far back to the system only when the
    /// machine has less than twice what the solve needs (collective).
    void
    release_free_memory_if_short() const;

    /// Collect the faces that carry a ghost penalty, each once.
    void
    find_ghost_penalty_faces();

    /// Which unknowns are pressures, whether the solve iterates, and with
    /// K's rows split among the ranks (#split_rows) this rank's range.
    void
    choose_solver();

    /// With the system as blocks: what the pattern keeps of each row (by
    /// system index; the flagged columns are the pressures): of the
    /// pressure rows their pressure columns (B is not held), with K's rows
    /// split of the velocity rows this rank does not hold their diagonal
    /// (but for the walls'), of the others all; empty otherwise.
    std::vector<ElementSparsity::Keep>
    rows_kept() const;

    /// The sparsity pattern of the fluid, rigid and ghost-penalty
    /// couplings (with K's rows split, of this rank's K rows only).
    void
    make_sparsity_pattern();

    /// Result::n_entries: the whole system's, also with K's rows split.
    void
    count_entries();

    /// Size the matrices (the unconstrained one between sliding walls, the
    /// pressure mass matrix for the iterative solver), the vectors and the
    /// cell scratch, and load the particles' external forces.
    void
    setup_system();

    /// Assemble the fluid cells: the volume terms and, on cut cells, the
    /// Nitsche terms of the particle's surface.
    void
    assemble_cells();

    /// Assemble the ghost penalties on the faces of cut cells.
    void
    assemble_ghost_penalties();

    /// With more than one rank, sum the ranks' shares of the system, the
    /// right-hand side, the pressure means and the walls' rows, so that
    /// every rank holds the whole (Settings::communicator).
    void
    sum_over_ranks();

    /// Add the particles' external forces and Settings::couplings to the
    /// rigid rows (matrix and right-hand side), once, after the ranks'
    /// shares are summed.
    void
    assemble_couplings();

    /// Scale the system symmetrically, solve it (directly or
    /// iteratively), measure the residual and distribute the constraints.
    void
    solve_linear_system();

    /// Each particle's velocity and angular velocity, from its rigid
    /// unknowns.
    void
    read_rigid_motion();

    /// The fluid's mean pressure and volume, each particle's stresslet
    /// and, for the exact inclusion, the velocity error.
    void
    measure_solution();

    /// For sliding walls, the mean stress the walls y = 0, 1 feel; NaN
    /// otherwise.
    void
    wall_stress();

    /// For sliding walls, wall_phi and wall_rows: the unconstrained
    /// matrix's rows that wall_stress() reads.
    void
    make_wall_rows();

    /// Their pattern, from the system's (a small part of it: a whole
    /// unconstrained copy was a fifth of a dense suspension's peak
    /// memory).
    void
    make_wall_pattern();

    /// For the exact inclusion, the errors of the particle's motion and
    /// stresslet.
    void
    exact_inclusion_errors();

    /// Hand the mesh, a copy of the DoFs and the fluid unknowns to
    /// Result::fields (Settings::keep_fields).
    void
    keep_fields();

    /// @}

    /// The box's side along axis @p d (Settings::box_sides).
    double
    side(const unsigned int d) const
    {
      return s.box_sides.empty() ? 1. : s.box_sides.at(d);
    }

    /// Whether axis @p d is periodic.
    bool
    is_periodic(const unsigned int d) const
    {
      return std::find(periodic_axes.begin(), periodic_axes.end(), d) !=
             periodic_axes.end();
    }

    /// Whether this rank assembles the @p k-th of the cells (or faces) of
    /// one kind, in the order every rank walks them: round robin, so that
    /// the costly cut cells are shared as evenly as the full ones.
    bool
    mine(const unsigned int k) const
    {
      return k % n_ranks == this_rank;
    }

    /// Where @p cell lies relative to the particles: every loop asks.
    const Placement &
    placed(const cell_iterator &cell) const
    {
      return mesh->placement(cell);
    }

    /// Whether the face between @p cell and @p neighbour carries a ghost
    /// penalty: both have fluid, at least one is cut.
    bool
    ghost_pair(const cell_iterator &cell, const cell_iterator &neighbour) const
    {
      return cell->active_fe_index() == 0 &&
             neighbour->active_fe_index() == 0 &&
             (placed(cell).n_cut > 0 || placed(neighbour).n_cut > 0);
    }

    /// What one thread needs to assemble cells: a full cell's FEValues,
    /// its own generator of cut-cell quadratures, and per shape function
    /// the values at one quadrature point. A copy is built afresh.
    struct CellScratch
    {
      explicit CellScratch(const CutStokesSolve &solve);
      CellScratch(const CellScratch &other)
        : CellScratch(other.solve)
      {}
      const CutStokesSolve                 &solve;
      const hp::QCollection<1>              q1d;
      NonMatching::QuadratureGenerator<dim> generator;
      FEValues<dim>                         fe_fluid;
      std::vector<types::global_dof_index>  dofs;
      /// The volume terms' kernel (add_volume()).
      StokesVolumeKernel<dim> volume;
      /// The surface terms' factors and their product (add_nitsche()).
      FullMatrix<double> surface_left, surface_right, product;
    };

    /// One cell's matrices on its shape functions and its particle's rigid
    /// unknowns (extended indices), for distribute_cell().
    struct CellCopy
    {
      explicit CellCopy(const CutStokesSolve &solve);
      /// Whether the cell has fluid (and so anything to add), and whether
      /// it is in this rank's share (else it only writes K's held rows).
      bool                                 fluid = false, share = true;
      FullMatrix<double>                   local, local_pressure;
      std::vector<types::global_dof_index> ext_dofs;
      /// With the split: the other ranks whose velocity rows the cell
      /// writes, which receive its matrix instead of integrating it.
      const std::vector<unsigned int> *destinations = nullptr;
    };

    /// What one thread needs to assemble ghost-penalty faces.
    struct FaceScratch
    {
      explicit FaceScratch(const CutStokesSolve &solve);
      FaceScratch(const FaceScratch &other)
        : FaceScratch(other.solve)
      {}
      const CutStokesSolve &solve;
      static UpdateFlags
      flags()
      {
        return update_gradients | update_hessians | update_JxW_values |
               update_normal_vectors | update_quadrature_points;
      }
      const QGauss<dim - 1>                    q_face;
      FEFaceValues<dim>                        fe_face, fe_neighbour;
      FESubfaceValues<dim>                     fe_coarser;
      std::vector<types::global_dof_index>     dofs, neighbour_dofs;
      std::vector<std::array<unsigned int, 2>> local_of;
      const TaylorHoodLayout<dim>              layout;
      /// The cell's index k of each component-0 velocity function (its
      /// scalar phi_k), and the rank of each pressure function.
      std::vector<unsigned int> scalar_of, pressure_rank;
      /// Per side, the face's scalar (and pressure) function of each of
      /// the cell's; per face scalar, its unknowns on the dim components;
      /// per face pressure function, its unknown.
      std::array<std::vector<unsigned int>, 2>   scalar_id, pressure_id;
      std::vector<std::array<unsigned int, dim>> velocity_of;
      std::vector<unsigned int>                  pressure_of;
      /// The weighted jumps per point (columns) and their products.
      FullMatrix<double> velocity_jumps, pressure_jumps, velocity_part,
        pressure_part;
    };

    /// One ghost-penalty face's matrix on the union of its two cells'
    /// DoFs.
    struct FaceCopy
    {
      /// Whether the face is in this rank's share (else it only writes
      /// K's held rows).
      bool                                 share = true;
      FullMatrix<double>                   face_matrix;
      std::vector<types::global_dof_index> face_dofs;
    };

    /// The matrices of one fluid @p cell (none for a cell inside a
    /// particle): the volume terms and, if it is cut, the Nitsche terms.
    void
    assemble_cell(const cell_iterator &cell,
                  CellScratch         &scratch,
                  CellCopy            &copy) const;

    /// Add the fluid terms of one cell on the quadrature @p fe_values to
    /// the cell matrix and its pressure mass matrix.
    void
    add_volume(const FEValues<dim> &fe_values,
               CellScratch         &scratch,
               CellCopy            &copy) const;

    /// Add the Nitsche terms of the surface of ball @p P in the cut
    /// @p cell of size @p h, on the scratch generator's surface quadrature.
    void
    add_nitsche(const cell_iterator &cell,
                const Ball          &P,
                const double         h,
                CellScratch         &scratch,
                CellCopy            &copy) const;

    /// Add one cut cell's matrices to the global ones (distribute()).
    void
    distribute_cell(const CellCopy &copy);

    /// Add the matrix @p local and the pressure mass @p local_pressure of
    /// a cell with the unknowns @p dofs to the system, its right-hand side
    /// (the constraints' inhomogeneities), the constant pressure's mass
    /// and, for the iterative solver, the pressure mass matrix: the rows of
    /// rows_written() for a full cell. Safe from several threads for
    /// cells whose rows differ.
    void
    distribute(const FullMatrix<double>                   &local,
               const FullMatrix<double>                   &local_pressure,
               const std::vector<types::global_dof_index> &dofs,
               const bool                                  share = true);

    /// With the split K (#split_rows): whether adding a cell or face with
    /// the unknowns @p dofs writes a velocity row of K this rank holds.
    bool
    writes_held_rows(const std::vector<types::global_dof_index> &dofs) const;

    /// With the split K: the other ranks that hold velocity rows of K that
    /// adding @p cell writes (rows_written()), ascending.
    std::vector<unsigned int>
    border_destinations(const cell_iterator &cell) const;

    /// With the split K: this rank's range of K's rows and each rank's
    /// (#k_bounds, #p_bounds), from the rows' weights (by system index,
    /// ElementSparsity::row_weights()).
    void
    split_velocity_rows(const std::vector<std::size_t> &weight);

    /// With the split K: the rank that holds the velocity row of K of the
    /// unknown @p i (a velocity).
    unsigned int
    velocity_row_rank(const types::global_dof_index i) const;

    /// With the split K: the rank that integrates each cut cell, given the
    /// rank that holds each one's first velocity row (@p home): its home
    /// while the home has fewer than an even share of the cut cells, else
    /// the first rank below its share. The same on every rank.
    std::vector<unsigned int>
    balance_cut_cells(const std::vector<unsigned int> &home) const;

    /// Cut cells' matrices sent to another rank: their extended DoFs
    /// (n_ext each), then their n_ext × n_ext matrices.
    using PackedCells =
      std::pair<std::vector<types::global_dof_index>, std::vector<double>>;

    /// With the split K: send each rank the matrices of this rank's cut
    /// cells in @p outgoing, and add those received to the rows this rank
    /// holds (add_to_held_rows()). Collective.
    void
    add_cells_of_other_ranks(
      const std::map<unsigned int, PackedCells> &outgoing);

    /// With the split K: @p local's entries in the velocity rows of K this
    /// rank holds (a cell outside this rank's share that writes them).
    void
    add_to_held_rows(const FullMatrix<double>                   &local,
                     const std::vector<types::global_dof_index> &dofs);

    /// With the split K: the ranks' velocity rows' diagonal, gathered into
    /// #held_diagonal after the sum.
    void
    gather_velocity_diagonal();

    /// Add @p local on the unknowns @p dofs to the system through the
    /// constraints (into its blocks, or into the one matrix), and what its
    /// inhomogeneities move to the right-hand side with @p local_rhs.
    void
    add_to_system(const FullMatrix<double>                   &local,
                  const Vector<double>                       &local_rhs,
                  const std::vector<types::global_dof_index> &dofs);

    /// The system's diagonal entry of row @p i.
    double
    system_diagonal(const unsigned int i) const
    {
      if (split_rows && blocks->kind[i] == 0)
        return velocity_diagonal[i];
      return blocks ? blocks->diag_element(i) : matrix.diag_element(i);
    }

    /// The rows of the global matrices that adding a full @p cell writes:
    /// its DoFs and those its constrained ones stand for.
    std::vector<types::global_dof_index>
    rows_written(const cell_iterator &cell) const;

    /// The ghost-penalty matrix of one face.
    void
    assemble_face(const GhostFace &ghost,
                  FaceScratch     &scratch,
                  FaceCopy        &copy) const;

    /// The symmetric diagonal scaling of the system, applied to the
    /// matrix: velocity and rigid unknowns by their diagonal, pressures by
    /// the diagonal of B diag(A)^-1 B^T.
    void
    scale_system();

    /// Whether the pressure at @p x lies in a thin gap
    /// (Settings::gap_threshold).
    bool
    in_thin_gap(const Point<dim> &x) const;

    /**
     * Fill @p scaled_solution with the previous solve's fields on this
     * mesh (Settings::initial_guess, CutInitialGuess), scaled as the
     * system is; the constrained unknowns with their rows' values. False,
     * and nothing written, without a previous solve of the same box and
     * number of particles.
     */
    bool
    initial_guess(const typename CutSaddlePointSolver<dim>::Layout &layout,
                  const Vector<double>                             &scaled_rhs,
                  Vector<double> &scaled_solution) const;

    /// The iterative solve of the scaled system: FGMRES with a block
    /// preconditioner (CutSaddlePointSolver); @p residual is A' x' - b'.
    void
    solve_iterative(const Vector<double> &scaled_rhs,
                    Vector<double>       &scaled_solution,
                    Vector<double>       &residual);

    /// dst = (A' - m' m'^T) src: the scaled system with the pressure's
    /// mean fixed, as both solvers solve it.
    void
    apply_system(Vector<double> &dst, const Vector<double> &src) const
    {
      matrix.vmult(dst, src);
      dst.add(-(scaled_mean * src), scaled_mean);
    }

    /// Whether the direct solver may factorise the system as symmetric
    /// (Settings::symmetric_factorisation, and every rigid coupling
    /// symmetric).
    bool
    system_is_symmetric() const;

    /// The direct solve of the scaled system over the ranks, MUMPS
    /// (MumpsSolver) with iterative refinement; @p residual is
    /// A' x' - b'.
    void
    solve_direct(const Vector<double> &scaled_rhs,
                 Vector<double>       &scaled_solution,
                 Vector<double>       &residual);

    /// Add the moments of the traction on ball @p P over its surface in
    /// the cut @p cell (on the generator's surface quadrature) to the
    /// stresslet of its particle, and those of the normal to
    /// @p normal_moment.
    void
    measure_surface(const cell_iterator                  &cell,
                    const Ball                           &P,
                    std::vector<SymmetricTensor<2, dim>> &normal_moment);

    /// The clock of the whole solve.
    Timer timer;
    /// The scene and the discretisation's parameters.
    const Settings &s;
    /// The particles of the settings.
    const std::vector<Particle> &particles;
    /// Viscosity and shear rate.
    const double eta, g;
    /// Sliding walls; the exact inclusion.
    const bool periodic, exact_case;
    /// The ranks that share the solve and this one's number among them
    /// (Settings::communicator; 1 and 0 without MPI).
    unsigned int n_ranks = 1, this_rank = 0;
    /// The periodic axes (every one but y between sliding walls).
    std::vector<unsigned int> periodic_axes;
    /// What the solve gives, filled stage by stage.
    Result result;

    /// The mesh, and where its cells lie.
    std::unique_ptr<const CutMesh<dim>> mesh;
    /// Taylor-Hood Q2-Q1 in the fluid, nothing inside the particles.
    const FESystem<dim>         taylor_hood;
    const FESystem<dim>         nothing;
    const hp::FECollection<dim> fe_collection;
    /// Shape functions of a fluid cell.
    const unsigned int               n_local;
    const FEValuesExtractors::Vector velocity;
    const FEValuesExtractors::Scalar pressure;
    const MappingCartesian<dim>      mapping;
    DoFHandler<dim>                  dof_handler;
    /// Fluid unknowns, and all of them (fluid and rigid).
    unsigned int n_fluid = 0, n_total = 0;
    /// The exact solution around the first particle.
    std::unique_ptr<const ExactRigidInclusion<dim>> exact;
    AffineConstraints<double>                       constraints;
    std::vector<GhostFace>                          ghost_faces;
    /// DoF indices of a cell and of its neighbour.
    std::vector<types::global_dof_index> dofs, neighbour_dofs;

    /// The system: one matrix (the direct solver, the AMG), or its
    /// blocks (the iterative solver with the multigrid; the pattern is
    /// then freed once they are made).
    RowPattern                       sparsity;
    SparseMatrix<double>             matrix;
    std::unique_ptr<CutSystemBlocks> blocks;
    /// Between sliding walls, the rows of the matrix without the
    /// constraints that the walls' stress reads (wall_rows; the others
    /// hold their diagonal only, zero), on their own pattern.
    RowPattern           wall_sparsity;
    SparseMatrix<double> unconstrained;
    /// Between sliding walls, the test functions of the walls' stress
    /// (side 0: y = 0, 1: y = H; one per component) and the rows where
    /// any is not zero.
    std::array<std::array<Vector<double>, dim>, 2> wall_phi;
    std::vector<bool>                              wall_rows;
    /// Whether the system is solved iteratively, and whether as the blocks
    /// of CutSystemBlocks (with the multigrid).
    bool iterative = false, as_blocks = false;
    /// On more than one rank with the multigrid: K's velocity rows split
    /// among the ranks, each holding the range [k_first, k_end) of K's
    /// rows (CutSystemBlocks::reinit()); and the velocity rows' diagonal,
    /// gathered from the ranks (by system index).
    bool         split_rows = false;
    unsigned int k_first = 0, k_end = 0;
    /// With the split, where each rank's rows of K start (and n_k last),
    /// and its pressures (and n_p last).
    std::vector<unsigned int> k_bounds, p_bounds;
    Vector<double>            velocity_diagonal;
    /// With the split, the velocity rows (by system index) in that range.
    std::vector<bool> held_velocity_rows;
    /// The pressure mass matrix over the fluid (iterative solver only).
    RowPattern           mass_sparsity;
    SparseMatrix<double> pressure_mass;
    /// The pressure mass of the constant pressure, m_i = int phi_i / eta
    /// over the fluid (zero but on the unconstrained pressures), and m'
    /// = D m / (1^T m)^(1/2) of the scaled system (solve_linear_system()).
    Vector<double> pressure_mean, scaled_mean;
    /// The pressure shape functions of a fluid cell.
    std::vector<unsigned int> pressure_shapes;
    Vector<double>            rhs, solution;

    /// The extended indices of a fluid cell (its shape functions and its
    /// particle's rigid unknowns); the pressure DoFs of a cell.
    unsigned int                         n_ext = 0;
    std::vector<types::global_dof_index> pressure_dof_indices;
    /// A full fluid cell's matrix (on its own DoFs) and pressure mass
    /// matrix, per level.
    std::map<int, std::pair<FullMatrix<double>, FullMatrix<double>>> full_cells;

    /// The cut cells' quadratures, for the stresslets after the solve.
    std::unique_ptr<const hp::QCollection<1>>              q1d;
    std::unique_ptr<NonMatching::QuadratureGenerator<dim>> generator;
    /// The unit box, the reference cell of the cut cells' level sets.
    const BoundingBox<dim> unit_box;
    /// The quadrature of a full cell.
    const QGauss<dim> q_cell;
    /// What the surface quadratures evaluate.
    const UpdateFlags surface_flags;

    /// Which unknowns are pressures, and the system's scaling.
    std::vector<bool> is_pressure;
    Vector<double>    scale;
  };
} // namespace Fidus

#endif
