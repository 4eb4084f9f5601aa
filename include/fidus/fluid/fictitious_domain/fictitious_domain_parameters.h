#ifndef fidus_fluid_fictitious_domain_fictitious_domain_parameters_h
#define fidus_fluid_fictitious_domain_fictitious_domain_parameters_h

#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /**
   * The fictitious domain's own entries: its penalty, rigidity and solid
   * (subsection Fluid) and its linear solver (subsection Fluid/Linear
   * solver), with their 'auto' rules. StokesSolver::Settings extends this
   * struct with what the run decides (viscosity, degree, verbosity), so the
   * solver reads the entries as parsed, with no copy kept in step.
   *
   * The defaults below are the solver's when it is used without a parameter
   * file (tests, benchmarks); a parsed file overwrites every field.
   */
  struct FictitiousDomainParameters
  {
    /// Register the entries of Fluid and Fluid/Linear solver that belong
    /// to the fictitious domain.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back. The 'auto' of Method, Preconditioner and Rigid-body
    /// correction depends on @p dim and @p velocity_degree; that of Shared
    /// cells and Reuse multiplier on the rest of the scene and is decided
    /// by resolve_shared_cells().
    void
    parse(dealii::ParameterHandler &prm,
          const unsigned int        dim,
          const unsigned int        velocity_degree);

    /// Decide the 'auto' of Shared cells and Reuse multiplier: a pair
    /// closer than a cell is released where something else
    /// (@p gaps_kept_apart: a contact model or the lubrication correction)
    /// keeps it apart.
    void
    resolve_shared_cells(const bool gaps_kept_apart);

    /// Throw an InputError for a tolerance that is not positive or a
    /// penalty factor not above 1.
    void
    check() const;

    /// r: the solid viscosity is r eta_f, and the Uzawa augmentation.
    double penalty_factor     = 1e3;
    double rigidity_tolerance = 1e-3;
    /// Compare rigidity_tolerance with the per-particle rigidity residual
    /// (UzawaProblem::Residual::particle) instead of the box's
    /// (UzawaProblem::Residual::held); Fluid/Rigidity measure.
    bool rigidity_per_particle = false;
    /// Uzawa stop on the particles' rigid velocities instead of the strain
    /// in the solid (0: off; see StokesSolver::solve()).
    double rigid_velocity_tolerance = 0.;
    /// Cells whose share of solid quadrature points is below this are held
    /// rigid by the penalty alone, not by the multiplier (0: off).
    double       sliver_threshold     = 0.;
    unsigned int max_uzawa_iterations = 50;
    /// Anderson acceleration of the Uzawa loop: how many earlier iterates
    /// the multiplier's update combines (0: the plain update).
    unsigned int uzawa_acceleration_depth = 0;
    /// Start the Uzawa loop from the previous step's multiplier.
    bool reuse_multiplier = true;
    /// Treat the solid part of shared cells (within half a cell diameter of
    /// two particles) as fluid; false: the seed's model (rigid wherever
    /// there is solid, which cannot be met there).
    bool release_shared_cells = false;
    /// The held solid of each particle is a ball of radius
    /// a - solid_retraction * h_finest.
    double solid_retraction = 0.;
    /// Width of the smoothed solid layer in finest cells; 0 samples the
    /// solid sharply.
    double solid_smoothing = 0.;

    /// Fluid/Linear solver/Tolerance: relative residual of FGMRES.
    double linear_tolerance = 1e-6;
    /// Inexact Uzawa: the FGMRES solves inside the loop stop at this
    /// factor times the loop's own tolerance (never below
    /// linear_tolerance); the final velocity is then carried on to
    /// linear_tolerance. 0: every solve to linear_tolerance.
    double       inexact_uzawa_factor  = 0.;
    unsigned int max_cheap_iterations  = 1000;
    unsigned int max_linear_iterations = 1000;
    /// Krylov vectors FGMRES keeps before it restarts (Fluid/Linear
    /// solver/GMRES restart).
    unsigned int gmres_restart = 200;
    /// Memory each rank may use, in bytes (Fluid/Linear solver/Memory per
    /// rank); 0: auto, the machine's available memory (MemoryBudget).
    double       memory_per_rank           = 0.;
    double       amg_aggregation_threshold = 0.;
    unsigned int amg_smoother_sweeps       = 4;
    std::string  amg_smoother_type         = "Chebyshev";
    /// Factorise the system once per solve (DirectStokesSolver) instead
    /// of FGMRES on meshes of at most this many unknowns (0: never); the
    /// preconditioner settings are then unused. Method, resolved.
    unsigned long long direct_max_unknowns = 0;
    /// Velocity-block preconditioner: geometric multigrid (true) or the
    /// ML AMG. Preconditioner, resolved.
    bool         geometric_multigrid    = false;
    unsigned int mg_smoother_degree     = 4;
    std::string  mg_viscosity_averaging = "galerkin";
    /// GMG smoother blocks: none or cut cells (VelocityMultigrid).
    std::string mg_smoother_blocks = "cut cells";
    /// With the geometric multigrid: multiply by the velocity block with
    /// the finest level's matrix-free operator and do not assemble it
    /// (false: assemble it as with the AMG).
    bool matrix_free_velocity_block = true;
    /// Correct each V-cycle with the particles' rigid motions
    /// (RigidModeCorrection).
    bool rigid_body_correction = true;

  private:
    /// The entries of Fluid: penalty, rigidity, Uzawa loop, solid (the
    /// subsection entered by declare()).
    static void
    declare_solid_entries(dealii::ParameterHandler &prm);

    /// The entries of Fluid/Linear solver on FGMRES itself: its
    /// tolerances, iterations, restart and memory budget (the subsection
    /// entered by declare()).
    static void
    declare_fgmres_entries(dealii::ParameterHandler &prm);

    /// The entries of Fluid/Linear solver on the choice of method and the
    /// preconditioners: AMG, GMG, the rigid-body correction.
    static void
    declare_preconditioner_entries(dealii::ParameterHandler &prm);

    /// Shared cells and Reuse multiplier as written, until
    /// resolve_shared_cells().
    std::string shared_cells_choice = "rigid";
    std::string reuse_choice        = "true";
  };
} // namespace Fidus

#endif
