#ifndef fidus_simulation_simulation_h
#define fidus_simulation_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <fidus/contact/contact_projector.h>
#include <fidus/core/parameters.h>
#include <fidus/core/shear_rate.h>
#include <fidus/core/warning_log.h>
#include <fidus/fluid/fluid_model.h>
#include <fidus/io/csv_writer.h>
#include <fidus/io/particle_output.h>
#include <fidus/lubrication/lubrication_correction.h>
#include <fidus/rheology/suspension_stress.h>
#include <fidus/simulation/box_geometry.h>
#include <fidus/simulation/checkpoint.h>
#include <fidus/simulation/gap_time_step.h>
#include <fidus/simulation/run_state.h>
#include <fidus/simulation/run_summary.h>
#include <fidus/time_stepping/time_scheme.h>
#include <memory>
#include <string>
#include <vector>

namespace Fidus
{
  /**
   * The time loop of fidus for one scene: the only place that knows the
   * order of the stages. Each stage is a member function with its timer;
   * what passes from one step to the next is the RunState, which a
   * checkpoint saves with the fluid model's part. run() reads as the
   * algorithm:
   *
   *   solve the fluid at the initial positions, write step 0
   *   (or resume from a checkpoint);
   *   while the End time is not reached:
   *     choose the time step (CFL, gaps);
   *     predict the velocities of the step (the time scheme: AB2, or the
   *       trapezoidal predictor-corrector, which solves the fluid where the
   *       step leads);
   *     add the sub-grid lubrication (when on);
   *     project them onto the admissible set K (contact, glue);
   *     move and turn the particles;
   *     get the velocities at the new positions (the time scheme, through
   *       the fluid model);
   *     measure the stress, write the output;
   *     checkpoint when due, stop when a signal asked for it.
   *
   * The fluid model (FluidModel, chosen by Fluid/Model) and the contact
   * module never see each other, and the loop never asks which fluid model
   * or time scheme it holds.
   */
  template <int dim>
  class Simulation : private TimeScheme<dim>::Stages
  {
  public:
    using Vec3       = RunState::Vec3;
    using Statistics = typename FluidModel<dim>::Statistics;
    using SolveLabel = typename FluidModel<dim>::SolveLabel;

    /// @p parameters must have passed Parameters::parse(). With @p resume
    /// (checked by Checkpoint::find_and_check) the run continues from that
    /// checkpoint; both must outlive the object. @p fluid_model replaces
    /// the one Fluid/Model names (tests drive the loop with a model of
    /// their own).
    explicit Simulation(const Parameters                &parameters,
                        const Checkpoint::ResumePoint   *resume      = nullptr,
                        std::unique_ptr<FluidModel<dim>> fluid_model = nullptr);
    ~Simulation() override;

    /// Run the scene; output goes to the output directory.
    RunSummary
    run();

  private:
    /// Step 0: the initial state, its velocities and output.
    void
    start();
    /// Load the checkpoint's state and the fluid model's part; continue the
    /// output files from its step.
    void
    resume_from_checkpoint();
    /// Whether the End time is reached.
    bool
    finished() const;
    /// Fixed, or CFL-limited by the fastest particle; then cut to the
    /// closing and opening gaps (Time stepping/Gap step fraction).
    double
    choose_time_step() const;
    /// TimeScheme::Stages: the lubrication and the contact projection of
    /// the predicted velocities.
    const std::vector<Vec3> &
    correct(PredictedVelocities &predicted, double dt, bool trial) override;
    /// Sub-grid lubrication: the squeeze resistance of gaps below the
    /// mesh scale, added implicitly to the predicted velocities
    /// (Fluid/Lubrication correction; nothing to do without it).
    void
    add_lubrication(const PredictedVelocities &predicted,
                    double                     dt,
                    bool                       trial);
    /// Warn when the lubricated velocities take a gap past zero within the
    /// step (no contact model holds it).
    void
    check_lubricated_gaps(double dt);
    /// Contact: projection of the (lubricated) velocities onto K; glued
    /// pairs take their normals at @p middle when it is given.
    void
    project_onto_admissible_set(const std::vector<Vec3> &predicted,
                                std::vector<Vec3>       &middle,
                                double                   dt,
                                bool                     trial);
    /// The projection with glued pairs' normals at the middle of the step,
    /// repeated until that middle is the one the corrected velocities
    /// reach.
    Contact::ProjectionStatistics
    project_with_normals_at_middle(const std::vector<Vec3> &predicted,
                                   std::vector<Vec3>       &middle,
                                   double                   dt);
    /// One projection of @p u (and, with friction, of w_corrected) into
    /// u_corrected (and w_corrected); glued rows' normals at @p middle
    /// unless it is null.
    Contact::ProjectionStatistics
    project(const std::vector<Vec3> &u,
            const std::vector<Vec3> *middle,
            double                   dt);
    /// Move and turn the particles; wrap periodic faces; stop the run if
    /// a particle crossed a face where it cannot stay.
    void
    advance_particles(double dt);
    /// Stop the run when particle @p i crossed a face where it cannot stay.
    void
    check_inside_box(unsigned int i) const;
    /// TimeScheme::Stages: the fluid model's rigid velocities at @p X.
    Statistics
    solve_at(const std::vector<Vec3> &X,
             double                   shear_rate,
             const SolveLabel        &label,
             std::vector<Vec3>       &U,
             std::vector<Vec3>       &W) override;
    /// TimeScheme::Stages: the rigid velocities at the current positions
    /// and time, into the run state.
    Statistics
    solve_at_current_positions() override;
    /// The suspension's stress: hydrodynamic from the fluid solve, contact
    /// and lubrication from the step of length @p dt that led to it (0 at
    /// the start); at a jump of the shear rate, the row describes the
    /// instant just before the jump (doc/rheology.md).
    void
    measure_stress(double dt);
    /// CSV rows, VTU/VTP output and the progress line of this step.
    void
    write_output(double dt);
    /// The particles.csv rows of this step.
    void
    write_particle_rows();
    /// The progress line, when one is due.
    void
    write_progress_line(double dt, double gap);
    /// Write a checkpoint when one is due; true when a signal asked the run
    /// to stop (a checkpoint is then written first).
    bool
    checkpoint_or_stop();
    /// Write a checkpoint of the current step (collective).
    void
    write_checkpoint();
    /// Wall seconds of the run so far, earlier parts included.
    double
    elapsed_wall_seconds() const;
    /// The run's summary after its last step.
    RunSummary
    summary() const;

