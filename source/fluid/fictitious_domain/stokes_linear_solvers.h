#ifndef fidus_source_fluid_stokes_linear_solvers_h
#define fidus_source_fluid_stokes_linear_solvers_h

// How StokesSolver solves its linear systems: one class per choice of
// Fluid/Linear solver (Method and Preconditioner). They are nested in
// StokesSolver, whose system, vectors and constraints they work on.
//
//   LinearSolver            the interface
//   DirectLinearSolver      Method = direct: factorise once per solve
//   IterativeLinearSolver   FGMRES with the block Schur preconditioner and
//                           the rigid-body correction, for
//     AmgLinearSolver       Preconditioner = AMG (ML with the rigid modes)
//     GmgLinearSolver       Preconditioner = GMG (VelocityMultigrid)

#include <Epetra_MultiVector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <fidus/fluid/fictitious_domain/rigid_mode_correction.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fidus/fluid/fictitious_domain/velocity_multigrid.h>
#include <memory>

namespace Fidus
{
  /**
   * What a choice of linear solver does at the three moments the Stokes
   * solver needs it: on a new mesh, after each assembly, and for each solve
   * of the Uzawa loop.
   */
  template <int dim>
  class StokesSolver<dim>::LinearSolver
  {
  public:
    explicit LinearSolver(StokesSolver<dim> &solver)
      : solver(solver)
    {}

    virtual ~LinearSolver() = default;

    /// Whether the system matrix holds an assembled velocity block (not
    /// when the geometric multigrid applies it without a matrix).
    virtual bool
    assembles_velocity_block() const
    {
      return true;
    }

    /// On a new mesh, once its constraints are known (setup_dofs()).
    virtual void
    prepare_mesh()
    {}

    /// After the assembly of a solve: factorise, or set up the
    /// preconditioners for the viscosity of @p solid and @p fluid_viscosity.
    virtual void
    setup(const SolidIndicator<dim> &solid,
          const Function<dim>       *fluid_viscosity) = 0;

    /// Solve the system for the current right-hand side into the solver's
    /// solution, to @p tolerance relative to the right-hand side; returns
    /// the FGMRES iterations (0 for a direct solve).
    virtual unsigned int
    solve(Statistics &stats, double tolerance) = 0;

    /// Whether solve() is exact whatever its tolerance.
    virtual bool
    solves_exactly() const
    {
      return false;
    }

  protected:
    StokesSolver<dim> &solver;
  };



  /**
   * Method = direct: the system is factorised once per solve
   * (DirectStokesSolver: MUMPS, or KLU where Trilinos has no MUMPS), so
   * that each Uzawa iteration is one substitution.
   */
  template <int dim>
  class StokesSolver<dim>::DirectLinearSolver : public LinearSolver
  {
  public:
    using LinearSolver::LinearSolver;

    /// Pin the pressure: the lowest unconstrained one.
    void
    prepare_mesh() override;

    void
    setup(const SolidIndicator<dim> &solid,
          const Function<dim>       *fluid_viscosity) override;

    unsigned int
    solve(Statistics &stats, double tolerance) override;

    bool
    solves_exactly() const override
    {
      return true;
    }

  private:
    /// The factorised system; analysed on the first solve of a mesh.
    std::unique_ptr<DirectStokesSolver> direct;
    /// The pressure unknown (within the pressure block) fixed at zero: the
    /// pressure is defined up to a constant.
    types::global_dof_index pinned_pressure = numbers::invalid_dof_index;
  };



  /**
   * FGMRES on the whole system with the block Schur preconditioner: a
   * velocity preconditioner (the derived class's), deflated by the
   * particles' rigid motions, and the Jacobi of the pressure mass; first
   * with one V-cycle for the velocity block, then, if that stalls, with
   * inner CG solves.
   */
  template <int dim>
  class StokesSolver<dim>::IterativeLinearSolver : public LinearSolver
  {
  public:
    using LinearSolver::LinearSolver;

    /// The pressure Jacobi, the velocity preconditioner
    /// (update_velocity_preconditioner()), the products with the velocity
    /// block, the rigid-body correction.
    void
    setup(const SolidIndicator<dim> &solid,
          const Function<dim>       *fluid_viscosity) override;

  protected:
    /// Build the velocity preconditioner for this assembly.
    virtual void
    update_velocity_preconditioner(const SolidIndicator<dim> &solid,
                                   const Function<dim> *fluid_viscosity) = 0;

