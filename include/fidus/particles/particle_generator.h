#ifndef fidus_contact_particle_generator_h
#define fidus_contact_particle_generator_h

#include <array>
#include <cstdint>
#include <fidus/contact/contact_types.h>
#include <vector>

namespace Fidus::Contact
{
  /// What ParticleGenerator should place, and where.
  struct GeneratorSettings
  {
    /// 2 or 3; in 2D the z components are ignored (and returned as 0).
    unsigned int dimension = 2;
    /// The region to fill, [lower, upper] per axis: the box or a sub-box.
    std::array<double, 3> lower = {{0., 0., 0.}};
    std::array<double, 3> upper = {{1., 1., 1.}};
    /// Periodic axes of the region (the period is upper - lower), e.g. x
    /// (and z in 3D) for the sliding-walls box. A sub-box that does not
    /// span a periodic axis of the domain must not be periodic in it.
    std::array<bool, 3> periodic = {{false, false, false}};
    /// Number of particles; give either this or target_fraction (not both).
    unsigned int n_particles = 0;
    /// Area fraction (2D) or volume fraction (3D) of the region: the number
    /// of particles is then the one whose total area or volume comes
    /// closest to it.
    double target_fraction = 0.;
    /// Radii [length]: {a} monodisperse, {a1, a2} bidisperse, more values
    /// for a discrete polydisperse distribution.
    std::vector<double> radii_values;
    /// Number fractions of the radii, same length, >= 0, sum 1 (to 1e-9);
    /// empty means equal number fractions.
    std::vector<double> radii_weights;
    /// Smallest surface-to-surface gap between particles and between a
    /// particle and a non-periodic face of the region [length], >= 0.
    double min_separation = 0.;
    /// Seed of the random numbers: the same settings and seed give the same
    /// particles bit for bit with the same build. The random numbers are
    /// the generator's own (std distributions depend on the standard
    /// library), so their sequence and the radii are the same with any
    /// build; another build may still round the positions differently
    /// (e.g. with fused multiply-adds) and the relaxation end elsewhere.
    std::uint64_t seed = 1;
    /// Cap on the relaxation sweeps before generate() gives up (see
    /// ParticleGenerator); a jammed growth gives up earlier.
    unsigned int max_iterations = 20000;
  };

  /// What ParticleGenerator::generate() returns.
  struct GeneratedParticles
  {
    /// Centres, inside the region (wrapped into [lower, upper) along
    /// periodic axes); z = 0 in 2D.
    std::vector<Vec3> positions;
    /// Radii, one per particle, in random order.
    std::vector<double> radii;
    /// Total particle area (2D) or volume (3D) over the region's.
    double fraction = 0.;
    /// Smallest surface-to-surface gap between two particles (minimum
    /// image along periodic axes) among pairs closer than min_separation +
    /// the smallest radius; +infinity if there is no such pair.
    double min_gap = 0.;
    /// Relaxation sweeps used.
    unsigned int iterations = 0;
  };

