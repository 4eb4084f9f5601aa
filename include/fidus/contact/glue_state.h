#ifndef fidus_contact_glue_state_h
#define fidus_contact_glue_state_h

#include <cstdint>
#include <vector>

namespace Fidus::Contact
{
  /**
   * What the projector remembers from one step to the next, per pair: the
   * glue variable gamma (numerics section 3; gamma < 0 means glued) and the
   * last multiplier lambda (the warm start of the dual solver).
   *
   * A pair is identified by (first, second): two particle indices with
   * first < second, or (particle, wall_key(w)) for a particle-wall pair.
   * Particle indices are stable in fidus, so the identity survives the step.
   * Entries are stored by first index (compressed rows), so that a lookup
   * scans the handful of neighbours of one particle: O(1), cache friendly,
   * and rebuilt in O(N + pairs) each step without hashing.
   */
  class GlueState
  {
  public:
    /// One remembered pair.
    struct Entry
    {
      std::uint32_t first  = 0;
      std::uint32_t second = 0;
      double        gamma  = 0.; ///< glue variable, <= 0
      double        lambda = 0.; ///< last multiplier (warm start)
    };

    /// Second index of the pair (particle, wall w).
    static constexpr std::uint32_t
    wall_key(const unsigned int w)
    {
      return wall_base + w;
    }

    /// Whether a second index denotes a wall.
    static constexpr bool
    is_wall_key(const std::uint32_t second)
    {
      return second >= wall_base;
    }

    /// Forget everything.
    void
    clear();

    /**
     * Replace the state by @p entries (any order, no duplicates). Entries
     * with gamma == 0 and lambda == 0 carry no information and are dropped.
     */
    void
    rebuild(std::vector<Entry> entries);

    /// Index of the entry of pair (first, second), or -1 if there is none.
    long
    find(std::uint32_t first, std::uint32_t second) const;

    /// All entries, grouped by first index.
    const std::vector<Entry> &
    entries() const
    {
      return data;
    }

    /// Number of glued pairs (gamma < 0).
    unsigned int
    n_glued() const;

    /// Number of glued pairs that involve each particle 0..n_particles-1.
    std::vector<unsigned int>
    glued_count_per_particle(std::size_t n_particles) const;

  private:
    static constexpr std::uint32_t wall_base = 0xF0000000u;

    std::vector<Entry>       data;
    std::vector<std::size_t> row_start; ///< CSR offsets by first index
  };
} // namespace Fidus::Contact

#endif
