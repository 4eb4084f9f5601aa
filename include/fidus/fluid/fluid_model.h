#ifndef fidus_fluid_fluid_model_h
#define fidus_fluid_fluid_model_h

#include <algorithm>
#include <array>
#include <fidus/rheology/hydrodynamic_stress.h>
#include <string>
#include <vector>

namespace Fidus
{
  namespace Contact
  {
    class LubricationCorrection;
  }

  struct RunState;
  struct RunSummary;

  /**
   * What the time loop asks of a fluid model: the rigid velocities of the
   * particles at given positions under a given shear rate, with the
   * statistics and the hydrodynamic stress of that solve, and the model's
   * share of the output and of a checkpoint. The time loop never asks
   * which model it holds; `Fluid/Model` picks one through
   * create_fluid_model() (fluid_model_factory.h).
   *
   * The three models of fidus:
   * - FictitiousDomainModel: penalised Stokes on the whole box with the
   *   rigidity multiplier (Uzawa), on an adaptive p4est mesh that follows
   *   the particles (doc/theory/fictitious_domain.md);
   * - CutElementModel: Stokes outside the particles only, on a cut mesh
   *   built for every solve, rigid motions by Nitsche's method
   *   (doc/theory/cut_element.md);
   * - UndisturbedShearModel: free-draining particles, each moving with the
   *   undisturbed shear flow at its centre (plus its external force over
   *   its isolated drag).
   *
   * A fourth model implements this class, adds its name to `Fluid/Model`
   * (Parameters) and one line to create_fluid_model(). Everything a model
   * needs (mesh, solver, its settings) it owns; nothing outside it knows
   * its type.
   */
  template <int dim>
  class FluidModel
  {
  public:
    using Vec3 = std::array<double, 3>;
    /// The hydrodynamic stress of the box and of each particle: the shared
    /// result type of every model.
    using Stress = typename HydrodynamicStress<dim>::Result;

    /// The work of one solve, for the statistics.csv row and the progress
    /// line.
    struct Statistics
    {
      /// Cells and unknowns of the mesh the solve used (0: no mesh).
      unsigned long long n_cells = 0, n_dofs = 0;
      /// Uzawa iterations (0 for a model without a rigidity multiplier)
      /// and linear-solver iterations (FGMRES; 0 when solved directly).
      unsigned int uzawa_iterations = 0, linear_iterations = 0;
      /// The rigidity residual the Uzawa loop stops on, the largest
      /// per-particle one, and the last iteration's largest change of a
      /// rigid velocity relative to the shear rate (NaN after one).
      double rigidity_residual = 0., particle_rigidity_residual = 0.,
             rigid_velocity_change = 0.;
      /// Cells whose solid was released, and the rigidity residual there.
      unsigned int shared_cells    = 0;
      double       shared_residual = 0.;
      /// False when the solve stopped short of its tolerance (the model
      /// has warned, naming the step).
      bool converged = true;
      /// Whether the mesh changed for this solve.
      bool remeshed = false;

      /// Statistics of @p later, a solve made after this one within the
      /// same time step (trapezoidal passes): its own values, with the
      /// iterations of both summed, the larger rigidity residual, and
      /// remeshed if either remeshed.
      Statistics
      followed_by(const Statistics &later) const;
    };

    /// Where a solve stands in the run, for its warnings: the step it
    /// belongs to and a description ("step 12, t = 0.3").
    struct SolveLabel
    {
      unsigned int step = 0;
      std::string  where;
    };

    virtual ~FluidModel() = default;

    /**
     * The rigid velocity @p U and angular velocity @p W of every particle
     * at positions @p X under the shear rate @p shear_rate (3-vectors, z =
     * 0 in 2D; @p W is (0, 0, omega) in 2D). Trouble that does not stop
     * the run is a warning naming @p label; trouble that does is a
     * RunError.
     */
    virtual Statistics
    rigid_velocities(const std::vector<Vec3> &X,
                     double                   shear_rate,
                     const SolveLabel        &label,
                     std::vector<Vec3>       &U,
                     std::vector<Vec3>       &W) = 0;

