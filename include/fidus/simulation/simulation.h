#ifndef fidus_simulation_simulation_h
#define fidus_simulation_simulation_h

#include <array>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <fidus/contact/contact_projector.h>
#include <fidus/contact/lubrication_correction.h>
#include <fidus/core/parameters.h>
#include <fidus/core/shear_rate.h>
#include <fidus/core/warning_log.h>
#include <fidus/fluid/boundary_velocity.h>
#include <fidus/fluid/exact_rigid_inclusion.h>
#include <fidus/fluid/stokes_solver.h>
#include <fidus/io/csv_writer.h>
#include <fidus/io/field_output.h>
#include <fidus/io/particle_output.h>
#include <fidus/mesh/mesh_refiner.h>
#include <fidus/particles/particle_force_density.h>
#include <fidus/particles/solid_indicator.h>
#include <fidus/rheology/hydrodynamic_stress.h>
#include <fidus/rheology/suspension_stress.h>
#include <fidus/simulation/box_geometry.h>
#include <fidus/simulation/checkpoint.h>
#include <fidus/simulation/gap_time_step.h>
#include <fidus/simulation/run_state.h>
#include <memory>
#include <string>
#include <vector>

namespace Fidus
{
  /// Summary of a run, for tests and benchmarks.
  struct RunSummary
  {
    unsigned int n_steps    = 0;
    double       final_time = 0.;
    /// State after the last step.
    std::vector<std::array<double, 3>> positions, velocities, omegas;
    /// Smallest gap between particles over the whole run (pairs only).
    double min_gap = 0.;
    /// Smallest normalised distance of particles 0 and 1 over the run.
    double min_normalised_distance = 0.;
    /// Largest Uzawa and linear iteration counts of any step.
    unsigned int max_uzawa_iterations = 0, max_linear_iterations = 0;
    /// Largest rigidity residual of any step.
    double max_rigidity_residual = 0.;
    /// Steps whose Uzawa loop or contact projection did not reach its
    /// tolerance (each was reported as a warning), and the largest number
    /// of dual-solver iterations of any projection.
    unsigned int uzawa_failures = 0, contact_failures = 0,
                 max_contact_iterations = 0;
    /// Largest number of shared cells of a solve (their solid released)
    /// and the largest rigidity residual in them.
    unsigned int max_shared_cells    = 0;
    double       max_shared_residual = 0.;
    /// Largest StokesSolver::multigrid_galerkin_defect() of the run.
    double multigrid_galerkin_defect = 0.;
    /// Cells and DoFs of the last solve.
    unsigned long long n_cells = 0, n_dofs = 0;
    /// Errors of the 'exact rigid inclusion' scene (else 0): L2 and H1 of u
    /// on the fluid part, |omega + g/2| / (g/2) and |U| / (g a).
    double u_l2_error = 0., u_h1_error = 0., omega_error = 0.,
           translation_error = 0.;
    /// L2 norm of the exact velocity on the same region (same scene).
    double u_l2_norm = 0.;
    /// Wall seconds of the whole run (earlier parts of a resumed run
    /// included).
    double wall_seconds = 0.;
    /// The signal that stopped the run before its End time (0: none).
    int stop_signal = 0;
    /// Stress of the last step: the statistics.csv columns, the
    /// hydrodynamic stress of the box by volume average and at the walls
    /// (3 x 3, row-major; NaN where a wall direction is missing), the box's
    /// mean strain rate, its solid fraction and every particle's stresslet
    /// (xx, xy, xz, yy, yz, zz).
    SuspensionStress                   stress;
    std::array<double, 9>              hydrodynamic_stress{}, wall_stress{};
    std::array<double, 9>              mean_strain_rate{};
    double                             solid_fraction = 0.;
    std::vector<std::array<double, 6>> stresslets;
  };

  /**
   * The time loop of fidus (numerics sections 5 and 6) for one scene: the
   * only place that knows the order of the stages. Each stage is a member
   * function; what passes from one step to the next is the RunState, which
   * a checkpoint saves with the mesh. run() reads as the algorithm:
   *
   *   predict the velocities at the initial positions, write step 0
   *   (or resume from a checkpoint);
   *   while the End time is not reached:
   *     choose the time step;
   *     extrapolate the rigid velocities (AB2);
   *     with the trapezoidal scheme, average them with the velocities
   *       solved at the positions they reach (predictor-corrector; that
   *       solve then stands for the one after the move);
   *     add the sub-grid lubrication (when on);
   *     project them onto the admissible set K (contact, glue);
   *     advance the particles;
   *     refine the mesh if the particles moved (fictitious domain);
   *     solve the fluid (penalised Stokes, Uzawa);
   *     extract each particle's rigid velocity;
   *     measure the stress, write the output;
   *     checkpoint when due, stop when a signal asked for it.
   *
   * The fluid and contact modules never see each other.
   */
  template <int dim>
  class Simulation
  {
  public:
    /// @p parameters must have passed Parameters::parse(). With @p resume
    /// (checked by Checkpoint::find_and_check) the run continues from that
    /// checkpoint; both must outlive the object.
    explicit Simulation(const Parameters              &parameters,
                        const Checkpoint::ResumePoint *resume = nullptr);
    ~Simulation();

