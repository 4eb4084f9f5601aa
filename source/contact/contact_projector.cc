#include <algorithm>
#include <chrono>
#include <cmath>
#include <fidus/contact/contact_projector.h>
#include <fidus/contact/vector_operations.h>
#include <sstream>

namespace Fidus::Contact
{
  namespace
  {
    using Clock = std::chrono::steady_clock;

    double
    seconds_since(const Clock::time_point start)
    {
      return std::chrono::duration<double>(Clock::now() - start).count();
    }

    std::string
    format_vector(const Vec3 &v, const unsigned int dim)
    {
      std::ostringstream s;
      s << '(' << v[0] << ", " << v[1];
      if (dim == 3)
        s << ", " << v[2];
      s << ')';
      return s.str();
    }

    /// "x (direction 0)" etc., for messages about periodic directions.
    std::string
    direction_name(const unsigned int d)
    {
      const char *names[] = {"x", "y", "z"};
      return std::string(d < 3 ? names[d] : "?") + " (direction " +
             std::to_string(d) + ")";
    }

    /**
     * Throw unless every period is larger than 2 (2 a_max + d_a) (d_a = 0
     * for minimum_gap()): a pair is then within reach through at most one
     * of its images. The message gives the direction, the period and the
     * requirement.
     */
    void
    require_unambiguous_image(const std::array<double, 3> &periods,
                              const unsigned int           dim,
                              const double                 a_max,
                              const double                 d_a,
                              const std::string           &where)
    {
      for (unsigned d = 0; d < dim; ++d)
        {
          const double required = 2. * (2. * a_max + d_a);
          if (periods[d] > 0. && !(periods[d] > required))
            {
              std::ostringstream s;
              s.precision(6);
              s << where << "the period " << periods[d]
                << " of the periodic direction " << direction_name(d)
                << " is too small: it must be larger than 2 (2 a_max + d_a) = "
                << required << " (largest radius a_max = " << a_max
                << ", alert distance d_a = " << d_a
                << "), else a pair can be within reach through two of its "
                   "periodic images and the minimum image is ambiguous";
              throw ContactError(s.str());
            }
        }
    }

    /**
     * The checks of set_periodicity(): periods >= 0 and finite, none in a
     * direction beyond @p dim, no wall normal to a periodic direction.
     */
    void
    check_periodicity(const std::array<double, 3> &periods,
                      const unsigned int           dim,
                      const std::vector<Wall>     &walls)
    {
      for (unsigned int d = 0; d < 3; ++d)
        {
          if (!(periods[d] >= 0.) || !std::isfinite(periods[d]))
            {
              std::ostringstream s;
              s << "the period of direction " << direction_name(d) << " is "
                << periods[d]
                << ": it must be > 0 (periodic) or 0 (not periodic)";
              throw ContactError(s.str());
            }
          if (d >= dim && periods[d] != 0.)
            throw ContactError(
              "a period is given for direction " + direction_name(d) +
              ", which does not exist in " + std::to_string(dim) + "D");
          if (periods[d] > 0.)
            for (std::size_t w = 0; w < walls.size(); ++w)
              if (walls[w].axis == d)
                throw ContactError("direction " + direction_name(d) +
                                   " cannot be periodic: wall " +
                                   std::to_string(w) + " is normal to it");
        }
    }

