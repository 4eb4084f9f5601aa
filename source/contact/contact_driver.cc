#include <fidus/contact/contact_driver.h>

namespace Fidus::Contact
{
  ContactDriver::ContactDriver(const Settings     &settings,
                               std::vector<Vec3>   positions,
                               std::vector<double> radii,
                               VelocityField       field)
    : contact(settings)
    , x(std::move(positions))
    , a(std::move(radii))
    , field(std::move(field))
  {
    if (!this->field)
      throw ContactError("ContactDriver: no velocity field given");
    if (x.size() != a.size())
      throw ContactError("ContactDriver: " + std::to_string(x.size()) +
                         " positions but " + std::to_string(a.size()) +
                         " radii");
  }



  void
  ContactDriver::set_walls(const std::vector<Wall> &new_walls)
  {
    contact.set_walls(new_walls);
    walls = new_walls;
  }



  void
  ContactDriver::set_periodicity(const std::array<double, 3> &periods)
  {
    contact.set_periodicity(periods);
  }



  ProjectionStatistics
  ContactDriver::step(const double dt)
  {
    const unsigned dim = contact.get_settings().dimension;
    u_star.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
      {
        u_star[i] = field(x[i], t);
        if (dim == 2)
          u_star[i][2] = 0.;
      }
    const ProjectionStatistics statistics =
      contact.project(x, a, u_star, dt, u);
    for (std::size_t i = 0; i < x.size(); ++i)
      for (unsigned d = 0; d < dim; ++d)
        x[i][d] += dt * u[i][d];
    t += dt;
    return statistics;
  }



  double
  ContactDriver::minimum_gap(const double search_distance) const
  {
    return ContactProjector::minimum_gap(x,
                                         a,
                                         walls,
                                         contact.get_settings().dimension,
                                         search_distance,
                                         contact.get_periodicity());
  }
} // namespace Fidus::Contact