    /// Run the scene; output goes to the output directory.
    RunSummary
    run();

  private:
    /// Step 0: the initial state, its velocities and output.
    void
    start();
    /// Load the checkpoint's mesh, multiplier and state; continue the
    /// output files from its step.
    void
    resume_from_checkpoint();
    /// Whether the End time is reached.
    bool
    finished() const;
    /// Fixed, or CFL-limited by the fastest particle (numerics section 5);
    /// then cut to the closing and opening gaps (Time stepping/Gap step
    /// fraction).
    double
    choose_time_step() const;
    /// AB2 extrapolation of U / shear rate to the middle of the step.
    void
    extrapolate_velocities(double dt);
    /// Time stepping/Scheme = trapezoidal: replace the extrapolated
    /// velocities by the mean of the velocities at the start of the step
    /// and those solved at the positions the step reaches (Trapezoidal
    /// iterations passes of a fixed-point iteration from the AB2
    /// prediction); nothing to do with AB2.
    void
    average_with_end_of_step_velocities(double dt);
    /// Sub-grid lubrication: the squeeze resistance of gaps below the
    /// mesh scale, added implicitly to the extrapolated velocities
    /// (Fluid/Lubrication correction; nothing to do without it).
    void
    add_lubrication(double dt);
    /// Contact: projection of the extrapolated velocities onto K.
    void
    project_onto_admissible_set(double dt);
    /// The projection of a trapezoidal step: glued pairs take their
    /// normals at the middle of the step, repeated until that middle is
    /// the one the corrected velocities reach.
    Contact::ProjectionStatistics
    project_with_normals_at_middle(const std::vector<RunState::Vec3> &predicted,
                                   double                             dt);
    /// Move and turn the particles; wrap periodic faces; stop the run if
    /// a particle crossed a face where it cannot stay.
    void
    advance_particles(double dt);
    /// Adapt the mesh to particles at @p X, unless they moved little since
    /// the last remesh.
    void
    refine_mesh_if_particles_moved(const std::vector<RunState::Vec3> &X);
    /// Penalised Stokes with the rigidity multiplier (Uzawa) and the shear
    /// rate @p g; a loop that stops short is reported for @p step, with
    /// @p where saying which solve it was.
    void
    solve_fluid(double g, unsigned int step, const std::string &where);
    /// Fluid/Model = cut finite element: the rigid velocities @p U, @p W
    /// of particles at @p X under the shear rate @p g from one cut-element
    /// solve on a mesh built for them (CutStokesInclusion), with every gap
    /// at least Fluid/Cut minimum gap; trouble is reported for @p step.
    void
    solve_cut_finite_element(const std::vector<RunState::Vec3> &X,
                             double                             g,
                             unsigned int                       step,
                             const std::string                 &where,
                             std::vector<RunState::Vec3>       &U,
                             std::vector<RunState::Vec3>       &W);
    /// The rigid velocity (U, omega) of each particle from the fluid.
    void
    extract_rigid_motion(std::vector<RunState::Vec3> &U,
                         std::vector<RunState::Vec3> &W);
    /// Rigid velocities @p U, @p W of particles at @p X under the shear
    /// rate @p g: the three stages above, or the undisturbed shear flow at
    /// the centres.
    void
    rigid_velocities_at(const std::vector<RunState::Vec3> &X,
                        double                             g,
                        unsigned int                       step,
                        const std::string                 &where,
                        std::vector<RunState::Vec3>       &U,
                        std::vector<RunState::Vec3>       &W);
    /// Velocities at the current positions and time (rigid_velocities_at),
    /// or, after trapezoidal passes, those of the last pass.
    void
    predict_velocities();
    /// The suspension's stress: hydrodynamic from the fluid solve, contact
    /// and lubrication from the step of length @p dt that led to it (0 at
    /// the start); at a jump of the shear rate, the row describes the
    /// instant just before the jump (doc/rheology.md).
    void
    measure_stress(double dt);
    /// CSV rows, VTU/VTP output and the progress line of this step.
    void
    write_output(double dt);
    /// Write a checkpoint when one is due; true when a signal asked the run
    /// to stop (a checkpoint is then written first).
    bool
    checkpoint_or_stop();
    /// Write a checkpoint of the current step (collective).
    void
    write_checkpoint();
    /// The 'exact rigid inclusion' scene: error norms of step 0.
    void
    report_exact_solution_errors();
    /// Wall seconds of the run so far, earlier parts included.
    double
    elapsed_wall_seconds() const;