    /// The glue-state entry of constraint row k with its current gamma and
    /// lambda. Wall rows store the particle first and the wall's key second
    /// (the constraint system numbers walls after the n particles).
    GlueState::Entry
    glue_entry(const ConstraintSystem &system,
               const std::size_t       k,
               const std::uint32_t     n)
    {
      GlueState::Entry e;
      if (system.first(k) >= n)
        {
          e.first  = system.second(k);
          e.second = GlueState::wall_key(system.first(k) - n);
        }
      else
        {
          e.first  = system.first(k);
          e.second = system.second(k);
        }
      e.gamma  = system.gamma(k);
      e.lambda = system.lambda(k);
      return e;
    }
    /// Contacts whose tangential impulse is on the rim of the cone (to a
    /// relative 1e-9, far below any tolerance that matters): sliding.
    unsigned int
    count_sliding(const ConstraintSystem &system, const double mu)
    {
      unsigned int n = 0;
      for (std::size_t k = 0; k < system.size(); ++k)
        {
          const double r = mu * system.lambda(k);
          if (r > 0. && norm(system.tangential_impulse(k)) >= (1. - 1e-9) * r)
            ++n;
        }
      return n;
    }
    /// The error of particles @p i and @p j overlapping by -@p gap at the
    /// start of a step, along the minimum-image separation @p e.
    std::string
    pair_overlap_message(const std::uint32_t        i,
                         const std::uint32_t        j,
                         const double               gap,
                         const Vec3                &e,
                         const std::vector<Vec3>   &positions,
                         const std::vector<double> &radii,
                         const unsigned int         dim,
                         const double               allowed_overlap)
    {
      std::ostringstream s;
      s.precision(6);
      s << "particles " << i << " and " << j << " overlap by " << -gap
        << " (gap D = " << gap << ", centres "
        << format_vector(positions[i], dim) << " and "
        << format_vector(positions[j], dim) << ", radii " << radii[i] << " and "
        << radii[j] << ")";
      // Across a periodic face the centres alone mislead: name the
      // nearest-image separation that the gap was measured along.
      bool wrapped = false;
      for (unsigned d = 0; d < dim; ++d)
        wrapped |= std::abs(e[d] - (positions[j][d] - positions[i][d])) >
                   1e-12 * (1. + std::abs(e[d]));
      if (wrapped)
        s << " across a periodic face (nearest-image separation "
          << format_vector(e, dim) << ")";
      s << " at the start of the step; the allowed overlap is "
        << allowed_overlap;
      return s.str();
    }
  } // namespace



  ContactProjector::ContactProjector(const Settings &settings_)
    : settings(settings_)
    , search((settings_.dimension == 2 || settings_.dimension == 3) ?
               settings_.dimension :
               throw ContactError("dimension must be 2 or 3, got " +
                                  std::to_string(settings_.dimension)),
             settings_.pair_search)
  {
    if (!(settings.tolerance > 0.))
      throw ContactError("tolerance must be positive");
    if (!(settings.glue_snap >= 0.))
      throw ContactError("glue_snap must be >= 0");
    if (!(settings.alert_distance >= 0.))
      throw ContactError("alert_distance must be >= 0");
    if (!(settings.friction >= 0.) || !std::isfinite(settings.friction))
      throw ContactError("friction coefficient " +
                         std::to_string(settings.friction) +
                         " is not allowed: it must be >= 0 and finite");
    if (settings.friction > 0. && settings.model == Model::none)
      throw ContactError("friction acts at contacts, and the contact model "
                         "'none' has none: choose 'inelastic' or 'gluey', "
                         "or friction 0");
    if (!(settings.contact_distance >= 0.) || !(settings.contact_distance < 1.))
      throw ContactError("contact distance " +
                         std::to_string(settings.contact_distance) +
                         " (in radii) is not allowed: it must lie in [0, 1)");
  }



  void
  ContactProjector::set_walls(const std::vector<Wall> &new_walls)
  {
    for (std::size_t w = 0; w < new_walls.size(); ++w)
      {
        const Wall &wall = new_walls[w];
        if (wall.axis >= settings.dimension)
          throw ContactError("wall " + std::to_string(w) + ": axis " +
                             std::to_string(wall.axis) +
                             " is not a coordinate direction in " +
                             std::to_string(settings.dimension) + "D");
        if (wall.side != 1 && wall.side != -1)
          throw ContactError("wall " + std::to_string(w) +
                             ": side must be +1 (lower wall) or -1 (upper "
                             "wall), got " +
                             std::to_string(wall.side));
        if (!std::isfinite(wall.position))
          throw ContactError("wall " + std::to_string(w) +
                             ": position is not finite");
        for (unsigned d = 0; d < settings.dimension; ++d)
          if (!std::isfinite(wall.velocity[d]))
            throw ContactError("wall " + std::to_string(w) +
                               ": velocity is not finite");
        if (wall.velocity[wall.axis] != 0.)
          throw ContactError(
            "wall " + std::to_string(w) + ": velocity " +
            format_vector(wall.velocity, settings.dimension) +
            " has a normal component: a face with in- or outflow is not a "
            "wall");
        if (get_periodicity()[wall.axis] > 0.)
          throw ContactError("wall " + std::to_string(w) + ": axis " +
                             std::to_string(wall.axis) +
                             " is a periodic direction, which has no walls");
      }
    const bool changed =
      new_walls.size() != walls.size() ||
      !std::equal(walls.begin(),
                  walls.end(),
                  new_walls.begin(),
                  [](const Wall &x, const Wall &y) {
                    return x.axis == y.axis && x.side == y.side;
                  });
    walls = new_walls;
    if (changed)
      {
        // Particle-wall glue refers to wall indices that may now mean
        // another face: drop it, keep the particle-particle state.
        std::vector<GlueState::Entry> kept;
        for (const auto &e : glue.entries())
          if (!GlueState::is_wall_key(e.second))
            kept.push_back(e);
        glue.rebuild(kept);
      }
  }



