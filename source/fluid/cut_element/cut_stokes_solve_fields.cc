#include "cut_stokes_solve.h"

#include <fidus/fluid/cut_element/cut_fields.h>

namespace Fidus
{
  template <int dim>
  void
  CutStokesSolve<dim>::keep_fields()
  {
    // The solve's own DoFHandler is a member that dies with it; a second
    // one on the same mesh, with the same finite element on every cell,
    // numbers the DoFs the same way (distribute_dofs is deterministic), so
    // the fluid unknowns carry over as they are.
    auto fields = std::make_shared<CutFields<dim>>();
    fields->dof_handler =
      std::make_unique<DoFHandler<dim>>(mesh->get_triangulation());
    for (const auto &cell : fields->dof_handler->active_cell_iterators())
      cell->set_active_fe_index(placed(cell).solid ? 1 : 0);
    fields->dof_handler->distribute_dofs(fe_collection);
    if (fields->dof_handler->n_dofs() != n_fluid)
      throw std::logic_error("CutStokesSolve: the kept DoFs differ from the "
                             "solve's");
    fields->solution.reinit(n_fluid);
    fields->is_pressure.resize(n_fluid);
    for (unsigned int i = 0; i < n_fluid; ++i)
      {
        fields->solution[i]    = solution[i];
        fields->is_pressure[i] = is_pressure[i];
      }
    fields->fluid_pressure = result.fluid_pressure;
    // The mesh goes last: the solve's DoFHandler, still attached to it,
    // detaches when the solve ends, and the mesh lives on in the fields.
    fields->mesh  = std::move(mesh);
    result.fields = fields;
  }

  template void
  CutStokesSolve<2>::keep_fields();
  template void
  CutStokesSolve<3>::keep_fields();
} // namespace Fidus
