#ifndef fidus_fluid_fictitious_domain_fictitious_domain_model_h
#define fidus_fluid_fictitious_domain_fictitious_domain_model_h

#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <fidus/core/parameters.h>
#include <fidus/core/warning_log.h>
#include <fidus/fluid/boundary_velocity.h>
#include <fidus/fluid/fictitious_domain/particle_force_density.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fidus/fluid/fluid_model.h>
#include <fidus/io/field_output.h>
#include <fidus/lubrication/lubrication_correction.h>
#include <fidus/mesh/mesh_refiner.h>
#include <fidus/simulation/box_geometry.h>
#include <fidus/verification/exact_rigid_inclusion.h>
#include <memory>

namespace Fidus
{
  /**
   * `Fluid/Model = fictitious domain`: Stokes on the whole box with a
   * penalised viscosity inside the particles and a rigidity multiplier
   * (Uzawa loop, StokesSolver), on a p4est mesh refined around the
   * particle surfaces and the gaps between them (MeshRefiner). Each solve
   * places the particles' solid (radii reduced by Fluid/Solid
   * retraction), adapts the mesh if a particle moved by more than a
   * fraction of the refined band, solves, and fits a rigid motion to the
   * velocity in each particle. The mesh and the multiplier are its part of
   * a checkpoint. With `Domain/Boundary condition = exact rigid inclusion`
   * it also measures its error against the exact solution after its first
   * solve.
   */
  template <int dim>
  class FictitiousDomainModel : public FluidModel<dim>
  {
  public:
    using typename FluidModel<dim>::Vec3;
    using typename FluidModel<dim>::Statistics;
    using typename FluidModel<dim>::SolveLabel;
    using typename FluidModel<dim>::Stress;

    /// The coarse mesh of @p box, globally refined unless the run
    /// continues from a checkpoint (@p resuming: the checkpoint's forest
    /// replaces it). @p timer and @p warnings must outlive the model.
    FictitiousDomainModel(const Parameters       &prm,
                          const BoxGeometry<dim> &box,
                          bool                    resuming,
                          dealii::TimerOutput    &timer,
                          WarningLog             &warnings);
    ~FictitiousDomainModel() override;

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

    /// True with `Fluid/Lubrication coupling = with the flow`.
    bool
    solves_subgrid_lubrication() const override;

    void
    set_subgrid_lubrication(
      Contact::LubricationCorrection *correction) override;

    void
    open_field_output(const std::string  &directory,
                      const unsigned int *resumed_step) override;

    void
    write_fields(unsigned int step, double time) override;

    void
    save_checkpoint(const std::string &folder, RunState &state) override;

    void
    load_checkpoint(const std::string &folder, const RunState &state) override;

    void
    add_to_summary(RunSummary &summary) const override;

  private:
    /// Adapt the mesh to particles at @p X, unless they moved little since
    /// the last remesh; true when the unknowns changed.
    bool
    refine_mesh_if_particles_moved(const std::vector<Vec3> &X);
    /// The Uzawa loop's statistics with the body force @p body_force (null:
    /// none); a loop that stopped short is a warning. With @p extra_force:
    /// the last solve again with that body force added to its loads
    /// (StokesSolver::resolve()), @p body_force unused. A positive
    /// @p linear_tolerance is the linear tolerance of the loop's solves.
    Statistics
    solve_stokes(double               shear_rate,
                 const SolveLabel    &label,
                 const Function<dim> *body_force,
                 const Function<dim> *extra_force      = nullptr,
                 double               linear_tolerance = 0.);
    /**
     * The solve with the sub-grid lubrication's bonds at @p X acting on the
     * particles as forces and torques (Contact::LubricationCoupling),
     * iterated with Anderson mixing until the rigid velocities @p U, @p W
     * agree to `Fluid/Lubrication coupling tolerance`. Returns the last
     * solve's statistics with the iterations of all of them summed.
     */
    Statistics
    solve_with_subgrid_lubrication(const std::vector<Vec3> &X,
                                   double                   shear_rate,
                                   const SolveLabel        &label,
                                   std::vector<Vec3>       &U,
                                   std::vector<Vec3>       &W);
    /// The rigid velocity (U, omega) of each particle from the velocity.
    void
    extract_rigid_motion(std::vector<Vec3> &U, std::vector<Vec3> &W);
    /// The exact rigid inclusion's error norms, printed and kept for the
    /// summary.
    void
    report_exact_solution_errors(const std::vector<Vec3> &U,
                                 const std::vector<Vec3> &W);

    const Parameters       &prm;
    const BoxGeometry<dim> &box;
    dealii::TimerOutput    &timer;
    WarningLog             &warnings;
    const unsigned int      n;
    /// Radii of the held solid (Fluid/Solid retraction); the contact model
    /// uses the particles' radii.
    std::vector<double> solid_radii;

    std::unique_ptr<dealii::parallel::distributed::Triangulation<dim>> tria;
    std::unique_ptr<StokesSolver<dim>>                                 solver;
    std::unique_ptr<MeshRefiner<dim>>                                  refiner;
    std::unique_ptr<HydrodynamicStress<dim>> stress_integrator;
    /// The exact solution of the 'exact rigid inclusion' scene (else null).
    std::unique_ptr<ExactRigidInclusion<dim>> exact;
    /// Body force of Particles/External force (null for force-free
    /// particles).
    std::unique_ptr<ParticleForceDensity<dim>> external_force;
    std::unique_ptr<FieldOutput<dim>>          field_output;
    /// The sub-grid lubrication solved with the flow (else null), and the
    /// forces and torques of its bonds that load_density spreads over the
    /// particles.
    Contact::LubricationCorrection            *subgrid = nullptr;
    std::vector<Vec3>                          load_force, load_torque;
    std::unique_ptr<ParticleForceDensity<dim>> load_density;
    BoundaryVelocity<dim>                      boundary;
    SolidIndicator<dim>                        solid;

    /// The shear rate of the last solve.
    double solved_shear_rate = 0.;
    /// Positions at the last remesh, and whether a mesh was adapted yet
    /// (saved by checkpoints).
    std::vector<Vec3> X_at_remesh;
    bool              mesh_ready = false;
    /// The exact scene's errors, once measured.
    bool exact_reported = false;
    /// The smallest GMRES restart a solve used (0: none was iterative).
    unsigned int          smallest_restart = 0;
    std::array<double, 5> exact_errors{};
  };
} // namespace Fidus

#endif