  void
  ContactProjector::set_periodicity(const std::array<double, 3> &periods)
  {
    check_periodicity(periods, settings.dimension, walls);
    search.set_periodicity(periods);
  }



  void
  ContactProjector::check_periods(const double a_max, const double d_a) const
  {
    require_unambiguous_image(get_periodicity(),
                              settings.dimension,
                              a_max,
                              d_a,
                              "");
  }



  void
  ContactProjector::set_weights(const std::vector<double> &new_weights)
  {
    for (std::size_t i = 0; i < new_weights.size(); ++i)
      if (!(new_weights[i] > 0.) || !std::isfinite(new_weights[i]))
        throw ContactError("weight of particle " + std::to_string(i) +
                           " must be positive and finite");
    weights = new_weights;
  }



  void
  ContactProjector::set_rotational_weights(
    const std::vector<double> &new_weights)
  {
    for (std::size_t i = 0; i < new_weights.size(); ++i)
      if (!(new_weights[i] > 0.) || !std::isfinite(new_weights[i]))
        throw ContactError("rotational weight of particle " +
                           std::to_string(i) + " must be positive and finite");
    rotational_weights = new_weights;
  }



  unsigned int
  ContactProjector::n_glued() const
  {
    return glue.n_glued();
  }



  std::vector<unsigned int>
  ContactProjector::glued_count_per_particle(
    const std::size_t n_particles) const
  {
    return glue.glued_count_per_particle(n_particles);
  }



  void
  ContactProjector::reset_glue()
  {
    glue.clear();
  }



  void
  ContactProjector::validate(const std::vector<Vec3>   &positions,
                             const std::vector<double> &radii,
                             const std::vector<Vec3>   &predicted,
                             const double               dt) const
  {
    const unsigned dim = settings.dimension;
    if (!(dt > 0.) || !std::isfinite(dt))
      {
        std::ostringstream s;
        s << "time step dt = " << dt << " is not allowed: it must be positive "
          << "and finite";
        throw ContactError(s.str());
      }
    if (radii.size() != positions.size() ||
        predicted.size() != positions.size())
      throw ContactError("size mismatch: " + std::to_string(positions.size()) +
                         " positions, " + std::to_string(radii.size()) +
                         " radii, " + std::to_string(predicted.size()) +
                         " predicted velocities (one of each per particle)");
    if (!weights.empty() && weights.size() != positions.size())
      throw ContactError("size mismatch: " + std::to_string(weights.size()) +
                         " weights for " + std::to_string(positions.size()) +
                         " particles");
    if (positions.size() >= (std::size_t(1) << 31))
      throw ContactError("too many particles for 32-bit pair indices");
    for (std::size_t i = 0; i < positions.size(); ++i)
      {
        for (unsigned d = 0; d < dim; ++d)
          {
            if (!std::isfinite(predicted[i][d]))
              throw ContactError(
                "predicted velocity of particle " + std::to_string(i) +
                " is not finite: " + format_vector(predicted[i], dim));
            if (!std::isfinite(positions[i][d]))
              throw ContactError(
                "position of particle " + std::to_string(i) +
                " is not finite: " + format_vector(positions[i], dim));
          }
        if (!(radii[i] > 0.) || !std::isfinite(radii[i]))
          {
            std::ostringstream s;
            s << "radius of particle " << i << " is " << radii[i]
              << ": it must be positive and finite";
            throw ContactError(s.str());
          }
      }
  }



