// Benchmark of the particle generator (not a test): time to place N
// particles at a given area (2D) or volume (3D) fraction, and the smallest
// gap reached.
//
// Usage: particle_generator DIM N PHI [SEED]
//   DIM 2 (bidisperse discs, radii 1 and 1.4, 50/50 by number, periodic in
//   x, walls in y) or 3 (monodisperse spheres of radius 1, periodic in x and
//   z, walls in y); N particles; PHI area or volume fraction.
// The box is a square (cube) sized so that N particles of the mean measure
// give PHI; the generator then picks the count closest to PHI.
// Prints one line: DIM N PHI_REACHED SECONDS MIN_GAP/A_MIN SWEEPS, or
// DIM N FAILED SECONDS - - MESSAGE (exit status 2).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fidus/contact/contact_error.h>
#include <fidus/particles/particle_generator.h>

using namespace Fidus::Contact;

int
main(int argc, char **argv)
{
  if (argc < 4)
    {
      std::fprintf(stderr, "usage: %s DIM N PHI [SEED]\n", argv[0]);
      return 1;
    }
  const unsigned    dim  = std::atoi(argv[1]);
  const double      n    = std::atof(argv[2]);
  const double      phi  = std::atof(argv[3]);
  const unsigned    seed = argc > 4 ? std::atoi(argv[4]) : 1;
  const double      pi   = 3.14159265358979323846;
  GeneratorSettings s;
  s.dimension         = dim;
  double mean_measure = 0., a_min = 1.;
  if (dim == 2)
    {
      s.radii_values  = {1., 1.4};
      s.radii_weights = {0.5, 0.5};
      s.periodic      = {{true, false, false}};
      mean_measure    = 0.5 * pi * (1. + 1.4 * 1.4);
    }
  else
    {
      s.radii_values  = {1.};
      s.radii_weights = {1.};
      s.periodic      = {{true, false, true}};
      mean_measure    = 4. / 3. * pi;
    }
  const double side = std::pow(n * mean_measure / phi, 1. / dim);
  s.lower           = {{0., 0., 0.}};
  s.upper           = {{side, side, dim == 3 ? side : 1.}};
  s.target_fraction = phi;
  s.seed            = seed;

  const auto start = std::chrono::steady_clock::now();
  try
    {
      const GeneratedParticles p = ParticleGenerator::generate(s);
      const double             seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      std::printf("%u %zu %.4f %.3f %.3g %u\n",
                  dim,
                  p.positions.size(),
                  p.fraction,
                  seconds,
                  p.min_gap / a_min,
                  p.iterations);
    }
  catch (const ContactError &e)
    {
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      std::printf("%u %.0f FAILED %.3f - - %s\n", dim, n, seconds, e.what());
      return 2;
    }
  return 0;
}
