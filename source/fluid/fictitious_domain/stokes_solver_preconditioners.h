#ifndef fidus_source_fluid_stokes_solver_preconditioners_h
#define fidus_source_fluid_stokes_solver_preconditioners_h

// The preconditioner objects of StokesSolver, shared by stokes_solver.cc
// (which applies them) and stokes_solver_preconditioners.cc (which builds
// them).

#include <Epetra_MultiVector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <fidus/fluid/fictitious_domain/rigid_mode_correction.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fidus/fluid/fictitious_domain/velocity_multigrid.h>
#include <memory>

namespace Fidus
{
  template <int dim>
  class StokesSolver<dim>::Preconditioners
  {
  public:
    TrilinosWrappers::PreconditionAMG    amg;
    TrilinosWrappers::PreconditionJacobi jacobi;
    /// Near-null space of the velocity block handed to ML; must outlive
    /// the AMG set-up.
    std::unique_ptr<Epetra_MultiVector> rigid_modes;
    /// Geometric multigrid (Settings::geometric_multigrid), rebuilt when
    /// the mesh changes.
    std::unique_ptr<VelocityMultigrid<dim>> multigrid;
    /// The particles' rigid motions (Settings::rigid_body_correction).
    RigidModeCorrection rigid_body_correction;
  };
} // namespace Fidus

#endif