  double
  ContactProjector::assemble(const std::vector<Vec3>   &positions,
                             const std::vector<double> &radii,
                             const double               d_a,
                             const std::vector<Vec3>   *glued_normal_positions)
  {
    const unsigned      dim   = settings.dimension;
    const std::uint32_t n     = static_cast<std::uint32_t>(positions.size());
    const bool          gluey = (settings.model == Model::gluey);
    const double        allowed_overlap = tolerated_overlap();

    system.clear();
    // Rough particles touch at a gap of their contact distance: search
    // that much further.
    double a_max = 0.;
    for (const double a : radii)
      a_max = std::max(a_max, a);
    const double d_search = d_a + settings.contact_distance * a_max;
    search.find_pairs(positions, radii, d_search, pairs);
    system.reserve(pairs.size() + n / 4 + 16);
    glue_seen.assign(glue.entries().size(), 0);
    double min_gap = std::numeric_limits<double>::infinity();

    auto warm = [&](const std::uint32_t first,
                    const std::uint32_t second,
                    double             &lambda,
                    double             &gamma) {
      const long k = glue.find(first, second);
      if (k >= 0)
        {
          glue_seen[k] = 1;
          lambda       = glue.entries()[k].lambda;
          gamma        = gluey ? glue.entries()[k].gamma : 0.;
        }
      else
        lambda = gamma = 0.;
    };

    auto add_pair = [&](const std::uint32_t i, const std::uint32_t j) {
      // Minimum-image separation (plain X_j - X_i without periodicity).
      Vec3   e  = search.separation(positions[i], positions[j]);
      double r2 = 0.;
      for (unsigned d = 0; d < dim; ++d)
        r2 += e[d] * e[d];
      const double r   = std::sqrt(r2);
      const double gap = r - radii[i] - radii[j];
      min_gap          = std::min(min_gap, gap);
      if (gap < -allowed_overlap || r == 0.)
        throw ContactError(pair_overlap_message(i,
                                                j,
                                                gap,
                                                e,
                                                positions,
                                                radii,
                                                dim,
                                                allowed_overlap));
      for (unsigned d = 0; d < dim; ++d)
        e[d] /= r;
      double lambda, gamma;
      warm(i, j, lambda, gamma);
      if (gamma < 0. && glued_normal_positions != nullptr)
        {
          // A glued pair: its line of centres at the middle of the step
          // (see project()).
          const Vec3 m  = search.separation((*glued_normal_positions)[i],
                                           (*glued_normal_positions)[j]);
          double     m2 = 0.;
          for (unsigned d = 0; d < dim; ++d)
            m2 += m[d] * m[d];
          if (m2 > 0.)
            for (unsigned d = 0; d < dim; ++d)
              e[d] = m[d] / std::sqrt(m2);
        }
      system.add_row(i, j, e, gap, gamma < 0., lambda, gamma);
      system.set_contact_geometry(radii[i],
                                  radii[j],
                                  settings.contact_distance *
                                    std::min(radii[i], radii[j]));
    };

    auto add_wall = [&](const std::uint32_t i, const unsigned int w) {
      const Wall  &wall = walls[w];
      const double gap =
        wall.side * (positions[i][wall.axis] - wall.position) - radii[i];
      Vec3 e{{0., 0., 0.}};
      e[wall.axis] = wall.side;
      double lambda, gamma;
      warm(i, GlueState::wall_key(w), lambda, gamma);
      system.add_row(n + w, i, e, gap, gamma < 0., lambda, gamma);
      system.set_contact_geometry(0.,
                                  radii[i],
                                  settings.contact_distance * radii[i],
                                  wall_surface_velocity(wall, positions[i]));
    };

    for (const auto &p : pairs)
      add_pair(p.first, p.second);

    // Walls: O(N W) with W <= 6; every gap is computed anyway for the
    // overlap check, and the rows within the alert distance are added.
    for (unsigned int w = 0; w < walls.size(); ++w)
      for (std::uint32_t i = 0; i < n; ++i)
        {
          const double gap =
            walls[w].side * (positions[i][walls[w].axis] - walls[w].position) -
            radii[i];
          min_gap = std::min(min_gap, gap);
          if (gap < -allowed_overlap)
            {
              std::ostringstream s;
              s.precision(6);
              s << "particle " << i << " and wall " << w << " (x["
                << walls[w].axis << "] = " << walls[w].position
                << ") overlap by " << -gap << " (gap D = " << gap << ", centre "
                << format_vector(positions[i], dim) << ", radius " << radii[i]
                << ") at the start of the step; the allowed overlap is "
                << allowed_overlap;
              throw ContactError(s.str());
            }
          if (gap < d_search)
            add_wall(i, w);
        }

    // Glued pairs stay in K whatever their distance (numerics section 3).
    if (gluey)
      for (std::size_t k = 0; k < glue.entries().size(); ++k)
        {
          const auto &entry = glue.entries()[k];
          if (glue_seen[k] || !(entry.gamma < 0.) || entry.first >= n)
            continue;
          if (GlueState::is_wall_key(entry.second))
            {
              const unsigned w = entry.second - GlueState::wall_key(0);
              if (w < walls.size())
                add_wall(entry.first, w);
            }
          else if (entry.second < n)
            add_pair(entry.first, entry.second);
        }
    return min_gap;
  }



