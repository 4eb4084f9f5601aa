#ifndef fidus_fluid_cut_element_element_sparsity_h
#define fidus_fluid_cut_element_element_sparsity_h

#include <cstddef>
#include <deal.II/lac/affine_constraints.h>
#include <fidus/fluid/cut_element/row_pattern.h>
#include <utility>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * A square sparsity pattern built from the DoF lists of elements (cells,
   * faces, or any group of unknowns that couple all with all), through
   * hanging-node and boundary constraints, row by row on the machine's
   * threads.
   *
   * add_element() records what AffineConstraints::
   * add_entries_local_to_global() with keep_constrained_entries would add
   * for the list: every pair of the list's unconstrained DoFs and the DoFs
   * its constrained ones are constrained to, and every pair of the list's
   * own DoFs one of which is constrained. build() then forms each row's
   * columns from the elements that touch it (a marker array per thread
   * instead of sorted insertions), which is what a
   * DynamicSparsityPattern's sorted rows made the longest part of a cut
   * element solve's set-up after the solver. The pattern holds the same
   * entries, and every diagonal.
   */
  class ElementSparsity
  {
  public:
    /// A pattern of @p n_dofs rows and columns, through @p constraints
    /// (closed), which must outlive the object.
    ElementSparsity(const unsigned int               n_dofs,
                    const AffineConstraints<double> &constraints);

    /// Couple the DoFs @p dofs all with all, through the constraints.
    void
    add_element(const std::vector<types::global_dof_index> &dofs);

    /// What build() keeps of a row: all its columns, those flagged in
    /// its kept_columns, or its diagonal alone.
    enum class Keep : unsigned char
    {
      all,
      flagged,
      diagonal
    };

    /**
     * Fill @p pattern with the couplings of all elements added, each row
     * i keeping what @p keep[i] says (all of every row if @p keep is
     * empty), and every diagonal: a rank that holds some rows of a block
     * whole, of others only their couplings to another block and of the
     * rest nothing builds no more than it keeps.
     */
    void
    build(RowPattern              &pattern,
          const std::vector<Keep> &keep         = {},
          const std::vector<bool> &kept_columns = {}) const;

    /**
     * Per row, the lengths of the lists build() merges into it, summed
     * (repeats counted): a bound on the row's length, proportional to it
     * where the elements are alike, and found in one pass over the
     * elements, before the pattern. The cut element splits its rows among
     * the ranks by it.
     */
    std::vector<std::size_t>
    row_weights() const;

  private:
    const unsigned int               n;
    const AffineConstraints<double> &constraints;

    /// Per element, three column lists, concatenated: its resolved DoFs
    /// (U: unconstrained DoFs and the DoFs the constrained ones are
    /// constrained to), its constrained DoFs (C) and its own DoFs (L).
    /// A row in U and L takes U and C, a row in U alone takes U, and a
    /// row in C takes L.
    std::vector<unsigned int> columns;
    /// Where each element's lists start in columns: U, C, L, end.
    std::vector<std::size_t> starts;

    /// Element @p e's list @p k (0: U, 1: C, 2: L), as [first, last).
    std::pair<const unsigned int *, const unsigned int *>
    list(const std::size_t e, const unsigned int k) const
    {
      return {columns.data() + starts[3 * e + k],
              columns.data() + starts[3 * e + k + 1]};
    }

    /// Call @p f(row, e, kind) for each row that element e touches, the
    /// elements in their order: kind 0 through U (and not L), 1 through U
    /// and L, 2 through C. What build() and row_weights() both walk.
    template <typename F>
    void
    for_each_touch(const F &f) const
    {
      std::vector<unsigned char> in_l(n, 0);
      for (std::size_t e = 0; 3 * e + 3 < starts.size(); ++e)
        {
          const auto [l0, l1] = list(e, 2);
          for (auto p = l0; p != l1; ++p)
            in_l[*p] = 1;
          const auto [u0, u1] = list(e, 0);
          for (auto p = u0; p != u1; ++p)
            f(*p, e, in_l[*p] ? 1 : 0);
          const auto [c0, c1] = list(e, 1);
          for (auto p = c0; p != c1; ++p)
            f(*p, e, 2);
          for (auto p = l0; p != l1; ++p)
            in_l[*p] = 0;
        }
    }
  };
} // namespace Fidus

#endif
