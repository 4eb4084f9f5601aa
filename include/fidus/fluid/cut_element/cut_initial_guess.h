#ifndef fidus_fluid_cut_element_cut_initial_guess_h
#define fidus_fluid_cut_element_cut_initial_guess_h

#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/cut_element/cut_fields.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The previous solve's fields as a function on the box: the starting
   * point of the next solve's FGMRES (reuse between steps). The particles
   * move a fraction of a cell per step, so the previous velocity and
   * pressure, evaluated at the new mesh's support points, leave a residual
   * of 1e-2 to 3e-3 of the right-hand side's, and FGMRES has fewer decades
   * to go to the same absolute tolerance: the answer is the one a start
   * from zero reaches, to the solver's tolerance. What is left lies mostly
   * where the mesh changed (the cut cells, a gap refined further), the
   * modes the preconditioner reduces slowest, so the iterations fall by
   * less than the decades saved (doc/theory/cut_element.md).
   *
   * Both meshes refine the same coarse grid of unit cells (CutMesh), so a
   * point is found by descending from its coarse cell, without a search.
   * Inside a particle, where the previous mesh has no fluid, the velocity
   * is the particle's previous rigid motion and the pressure the previous
   * mean; elsewhere the previous Q2-Q1 field of the active cell that holds
   * the point.
   */
  template <int dim>
  class CutInitialGuess
  {
  public:
    /**
     * Read @p previous, whose unknowns are multiplied by @p factor (the
     * ratio of the shear rates when the flow is proportional to it, else
     * 1).
     */
    CutInitialGuess(const CutFields<dim> &previous, const double factor);

    /**
     * Carry the previous field with the particles: near particle k
     * (within a radius of its surface, fading out over the next) the field
     * is read where it was before the particle moved by
     * @p displacement[k], so that the previous rigid motion stays on the
     * surface, where Nitsche's penalty weighs a mismatch by eta / h; far
     * from every particle it is read where it is. @p balls are the new
     * surfaces with their periodic images (CutMesh::get_balls()),
     * @p periodic the box's periodic axes.
     */
    void
    follow(const std::vector<typename CutMesh<dim>::Ball> &balls,
           const std::vector<Tensor<1, dim>>              &displacement,
           const std::vector<bool>                        &periodic);

    /// True when @p previous describes the same box (the sides of
    /// @p sides) and @p n_particles particles.
    static bool
    applies(const CutFields<dim>      &previous,
            const std::vector<double> &sides,
            const unsigned int         n_particles);

    /**
     * Component @p component (0 to dim - 1 the velocity, dim the pressure)
     * at @p x, a point of the box.
     */
    double
    value(const Point<dim> &x, const unsigned int component) const;

    /// The previous solve's rigid unknowns of particle @p p (U then
    /// omega, as the system orders them), times the factor.
    std::vector<double>
    rigid(const unsigned int p) const;

  private:
    using cell_iterator = typename DoFHandler<dim>::active_cell_iterator;

    /// The active cell of the previous mesh that holds @p x.
    cell_iterator
    find(const Point<dim> &x) const;

    /// The rigid velocity component @p component at @p x of the particle
    /// whose ball holds it (the nearest surface's when none does).
    double
    rigid_value(const Point<dim> &x, const unsigned int component) const;

    /// Where the field at @p x is read in the previous solve.
    Point<dim>
    origin(const Point<dim> &x) const;

    const CutFields<dim> &previous;
    const double          factor;
    /// follow()'s surfaces, displacements and periodic axes.
    std::vector<typename CutMesh<dim>::Ball> balls;
    std::vector<Tensor<1, dim>>              displacement;
    std::vector<bool>                        periodic;
    /// The cell whose values are cached (level and index), and its
    /// unknowns: a new cell's support points fall in few previous cells.
    mutable int                 cached_level = -1, cached_index = -1;
    mutable std::vector<double> cached_values;
    mutable std::vector<types::global_dof_index> indices;
  };
} // namespace Fidus

#endif
