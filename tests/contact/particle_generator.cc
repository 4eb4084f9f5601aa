// The particle generator: dense configurations without overlap (checked by
// brute force, with the minimum image across periodic faces) and inside the
// region, for 2D bidisperse discs at area fraction 0.6 (x periodic) and 3D
// spheres at volume fraction 0.5 (x and z periodic), each at four seeds;
// the count or fraction asked for is met to its definition; the same seed
// gives the same particles bit for bit, another seed other ones; bad
// settings and a jammed target throw ContactError.

#include "test_tools.h"

#include <algorithm>
#include <cmath>
#include <fidus/contact/contact_error.h>
#include <fidus/particles/particle_generator.h>
#include <limits>
#include <string>

using namespace Fidus::Contact;

namespace
{
  const double pi = 3.14159265358979323846;

  /// Area (2D) or volume (3D) of a particle.
  double
  measure(const unsigned dim, const double a)
  {
    return dim == 2 ? pi * a * a : 4. / 3. * pi * a * a * a;
  }

  /// Area (2D) or volume (3D) of the region.
  double
  region_measure(const GeneratorSettings &s)
  {
    double m = 1.;
    for (unsigned d = 0; d < s.dimension; ++d)
      m *= s.upper[d] - s.lower[d];
    return m;
  }

  /// Smallest gap over all pairs, O(N^2), minimum image along periodic axes.
  double
  brute_force_min_gap(const GeneratorSettings &s, const GeneratedParticles &p)
  {
    double            gap = std::numeric_limits<double>::infinity();
    const std::size_t n   = p.positions.size();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        {
          double r2 = 0.;
          for (unsigned d = 0; d < s.dimension; ++d)
            {
              double dx = p.positions[j][d] - p.positions[i][d];
              if (s.periodic[d])
                {
                  const double L = s.upper[d] - s.lower[d];
                  dx -= L * std::round(dx / L);
                }
              r2 += dx * dx;
            }
          gap = std::min(gap, std::sqrt(r2) - p.radii[i] - p.radii[j]);
        }
    return gap;
  }

  /// Every centre inside the region: in [lower, upper) along periodic axes,
  /// at least radius + min_separation from the other faces; z = 0 in 2D.
  bool
  all_inside(const GeneratorSettings &s, const GeneratedParticles &p)
  {
    bool ok = p.positions.size() == p.radii.size();
    for (std::size_t i = 0; i < p.positions.size(); ++i)
      {
        for (unsigned d = 0; d < s.dimension; ++d)
          {
            const double x = p.positions[i][d];
            ok             = ok && (s.periodic[d] ?
                                      x >= s.lower[d] && x < s.upper[d] :
                                      x >= s.lower[d] + p.radii[i] + s.min_separation &&
                            x <= s.upper[d] - p.radii[i] - s.min_separation);
          }
        if (s.dimension == 2)
          ok = ok && p.positions[i][2] == 0.;
      }
    return ok;
  }

  /// The target fraction of @p s is met to half the measure of its
  /// largest particle: the count whose total measure is nearest the target.
  bool
  fraction_met(const GeneratorSettings &s, const GeneratedParticles &p)
  {
    const double largest =
      *std::max_element(s.radii_values.begin(), s.radii_values.end());
    return std::abs(p.fraction - s.target_fraction) <=
           0.5 * measure(s.dimension, largest) / region_measure(s);
  }

  /// Checks common to every generated configuration; @p name heads the
  /// lines.
  void
  check_configuration(const std::string        &name,
                      const GeneratorSettings  &s,
                      const GeneratedParticles &p)
  {
    const double a_min =
      *std::min_element(s.radii_values.begin(), s.radii_values.end());
    const double gap = brute_force_min_gap(s, p);
    TestTools::check(name + ": smallest gap - min separation in [-1e-12 a_min, "
                            "inf) (brute force, minimum image)",
                     gap - s.min_separation >= -1e-12 * a_min);
    TestTools::check(name + ": every particle inside the region",
                     all_inside(s, p));
    double total = 0.;
    for (const double a : p.radii)
      total += measure(s.dimension, a);
    TestTools::check(name + ": reported fraction = total measure / region "
                            "measure",
                     std::abs(p.fraction - total / region_measure(s)) <=
                       1e-12 * p.fraction);
    TestTools::check(name + ": reported smallest gap agrees with brute force",
                     std::abs(p.min_gap - gap) <= 1e-9 * a_min);
  }

  /// 2D bidisperse discs, radii 1 and 1.4 by equal numbers, x periodic,
  /// walls in y: about 990 discs at area fraction 0.6.
  GeneratorSettings
  settings_2d()
  {
    GeneratorSettings s;
    s.dimension       = 2;
    s.lower           = {{-40., 2., 0.}};
    s.upper           = {{40., 98., 0.}};
    s.periodic        = {{true, false, false}};
    s.radii_values    = {1., 1.4};
    s.radii_weights   = {0.5, 0.5};
    s.target_fraction = 0.6;
    s.seed            = 7;
    return s;
  }

