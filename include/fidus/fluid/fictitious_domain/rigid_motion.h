#ifndef fidus_particles_rigid_motion_h
#define fidus_particles_rigid_motion_h

#include <array>
#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /// Rigid velocity of one particle.
  struct RigidMotion
  {
    std::array<double, 3> velocity = {{0., 0., 0.}};
    /// Angular velocity (2D: only the z component is used).
    std::array<double, 3> omega  = {{0., 0., 0.}};
    double                volume = 0.; ///< discrete |P_i|
  };

  /**
   * L2 projection of the discrete velocity onto the rigid motions of each
   * particle (numerics section 2), with the same indicator and quadrature as
   * the penalty term: (U_i, omega_i) minimise int_{P_i} |u - U - omega x r|^2,
   * r = x - X_i, i.e.
   *   |P_i| U - c x omega = int_{P_i} u,   c x U + J_i omega = int_{P_i} r x u,
   *   J_i = int_{P_i} (|r|^2 I - r (x) r),   c = int_{P_i} r,
   * solved as one system. For a whole particle c vanishes up to quadrature
   * and this is U_i = mean of u, omega_i = J_i^{-1} int r x u; it does not
   * vanish when cells are left out. Integrals are summed over locally owned
   * cells and reduced over MPI, so every rank gets every particle's motion.
   * Cells flagged in
   * @p excluded_cells (indexed by active_cell_index; shared cells, whose
   * solid part is not held rigid) are left out.
   */
  template <int dim>
  std::vector<RigidMotion>
  compute_rigid_motions(
    const DoFHandler<dim> &dof_handler,
    const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells,
    const TrilinosWrappers::MPI::BlockVector                          &solution,
    const SolidIndicator<dim>                                         &solid,
    const Quadrature<dim>   &quadrature,
    const std::vector<bool> *excluded_cells = nullptr);
} // namespace Fidus

#endif