    const Parameters                    &prm;
    const Checkpoint::ResumePoint       *resume;
    const MPI_Comm                       comm;
    const bool                           root;
    dealii::ConditionalOStream           pcout;
    std::unique_ptr<dealii::TimerOutput> timer;
    dealii::Timer                        wall_clock;
    WarningLog                           warnings;

    const BoxGeometry<dim> box;
    const ShearRate        shear;
    const unsigned int     n;

    std::unique_ptr<FluidModel<dim>> fluid;
    std::unique_ptr<TimeScheme<dim>> scheme;
    Contact::Settings                contact_settings;
    Contact::ContactProjector        projector;
    /// The gap limit of the step (null: Gap step fraction 0).
    std::unique_ptr<GapTimeStep> gap_step;
    /// The sub-grid lubrication (null: Fluid/Lubrication correction off).
    std::unique_ptr<Contact::LubricationCorrection> lubrication;
    /// Whether the fluid model solves the sub-grid lubrication with the
    /// flow (FluidModel::resolved_gap_fraction() > 0): the correction
    /// stage then only passes the velocities on, and each solve measures
    /// the bonds' forces (the statistics of the last one).
    bool                           lubrication_in_fluid = false;
    Contact::LubricationStatistics fluid_lubrication;
    /// Force per unit velocity of a contact correction (Contact/Drag
    /// coefficient, or the isolated particle's drag).
    double contact_drag = 0.;

    std::unique_ptr<CsvWriter>      particles_csv, statistics_csv;
    std::unique_ptr<ParticleOutput> particle_output;

    /// What passes from step to step (saved by checkpoints).
    RunState state;

    /// This step's work and results, for its output row.
    struct StepRecord
    {
      Statistics                       fluid;
      Contact::ProjectionStatistics    projection;
      Contact::LubricationStatistics   lubrication;
      typename FluidModel<dim>::Stress hydrodynamic;
      SuspensionStress                 stress;
      /// The factor from the bonds' forces to the row's shear rate: not 1
      /// only at a jump of the rate with the bonds solved with the flow,
      /// whose forces belong to the solve at the new rate.
      double lubrication_scale = 1.;
    } record;
    /// The step's predicted velocities, the lubricated ones and the
    /// corrected ones the particles move with.
    PredictedVelocities predicted;
    std::vector<Vec3>   u_lubricated, w_lubricated, u_corrected, w_corrected;

    /// Wall clock of the last progress line and checkpoint.
    double last_progress_wall = -1., last_checkpoint_wall = 0.;
    /// Signal that stopped the run (0: none).
    int stop_signal = 0;
  };

  /// Run a scene in its dimension (picks Simulation<2> or <3>), from the
  /// start or from @p resume; @p used_parameters, when given, is written to
  /// used_parameters.prm in the output directory once the scene is
  /// accepted.
  RunSummary
  run_simulation(const Parameters              &parameters,
                 const Checkpoint::ResumePoint *resume          = nullptr,
                 const std::string             &used_parameters = "");
} // namespace Fidus

#endif
