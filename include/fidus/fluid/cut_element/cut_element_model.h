#ifndef fidus_fluid_cut_element_cut_element_model_h
#define fidus_fluid_cut_element_cut_element_model_h

#include <deal.II/base/timer.h>
#include <fidus/core/parameters.h>
#include <fidus/core/warning_log.h>
#include <fidus/fluid/cut_element/cut_fields.h>
#include <fidus/fluid/cut_element/cut_stokes_inclusion.h>
#include <fidus/fluid/fluid_model.h>
#include <fidus/io/field_output.h>
#include <fidus/simulation/box_geometry.h>
#include <memory>

namespace Fidus
{
  /**
   * `Fluid/Model = cut finite element`: Stokes outside the particles only,
   * on a cut mesh built for every solve (CutStokesInclusion), with the
   * particles' rigid motions as unknowns coupled by Nitsche's method. It
   * has no accuracy floor and resolves thin gaps down to `Fluid/Cut
   * minimum gap`; its solvers are serial, so it runs on one MPI rank
   * (refused on more, naming the entry). Touching or overlapping
   * particles, which the contact models allow, are seen by its fluid with
   * radii reduced until every gap is the minimum gap.
   *
   * The box may have any size (CutMesh divides it into coarse cells of
   * about the shortest side, cubes where a side is a whole multiple of
   * it): Stokes flow is
   * invariant under translation and scaling, so the solver works in the
   * box shifted to the origin and scaled by the shortest side (velocities
   * scale with the length, forces with its power dim - 1, stresslets with
   * its power dim; the shear rate and the stress do not change), and the
   * answers are scaled back.
   */
  template <int dim>
  class CutElementModel : public FluidModel<dim>
  {
  public:
    using typename FluidModel<dim>::Vec3;
    using typename FluidModel<dim>::Statistics;
    using typename FluidModel<dim>::SolveLabel;
    using typename FluidModel<dim>::Stress;

    /// Throws an InputError on more than one MPI rank. @p timer and
    /// @p warnings must outlive the model.
    CutElementModel(const Parameters       &prm,
                    const BoxGeometry<dim> &box,
                    dealii::TimerOutput    &timer,
                    WarningLog             &warnings);

    Statistics
    rigid_velocities(const std::vector<Vec3> &X,
                     double                   shear_rate,
                     const SolveLabel        &label,
                     std::vector<Vec3>       &U,
                     std::vector<Vec3>       &W) override;

    Stress
    hydrodynamic_stress(double shear_rate) override;

    double
    cfl_length() const override;

    bool
    resolves_gap_flow() const override;

    double
    resolved_gap_fraction() const override;

    void
    set_subgrid_lubrication(
      Contact::LubricationCorrection *correction) override;

    void
    add_to_summary(RunSummary &summary) const override;

    /// Field output to @p directory (with Output/Field output interval >
    /// 0): the velocity and the pressure (relative to the fluid's mean) on
    /// the cut mesh of the last solve, and per cell its placement (0 fluid,
    /// 1 cut, 2 inside a particle) and level.
    void
    open_field_output(const std::string  &directory,
                      const unsigned int *resumed_step) override;

    void
    write_fields(unsigned int step, double time) override;

  private:
    /// The radius each particle's fluid sees at @p X: reduced so that every
    /// gap, to a wall or to another particle, is at least Fluid/Cut
    /// minimum gap (an overlap is a warning naming @p label).
    std::vector<double>
    fluid_radii(const std::vector<Vec3> &X, const SolveLabel &label) const;

    /// The sub-grid lubrication's bonds at @p X as resistances among the
    /// solver's rigid unknowns (in its units), none without the correction;
    /// each gap resolved at its width between the @p fluid radii.
    std::vector<typename CutStokesInclusion<dim>::RigidCoupling>
    subgrid_couplings(const std::vector<Vec3>   &X,
                      const std::vector<double> &fluid) const;

    /// With Output/Verbosity = verbose: the solve's size, its solver and
    /// the seconds of its stages, one line.
    void
    print_stages(const typename CutStokesInclusion<dim>::Result &r) const;

    const Parameters       &prm;
    const BoxGeometry<dim> &box;
    dealii::TimerOutput    &timer;
    WarningLog             &warnings;
    const unsigned int      n;

    /// The solver's length unit (the box's shortest side) and the box in
    /// it.
    double              unit = 1.;
    std::vector<double> box_sides;

    /// Stress, cells and unknowns of the last solve, and its shear rate.
    Stress             last_stress;
    unsigned long long last_cells = 0, last_dofs = 0;
    double             solved_shear_rate = 0.;

    /// The fields of the last solve (kept with field output, and as the
    /// next solve's start with the iterative solver), and their writer.
    std::shared_ptr<const CutFields<dim>> last_fields;

    /// The sub-grid lubrication solved with the flow (null: none).
    Contact::LubricationCorrection   *subgrid = nullptr;
    std::unique_ptr<FieldOutput<dim>> field_output;
  };
} // namespace Fidus

#endif