    /// The products with the velocity block when it is not assembled.
    virtual std::unique_ptr<VelocityBlock>
    matrix_free_velocity_block()
    {
      return nullptr;
    }

    /// What the derived class reports once set up (verbose output).
    virtual void
    report_setup()
    {}

    /// One FGMRES solve with @p velocity as the velocity preconditioner.
    template <class VelocityPreconditioner>
    unsigned int
    fgmres(Statistics                   &stats,
           const VelocityPreconditioner &velocity,
           double                        tolerance);

    /// The rigid motions of every particle on the DoFs of its solid.
    void
    build_rigid_body_correction(const SolidIndicator<dim> &solid);

    /// Component @p c of the rigid motions at offset @p x from the centre:
    /// the dim translations, then the rotations (about z in 2D; about x, y
    /// and z in 3D), appended to @p values.
    static void
    append_rigid_modes(const unsigned int    c,
                       const Tensor<1, dim> &x,
                       std::vector<double>  &values)
    {
      for (unsigned int m = 0; m < dim; ++m)
        values.push_back(m == c ? 1. : 0.);
      if (dim == 2)
        values.push_back(c == 0 ? -x[1] : x[0]);
      else
        {
          // rotations about x, y, z: (0,-z,y), (z,0,-x), (-y,x,0)
          const double rot[3][3] = {{0, x[dim - 1], -x[1]},
                                    {-x[dim - 1], 0, x[0]},
                                    {x[1], -x[0], 0}};
          for (unsigned int m = 0; m < 3; ++m)
            values.push_back(rot[c][m]);
        }
    }

    /// The restart of this mesh's FGMRES: Settings::gmres_restart, or less
    /// where its basis would not fit beside the system in the memory
    /// budget (stokes_solver_memory.cc).
    void
    fit_restart();

    /// The restart fit_restart() chose.
    unsigned int                         restart = 0;
    TrilinosWrappers::PreconditionJacobi jacobi;
    /// The particles' rigid motions (Settings::rigid_body_correction).
    RigidModeCorrection rigid_body_correction;
    /// Products with the velocity block (assembled or matrix-free).
    std::unique_ptr<VelocityBlock> velocity_block;
  };



  /**
   * Preconditioner = AMG: Trilinos ML on the assembled velocity block, with
   * the translations and rotations as its near-null space.
   */
  template <int dim>
  class StokesSolver<dim>::AmgLinearSolver : public IterativeLinearSolver
  {
  public:
    using IterativeLinearSolver::IterativeLinearSolver;

    unsigned int
    solve(Statistics &stats, double tolerance) override;

  private:
    void
    update_velocity_preconditioner(
      const SolidIndicator<dim> &solid,
      const Function<dim>       *fluid_viscosity) override;

    TrilinosWrappers::PreconditionAMG amg;
    /// Near-null space of the velocity block handed to ML; must outlive
    /// the AMG set-up.
    std::unique_ptr<Epetra_MultiVector> rigid_modes;
  };



  /**
   * Preconditioner = GMG: the geometric multigrid of VelocityMultigrid,
   * whose hierarchy is built once per mesh; with Matrix-free velocity block
   * it also applies the velocity block, which is then not assembled.
   */
  template <int dim>
  class StokesSolver<dim>::GmgLinearSolver : public IterativeLinearSolver
  {
  public:
    /// Build the hierarchy on the solver's mesh; throws deal.II's
    /// exception where the global-coarsening transfer refuses the mesh.
    explicit GmgLinearSolver(StokesSolver<dim> &solver);

    bool
    assembles_velocity_block() const override;

    /// Without an assembled velocity block, also the load of the boundary
    /// values that the assembly leaves out.
    void
    setup(const SolidIndicator<dim> &solid,
          const Function<dim>       *fluid_viscosity) override;

    unsigned int
    solve(Statistics &stats, double tolerance) override;

  private:
    void
    update_velocity_preconditioner(
      const SolidIndicator<dim> &solid,
      const Function<dim>       *fluid_viscosity) override;

    std::unique_ptr<VelocityBlock>
    matrix_free_velocity_block() override;

    /// The Galerkin defect of the hierarchy, and the verbose report.
    void
    report_setup() override;

    std::unique_ptr<VelocityMultigrid<dim>> multigrid;
  };
} // namespace Fidus

#endif
