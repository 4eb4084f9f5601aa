#include "cut_stokes_solve.h"

#include <algorithm>

namespace Fidus
{
  // How the iterative solve's rows of K are split among the ranks, and
  // which rank integrates each cut cell.

  template <int dim>
  unsigned int
  CutStokesSolve<dim>::velocity_row_rank(const types::global_dof_index i) const
  {
    // The last rank whose range starts at or before the row (a rank may
    // hold none).
    const auto next =
      std::upper_bound(k_bounds.begin(), k_bounds.end() - 1, blocks->local[i]);
    return (next - k_bounds.begin()) - 1;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::split_velocity_rows(
    const std::vector<std::size_t> &weight)
  {
    // K's rows split by their weight, not their number: the rows near the
    // particles couple through the ghost penalties to twice as far and are
    // up to three times longer than the coarse cells' far off (the paper's
    // pair 0.01 a apart: 23 and 66 million entries in two halves), and
    // every stage of the solve follows the entries. The split points are
    // taken in the system's numbering, where the pressures lie among the
    // velocities, and the pressures split there too, so that a rank's
    // pressures lie where its velocities do. The rigid rows (K's last) go
    // with the last rank.
    std::size_t total = 0;
    for (unsigned int i = 0; i < n_fluid; ++i)
      if (!is_pressure[i])
        total += weight[i];
    const unsigned int n_p =
      std::count(is_pressure.begin(), is_pressure.begin() + n_fluid, true);
    k_bounds.assign(n_ranks + 1, n_total - n_p);
    p_bounds.assign(n_ranks + 1, n_p);
    k_bounds[0] = p_bounds[0] = 0;
    std::size_t  sum          = 0;
    unsigned int k = 0, p = 0, r = 1;
    for (unsigned int i = 0; i < n_fluid && r < n_ranks; ++i)
      {
        while (r < n_ranks && sum * n_ranks >= total * r)
          {
            k_bounds[r] = k;
            p_bounds[r] = p;
            ++r;
          }
        if (is_pressure[i])
          ++p;
        else
          {
            sum += weight[i];
            ++k;
          }
      }
    k_first = k_bounds[this_rank];
    k_end   = k_bounds[this_rank + 1];
    held_velocity_rows.assign(n_total, false);
    k = 0;
    for (unsigned int i = 0; i < n_fluid; ++i)
      if (!is_pressure[i])
        {
          held_velocity_rows[i] = k >= k_first && k < k_end;
          ++k;
        }
  }

  template <int dim>
  std::vector<unsigned int>
  CutStokesSolve<dim>::balance_cut_cells(
    const std::vector<unsigned int> &home) const
  {
    // Rows split by their weight need not split the cut cells evenly: the
    // DoFs are numbered cell by cell, level by level, so the cut cells, on
    // the finest levels, can fall mostly in one rank's rows (all of them,
    // when the rows were split evenly in number), which then integrates
    // them while the others wait. A cell moved off its home is sent to the
    // ranks whose rows it writes, as a cell on the border is.
    const unsigned int        n     = home.size();
    const unsigned int        quota = (n + n_ranks - 1) / n_ranks;
    std::vector<unsigned int> load(n_ranks, 0);
    std::vector<unsigned int> rank(n, numbers::invalid_unsigned_int);
    for (unsigned int k = 0; k < n; ++k)
      if (load[home[k]] < quota)
        {
          rank[k] = home[k];
          ++load[home[k]];
        }
    unsigned int r = 0;
    for (unsigned int k = 0; k < n; ++k)
      if (rank[k] == numbers::invalid_unsigned_int)
        {
          while (load[r] >= quota)
            ++r;
          rank[k] = r;
          ++load[r];
        }
    return rank;
  }

  template void
  CutStokesSolve<2>::split_velocity_rows(const std::vector<std::size_t> &);
  template unsigned int
  CutStokesSolve<2>::velocity_row_rank(const types::global_dof_index) const;
  template std::vector<unsigned int>
  CutStokesSolve<2>::balance_cut_cells(const std::vector<unsigned int> &) const;
  template void
  CutStokesSolve<3>::split_velocity_rows(const std::vector<std::size_t> &);
  template unsigned int
  CutStokesSolve<3>::velocity_row_rank(const types::global_dof_index) const;
  template std::vector<unsigned int>
  CutStokesSolve<3>::balance_cut_cells(const std::vector<unsigned int> &) const;
} // namespace Fidus
