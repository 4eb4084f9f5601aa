#ifndef fidus_fluid_cut_stokes_inclusion_h
#define fidus_fluid_cut_stokes_inclusion_h

#include <cstddef>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <memory>
#include <mpi.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  template <int dim>
  struct CutFields;

  /**
   * A cut finite element solver for rigid particles held in Stokes flow in
   * a box of unit cells (the unit box by default): the exact rigid inclusion
   * (one force- and torque-free particle in linear shear, ExactRigidInclusion),
   * the reference case of the converged-answers work, and a few particles
   * pushed by forces or carried by a shear, for the squeeze of a thin gap; and,
   * with the particles where the time loop has them, the predictor of
   * 'Fluid/Model = cut finite element' (doc/cut_element.md).
   *
   * The fictitious-domain predictor of the time loop holds the cut cells
   * rigid, so a particle acts like a body between itself and the staircase
   * of its cut cells, and its rigid velocity stops converging near 1e-3 to
   * 1e-4 (doc/uzawa.md). Here the fluid lives only outside the particle: the
   * Taylor-Hood Q2-Q1 field of a cut cell is integrated over its fluid part
   * only (deal.II's NonMatching::QuadratureGenerator on the exact circle or
   * sphere), the rigid motion U + omega x (x - X) is imposed on the surface
   * by Nitsche's method, with U and omega as unknowns of the same symmetric
   * system (so the particle is force- and torque-free weakly, the
   * consistency terms being its traction), and ghost penalties on the faces
   * of cut cells keep the system well conditioned however small the fluid
   * part of a cell is (Burman & Hansbo 2014; Guzman & Olshanskii 2018 for
   * Taylor-Hood). Cells inside the particle carry no unknowns
   * (FE_Nothing). The box boundary takes the exact velocity, or, with
   * sliding walls, the walls y = 0, H take the shear's velocity and the
   * other axes are periodic (CutMesh matches the faces cell for cell).
   * Stokes flow is invariant under translation and scaling, so a box of
   * any size is solved with its shortest side as the length unit
   * (CutElementModel scales it).
   *
   * It solves one serial system, on a mesh built for the particles given:
   * with a sparse direct solver in 2D, and iteratively
   * (CutSaddlePointSolver) in 3D, where the factorisation is the limit.
   */
  template <int dim>
  class CutStokesInclusion
  {
  public:
    /// One rigid particle.
    struct Particle
    {
      /// Centre, in the box (any value along a periodic axis).
      Point<dim> center;
      /// Radius.
      double radius = 0.1;
      /// External force on it (none: force-free).
      Tensor<1, dim> force;
    };

    /// The velocity the box's boundary takes.
    enum class Boundary
    {
      /// The exact solution around one force-free particle
      /// (ExactRigidInclusion); needs exactly one particle.
      exact_inclusion,
      /// g (y - H/2) e_x, H the box's height (at rest for g = 0).
      linear_shear,
      /// g (y - H/2) e_x on the walls y = 0 and y = H, periodic along
      /// every other axis (a particle may cross those faces).
      sliding_walls
    };

    /// How the linear system is solved.
    enum class LinearSolver
    {
      /// Iterative in 3D above 15 000 unknowns on one rank, where the
      /// factorisation is slower and takes more memory
      /// (doc/theory/cut_element.md, "Solvers"); direct otherwise.
      automatic,
      /// MUMPS (MumpsSolver), LDL^T of the symmetric system, over the
      /// ranks of Settings::communicator, with iterative refinement.
      direct,
      /// FGMRES with a block preconditioner (CutSaddlePointSolver).
      iterative
    };

    /// What stands for the inverse of the velocity block in the iterative
    /// solver.
    enum class VelocityPreconditioner
    {
      /// One ML AMG cycle.
      amg,
      /// One cycle of the geometric multigrid (CutVelocityMultigrid).
      multigrid
    };

    /**
     * A resistance among the rigid unknowns of one or two particles, added
     * to the system: the sub-grid lubrication of a gap narrower than the
     * one the fluid sees (Fluid/Lubrication correction). Its unknowns are
     * those of each particle of @p owners in turn: U, then omega (omega_z
     * in 2D). The particles' rows then balance the fluid's traction, the
     * external force and the resistance's load -matrix x + load (@p load:
     * that of a moving wall at rest particles).
     */
    struct RigidCoupling
    {
      std::vector<unsigned int> owners;
      /// Square, of size owners.size() times the rigid unknowns per
      /// particle (dim (dim + 1) / 2).
      std::vector<std::vector<double>> matrix;
      std::vector<double>              load;
    };

    /// The scene and the discretisation's parameters.
    struct Settings
    {
      /// Resistances among the rigid unknowns (none by default).
      std::vector<RigidCoupling> couplings;
      /// The particles (they must not overlap, nor touch the box's walls;
      /// along periodic axes the gaps are taken to the nearest image).
      std::vector<Particle> particles;
      /// The box's velocity.
      Boundary boundary = Boundary::exact_inclusion;
      /// Shear rate g of the far field g (y - y_c) e_x (y_c the particle's
      /// centre for the exact inclusion, H/2 otherwise).
      double shear_rate = 1.;
      /// Fluid viscosity.
      double viscosity = 1.;
      /// The box [0, L_0] x ... x [0, L_{dim-1}], every side at least 1
      /// (the shortest side is the length unit; CutMesh divides it into
      /// coarse cells of about unit size); empty: the unit box.
      std::vector<double> box_sides;
      /// Global refinement of the box's coarse cells.
      unsigned int global_level = 4;
      /// Further levels in a band around the particle surface (the band
      /// reaches band_cells cells of each new level beyond the surface, so
      /// that every cut cell and its neighbours are on the finest level).
      unsigned int band_levels = 0;
      /// Width of that band in cells of the level being refined.
      double band_cells = 3.;
      /// Nitsche parameter: the penalty is nitsche * viscosity / h. At 40
      /// the velocity block lost its positive definiteness on some cut
      /// cells of pairs whose line of centres is not on a mesh diagonal,
      /// and FGMRES stalled (doc/theory/cut_element.md, "The Nitsche
      /// parameter").
      double nitsche = 100.;
      /// Ghost penalty of the velocity, times viscosity h^(2k-1) for the
      /// jumps of the k-th normal derivatives, k = 1, 2.
      double ghost_velocity = 1e-3;
      /// Ghost penalty of the pressure, times h^3 / viscosity for the jump
      /// of the normal derivative.
      double ghost_pressure = 1e-3;
      /// Gauss points per direction of the cut-cell quadratures.
      unsigned int quadrature_points = 4;
      /// A cut cell closer than this many of its own sizes to another
      /// particle's surface is refined (so that a thin gap has cells across
      /// it); 0 refines only cells cut by two particles, which must be.
      double gap_cells = 0.;
      /// At most this many levels beyond global_level + band_levels for
      /// those refinements.
      unsigned int max_gap_levels = 14;
      /// The linear solver.
      LinearSolver linear_solver = LinearSolver::automatic;
      /// The direct solver factorises the system as symmetric (MUMPS's
      /// LDL^T from one triangle: about half the time and memory of LU).
      /// Every term is (the symmetric Nitsche form, the ghost penalties,
      /// the constraints, the pressure's mean); a rigid coupling that is
      /// not makes it LU whatever this says. false: LU.
      bool symmetric_factorisation = true;
      /// Relative residual of the diagonally scaled system at which the
      /// iterative solver stops (fidus sets it from Fluid/Cut linear
      /// tolerance; 1e-10 here, the benchmarks' and tests' value).
      double iterative_tolerance = 1e-10;
      /// FGMRES iterations after which the iterative solver gives up (and
      /// throws, naming the residual reached).
      unsigned int iterative_max_iterations = 2000;
      /// The velocity block's preconditioner in the iterative solver.
      VelocityPreconditioner velocity_preconditioner =
        VelocityPreconditioner::multigrid;
      /// Weight of the thin gaps' pressure Laplacian in the iterative
      /// solver's pressure preconditioner
      /// (CutSaddlePointSolver::build_gap_laplacian()); 0: the pressure
      /// mass alone. 0.01 to 0.03 gave the fewest FGMRES iterations on
      /// pairs at gaps from 0.5 a to 0.001 a (doc/theory/cut_element.md,
      /// "The pressure side").
      double gap_laplacian = 0.01;
      /// A pressure is in a thin gap where the distances from it to its two
      /// nearest surfaces (particles or walls) add up to less than this
      /// many reduced radii a1 a2 / (a1 + a2) (a wall's radius infinite).
      /// From 0.25 to 2 the 2D pairs' counts were the same to an
      /// iteration; the smallest region is the cheapest to set up.
      double gap_threshold = 0.25;
      /// Cut-cell blocks in the multigrid's smoother (CutCellBlockJacobi);
      /// false: point Jacobi, as before they were added (for comparisons).
      bool cut_cell_blocks = true;
      /// Matrix-vector products per smoothing of the velocity multigrid,
      /// before and after (CutVelocityMultigrid::Settings).
      unsigned int smoother_degree = 2;
      /// The velocity multigrid's cycle in single precision
      /// (CutVelocityMultigrid::Settings); false: double (for comparisons).
      bool single_precision_cycle = true;
      /// The velocity multigrid's levels built without the couplings
      /// between velocity components
      /// (CutVelocityMultigrid::Settings::separate_components); false:
      /// the full block. On in 3D, where it took a quarter off a solve
      /// (more iterations, each cheaper); off in 2D, where it saved no
      /// time and took a fifth more iterations (doc/theory/cut_element.md,
      /// "Solvers").
      bool separate_components = dim == 3;
      /// Bytes the solve may use in all, > 0; 0: what the machine has
      /// available (MemoryBudget). A mesh whose system would not fit
      /// (estimated from its unknowns) throws, naming what to change,
      /// before its system is built.
      double memory_limit = 0.;
      /// Keep the mesh, the DoFs and the solution for output
      /// (Result::fields).
      bool keep_fields = false;
      /// The previous solve's fields (Result::fields of a solve with
      /// keep_fields), from which the iterative solver starts
      /// (CutInitialGuess); null, or a different box or number of
      /// particles: it starts from zero. The direct solver ignores it.
      std::shared_ptr<const CutFields<dim>> initial_guess;
      /// The ranks that share the solve, all with the same settings. Every
      /// rank builds the same mesh and DoFs and ends with the same
      /// answer; the cells and faces are assembled in shares and summed,
      /// and the direct solver factorises over the ranks. The iterative
      /// solver runs on one rank (more throw; 'automatic' is direct on
      /// more). MPI must be started for more than one rank.
      MPI_Comm communicator = MPI_COMM_SELF;
    };

    /// What one solve gives.
    struct Result
    {
      /// Each particle's velocity U and angular velocity omega (only the
      /// third component in 2D).
      std::vector<Tensor<1, dim>> velocity;
      std::vector<Tensor<1, 3>>   angular_velocity;
      /// For the exact inclusion: |omega - omega_exact| / (g/2) (omega_z in
      /// 3D).
      double omega_error = 0.;
      /// For the exact inclusion: |U| / (g a); the exact particle does not
      /// translate.
      double translation = 0.;
      /// For the exact inclusion: |dev S - S_exact| / |S_exact| (Frobenius
      /// norms; the isotropic part depends on the reference pressure),
      /// with the unbounded stresslet S_exact = 4 pi eta a^2 E in 2D and
      /// (20/3) pi eta a^3 E in 3D, E the far field's strain rate.
      double stresslet_error = 0.;
      /// For the exact inclusion: ||u - u_exact||_{L2(fluid)} / (g a
      /// |fluid|^(1/2)).
      double velocity_error = 0.;
      /// Each particle's stresslet: int over its surface of
      /// sym((x - X) (x) t), t the consistent traction the fluid exerts on
      /// it (the one its force and torque balance), with the pressure
      /// taken relative to the fluid's mean (doc/cut_element.md, "The
      /// stress"). In 2D per unit length.
      std::vector<SymmetricTensor<2, dim>> stresslets;
      /// Mean pressure over the fluid, and the fluid's volume.
      double fluid_pressure = 0., fluid_volume = 0.;
      /// For sliding walls: the mean of sigma e_y over the wall y = H and
      /// over the wall y = 0, from the consistent residual of the walls'
      /// velocity DoFs, the pressure taken relative to the fluid's mean
      /// (doc/cut_element.md, "Periodic faces"); NaN otherwise. Both equal
      /// the box's mean stress sigma e_y when the particles are force-free.
      Tensor<1, dim> top_wall_stress, bottom_wall_stress;
      /// Unknowns (fluid and rigid), active cells, cut cells.
      unsigned int n_dofs = 0, n_cells = 0, n_cut_cells = 0;
      /// Entries of the system's sparsity pattern.
      std::size_t n_entries = 0;
      /// Refinement flags set for thin gaps, over all passes, and for
      /// matching the periodic faces.
      unsigned int n_gap_refinements = 0, n_periodic_refinements = 0;
      /// Finest cell size.
      double h = 0.;
      /// ||A x - b|| / ||b|| of the solve.
      double residual = 0.;
      /// Whether the direct solver factorised the system as symmetric
      /// (LDL^T; Settings::symmetric_factorisation).
      bool symmetric_factorisation = false;
      /// FGMRES iterations, and CG iterations of its setup, of the
      /// iterative solver (0 for the direct one).
      unsigned int n_iterations = 0, n_setup_iterations = 0;
      /// Wall seconds of the whole solve (setup, assembly, factorisation).
      double seconds = 0.;
      /// The iterative solver's initial residual over the right-hand
      /// side's (1 from zero; below it from Settings::initial_guess).
      double initial_residual = 1.;
      /// Whether the iterative solver solved (n_iterations may be 0 when
      /// its start meets the tolerance).
      bool iterative = false;
      /// Wall seconds of its stages: the mesh (built and its cells
      /// placed), the DoFs (constraints, ghost-penalty faces, sparsity
      /// pattern, matrices allocated), the assembly (cells, ghost
      /// penalties, sub-grid couplings), the linear solve (scaling,
      /// factorisation or preconditioner set-up, and FGMRES) and the
      /// measurement (rigid motions, stresslets, walls, fields). They add
      /// up to #seconds, less the settings' check. Of the solve, the
      /// FGMRES iterations alone (0 with the direct solver); the rest of
      /// it is the set-up (scaling, multigrid hierarchy or factorisation).
      struct StageSeconds
      {
        double mesh = 0., dofs = 0., assembly = 0., solve = 0., measure = 0.;
        double fgmres = 0.;
        /// Of solve, the iterative solver's set-up: the blocks, the
        /// pressure's preconditioner, the velocity's.
        double blocks = 0., pressure = 0., velocity = 0.;
      } stage_seconds;
      /// With Settings::keep_fields, the mesh, DoFs and solution (else
      /// null).
      std::shared_ptr<const CutFields<dim>> fields;
    };

    /// Build the mesh, assemble, solve and measure for @p settings.
    static Result
    solve(const Settings &settings);
  };
} // namespace Fidus

#endif
