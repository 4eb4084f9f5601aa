#ifndef fidus_mesh_canonical_cell_order_h
#define fidus_mesh_canonical_cell_order_h

#include <deal.II/dofs/dof_handler.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The active cells of @p dof_handler that are not artificial (locally
   * owned and ghost), ordered by CellId: coarse cell, then children in
   * z-order. That order depends only on the mesh. The order in which a
   * distributed triangulation stores its cells also depends on how the mesh
   * got there (coarsening frees slots that later refinements reuse), and a
   * mesh loaded from a checkpoint is stored afresh. Loops that add up over
   * cells (assembly, integrals over the particles) use this order, so that
   * a run resumed from a checkpoint adds in the same order and computes the
   * same numbers, to the bit, as the run that wrote it.
   */
  template <int dim>
  std::vector<typename DoFHandler<dim>::active_cell_iterator>
  canonical_cell_order(const DoFHandler<dim> &dof_handler);
} // namespace Fidus

#endif