  /**
   * Places particles without overlap in a box or sub-box, for initial
   * configurations of suspensions: a given number of particles, or a target
   * area fraction (2D) / volume fraction (3D), with mono-, bi- or
   * polydisperse radii (a discrete distribution), reproducibly from a seed.
   *
   * <b>Method: growth with overlap removal.</b> Random sequential addition
   * (RSA) cannot go beyond its jamming limit (0.547 in 2D, 0.38 in 3D) and
   * slows down long before, while suspensions need 0.6 in 2D and 0.5 in 3D
   * and more. So the particles are not added one by one; instead:
   *  -# the radii are drawn (counts from the weights by largest remainder,
   *     then shuffled) and all centres are placed uniformly at random in the
   *     region, each at least its full radius + min_separation from the
   *     non-periodic faces (the final constraint, imposed from the start so
   *     that the faces never need to move);
   *  -# all radii are scaled by a factor s < 1 such that the scaled
   *     fraction is 0.1, where random centres overlap little (s = 1 for
   *     targets below 0.1);
   *  -# repeatedly: one Gauss-Seidel sweep over the pairs closer than the
   *     target gap pushes each overlapping pair apart along its line of
   *     centres, shared in inverse proportion to the particle areas
   *     (volumes), so that a large particle moves less, and clamps both
   *     centres back into the region; when the largest overlap of a sweep
   *     is below the smallest scaled radius, s grows by a factor 1 + g,
   *     with g (between 1e-4 and 0.1) raised when the last growth relaxed
   *     in at most 2 sweeps and halved when it needed more than 8;
   *  -# once s = 1, sweeps go on until no pair is closer than
   *     min_separation; this is then checked with a fresh pair search, the
   *     postcondition: every minimum-image gap >= min_separation
   *     - 1e-12 a_min, every centre inside the region.
   *
   * Why this method: it is the collective-rearrangement ("growth and
   * relaxation") idea, simple, deterministic and O(N) per sweep. The
   * overlaps allowed during the growth are large (the growth only waits
   * for the relaxation to keep up), and overlaps below 0.3 s a_min are
   * over-relaxed: pushed 1.95 times their overlap. This is projected SOR on
   * the almost linear problem of small overlaps; plain projections
   * (factor 1) converge slowly once contacts form chains (measured with
   * 10^4 particles: 658 instead of 73 sweeps at 0.6 in 2D, 5542 instead of
   * 177 at 0.6 in 3D). Large overlaps are pushed by exactly their overlap,
   * since an overshoot there can run away (measured: factor 1.8 on every
   * overlap diverged at 0.6 in 3D). The pushes aim at a gap min_separation +
   * 1e-9 a_min rather than exactly min_separation, so that the sweeps end, in
   * finitely many steps, with every gap >= min_separation instead of
   * approaching it from below. Measured cost
   * (contrib/benchmarks/particle_generator.sh, one core): 50 to 130 sweeps at
   * 0.6 in 2D (bidisperse) and 30 to 40 at 0.5 in 3D; 0.75 s and 1.4 s for 10^5
   * particles. Closer to random close packing (about 0.84 for bidisperse discs,
   * 0.64 for spheres, lower with non-periodic faces) the sweeps multiply; when
   * neither s has grown nor the largest overlap halved for 1000 sweeps
   * (jammed), or after max_iterations sweeps, generate() throws.
   *
   * Neighbours come from PairSearch (cell list, minimum image along the
   * periodic axes) with a skin of 0.5 s a_max, as a Verlet list: it is
   * rebuilt only when twice the largest displacement plus twice the growth
   * of the largest radius since the last build reach the skin, so that no
   * pair outside the list can have come closer than the target gap. The
   * particles are processed in an order sorted by cells (so that a sweep
   * reads nearby memory) but returned in the order they were drawn: random,
   * with the radius of a particle independent of where it is.
   */
  class ParticleGenerator
  {
  public:
    /**
     * Check the settings and draw the radii. Throws ContactError, with a
     * message naming the entry, the value and what is allowed, for: a
     * dimension other than 2 or 3; a non-finite region or lower >= upper
     * along an axis; a periodic z axis in 2D; empty radii, a radius <= 0;
     * weights of another length than the radii, negative, or not summing to
     * 1; both or neither of n_particles and target_fraction given; a
     * fraction (requested or following from n_particles) >= pi / (2 sqrt 3)
     * = 0.9069 in 2D or >= pi / (3 sqrt 2) = 0.7405 in 3D (the densest
     * packings), or that limit reached by particles of radius a +
     * min_separation / 2; a target fraction so small that no particle is
     * placed; a negative min_separation; a region too narrow for the largest
     * particle (width <= 2 (a_max + min_separation) along a non-periodic axis,
     * period <= 2 (2 a_max + min_separation) along a periodic one, below
     * which one pair could overlap through two periodic images).
     */
    explicit ParticleGenerator(const GeneratorSettings &settings);

    /// Number of particles that generate() places.
    std::size_t
    n_particles() const
    {
      return radii.size();
    }

    /// Area (2D) or volume (3D) fraction that generate() reaches.
    double
    fraction() const
    {
      return particle_fraction;
    }

    /**
     * Place the particles (see the class documentation); the result meets
     * the postcondition checked there. Throws ContactError if the growth
     * stalls (neither growth nor a halving of the largest overlap for 1000
     * sweeps: jammed) or after settings.max_iterations sweeps; the message
     * gives the target fraction, the fraction at which the last centres are
     * free of overlap (all radii scaled down until they are) and the number
     * of sweeps.
     */
    GeneratedParticles
    generate() const;

    /**
     * Convenience: ParticleGenerator(settings).generate().
     */
    static GeneratedParticles
    generate(const GeneratorSettings &settings);

  private:
    GeneratorSettings   settings;
    std::vector<double> radii;
    double              particle_fraction = 0.;
  };
} // namespace Fidus::Contact

#endif
