#ifndef fidus_fluid_cut_system_blocks_h
#define fidus_fluid_cut_system_blocks_h

#include <deal.II/base/types.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/cut_element/row_pattern.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The cut finite element's system as its iterative solver with the
   * velocity multigrid keeps it (CutSaddlePointSolver): three blocks,
   *
   *   K = [A_uu A_uV; A_Vu A_VV]   (rows and columns: the fluid
   *                                  velocities, then the rigid unknowns)
   *   B^T                           (rows as K, columns the pressures)
   *   P                             (the pressure block, -C)
   *
   * of the symmetric system [K B^T; B P]. B, the pressure rows' columns of
   * K's kinds, is B^T's transpose and is not held: what is added there is
   * dropped (the solver multiplies by B^T's transpose): it held as many
   * entries as B^T, and on more ranks every rank held it whole.
   *
   * assembled directly: AffineConstraints::distribute_local_to_global()
   * writes into an object of this class as into one matrix of the
   * system's numbering (add(), m(), n()), and each entry goes to its block.
   * The system as one matrix is never held: copying it into the blocks
   * held every entry twice, the solve's peak memory, and took a tenth of a
   * 3D solve.
   *
   * Within each kind the unknowns keep the system's order, and the rigid
   * unknowns are numbered after the fluid's, so each block's row keeps its
   * columns in ascending order and an added row is walked once.
   *
   * On more than one rank (the second reinit()) a rank's K and B^T hold
   * only its own velocity rows, each assembled whole there, and the rigid
   * rows and P are summed over the ranks' shares of the cells (Part).
   */
  class CutSystemBlocks
  {
  public:
    using size_type  = types::global_dof_index;
    using value_type = double;

    /// Virtual: AffineConstraints tries a dynamic_cast of the matrix it
    /// writes into to SparseMatrix, which needs a polymorphic type.
    virtual ~CutSystemBlocks() = default;

    /**
     * The blocks of the system whose pattern is @p system, each unknown
     * i of the kind @p kind[i] (0: velocity, 1: pressure, 2: rigid, the
     * rigid ones numbered after all the others), with zero entries. The
     * caller may free @p system afterwards.
     */
    void
    reinit(const SparsityPattern            &system,
           const std::vector<unsigned char> &kind);

    /**
     * The same for a rank of several that share the solve: K and Bᵀ hold
     * only the velocity rows numbered @p k_first to @p k_end - 1 within K
     * (the rows this rank owns; the others keep an empty diagonal in K and
     * nothing in Bᵀ), and the rigid rows and P whole (summed over the
     * ranks' shares of the cells). Write into it through Part.
     */
    void
    reinit(const SparsityPattern            &system,
           const std::vector<unsigned char> &kind,
           const unsigned int                k_first,
           const unsigned int                k_end);

    /// Whether system row @p i is a velocity row of K that this rank owns
    /// (every velocity row without the split).
    bool
    owns_velocity_row(const size_type i) const
    {
      return kind[i] == 0 && local[i] >= k_first && local[i] < k_end;
    }

    /**
     * What one cell or face adds with the split K: its entries in the
     * velocity rows this rank owns (K's and Bᵀ's) always; with
     * @p summed_rows (the cell is in this rank's share, whose sum over the
     * ranks is the system) also those of P and the rigid rows. A matrix to
     * AffineConstraints::distribute_local_to_global() as CutSystemBlocks
     * is.
     */
    class Part
    {
    public:
      using size_type  = types::global_dof_index;
      using value_type = double;
      Part(CutSystemBlocks &blocks, const bool summed_rows)
        : blocks(blocks)
        , summed_rows(summed_rows)
      {}
      virtual ~Part() = default;
      size_type
      m() const
      {
        return blocks.m();
      }
      size_type
      n() const
      {
        return blocks.n();
      }
      void
      add(const size_type  row,
          const size_type  n_columns,
          const size_type *columns,
          const double    *values,
          const bool       elide_zero_values      = false,
          const bool       col_indices_are_sorted = false)
      {
        blocks.add_part(row,
                        n_columns,
                        columns,
                        values,
                        elide_zero_values,
                        col_indices_are_sorted,
                        summed_rows);
      }

      void
      add(const size_type i, const size_type j, const double value)
      {
        add(i, 1, &j, &value);
      }

    private:
      CutSystemBlocks &blocks;
      const bool       summed_rows;
    };

    /// The system's size (both dimensions).
    size_type
    m() const
    {
      return kind.size();
    }
    size_type
    n() const
    {
      return kind.size();
    }

    /// The system's entries (@p row, @p columns[k]) += @p values[k]; the
    /// entries must be in the pattern given to reinit().
    void
    add(const size_type  row,
        const size_type  n_columns,
        const size_type *columns,
        const double    *values,
        const bool       elide_zero_values      = false,
        const bool       col_indices_are_sorted = false);

    /// add() of the rows Part lets through (see there).
    void
    add_part(const size_type  row,
             const size_type  n_columns,
             const size_type *columns,
             const double    *values,
             const bool       elide_zero_values,
             const bool       col_indices_are_sorted,
             const bool       summed_rows);
    /// The system's entry (@p i, @p j) += @p value.
    void
    add(const size_type i, const size_type j, const double value)
    {
      add(i, 1, &j, &value);
    }

    /// The system's diagonal entry of row @p i.
    double
    diag_element(const size_type i) const;

    /**
     * f(j, value) on the entries held of the system's row @p i (a
     * pressure row's of P only), with j the system's column; value is the
     * block's entry (assignable).
     */
    template <typename F>
    void
    for_row(const size_type i, const F &f);

    /// The rows of K and Bᵀ (velocities, then rigid unknowns) and of P
    /// (pressures), by their system index.
    std::vector<unsigned int> k_rows, p_rows;
    /// The velocity rows of K held (all without the split).
    unsigned int k_first = 0, k_end = static_cast<unsigned int>(-1);
    /// Each unknown's kind, and its row within K or within P.
    std::vector<unsigned char> kind;
    std::vector<unsigned int>  local;
    /// The blocks and their patterns.
    RowPattern           k_pattern, bt_pattern, p_pattern;
    SparseMatrix<double> k, bt, p;
  };



  template <typename F>
  void
  CutSystemBlocks::for_row(const size_type i, const F &f)
  {
    const auto walk = [&](SparseMatrix<double>            &block,
                          const std::vector<unsigned int> &columns) {
      for (auto it = block.begin(local[i]), end = block.end(local[i]);
           it != end;
           ++it)
        f(columns[it->column()], it->value());
    };
    if (kind[i] != 1)
      walk(k, k_rows);
    walk(kind[i] != 1 ? bt : p, p_rows);
  }
} // namespace Fidus

#endif
