#ifndef fidus_io_particle_output_h
#define fidus_io_particle_output_h

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace Fidus
{
  /**
   * Writes the particles of one step as particles-NNNNN.vtp (VTK PolyData:
   * one point per particle with radius, velocity, angular velocity and the
   * number of glued contacts) and keeps particles.pvd up to date. Written by
   * one rank only (every rank holds all particles). In ParaView, a Glyph
   * filter with sphere glyphs scaled by 'radius' shows the particles.
   */
  class ParticleOutput
  {
  public:
    /// Files go to @p directory; nothing is written unless @p active.
    ParticleOutput(const std::string &directory, const bool active)
      : directory(directory)
      , active(active)
    {}

    /// Write one output number @p step at @p time.
    void
    write(const unsigned int                        step,
          const double                              time,
          const std::vector<std::array<double, 3>> &positions,
          const std::vector<double>                &radii,
          const std::vector<std::array<double, 3>> &velocities,
          const std::vector<std::array<double, 3>> &omegas,
          const std::vector<unsigned int>          &glued);

    /// A resumed run: keep the collection entries of steps up to
    /// @p last_step (the checkpoint's) and rewrite particles.pvd with them.
    void
    resume(unsigned int last_step);

  private:
    /// Write particles.pvd from the records.
    void
    write_collection() const;

    std::string                                 directory;
    bool                                        active;
    std::vector<std::pair<double, std::string>> records;
  };
} // namespace Fidus

#endif
