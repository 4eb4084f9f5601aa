#include <algorithm>
#include <cmath>
#include <fidus/contact/pair_search.h>
#include <fidus/simulation/gap_time_step.h>
#include <limits>
#include <stdexcept>
#include <string>

namespace Fidus
{
  GapTimeStep::GapTimeStep(const double                      fraction,
                           const double                      floor,
                           const unsigned int                dimension,
                           const std::vector<Contact::Wall> &walls,
                           const std::array<double, 3>      &periods)
    : fraction(fraction)
    , floor(floor)
    , dimension(dimension)
    , walls(walls)
    , search(dimension, Contact::PairSearchMethod::cell_list)
  {
    search.set_periodicity(periods);
    if (!(fraction > 0. && fraction <= 1.))
      throw std::invalid_argument("GapTimeStep: the fraction " +
                                  std::to_string(fraction) +
                                  " is not in (0, 1]");
    if (!(floor >= 0.))
      throw std::invalid_argument("GapTimeStep: the floor " +
                                  std::to_string(floor) + " is negative");
  }



  GapTimeStep::Limit
  GapTimeStep::limit(const std::vector<Vec3>   &positions,
                     const std::vector<double> &radii,
                     const std::vector<Vec3>   &velocities,
                     const double               upper,
                     const Contact::GlueState  *glue) const
  {
    Limit result;
    result.dt = upper;

    double u_max = 0.;
    for (const Vec3 &u : velocities)
      {
        double u2 = 0.;
        for (unsigned int d = 0; d < dimension; ++d)
          u2 += u[d] * u[d];
        u_max = std::max(u_max, std::sqrt(u2));
      }
    if (u_max == 0.)
      return result;

    const auto glued = [&](const std::uint32_t first,
                           const std::uint32_t second) {
      if (glue == nullptr)
        return false;
      const long k = glue->find(first, second);
      return k >= 0 && glue->entries()[k].gamma < 0.;
    };
    const auto consider = [&](const double gap,
                              const double closing,
                              const double sliding,
                              const double distance,
                              const double a,
                              const int    i,
                              const int    j) {
      if (gap < floor * a ||
          glued(i,
                j >= 0 ? std::uint32_t(j) :
                         Contact::GlueState::wall_key(-1 - j)))
        return;
      // Opening counts as closing does. The resistance of a gap falls as
      // it opens, so a long step from the start-of-step velocity opens it
      // too little, as it closes an approaching gap too much; followed
      // only on the way in, a passing pair lingered on the way out and
      // ended up to 1.2 a from the fine fixed step's trajectory
      // (doc/results.md).
      double dt = std::numeric_limits<double>::infinity();
      if (closing != 0.)
        dt = fraction * gap / std::abs(closing);
      // A straight step of a pair sliding past each other at v_t moves
      // the centres apart by the chord error (v_t dt)^2 / (2 r).
      if (sliding > 0. && distance > 0.)
        dt = std::min(dt, std::sqrt(2. * distance * fraction * gap) / sliding);
      if (dt < result.dt)
        {
          result.dt            = dt;
          result.limited       = true;
          result.i             = i;
          result.j             = j;
          result.gap           = gap;
          result.closing_speed = closing;
          result.sliding_speed = sliding;
        }
    };

    // A pair closes at most at 2 u_max, so only gaps below
    // 2 u_max upper / f can limit the step below the upper bound.
    const double reach = 2. * u_max * upper / fraction;
    search.find_pairs(positions, radii, reach, pairs);
    for (const auto &p : pairs)
      {
        const Vec3 dx =
          search.separation(positions[p.first], positions[p.second]);
        double r2 = 0., rate = 0., v2 = 0.;
        for (unsigned int d = 0; d < dimension; ++d)
          {
            const double dv = velocities[p.second][d] - velocities[p.first][d];
            r2 += dx[d] * dx[d];
            rate += dx[d] * dv;
            v2 += dv * dv;
          }
        const double r = std::sqrt(r2);
        if (r == 0.)
          continue;
        const double normal = rate / r;
        consider(r - radii[p.first] - radii[p.second],
                 -normal,
                 std::sqrt(std::max(0., v2 - normal * normal)),
                 r,
                 std::min(radii[p.first], radii[p.second]),
                 p.first,
                 p.second);
      }

    for (unsigned int w = 0; w < walls.size(); ++w)
      {
        const Contact::Wall &wall = walls[w];
        for (unsigned int i = 0; i < positions.size(); ++i)
          consider(wall.side * (positions[i][wall.axis] - wall.position) -
                     radii[i],
                   -wall.side * velocities[i][wall.axis],
                   0.,
                   0.,
                   radii[i],
                   i,
                   -1 - int(w));
      }
    return result;
  }
} // namespace Fidus