  ProjectionStatistics
  ContactProjector::project(const std::vector<Vec3>   &positions,
                            const std::vector<double> &radii,
                            const std::vector<Vec3>   &predicted,
                            const double               dt,
                            std::vector<Vec3>         &corrected,
                            const std::vector<Vec3>   &normal_positions)
  {
    if (normal_positions.size() != positions.size())
      throw ContactError("the glued pairs' normal positions have " +
                         std::to_string(normal_positions.size()) +
                         " entries for " + std::to_string(positions.size()) +
                         " particles");
    return project_with(positions,
                        radii,
                        predicted,
                        dt,
                        corrected,
                        &normal_positions,
                        {nullptr, nullptr});
  }



  ProjectionStatistics
  ContactProjector::project(const std::vector<Vec3>   &positions,
                            const std::vector<double> &radii,
                            const std::vector<Vec3>   &predicted,
                            const double               dt,
                            std::vector<Vec3>         &corrected)
  {
    return project_with(positions,
                        radii,
                        predicted,
                        dt,
                        corrected,
                        nullptr,
                        {nullptr, nullptr});
  }



  ProjectionStatistics
  ContactProjector::project(const std::vector<Vec3>   &positions,
                            const std::vector<double> &radii,
                            const std::vector<Vec3>   &predicted,
                            const std::vector<Vec3>   &predicted_rotation,
                            const double               dt,
                            std::vector<Vec3>         &corrected,
                            std::vector<Vec3>         &corrected_rotation,
                            const std::vector<Vec3>   *normal_positions)
  {
    if (normal_positions != nullptr &&
        normal_positions->size() != positions.size())
      throw ContactError("the glued pairs' normal positions have " +
                         std::to_string(normal_positions->size()) +
                         " entries for " + std::to_string(positions.size()) +
                         " particles");
    if (predicted_rotation.size() != positions.size())
      throw ContactError(
        "size mismatch: " + std::to_string(predicted_rotation.size()) +
        " angular velocities for " + std::to_string(positions.size()) +
        " particles");
    for (std::size_t i = 0; i < predicted_rotation.size(); ++i)
      for (unsigned d = 0; d < 3; ++d)
        if (!std::isfinite(predicted_rotation[i][d]))
          throw ContactError(
            "predicted angular velocity of particle " + std::to_string(i) +
            " is not finite: " + format_vector(predicted_rotation[i], 3));
    return project_with(positions,
                        radii,
                        predicted,
                        dt,
                        corrected,
                        normal_positions,
                        {&predicted_rotation, &corrected_rotation});
  }



  ConstraintSystem::Result
  ContactProjector::solve_rows(const double dt)
  {
    // Friction has one solver, Gauss-Seidel with the subspace step on the
    // normal impulses, whatever the frictionless solver chosen.
    if (settings.friction > 0.)
      return system.solve_frictional(settings.friction,
                                     u_star,
                                     w_star,
                                     inv_w,
                                     inv_j,
                                     dt,
                                     settings.tolerance,
                                     settings.max_iterations,
                                     true,
                                     u,
                                     w);
    return system.solve(settings.solver,
                        u_star,
                        inv_w,
                        dt,
                        settings.tolerance,
                        settings.max_iterations,
                        u);
  }



  void
  ContactProjector::set_up_rotations(const std::vector<double> &radii,
                                     const std::vector<Vec3>   &rotation)
  {
    // Rotations: a 2D particle turns about z only; walls do not turn.
    const unsigned dim = settings.dimension;
    const auto     n   = radii.size();
    w_star.assign(n + walls.size(), Vec3{{0., 0., 0.}});
    inv_j.assign(n + walls.size(), 0.);
    const double ratio = dim == 3 ? 4. / 3. : 1.;
    for (std::size_t i = 0; i < n; ++i)
      {
        for (unsigned d = (dim == 3 ? 0 : 2); d < 3; ++d)
          w_star[i][d] = rotation[i][d];
        inv_j[i] = rotational_weights.empty() ?
                     inv_w[i] / (ratio * radii[i] * radii[i]) :
                     1. / rotational_weights[i];
      }
  }



