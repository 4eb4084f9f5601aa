#ifndef fidus_contact_pair_search_h
#define fidus_contact_pair_search_h

#include <cstdint>
#include <fidus/contact/contact_types.h>
#include <utility>
#include <vector>

namespace Fidus::Contact
{
  /**
   * Finds every pair of spheres (discs in 2D) whose gap
   * D_ij = |X_j - X_i| - a_i - a_j is below a cut-off distance (the alert
   * distance of numerics section 3). The cost is O(N) for the cell list
   * (counting sort into a uniform grid, half stencil of neighbour cells) and
   * O(N log N) for the R-tree; never O(N^2).
   *
   * The object keeps its work arrays between calls so that a time loop does
   * not reallocate them every step.
   */
  class PairSearch
  {
  public:
    /// A pair (i, j) with i < j.
    using Pair = std::pair<std::uint32_t, std::uint32_t>;

    /**
     * @param dimension 2 or 3; in 2D the z components are ignored.
     * @param method cell list or R-tree.
     */
    PairSearch(unsigned int dimension, PairSearchMethod method);

    /**
     * Replace @p pairs by all pairs (i < j) with gap D_ij < @p cutoff.
     * The order is deterministic (it follows the cells, so that neighbouring
     * pairs are neighbours in the list, which the Gauss-Seidel solver likes).
     */
    void
    find_pairs(const std::vector<Vec3>   &positions,
               const std::vector<double> &radii,
               double                     cutoff,
               std::vector<Pair>         &pairs);

  private:
    void
    find_pairs_cell_list(const std::vector<Vec3>   &positions,
                         const std::vector<double> &radii,
                         double                     cutoff,
                         std::vector<Pair>         &pairs);

    template <int dim>
    void
    find_pairs_rtree(const std::vector<Vec3>   &positions,
                     const std::vector<double> &radii,
                     double                     cutoff,
                     std::vector<Pair>         &pairs) const;

    unsigned int     dimension;
    PairSearchMethod method;

    /// Cell list work arrays: CSR of particles by cell, and the particle
    /// data copied in cell order so that the inner loop reads contiguously.
    std::vector<std::uint32_t> cell_of;
    std::vector<std::uint32_t> cell_start;
    std::vector<std::uint32_t> sorted_index;
    std::vector<Vec3>          sorted_position;
    std::vector<double>        sorted_radius;
  };
} // namespace Fidus::Contact

#endif