    const Parameters                    &prm;
    const Checkpoint::ResumePoint       *resume;
    const MPI_Comm                       comm;
    const bool                           root;
    dealii::ConditionalOStream           pcout;
    std::unique_ptr<dealii::TimerOutput> timer;
    dealii::Timer                        wall_clock;

    const BoxGeometry<dim> box;
    const ShearRate        shear;
    const bool             fictitious;
    /// Fluid/Model = cut finite element (no persistent mesh: one is built
    /// for every solve).
    const bool         cut;
    const unsigned int n;
    /// Radii of the held solid (Fluid/Solid retraction); the contact model
    /// uses the particles' radii.
    std::vector<double> solid_radii;

    Contact::Settings         contact_settings;
    Contact::ContactProjector projector;
    /// The gap limit of the step (null: Gap step fraction 0).
    std::unique_ptr<GapTimeStep>                    gap_step;
    std::unique_ptr<Contact::LubricationCorrection> lubrication;

    std::unique_ptr<dealii::parallel::distributed::Triangulation<dim>> tria;
    std::unique_ptr<StokesSolver<dim>>                                 solver;
    std::unique_ptr<MeshRefiner<dim>>                                  refiner;
    std::unique_ptr<ExactRigidInclusion<dim>>                          exact;
    /// Body force of Particles/External force (null for force-free
    /// particles).
    std::unique_ptr<ParticleForceDensity<dim>> external_force;
    std::unique_ptr<HydrodynamicStress<dim>>   hydrodynamic_stress;
    BoundaryVelocity<dim>                      boundary;
    SolidIndicator<dim>                        solid;

    std::unique_ptr<CsvWriter>        particles_csv, statistics_csv;
    std::unique_ptr<ParticleOutput>   particle_output;
    std::unique_ptr<FieldOutput<dim>> field_output;
    WarningLog                        warnings;

    /// What passes from step to step (saved by checkpoints).
    RunState state;

    /// This step's work, for its output row.
    typename StokesSolver<dim>::Statistics fluid_stats;
    bool                                   remeshed = false;
    /// Cells, unknowns and stress of the last cut-element solve.
    unsigned long long                       cut_cells = 0, cut_dofs = 0;
    typename HydrodynamicStress<dim>::Result cut_stress;
    /// The trapezoidal passes of this step: the velocities of the last
    /// (the end of the step's, until predict_velocities() takes them),
    /// their iterations summed and whether one of them remeshed.
    std::vector<RunState::Vec3> U_end, W_end;
    /// The middle of the step the last pass reached, where glued pairs
    /// take their normals in the next projection (empty outside a
    /// trapezoidal step).
    std::vector<RunState::Vec3> X_mid;
    /// Set while a trapezoidal pass places its solve: its lubrication and
    /// projection are trials, whose trouble the step's final ones report.
    bool                                   trial_pass    = false;
    bool                                   passes_solved = false;
    typename StokesSolver<dim>::Statistics pass_stats;
    bool                                   pass_remeshed = false;
    unsigned int n_active = 0, n_glued = 0, contact_iterations = 0;
    /// Extrapolated, lubricated and contact-corrected velocities.
    std::vector<RunState::Vec3> u_star, w_star, u_lubricated, w_lubricated,
      u_corrected;
    Contact::LubricationStatistics           lubrication_stats;
    typename HydrodynamicStress<dim>::Result hydrodynamic;
    SuspensionStress                         stress;
    /// Force per unit velocity of a contact correction (Contact/Drag
    /// coefficient, or the Stokes drag).
    double contact_drag = 0.;

    /// Wall clock of the last progress line and checkpoint.
    double last_progress_wall = -1., last_checkpoint_wall = 0.;
    /// Errors of the exact-solution scene (step 0).
    RunSummary exact_errors;
    /// Signal that stopped the run (0: none).
    int stop_signal = 0;
  };

  /// Run a scene in its dimension (picks Simulation<2> or <3>), from the
  /// start or from @p resume.
  RunSummary
  run_simulation(const Parameters              &parameters,
                 const Checkpoint::ResumePoint *resume = nullptr);
} // namespace Fidus

#endif
