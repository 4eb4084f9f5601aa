#ifndef fidus_contact_contact_driver_h
#define fidus_contact_contact_driver_h

#include <fidus/contact/contact_projector.h>
#include <functional>
#include <vector>

namespace Fidus::Contact
{
  /**
   * Moves particles with a prescribed velocity field and the contact
   * projection, without any fluid: u*_i = u(X_i, t), u = projection of u*
   * onto K, X_i += dt u_i (explicit Euler). This is the `undisturbed shear`
   * fluid model of numerics section 6 reduced to its contact part, used by
   * the tests (validation cases 4 and 5, squeezed packings) and by the
   * benchmark.
   */
  class ContactDriver
  {
  public:
    /// A velocity field u(x, t).
    using VelocityField = std::function<Vec3(const Vec3 &x, double t)>;

    /**
     * @param settings contact settings (model, solver, dimension, ...).
     * @param positions initial centres, @param radii radii (one per particle).
     * @param field the prescribed velocity u(x, t).
     */
    ContactDriver(const Settings     &settings,
                  std::vector<Vec3>   positions,
                  std::vector<double> radii,
                  VelocityField       field);

    /// Set the walls (see ContactProjector::set_walls()).
    void
    set_walls(const std::vector<Wall> &walls);

    /**
     * Set the periodic directions (see ContactProjector::set_periodicity());
     * minimum_gap() then uses the minimum image too. The driver does not wrap
     * the positions into the box (the projector does not need it), so the
     * velocity field should be periodic itself.
     */
    void
    set_periodicity(const std::array<double, 3> &periods);

    /**
     * One step of size @p dt: predict, project, move, advance time. Returns
     * the statistics of the projection; throws ContactError like
     * ContactProjector::project().
     */
    ProjectionStatistics
    step(double dt);

    /// Current centres.
    const std::vector<Vec3> &
    positions() const
    {
      return x;
    }

    /// Radii.
    const std::vector<double> &
    radii() const
    {
      return a;
    }

    /// Predicted velocities u* of the last step.
    const std::vector<Vec3> &
    predicted_velocities() const
    {
      return u_star;
    }

    /// Corrected velocities u of the last step.
    const std::vector<Vec3> &
    velocities() const
    {
      return u;
    }

    /// Current time.
    double
    time() const
    {
      return t;
    }

    /// The projector (glue state, constraints of the last step).
    ContactProjector &
    projector()
    {
      return contact;
    }

    /// Smallest gap of the current configuration (pairs within
    /// @p search_distance, and walls); see ContactProjector::minimum_gap().
    double
    minimum_gap(double search_distance) const;

  private:
    ContactProjector    contact;
    std::vector<Wall>   walls;
    std::vector<Vec3>   x;
    std::vector<double> a;
    VelocityField       field;
    std::vector<Vec3>   u_star, u;
    double              t = 0.;
  };
} // namespace Fidus::Contact

#endif
