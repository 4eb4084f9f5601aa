#ifndef fidus_particles_particle_parameters_h
#define fidus_particles_particle_parameters_h

#include <array>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  struct DomainParameters;

  /**
   * The particles of the scene: the entries of the subsection Particles and
   * its Generator, read into one position and one radius per particle. The
   * header and the struct are free of deal.II, like the rest of
   * particles/; declare() and parse() live in the deal.II part of fidus
   * (fidus_core).
   */
  struct ParticleParameters
  {
    /// Register the entries of the subsection Particles.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back: positions given, from a file (relative to
    /// @p input_name, the parameter file) or placed by the generator in
    /// @p domain; one radius and external force per particle.
    void
    parse(dealii::ParameterHandler &prm,
          const unsigned int        dim,
          const DomainParameters   &domain,
          const std::string        &input_name);

    std::vector<std::array<double, 3>> positions;
    std::vector<double>                radii;
    /// External force on each particle; empty when every particle is
    /// force-free.
    std::vector<std::array<double, 3>> external_forces;
    /// Particles/Positions file as written (empty if none).
    std::string positions_file;
  };
} // namespace Fidus

#endif
