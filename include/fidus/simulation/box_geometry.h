#ifndef fidus_simulation_box_geometry_h
#define fidus_simulation_box_geometry_h

#include <array>
#include <deal.II/base/point.h>
#include <deal.II/base/types.h>
#include <fidus/contact/contact_types.h>
#include <fidus/core/parameters.h>
#include <set>
#include <vector>

namespace Fidus
{
  /**
   * What the box of a scene means for each stage (numerics section 1):
   * which faces are periodic (sliding walls: x, and z in 3D), which carry
   * an imposed velocity, which are walls for the contact model (the
   * imposed velocity has no normal component there), and the length
   * scales that tolerances and the time step are measured with.
   */
  template <int dim>
  struct BoxGeometry
  {
    explicit BoxGeometry(const Parameters &prm);

    dealii::Point<dim> lo, hi;
    double             y_mid = 0.;

    /// Smallest and largest particle radius (1 when there are none).
    double a_min = 1., a_max = 1.;

    /// Shortest box side, and the finest cell size it gives.
    double smallest_side = 1., h_finest = 1.;

    /// How far from a point the mesh refinement looks for particle
    /// surfaces and close pairs, on the coarsest cells (MeshRefiner: the
    /// band of (band + 1/2) cell diameters, the gap rule): the halo of
    /// periodic images the solid indicator needs near a periodic face.
    double query_reach = 0.;

    /// Periodic axes, as a list and per axis; their periods (0: not).
    std::vector<unsigned int> periodic;
    std::array<bool, dim>     is_periodic = {};
    std::array<double, 3>     periods     = {{0., 0., 0.}};

    /// Boundary ids with an imposed velocity (2d, 2d+1 for axis d).
    std::set<dealii::types::boundary_id> dirichlet_ids;

    /// Axes whose faces are walls, and the contact walls on them.
    std::vector<bool>          is_wall_axis;
    std::vector<Contact::Wall> walls;

    /// Bring centres that crossed a periodic face back into the box.
    void
    wrap(std::vector<std::array<double, 3>> &positions) const;

    /**
     * The velocity of @p wall at @p point on it when the box is sheared at
     * @p shear_rate: the imposed boundary velocity (BoundaryVelocity),
     * g (y - y_mid) e_x, on the y walls and, in linear shear, on the z
     * walls; zero on the cavity's fixed walls.
     */
    Contact::Vec3
    wall_velocity(const Contact::Wall &wall,
                  const Contact::Vec3 &point,
                  const double         shear_rate) const;

    /// Whether only the y walls move (BoundaryCondition::cavity).
    bool cavity = false;
  };
} // namespace Fidus

#endif