    /**
     * The hydrodynamic stress of the configuration of the last solve under
     * the shear rate @p shear_rate (Stokes flow is linear in it; without
     * external forces the time loop may ask for the rate just before a
     * jump, doc/theory/stress.md).
     */
    virtual Stress
    hydrodynamic_stress(double shear_rate) = 0;

    /// The length the CFL time step divides by the fastest speed: the
    /// finest cell where the model has a mesh, the smallest radius where
    /// it has none.
    virtual double
    cfl_length() const = 0;

    /// Whether the model resolves part of the flow in a thin gap (its
    /// mesh does down to the cell size), which the sub-grid lubrication
    /// then leaves out; false: the correction adds the whole two-particle
    /// resistance.
    virtual bool
    resolves_gap_flow() const = 0;

    /// > 0: the model resolves every gap down to this fraction of the
    /// smaller radius of a pair (the radius for a wall) and sees the
    /// narrower ones at that width, so the sub-grid lubrication corrects
    /// from that gap, bond by bond; 0: it resolves down to a fraction of
    /// the finest cell (Fluid/Lubrication range and its kin).
    virtual double
    resolved_gap_fraction() const
    {
      return 0.;
    }

    /// Whether the sub-grid lubrication is solved with this model's flow
    /// (set_subgrid_lubrication()) rather than after it: a model that
    /// resolves every gap to a fraction of the radii does so always, the
    /// fictitious domain with `Fluid/Lubrication coupling = with the flow`.
    virtual bool
    solves_subgrid_lubrication() const
    {
      return resolved_gap_fraction() > 0.;
    }
    /// For a model that solves_subgrid_lubrication(): the sub-grid
    /// lubrication whose bonds (LubricationCorrection::find_bonds()) every
    /// later solve adds to its own system, so that the fluid and the
    /// sub-grid resistance are solved together. The caller keeps
    /// @p correction alive and measures the bonds' forces after the solve.
    virtual void
    set_subgrid_lubrication(Contact::LubricationCorrection *correction)
    {
      (void)correction;
    }

    /// Field output (velocity, pressure, ...) to @p directory, continued
    /// after @p resumed_step when the run resumes (else null). Models with
    /// no field refuse Output/Field output interval when the parameters
    /// are read, so the default does nothing.
    virtual void
    open_field_output(const std::string  &directory,
                      const unsigned int *resumed_step)
    {
      (void)directory;
      (void)resumed_step;
    }

    /// Write the fields of the last solve (collective).
    virtual void
    write_fields(unsigned int step, double time)
    {
      (void)step;
      (void)time;
    }

    /// Save the model's part of a checkpoint to @p folder (collective) and
    /// its scalars to @p state, which the checkpoint stores.
    virtual void
    save_checkpoint(const std::string &folder, RunState &state)
    {
      (void)folder;
      (void)state;
    }

    /// Load what save_checkpoint() saved (collective).
    virtual void
    load_checkpoint(const std::string &folder, const RunState &state)
    {
      (void)folder;
      (void)state;
    }

    /// The model's entries of the run's summary (mesh size, verification
    /// errors); the default leaves them 0.
    virtual void
    add_to_summary(RunSummary &summary) const
    {
      (void)summary;
    }
  };



  template <int dim>
  typename FluidModel<dim>::Statistics
  FluidModel<dim>::Statistics::followed_by(const Statistics &later) const
  {
    Statistics s = later;
    s.uzawa_iterations += uzawa_iterations;
    s.linear_iterations += linear_iterations;
    s.rigidity_residual = std::max(rigidity_residual, later.rigidity_residual);
    s.remeshed          = remeshed || later.remeshed;
    return s;
  }
} // namespace Fidus

#endif
