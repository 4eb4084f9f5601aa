#ifndef fidus_contact_pair_search_h
#define fidus_contact_pair_search_h

#include <array>
#include <cmath>
#include <cstdint>
#include <fidus/contact/contact_types.h>
#include <utility>
#include <vector>

namespace Fidus::Contact
{
  namespace internal
  {
    /// The uniform grid of the cell list of PairSearch (defined in
    /// pair_search.cc, where it is built and used).
    struct CellGrid;
  } // namespace internal

  /**
   * Finds every pair of spheres (discs in 2D) whose gap
   * D_ij = |X_j - X_i| - a_i - a_j is below a cut-off distance (the alert
   * distance of numerics section 3). The cost is O(N) for the cell list
   * (counting sort into a uniform grid, half stencil of neighbour cells) and
   * O(N log N) for the R-tree; never O(N^2).
   *
   * Directions may be periodic (set_periodicity()): then X_j - X_i is
   * replaced by its minimum image, so positions may be given wrapped into
   * the box or not, and a pair across a periodic face is found like any
   * other, exactly once.
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
     * Make direction d periodic with period @p periods[d] > 0 (0: not
     * periodic, the default). Only the period matters, not where the box
     * starts: the minimum image of a difference does not depend on it.
     * Throws ContactError for a negative or non-finite period, or a period
     * in z in 2D (z is ignored there, so a period would silently do
     * nothing).
     *
     * This does not check that the periods are large compared with the
     * particles (the projector does, since that depends on the radii and the
     * alert distance): with any period, the search returns each pair once
     * with its minimum-image gap, which is then the closest of its images.
     */
    void
    set_periodicity(const std::array<double, 3> &periods);

    /// The periods (0: not periodic) set with set_periodicity().
    const std::array<double, 3> &
    get_periodicity() const
    {
      return period;
    }

    /**
     * Minimum image of a difference @p dx along a direction of period
     * @p period (> 0): dx - L round(dx / L), in [-L/2, L/2]. Returns @p dx
     * unchanged if @p period is 0 (not periodic).
     */
    static double
    minimum_image(const double dx, const double period)
    {
      return period > 0. ? dx - period * std::round(dx / period) : dx;
    }

    /**
     * The separation X_to - X_from, replaced by its minimum image in the
     * periodic directions; in 2D the z component is 0. The projector takes
     * gaps and normals from it, with the periods of this search, so that
     * the rows and the pair search agree on which image is meant.
     */
    Vec3
    separation(const Vec3 &from, const Vec3 &to) const
    {
      Vec3 dx{{0., 0., 0.}};
      for (unsigned int d = 0; d < dimension; ++d)
        dx[d] = minimum_image(to[d] - from[d], period[d]);
      return dx;
    }

    /**
     * Replace @p pairs by all pairs (i < j) with gap D_ij < @p cutoff
     * (minimum-image gap in the periodic directions).
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

    /// The counting sort of the particles into the cells of @p grid: fills
    /// the CSR arrays and the particle data in cell order. Separate from
    /// the scan so that each stage of the cell list reads on its own.
    void
    sort_into_cells(const std::vector<Vec3>   &positions,
                    const std::vector<double> &radii,
                    const internal::CellGrid  &grid);

    /// The scan over the sorted cells: appends to @p pairs every pair of
    /// the same or a stencil-neighbour cell for which @p close(p, q) holds
    /// (a template so that the distance test with or without minimum image
    /// is inlined).
    template <typename Close>
    void
    scan_cells(const internal::CellGrid              &grid,
               const std::vector<std::array<int, 3>> &stencil,
               const Close                           &close,
               std::vector<Pair>                     &pairs) const;

    template <int dim>
    void
    find_pairs_rtree(const std::vector<Vec3>   &positions,
                     const std::vector<double> &radii,
                     double                     cutoff,
                     std::vector<Pair>         &pairs) const;

    unsigned int          dimension;
    PairSearchMethod      method;
    std::array<double, 3> period = {{0., 0., 0.}};

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