  /// 3D spheres of radius 1, x and z periodic, walls in y: about 2150
  /// spheres at volume fraction 0.5.
  GeneratorSettings
  settings_3d()
  {
    GeneratorSettings s;
    s.dimension       = 3;
    s.lower           = {{0., 0., 0.}};
    s.upper           = {{30., 20., 30.}};
    s.periodic        = {{true, false, true}};
    s.radii_values    = {1.};
    s.radii_weights   = {1.};
    s.target_fraction = 0.5;
    s.seed            = 3;
    return s;
  }
} // namespace

int
main()
{
  // Dense configurations at the target fractions.
  {
    const GeneratorSettings  s = settings_2d();
    const GeneratedParticles p = ParticleGenerator::generate(s);
    check_configuration("2D bidisperse, area fraction 0.6, x periodic", s, p);
    TestTools::check("2D: area fraction 0.6 met to half a large disc",
                     fraction_met(s, p));
    const auto n_small = std::count(p.radii.begin(), p.radii.end(), 1.);
    const auto n_large = std::count(p.radii.begin(), p.radii.end(), 1.4);
    TestTools::check("2D: radii 1 and 1.4 only, numbers differ by at most 1",
                     n_small + n_large == static_cast<long>(p.radii.size()) &&
                       std::abs(n_small - n_large) <= 1);
    // Without walls in y any more: all axes periodic.
    GeneratorSettings all_periodic = s;
    all_periodic.periodic          = {{true, true, false}};
    all_periodic.seed              = 11;
    check_configuration("2D bidisperse, area fraction 0.6, x and y periodic",
                        all_periodic,
                        ParticleGenerator::generate(all_periodic));
  }
  {
    const GeneratorSettings  s = settings_3d();
    const GeneratedParticles p = ParticleGenerator::generate(s);
    check_configuration("3D monodisperse, volume fraction 0.5, x and z "
                        "periodic",
                        s,
                        p);
    TestTools::check("3D: volume fraction 0.5 met to half a sphere",
                     fraction_met(s, p));
  }

  // Further seeds: each reaches its fraction without overlap, not only the
  // seeds above.
  for (const unsigned int seed : {21u, 22u, 23u})
    for (const bool three_d : {false, true})
      {
        GeneratorSettings s    = three_d ? settings_3d() : settings_2d();
        s.seed                 = seed;
        const auto        p    = ParticleGenerator::generate(s);
        const std::string name = (three_d ? "3D volume fraction 0.5, seed " :
                                            "2D area fraction 0.6, seed ") +
                                 std::to_string(seed);
        check_configuration(name, s, p);
        TestTools::check(name + (three_d ?
                                   ": fraction met to half a sphere" :
                                   ": fraction met to half a large disc"),
                         fraction_met(s, p));
      }

  // A given number of particles, a minimum separation, a sub-box with
  // walls on every side, three radii.
  {
    GeneratorSettings s;
    s.dimension                = 3;
    s.lower                    = {{-5., 1., 2.}};
    s.upper                    = {{5., 11., 12.}};
    s.n_particles              = 300;
    s.radii_values             = {0.3, 0.5, 0.6};
    s.radii_weights            = {0.2, 0.3, 0.5};
    s.min_separation           = 0.05;
    const GeneratedParticles p = ParticleGenerator::generate(s);
    check_configuration("3D three radii, 300 particles, separation 0.05, "
                        "walls",
                        s,
                        p);
    TestTools::check("3D: 300 particles, 60, 90 and 150 of radii 0.3, 0.5, "
                     "0.6",
                     p.radii.size() == 300 &&
                       std::count(p.radii.begin(), p.radii.end(), 0.3) == 60 &&
                       std::count(p.radii.begin(), p.radii.end(), 0.5) == 90 &&
                       std::count(p.radii.begin(), p.radii.end(), 0.6) == 150);
  }
  {
    GeneratorSettings s = settings_2d();
    s.target_fraction   = 0.;
    s.n_particles       = 501;
    s.min_separation    = 0.1;
    const ParticleGenerator  generator(s);
    const GeneratedParticles p = generator.generate();
    check_configuration("2D 501 discs, separation 0.1", s, p);
    TestTools::check(
      "2D: 501 particles, 251 and 250 by weight rounding",
      generator.n_particles() == 501 && p.positions.size() == 501 &&
        std::count(p.radii.begin(), p.radii.end(), 1.) +
            std::count(p.radii.begin(), p.radii.end(), 1.4) ==
          501 &&
        std::abs(std::count(p.radii.begin(), p.radii.end(), 1.) -
                 std::count(p.radii.begin(), p.radii.end(), 1.4)) == 1 &&
        generator.fraction() == p.fraction);
  }

  // Reproducibility.
  for (const unsigned dim : {2u, 3u})
    {
      GeneratorSettings s = dim == 2 ? settings_2d() : settings_3d();
      // Smaller, so that the five runs stay fast.
      s.upper[0] /= 2;
      const GeneratedParticles p1 = ParticleGenerator::generate(s);
      const GeneratedParticles p2 = ParticleGenerator::generate(s);
      s.seed += 1;
      const GeneratedParticles p3   = ParticleGenerator::generate(s);
      const std::string        head = std::to_string(dim) + "D: ";
      TestTools::check(head + "same seed, same positions and radii bit for bit",
                       p1.positions == p2.positions && p1.radii == p2.radii &&
                         p1.iterations == p2.iterations);
      TestTools::check(head + "another seed, other positions and radii order",
                       p1.positions != p3.positions &&
                         p1.radii.size() == p3.radii.size() &&
                         (dim == 3 || p1.radii != p3.radii));
    }

  // Bad settings.
  auto generate_with = [](const auto &change) {
    return [change]() {
      GeneratorSettings s = settings_2d();
      change(s);
      ParticleGenerator::generate(s);
    };
  };
  TestTools::expect_error("2D area fraction 0.9069 rejected",
                          generate_with(
                            [](auto &s) { s.target_fraction = 0.9069; }),
                          {"area fraction", "0.9069"});
  TestTools::expect_error("2D area fraction 0.95 rejected",
                          generate_with(
                            [](auto &s) { s.target_fraction = 0.95; }),
                          {"area fraction", "0.95"});
  TestTools::expect_error("3D volume fraction 0.7405 rejected",
                          generate_with([](auto &s) {
                            s                 = settings_3d();
                            s.target_fraction = 0.7405;
                          }),
                          {"volume fraction", "0.7405"});
  TestTools::expect_error("too many particles for the area rejected",
                          generate_with([](auto &s) {
                            s.target_fraction = 0.;
                            s.n_particles     = 100000;
                          }),
                          {"100000 particles", "area fraction"});
  TestTools::expect_error("weights not summing to 1 rejected",
                          generate_with([](auto &s) {
                            s.radii_weights = {0.5, 0.6};
                          }),
                          {"weights sum to 1.1"});
  TestTools::expect_error("weights of another length rejected",
                          generate_with(
                            [](auto &s) { s.radii_weights = {1.}; }),
                          {"1 weights for 2 radii"});
  TestTools::expect_error("empty radii rejected",
                          generate_with([](auto &s) {
                            s.radii_values.clear();
                            s.radii_weights.clear();
                          }),
                          {"no radius"});
  TestTools::expect_error("radius 0 rejected",
                          generate_with([](auto &s) {
                            s.radii_values = {1., 0.};
                          }),
                          {"radius 0"});
  TestTools::expect_error("region with lower = upper rejected",
                          generate_with(
                            [](auto &s) { s.upper[1] = s.lower[1]; }),
                          {"region along y"});
  TestTools::expect_error("region with lower > upper rejected",
                          generate_with(
                            [](auto &s) { std::swap(s.lower, s.upper); }),
                          {"region along x"});
  TestTools::expect_error("both a count and a fraction rejected",
                          generate_with([](auto &s) { s.n_particles = 10; }),
                          {"not both"});
  TestTools::expect_error("neither a count nor a fraction rejected",
                          generate_with(
                            [](auto &s) { s.target_fraction = 0.; }),
                          {"not neither"});
  TestTools::expect_error("negative minimum separation rejected",
                          generate_with(
                            [](auto &s) { s.min_separation = -0.1; }),
                          {"minimum separation"});
  TestTools::expect_error(
    "minimum separation too large for the fraction rejected",
    generate_with([](auto &s) {
      s.min_separation  = 2.;
      s.target_fraction = 0.3;
    }),
    {"minimum separation 2", "area fraction"});
  TestTools::expect_error("region narrower than a particle rejected",
                          generate_with([](auto &s) {
                            s.upper[1]        = s.lower[1] + 2.5;
                            s.target_fraction = 0.1;
                          }),
                          {"too narrow"});
  TestTools::expect_error("period too short for the minimum image rejected",
                          generate_with([](auto &s) {
                            s.upper[0]        = s.lower[0] + 5.;
                            s.target_fraction = 0.1;
                          }),
                          {"(periodic)", "too narrow"});
  TestTools::expect_error("periodic z in 2D rejected",
                          generate_with([](auto &s) { s.periodic[2] = true; }),
                          {"z is periodic"});
  TestTools::expect_error("dimension 4 rejected",
                          generate_with([](auto &s) { s.dimension = 4; }),
                          {"dimension"});

  // Above random close packing (bidisperse discs jam near 0.84): the growth
  // stalls, and the message names the target and the fraction reached.
  TestTools::expect_error(
    "2D area fraction 0.88 (jammed) throws naming target and "
    "fraction reached",
    generate_with([](auto &s) {
      s.upper           = {{-20., 30., 0.}};
      s.target_fraction = 0.88;
    }),
    {"could not reach the area fraction 0.88",
     "without overlap, the centres reached hold only"});

  return TestTools::failures() == 0 ? 0 : 1;
}