  Vec3
  ContactProjector::wall_surface_velocity(const Wall &wall,
                                          const Vec3 &centre) const
  {
    // The wall's own velocity at the contact point, beyond the one
    // velocity its body has (friction only).
    Vec3 surface{{0., 0., 0.}};
    if (!wall_velocity || !(settings.friction > 0.))
      return surface;
    Vec3 point        = centre;
    point[wall.axis]  = wall.position;
    const Vec3 v_wall = wall_velocity(wall, point);
    for (unsigned d = 0; d < settings.dimension; ++d)
      if (d != wall.axis)
        surface[d] = v_wall[d] - wall.velocity[d];
    return surface;
  }



  ProjectionStatistics
  ContactProjector::project_with(
    const std::vector<Vec3>   &positions,
    const std::vector<double> &radii,
    const std::vector<Vec3>   &predicted,
    const double               dt,
    std::vector<Vec3>         &corrected,
    const std::vector<Vec3>   *glued_normal_positions,
    const std::pair<const std::vector<Vec3> *, std::vector<Vec3> *> &rotation)
  {
    validate(positions, radii, predicted, dt);
    const unsigned dim      = settings.dimension;
    const auto     n        = static_cast<std::uint32_t>(positions.size());
    const bool     friction = settings.friction > 0.;
    if (friction && rotation.first == nullptr)
      throw ContactError("friction turns the particles: the projection needs "
                         "their angular velocities (project() with "
                         "rotations)");
    if (!rotational_weights.empty() && rotational_weights.size() != n)
      throw ContactError(
        "size mismatch: " + std::to_string(rotational_weights.size()) +
        " rotational weights for " + std::to_string(n) + " particles");

    ProjectionStatistics statistics;
    corrected = predicted;
    if (rotation.first != nullptr)
      *rotation.second = *rotation.first;
    if (settings.model == Model::none)
      {
        // No admissible set: nothing to search, nothing to remember.
        statistics.min_gap = std::numeric_limits<double>::quiet_NaN();
        statistics.n_glued = 0;
        return statistics;
      }

    // Bodies: particles, then walls (zero inverse weight, own velocity).
    u_star.assign(n + walls.size(), Vec3{{0., 0., 0.}});
    inv_w.assign(n + walls.size(), 0.);
    double u_max = 0., a_max = 0.;
    for (std::uint32_t i = 0; i < n; ++i)
      {
        a_max    = std::max(a_max, radii[i]);
        double s = 0.;
        for (unsigned d = 0; d < dim; ++d)
          {
            u_star[i][d] = predicted[i][d];
            s += predicted[i][d] * predicted[i][d];
          }
        u_max    = std::max(u_max, std::sqrt(s));
        inv_w[i] = weights.empty() ? 1. : 1. / weights[i];
      }
    for (std::size_t w = 0; w < walls.size(); ++w)
      for (unsigned d = 0; d < dim; ++d)
        u_star[n + w][d] = walls[w].velocity[d];
    if (friction)
      set_up_rotations(radii, *rotation.first);

    const double factor = std::max(2., settings.alert_factor);
    double       d_a = std::max(settings.alert_distance, factor * dt * u_max);
    check_periods(a_max, d_a + settings.contact_distance * a_max);

    ConstraintSystem::Result result;
    while (true)
      {
        const auto   start_search = Clock::now();
        const double min_gap =
          assemble(positions, radii, d_a, glued_normal_positions);
        statistics.search_seconds += seconds_since(start_search);
        if (statistics.n_search_repeats == 0)
          statistics.min_gap = min_gap;

        const auto         start_solve       = Clock::now();
        const unsigned int iterations_before = result.iterations;
        result                               = solve_rows(dt);
        result.iterations += iterations_before;
        statistics.relaxation =
          std::min(statistics.relaxation, result.relaxation);
        statistics.solve_seconds += seconds_since(start_solve);

        // A posteriori check of the alert distance (see the header).
        double u_corrected_max = 0.;
        for (std::uint32_t i = 0; i < n; ++i)
          u_corrected_max =
            std::max(u_corrected_max,
                     std::sqrt(u[i][0] * u[i][0] + u[i][1] * u[i][1] +
                               u[i][2] * u[i][2]));
        if (2. * dt * u_corrected_max <= d_a ||
            statistics.n_search_repeats >= 8)
          break;
        d_a = factor * dt * u_corrected_max;
        ++statistics.n_search_repeats;
        // Before the glue state is touched, so that a throw leaves it as it
        // was.
        check_periods(a_max, d_a + settings.contact_distance * a_max);

        // Warm start the repeated solve with what was just computed.
        std::vector<GlueState::Entry> entries;
        entries.reserve(system.size());
        for (std::size_t k = 0; k < system.size(); ++k)
          entries.push_back(glue_entry(system, k, n));
        glue.rebuild(std::move(entries));
      }

    // New state: glue update gamma <- min(0, gamma - dt lambda) (gluey), and
    // the multipliers as the next warm start.
    std::vector<GlueState::Entry> entries;
    entries.reserve(system.size());
    unsigned int n_active = 0;
    for (std::size_t k = 0; k < system.size(); ++k)
      {
        GlueState::Entry e = glue_entry(system, k, n);
        // Only gluey contacts keep a glue variable from step to step.
        e.gamma = 0.;
        if (settings.model == Model::gluey)
          {
            e.gamma = std::min(0., system.gamma(k) - dt * e.lambda);
            if (e.gamma > -settings.glue_snap)
              e.gamma = 0.;
          }
        if (e.lambda != 0.)
          ++n_active;
        entries.push_back(e);
      }
    glue.rebuild(std::move(entries));

    for (std::uint32_t i = 0; i < n; ++i)
      for (unsigned d = 0; d < dim; ++d)
        corrected[i][d] = u[i][d];
    if (friction)
      {
        for (std::uint32_t i = 0; i < n; ++i)
          (*rotation.second)[i] = w[i];
        statistics.n_sliding = count_sliding(system, settings.friction);
      }

    statistics.n_constraints  = static_cast<unsigned int>(system.size());
    statistics.n_active       = n_active;
    statistics.n_glued        = glue.n_glued();
    statistics.iterations     = result.iterations;
    statistics.residual       = result.residual;
    statistics.converged      = result.converged;
    carried_overlap           = result.converged ? 0. : 2. * result.residual;
    statistics.alert_distance = d_a;
    return statistics;
  }



