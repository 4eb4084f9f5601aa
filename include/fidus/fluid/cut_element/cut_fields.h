#ifndef fidus_fluid_cut_element_cut_fields_h
#define fidus_fluid_cut_element_cut_fields_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/cut_element/cut_mesh.h>
#include <memory>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The fields of one CutStokesInclusion solve, kept for output
   * (CutStokesInclusion::Settings::keep_fields) and as the next solve's
   * initial guess (CutInitialGuess): the cut mesh with its
   * cells' placements, the DoFs of the Taylor-Hood field (nothing inside
   * the particles), and the fluid unknowns of the solution with the
   * constraints applied. In the solver's box of unit cells.
   */
  template <int dim>
  struct CutFields
  {
    /// The mesh (declared first: the DoFs, attached to it, go first).
    std::unique_ptr<const CutMesh<dim>> mesh;
    /// The DoFs of the velocity and pressure.
    std::unique_ptr<DoFHandler<dim>> dof_handler;
    /// The fluid unknowns: velocity, and pressure with the solver's own
    /// constant (fluid_pressure is its mean over the fluid).
    Vector<double> solution;
    /// Which of them are pressures.
    std::vector<bool> is_pressure;
    /// The pressure's mean over the fluid.
    double fluid_pressure = 0.;
    /// The particles' centres as the solve was given them.
    std::vector<Point<dim>> centers;
    /// The particles' rigid unknowns, particle by particle (U, then omega).
    std::vector<double> rigid;
    /// The shear rate solved for, and whether the flow is proportional to
    /// it (no external force on any particle): the next solve's initial
    /// guess (CutInitialGuess) scales by the ratio of the rates.
    double shear_rate   = 0.;
    bool   proportional = true;
  };
} // namespace Fidus

#endif
