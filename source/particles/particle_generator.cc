#include <algorithm>
#include <cmath>
#include <fidus/contact/contact_error.h>
#include <fidus/contact/pair_search.h>
#include <fidus/particles/particle_generator.h>
#include <fidus/particles/particle_measure.h>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>

namespace Fidus::Contact
{
  namespace
  {
    /// Densest packings: hexagonal discs, FCC spheres.
    constexpr double densest_2d = 0.90689968211710892; // pi / (2 sqrt 3)
    constexpr double densest_3d = 0.74048048969306104; // pi / (3 sqrt 2)

    /// Pushes aim at a gap min_separation + margin_factor a_min, so that
    /// the sweeps end, in finitely many steps, with every gap at least
    /// min_separation (instead of converging to it from below).
    constexpr double margin_factor = 1e-9;

    /// Allowed overlap of the postcondition, relative to a_min (rounding).
    constexpr double overlap_tolerance = 1e-12;

    /// Scaled fraction of the first, random configuration.
    constexpr double initial_fraction = 0.1;

    /// s grows when the largest overlap of a sweep is below this times the
    /// smallest scaled radius.
    constexpr double growth_tolerance = 1.;

    /// Growth factor s <- s (1 + g): first value and bounds.
    constexpr double g_initial = 0.02;
    constexpr double g_min     = 1e-4;
    constexpr double g_max     = 0.1;

    /// Over-relaxation factor of the pushes, used for overlaps below
    /// omega_range times the smallest scaled radius (see generate()).
    constexpr double omega       = 1.95;
    constexpr double omega_range = 0.3;

    /// Verlet skin, relative to the largest scaled radius.
    constexpr double skin_factor = 0.5;

    /// The growth has stalled (jammed) if s has not grown for this many
    /// sweeps.
    constexpr unsigned int stall_sweeps = 1000;

    /**
     * splitmix64: portable, so that a seed gives the same particles with
     * any standard library (std::uniform_real_distribution and
     * std::shuffle are implementation-defined). Independent streams for the
     * radii and the positions, so that one does not shift the other.
     */
    class Random
    {
    public:
      Random(const std::uint64_t seed, const std::uint64_t stream)
        : state(seed * 0x9e3779b97f4a7c15ull + stream * 0xd1b54a32d192ed03ull)
      {}

      std::uint64_t
      next()
      {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z               = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z               = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
      }

      /// Uniform in [0, 1).
      double
      uniform()
      {
        return static_cast<double>(next() >> 11) * 0x1.0p-53;
      }

      /// Uniform integer in [0, n), n >= 1 (the bias, below n / 2^53, is
      /// irrelevant here).
      std::size_t
      below(const std::size_t n)
      {
        return std::min(n - 1,
                        static_cast<std::size_t>(uniform() *
                                                 static_cast<double>(n)));
      }

    private:
      std::uint64_t state;
    };

    std::string
    axis_name(const unsigned int d)
    {
      const char *names[] = {"x", "y", "z"};
      return names[d];
    }

    std::string
    to_text(const double x)
    {
      std::ostringstream s;
      s.precision(6);
      s << x;
      return s.str();
    }

