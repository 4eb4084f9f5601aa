#include <algorithm>
#include <cmath>
#include <fidus/simulation/box_geometry.h>

namespace Fidus
{
  template <int dim>
  BoxGeometry<dim>::BoxGeometry(const Parameters &prm)
  {
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] = prm.domain.lower_left[d];
        hi[d] = prm.domain.upper_right[d];
      }
    y_mid  = 0.5 * (lo[1] + hi[1]);
    cavity = prm.domain.boundary_condition == BoundaryCondition::cavity;
    if (!prm.particles.radii.empty())
      {
        a_min = *std::min_element(prm.particles.radii.begin(),
                                  prm.particles.radii.end());
        a_max = *std::max_element(prm.particles.radii.begin(),
                                  prm.particles.radii.end());
      }
    smallest_side = prm.smallest_side();
    h_finest      = prm.finest_cell_size();
    // The coarse cells of create_box_mesh: each side divided into
    // round(side / smallest side) parts, then refined globally.
    double coarse_diameter2 = 0;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double side = hi[d] - lo[d];
        coarse_diameter2 +=
          std::pow(side / std::max(1., std::round(side / smallest_side)), 2);
      }
    const double h_coarsest =
      std::sqrt(coarse_diameter2) /
      std::pow(2.,
               std::min(prm.refinement.initial_global_refinement,
                        prm.refinement.minimum_level));
    query_reach = std::max((prm.refinement.interface_band + 0.5) * h_coarsest,
                           prm.refinement.gap_refinement_distance * a_max +
                             0.5 * h_coarsest);

    if (prm.domain.boundary_condition == BoundaryCondition::sliding_walls)
      for (unsigned int d = 0; d < dim; ++d)
        if (d != 1)
          {
            periodic.push_back(d);
            is_periodic[d] = true;
            periods[d]     = hi[d] - lo[d];
          }
    for (unsigned int d = 0; d < dim; ++d)
      if (!is_periodic[d])
        {
          dirichlet_ids.insert(2 * d);
          dirichlet_ids.insert(2 * d + 1);
        }

    // A face is a wall if the imposed velocity has no normal component:
    // the y faces always; x and z faces for the cavity; z faces in linear
    // shear (u = g (y - y_mid) e_x is tangential there).
    is_wall_axis.assign(dim, false);
    if (prm.domain.boundary_condition !=
        BoundaryCondition::exact_rigid_inclusion)
      for (unsigned int d = 0; d < dim; ++d)
        is_wall_axis[d] =
          d == 1 ||
          prm.domain.boundary_condition == BoundaryCondition::cavity ||
          (prm.domain.boundary_condition == BoundaryCondition::linear_shear &&
           d == 2);
    if (prm.contact.walls)
      for (unsigned int d = 0; d < dim; ++d)
        if (is_wall_axis[d])
          for (const int side : {1, -1})
            {
              Contact::Wall w;
              w.axis     = d;
              w.side     = side;
              w.position = side > 0 ? lo[d] : hi[d];
              walls.push_back(w);
            }
  }



  template <int dim>
  Contact::Vec3
  BoxGeometry<dim>::wall_velocity(const Contact::Wall &wall,
                                  const Contact::Vec3 &point,
                                  const double         shear_rate) const
  {
    Contact::Vec3 u = {{0., 0., 0.}};
    if (!cavity || wall.axis == 1)
      u[0] = shear_rate * (point[1] - y_mid);
    return u;
  }



  template <int dim>
  void
  BoxGeometry<dim>::wrap(std::vector<std::array<double, 3>> &X) const
  {
    for (auto &x : X)
      for (const unsigned int d : periodic)
        {
          const double L = hi[d] - lo[d];
          if (x[d] < lo[d])
            x[d] += L;
          else if (x[d] >= hi[d])
            x[d] -= L;
        }
  }

  template struct BoxGeometry<2>;
  template struct BoxGeometry<3>;
} // namespace Fidus