  double
  ContactProjector::tolerated_overlap() const
  {
    const double base = settings.overlap_tolerance > 0. ?
                          settings.overlap_tolerance :
                          10. * settings.tolerance;
    return std::max(base, carried_overlap);
  }



  double
  ContactProjector::minimum_gap(const std::vector<Vec3>     &positions,
                                const std::vector<double>   &radii,
                                const std::vector<Wall>     &walls,
                                const unsigned int           dimension,
                                const double                 search_distance,
                                const std::array<double, 3> &periods)
  {
    if (radii.size() != positions.size())
      throw ContactError("minimum_gap: size mismatch between positions and "
                         "radii");
    check_periodicity(periods, dimension, walls);
    double a_max = 0.;
    for (const double a : radii)
      a_max = std::max(a_max, a);
    // Only overlaps need an unambiguous image here (alert distance 0): the
    // minimum image is the closest image whatever the search distance.
    require_unambiguous_image(periods, dimension, a_max, 0., "minimum_gap: ");

    PairSearch search(dimension, PairSearchMethod::cell_list);
    search.set_periodicity(periods);
    std::vector<PairSearch::Pair> pairs;
    search.find_pairs(positions, radii, search_distance, pairs);
    double min_gap = std::numeric_limits<double>::infinity();
    for (const auto &p : pairs)
      {
        const Vec3 dx =
          search.separation(positions[p.first], positions[p.second]);
        double r2 = 0.;
        for (unsigned d = 0; d < dimension; ++d)
          r2 += dx[d] * dx[d];
        min_gap =
          std::min(min_gap, std::sqrt(r2) - radii[p.first] - radii[p.second]);
      }
    for (const auto &wall : walls)
      for (std::size_t i = 0; i < positions.size(); ++i)
        min_gap =
          std::min(min_gap,
                   wall.side * (positions[i][wall.axis] - wall.position) -
                     radii[i]);
    return min_gap;
  }
} // namespace Fidus::Contact