    /**
     * Counts per radius value for N particles: floor(N w_k), the remaining
     * ones to the largest remainders (ties to the smaller index), so that
     * they sum to N and each is within 1 of N w_k.
     */
    std::vector<std::size_t>
    counts_from_weights(const std::size_t n, const std::vector<double> &weights)
    {
      const std::size_t        k = weights.size();
      std::vector<std::size_t> counts(k);
      std::vector<double>      remainder(k);
      std::size_t              total = 0;
      for (std::size_t i = 0; i < k; ++i)
        {
          const double exact = static_cast<double>(n) * weights[i];
          counts[i]          = static_cast<std::size_t>(std::floor(exact));
          remainder[i]       = exact - static_cast<double>(counts[i]);
          total += counts[i];
        }
      std::vector<std::size_t> order(k);
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) {
        return remainder[i] > remainder[j];
      });
      for (std::size_t r = 0; total < n; ++r, ++total)
        ++counts[order[r % k]];
      // Rounding of N w_k can in principle overshoot by one.
      for (std::size_t r = k; total > n; --total)
        {
          while (counts[order[--r]] == 0)
            ;
          --counts[order[r]];
        }
      return counts;
    }

    /// Area (2D) or volume (3D) of the region; throws unless its bounds are
    /// finite and ordered and z is not periodic in 2D.
    double
    checked_region_measure(const GeneratorSettings &s)
    {
      const unsigned int dim            = s.dimension;
      double             region_measure = 1.;
      for (unsigned d = 0; d < dim; ++d)
        {
          if (!std::isfinite(s.lower[d]) || !std::isfinite(s.upper[d]) ||
              !(s.lower[d] < s.upper[d]))
            throw ContactError("particle generator: the region along " +
                               axis_name(d) + " is [" + to_text(s.lower[d]) +
                               ", " + to_text(s.upper[d]) +
                               "]; allowed: finite bounds with lower < upper");
          region_measure *= s.upper[d] - s.lower[d];
        }
      if (dim == 2 && s.periodic[2])
        throw ContactError("particle generator: z is periodic in 2D, where it "
                           "does not exist");
      return region_measure;
    }



    /// The number fraction of each radius value, normalised to sum 1;
    /// throws for invalid radii or weights.
    std::vector<double>
    checked_weights(const GeneratorSettings &s)
    {
      if (s.radii_values.empty())
        throw ContactError("particle generator: no radius given; allowed: one "
                           "value (monodisperse) or several (with weights)");
      for (const double a : s.radii_values)
        if (!(a > 0.) || !std::isfinite(a))
          throw ContactError("particle generator: radius " + to_text(a) +
                             "; allowed: finite radii > 0");
      std::vector<double> weights = s.radii_weights;
      if (weights.empty())
        weights.assign(s.radii_values.size(),
                       1. / static_cast<double>(s.radii_values.size()));
      if (weights.size() != s.radii_values.size())
        throw ContactError(
          "particle generator: " + std::to_string(weights.size()) +
          " weights for " + std::to_string(s.radii_values.size()) +
          " radii; allowed: one number fraction per radius "
          "(or none: equal fractions)");
      double weight_sum = 0.;
      for (const double w : weights)
        {
          if (!(w >= 0.) || !std::isfinite(w))
            throw ContactError("particle generator: radius weight " +
                               to_text(w) +
                               "; allowed: number fractions >= 0 summing to 1");
          weight_sum += w;
        }
      // 1e-9 accepts decimal input such as 0.3, 0.7 but not a forgotten
      // value.
      if (!(std::abs(weight_sum - 1.) <= 1e-9))
        throw ContactError("particle generator: the radius weights sum to " +
                           to_text(weight_sum) +
                           "; allowed: number fractions summing to 1");
      for (double &w : weights)
        w /= weight_sum;
      return weights;
    }



    /// The densest packing of the dimension, with the words the messages
    /// use for it.
    struct FractionLimit
    {
      double      densest;
      std::string what_fraction;
      std::string limit_text;
    };

    FractionLimit
    fraction_limit(const unsigned int dim)
    {
      const double      densest = dim == 2 ? densest_2d : densest_3d;
      const std::string what_fraction =
        dim == 2 ? "area fraction" : "volume fraction";
      const std::string limit_text = dim == 2 ?
                                       "0.9069 (hexagonal packing of discs)" :
                                       "0.7405 (densest packing of spheres)";
      return {densest, what_fraction, limit_text};
    }



    /// Total area (volume) of @p counts particles of each radius value.
    double
    measure_of(const GeneratorSettings        &s,
               const std::vector<std::size_t> &counts)
    {
      double m = 0.;
      for (std::size_t k = 0; k < counts.size(); ++k)
        m += static_cast<double>(counts[k]) *
             particle_measure(s.dimension, s.radii_values[k]);
      return m;
    }



    /// The number of particles: given, or the one (with its rounded counts)
    /// whose total measure comes closest to the target fraction; throws if
    /// both or neither are given, or for a target out of range.
    std::size_t
    number_of_particles(const GeneratorSettings   &s,
                        const std::vector<double> &weights,
                        const double               region_measure,
                        const FractionLimit       &limit)
    {
      const unsigned int dim         = s.dimension;
      const bool         by_count    = s.n_particles > 0;
      const bool         by_fraction = s.target_fraction != 0.;
      if (by_count == by_fraction)
        throw ContactError(
          "particle generator: give either a number of particles (> 0) or a "
          "target fraction (> 0), not " +
          std::string(by_count ? "both" : "neither"));
      if (by_fraction &&
          (!(s.target_fraction > 0.) || !(s.target_fraction < limit.densest)))
        throw ContactError("particle generator: target " + limit.what_fraction +
                           " " + to_text(s.target_fraction) +
                           "; allowed: > 0 and < " + limit.limit_text);

      // The number of particles: given, or the one (with its rounded counts)
      // whose total measure comes closest to the target fraction.
      std::size_t n = s.n_particles;
      if (by_fraction)
        {
          double mean = 0.;
          for (std::size_t k = 0; k < weights.size(); ++k)
            mean += weights[k] * particle_measure(dim, s.radii_values[k]);
          const double target = s.target_fraction * region_measure;
          const auto   guess  = static_cast<std::size_t>(target / mean);
          double       best   = std::numeric_limits<double>::infinity();
          n                   = 0;
          for (std::size_t m = (guess > 2 ? guess - 2 : 1); m <= guess + 2; ++m)
            {
              const double error = std::abs(
                measure_of(s, counts_from_weights(m, weights)) - target);
              if (error < best)
                {
                  best = error;
                  n    = m;
                }
            }
          // One particle too many for a tiny target (more than half of it).
          if (measure_of(s, counts_from_weights(n, weights)) > 2. * target)
            throw ContactError(
              "particle generator: target " + limit.what_fraction + " " +
              to_text(s.target_fraction) +
              " is less than half the fraction of one particle; allowed: a "
              "fraction that places at least one particle");
        }
      if (n > std::numeric_limits<std::uint32_t>::max() / 2)
        throw ContactError("particle generator: " + std::to_string(n) +
                           " particles; allowed: fewer than 2^31");
      return n;
    }



    /// Throws if particles kept min_separation apart cannot fit: they cannot
    /// be denser than particles of radius a + min_separation / 2 in contact.
    void
    check_room_for_separation(const GeneratorSettings        &s,
                              const std::vector<std::size_t> &counts,
                              const double                    region_measure,
                              const FractionLimit            &limit)
    {
      const unsigned int dim = s.dimension;
      // Particles kept min_separation apart cannot be denser than particles
      // of radius a + min_separation / 2 in contact.
      if (s.min_separation > 0.)
        {
          double effective = 0.;
          for (std::size_t k = 0; k < counts.size(); ++k)
            effective +=
              static_cast<double>(counts[k]) *
              particle_measure(dim, s.radii_values[k] + 0.5 * s.min_separation);
          effective /= region_measure;
          if (!(effective < limit.densest))
            throw ContactError(
              "particle generator: with the minimum separation " +
              to_text(s.min_separation) +
              " each particle needs the room of one of radius a + " +
              to_text(0.5 * s.min_separation) + ", an " + limit.what_fraction +
              " of " + to_text(effective) + "; allowed: < " + limit.limit_text);
        }
    }



    /// Throws if the region is too narrow along an axis for the largest
    /// radius in use and the minimum separation.
    void
    check_region_width(const GeneratorSettings        &s,
                       const std::vector<std::size_t> &counts)
    {
      const unsigned int dim   = s.dimension;
      double             a_max = 0.;
      for (std::size_t k = 0; k < counts.size(); ++k)
        if (counts[k] > 0)
          a_max = std::max(a_max, s.radii_values[k]);
      const double h = s.min_separation;
      for (unsigned d = 0; d < dim; ++d)
        {
          const double width = s.upper[d] - s.lower[d];
          // Along a periodic axis one pair must not overlap through two of
          // its images (the minimum image would miss one).
          const double needed =
            s.periodic[d] ? 2. * (2. * a_max + h) : 2. * (a_max + h);
          if (!(width > needed))
            throw ContactError("particle generator: the region is " +
                               to_text(width) + " wide along " + axis_name(d) +
                               (s.periodic[d] ? " (periodic)" : "") +
                               ", too narrow for the largest radius " +
                               to_text(a_max) + " and minimum separation " +
                               to_text(h) + "; allowed: wider than " +
                               to_text(needed));
        }
    }



    /**
     * The state of generate() and its stages: random centres, then radii
     * grown by a factor s up to 1 while Gauss-Seidel sweeps of pairwise
     * pushes (on a Verlet list) remove the overlaps. A class because the
     * stages share most of this state.
     */
    class Relaxation
    {
    public:
      Relaxation(const GeneratorSettings   &settings,
                 const std::vector<double> &radii,
                 const double               particle_fraction)
        : settings(settings)
        , radii(radii)
        , particle_fraction(particle_fraction)
        , dim(settings.dimension)
        , n(radii.size())
        , h(settings.min_separation)
        , lower(settings.lower)
        , upper(settings.upper)
        , periodic(settings.periodic)
        , search(dim, PairSearchMethod::cell_list)
      {
        for (const double a : radii)
          {
            a_min = std::min(a_min, a);
            a_max = std::max(a_max, a);
          }

        for (unsigned d = 0; d < dim; ++d)
          if (periodic[d])
            periods[d] = upper[d] - lower[d];
        search.set_periodicity(periods);
      }

      /// The sweeps until the particles are free of overlap at s = 1.
      GeneratedParticles
      run();

    private:
      /// Centre of particle i along a non-periodic axis: in
      /// [lower + a_i + h, upper - a_i - h] (not empty: checked).
      void
      clamp(Vec3 &x, const double a) const
      {
        for (unsigned d = 0; d < dim; ++d)
          if (!periodic[d])
            x[d] = std::min(std::max(x[d], lower[d] + a + h), upper[d] - a - h);
      }

      /// Wrap into [lower, upper) along the periodic axes.
      void
      wrap(Vec3 &x) const
      {
        for (unsigned d = 0; d < dim; ++d)
          if (periodic[d])
            {
              const double L = periods[d];
              double       w = x[d] - L * std::floor((x[d] - lower[d]) / L);
              // Rounding can land on upper (or just below lower).
              if (!(w < upper[d]) || w < lower[d])
                w = lower[d];
              x[d] = w;
            }
      }

      /// Minimum image of a difference of two centres. Centres are wrapped
      /// at every build of the neighbour list and move less than the skin
      /// (< L / 2) until the next one, so a few subtractions replace the
      /// slower L round(dx / L).
      double
      minimum_image(double dx, const unsigned d) const
      {
        if (periodic[d])
          {
            const double L = periods[d];
            while (dx > 0.5 * L)
              dx -= L;
            while (dx < -0.5 * L)
              dx += L;
          }
        return dx;
      }

      std::vector<Vec3>
      draw_centres() const;

      void
      sort_by_cells(const std::vector<Vec3> &drawn);

      void
      update_verlet_list();

      double
      sweep();

      double
      checked_min_gap();

      GeneratedParticles
      particles_in_drawn_order(double min_gap) const;

      void
      give_up(bool stalled);

      const GeneratorSettings   &settings;
      const std::vector<double> &radii;
      const double               particle_fraction;

      const unsigned int           dim;
      const std::size_t            n;
      const double                 h;
      const std::array<double, 3> &lower;
      const std::array<double, 3> &upper;
      const std::array<bool, 3>   &periodic;

      double                a_min = std::numeric_limits<double>::max();
      double                a_max = 0.;
      std::array<double, 3> periods{{0., 0., 0.}};
      PairSearch            search;

      /// Particles in cell order: their index in the drawn order, centres,
      /// radii and inverse measures.
      std::vector<std::uint32_t> order;
      std::vector<Vec3>          x;
      std::vector<double>        a, inv_measure;

      double margin = 0., target_gap = 0.;
      /// Radii scaled by s, and the growth factor of s.
      double s = 0., g = g_initial;

      std::vector<double>           scaled;
      std::vector<Vec3>             x_build;
      std::vector<PairSearch::Pair> pairs;
      double                        s_build = 0., skin = 0.;
      bool                          need_build = true;

      unsigned int sweeps = 0, sweeps_since_growth = 0,
                   sweeps_since_progress = 0;
      /// Smallest largest-overlap of a sweep seen at s = 1, for the stall
      /// test.
      double best_overlap = std::numeric_limits<double>::infinity();
    };



    /// The starting centres, from the position stream of the seed.
    std::vector<Vec3>
    Relaxation::draw_centres() const
    {
      // Random centres, each inside the region for its full radius.
      std::vector<Vec3> drawn(n, Vec3{{0., 0., 0.}});
      Random            random(settings.seed, 2);
      for (std::size_t i = 0; i < n; ++i)
        {
          for (unsigned d = 0; d < dim; ++d)
            {
              const double lo =
                periodic[d] ? lower[d] : lower[d] + radii[i] + h;
              const double hi =
                periodic[d] ? upper[d] : upper[d] - radii[i] - h;
              drawn[i][d] = lo + (hi - lo) * random.uniform();
            }
          clamp(drawn[i], radii[i]);
          wrap(drawn[i]);
        }
      return drawn;
    }



    /// Sets order, x, a and inv_measure: the particles sorted by cells.
    void
    Relaxation::sort_by_cells(const std::vector<Vec3> &drawn)
    {
      // Work in an order sorted by cells of size 2 a_max (x fastest, as the
      // cell list scans them), so that the pairs of a sweep touch nearby
      // memory: particles move only a few radii in all, so one sort at the
      // start is enough. The result is given back in the drawn order.
      order.resize(n);
      {
        std::vector<std::uint64_t> key(n, 0);
        for (std::size_t i = 0; i < n; ++i)
          for (int d = static_cast<int>(dim) - 1; d >= 0; --d)
            {
              const double width = upper[d] - lower[d];
              const auto   cells = static_cast<std::uint64_t>(
                std::max(1., std::min(1e5, std::floor(width / (2. * a_max)))));
              const auto c = std::min(cells - 1,
                                      static_cast<std::uint64_t>(
                                        (drawn[i][d] - lower[d]) / width *
                                        static_cast<double>(cells)));
              key[i]       = key[i] * cells + c;
            }
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) {
          return key[i] < key[j];
        });
      }
      x.resize(n);
      a.resize(n);
      inv_measure.resize(n);
      for (std::size_t k = 0; k < n; ++k)
        {
          x[k] = drawn[order[k]];
          a[k] = radii[order[k]];
          // Share of a correction taken by each particle of a pair: inverse
          // volumes (areas), so that a large particle moves less.
          inv_measure[k] = 1. / std::pow(a[k], dim);
        }
    }



    /// Rebuilds the Verlet list of pairs if needed.
    void
    Relaxation::update_verlet_list()
    {
      // Verlet list: rebuild when a pair outside it could have come
      // closer than the target gap (displacements plus radius growth).
      if (!need_build)
        {
          double d2_max = 0.;
          for (std::size_t i = 0; i < n; ++i)
            {
              double d2 = 0.;
              for (unsigned d = 0; d < dim; ++d)
                d2 += (x[i][d] - x_build[i][d]) * (x[i][d] - x_build[i][d]);
              d2_max = std::max(d2_max, d2);
            }
          need_build =
            2. * std::sqrt(d2_max) + 2. * (s - s_build) * a_max >= skin;
        }
      if (need_build)
        {
          for (std::size_t i = 0; i < n; ++i)
            {
              wrap(x[i]);
              scaled[i] = s * a[i];
            }
          skin = skin_factor * s * a_max;
          search.find_pairs(x, scaled, target_gap + skin, pairs);
          x_build    = x;
          s_build    = s;
          need_build = false;
        }
    }



    /// One sweep over the Verlet list; returns the largest overlap seen.
    double
    Relaxation::sweep()
    {
      // One Gauss-Seidel sweep of pairwise corrections. Small overlaps
      // are over-relaxed (pushed omega times their overlap, omega < 2):
      // that is projected SOR on the nearly linear problem, whose rate is
      // much better than plain projections once contacts form chains.
      // Large overlaps (early, or just after a growth) are pushed exactly
      // by their overlap: there the problem is far from linear and an
      // overshoot could run away.
      double overlap_max = 0.;
      for (const auto &p : pairs)
        {
          const std::uint32_t i = p.first, j = p.second;
          Vec3                dx{{0., 0., 0.}};
          double              r2 = 0.;
          for (unsigned d = 0; d < dim; ++d)
            {
              dx[d] = minimum_image(x[j][d] - x[i][d], d);
              r2 += dx[d] * dx[d];
            }
          const double reach = s * (a[i] + a[j]) + target_gap;
          if (r2 >= reach * reach)
            continue;
          const double r       = std::sqrt(r2);
          const double overlap = reach - r;
          overlap_max          = std::max(overlap_max, overlap);
          const double push =
            (overlap < omega_range * s * a_min ? omega : 1.) * overlap;
          Vec3 normal{{1., 0., 0.}};
          if (r > 0.)
            for (unsigned d = 0; d < dim; ++d)
              normal[d] = dx[d] / r;
          // else: coincident centres (not seen in practice); any
          // deterministic direction separates them.
          const double share_i =
            inv_measure[i] / (inv_measure[i] + inv_measure[j]);
          for (unsigned d = 0; d < dim; ++d)
            {
              x[i][d] -= push * share_i * normal[d];
              x[j][d] += push * (1. - share_i) * normal[d];
            }
          clamp(x[i], a[i]);
          clamp(x[j], a[j]);
        }
      return overlap_max;
    }



    /// The smallest gap of the current centres by a fresh search; throws if
    /// a particle left the region.
    double
    Relaxation::checked_min_gap()
    {
      // Every pair had a gap >= h when the sweep visited it. Check
      // the configuration with a fresh search; the postcondition
      // should not rely on the Verlet list.
      for (std::size_t i = 0; i < n; ++i)
        wrap(x[i]);
      need_build = true;
      search.find_pairs(x, a, h + a_min, pairs);
      double min_gap = std::numeric_limits<double>::infinity();
      for (const auto &p : pairs)
        {
          const Vec3 dx = search.separation(x[p.first], x[p.second]);
          double     r2 = 0.;
          for (unsigned d = 0; d < dim; ++d)
            r2 += dx[d] * dx[d];
          min_gap = std::min(min_gap, std::sqrt(r2) - a[p.first] - a[p.second]);
        }
      bool inside = true;
      for (std::size_t i = 0; i < n; ++i)
        for (unsigned d = 0; d < dim; ++d)
          inside =
            inside && (periodic[d] ? x[i][d] >= lower[d] && x[i][d] < upper[d] :
                                     x[i][d] >= lower[d] + a[i] + h &&
                                       x[i][d] <= upper[d] - a[i] - h);
      if (!inside)
        throw ContactError("particle generator: internal error, a "
                           "particle is outside the region");
      return min_gap;
    }



    /// The particles in the drawn order.
    GeneratedParticles
    Relaxation::particles_in_drawn_order(const double min_gap) const
    {
      GeneratedParticles result;
      result.positions.resize(n);
      result.radii.resize(n);
      for (std::size_t k = 0; k < n; ++k)
        {
          result.positions[order[k]] = x[k];
          result.radii[order[k]]     = a[k];
        }
      result.fraction   = particle_fraction;
      result.min_gap    = min_gap;
      result.iterations = sweeps;
      return result;
    }



    /// Throws, naming the target and the fraction reached.
    void
    Relaxation::give_up(const bool stalled)
    {
      // Throw, naming the target and the fraction reached: the largest
      // fraction at which the current centres are free of overlap, i.e. with
      // all radii scaled by the largest s' <= s that opens every pair to the
      // minimum separation. Only pairs closer than that at scale s can limit
      // s' (the faces hold for the full radii).
      for (std::size_t i = 0; i < n; ++i)
        {
          wrap(x[i]);
          scaled[i] = s * a[i];
        }
      search.find_pairs(x, scaled, h, pairs);
      double s_free = s, overlap_max = 0.;
      for (const auto &p : pairs)
        {
          const Vec3 dx = search.separation(x[p.first], x[p.second]);
          double     r2 = 0.;
          for (unsigned d = 0; d < dim; ++d)
            r2 += dx[d] * dx[d];
          const double r = std::sqrt(r2), a_sum = a[p.first] + a[p.second];
          s_free      = std::min(s_free, (r - h) / a_sum);
          overlap_max = std::max(overlap_max, s * a_sum + h - r);
        }
      s_free                  = std::max(s_free, 0.);
      const std::string  what = dim == 2 ? "area fraction" : "volume fraction";
      std::ostringstream m;
      m.precision(4);
      m << "particle generator: could not reach the " << what << ' '
        << particle_fraction << " (" << n << " particles) within " << sweeps
        << " relaxation sweeps ("
        << (stalled ? "the growth stalled" : "iteration limit")
        << "): the radii grew to " << what << ' '
        << particle_fraction * std::pow(s, dim) << " with overlaps up to "
        << overlap_max / a_min
        << " times the smallest radius; without overlap, the centres reached "
           "hold only "
        << what << ' ' << particle_fraction * std::pow(s_free, dim)
        << ". The target may be too close to random close packing (about "
           "0.84 for bidisperse discs, 0.64 for spheres, less with walls), or "
           "the region too narrow for the particles; lower the fraction"
        << (stalled ? "" : " or allow more iterations");
      throw ContactError(m.str());
    }



    GeneratedParticles
    Relaxation::run()
    {
      sort_by_cells(draw_centres());

      margin     = margin_factor * a_min;
      target_gap = h + margin;
      // Radii scaled by s; s starts where the random centres have few
      // overlaps.
      s =
        std::min(1., std::pow(initial_fraction / particle_fraction, 1. / dim));
      g = g_initial;

      scaled.resize(n);
      x_build.resize(n);

      while (true)
        {
          update_verlet_list();
          const double overlap_max = sweep();
          ++sweeps;
          ++sweeps_since_growth;
          ++sweeps_since_progress;

          if (s < 1.)
            {
              if (overlap_max <= growth_tolerance * s * a_min)
                {
                  // Adapt the growth to how many sweeps the last one needed.
                  if (sweeps_since_growth <= 2)
                    g = std::min(g_max, 1.5 * g);
                  else if (sweeps_since_growth > 8)
                    g = std::max(g_min, 0.5 * g);
                  s                     = std::min(1., s * (1. + g));
                  sweeps_since_growth   = 0;
                  sweeps_since_progress = 0;
                }
            }
          else if (overlap_max <= margin)
            {
              const double min_gap = checked_min_gap();
              if (min_gap >= h - overlap_tolerance * a_min)
                return particles_in_drawn_order(min_gap);
            }
          else if (overlap_max < 0.5 * best_overlap)
            {
              best_overlap          = overlap_max;
              sweeps_since_progress = 0;
            }

          // Jammed (or nearly): neither growth nor a halving of the overlap
          // for many sweeps.
          if (sweeps_since_progress >= stall_sweeps)
            give_up(true);
          if (sweeps >= settings.max_iterations)
            give_up(false);
        }
    }
  } // namespace



  ParticleGenerator::ParticleGenerator(const GeneratorSettings &s)
    : settings(s)
  {
    const unsigned int dim = s.dimension;
    if (dim != 2 && dim != 3)
      throw ContactError("particle generator: dimension must be 2 or 3, got " +
                         std::to_string(dim));

    const double              region_measure = checked_region_measure(s);
    const std::vector<double> weights        = checked_weights(s);

    if (!(s.min_separation >= 0.) || !std::isfinite(s.min_separation))
      throw ContactError("particle generator: minimum separation " +
                         to_text(s.min_separation) + "; allowed: >= 0");

    const FractionLimit limit = fraction_limit(dim);
    const std::size_t   n =
      number_of_particles(s, weights, region_measure, limit);

    const std::vector<std::size_t> counts = counts_from_weights(n, weights);
    particle_fraction = measure_of(s, counts) / region_measure;
    if (!(particle_fraction < limit.densest))
      throw ContactError("particle generator: " + std::to_string(n) +
                         " particles give " + limit.what_fraction + " " +
                         to_text(particle_fraction) + "; allowed: < " +
                         limit.limit_text);

    check_room_for_separation(s, counts, region_measure, limit);
    check_region_width(s, counts);

    // Radii by counts, then shuffled (Fisher-Yates), so that radius and
    // position are independent.
    radii.clear();
    radii.reserve(n);
    for (std::size_t k = 0; k < counts.size(); ++k)
      radii.insert(radii.end(), counts[k], s.radii_values[k]);
    Random random(s.seed, 1);
    for (std::size_t i = radii.size(); i > 1; --i)
      std::swap(radii[i - 1], radii[random.below(i)]);
  }



  GeneratedParticles
  ParticleGenerator::generate(const GeneratorSettings &settings)
  {
    return ParticleGenerator(settings).generate();
  }



  GeneratedParticles
  ParticleGenerator::generate() const
  {
    return Relaxation(settings, radii, particle_fraction).run();
  }
} // namespace Fidus::Contact
