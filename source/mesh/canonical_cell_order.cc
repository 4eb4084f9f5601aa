#include <algorithm>
#include <deal.II/grid/cell_id.h>
#include <fidus/mesh/canonical_cell_order.h>
#include <utility>

namespace Fidus
{
  template <int dim>
  std::vector<typename DoFHandler<dim>::active_cell_iterator>
  canonical_cell_order(const DoFHandler<dim> &dof_handler)
  {
    using Iterator = typename DoFHandler<dim>::active_cell_iterator;
    std::vector<std::pair<CellId, Iterator>> keyed;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        keyed.emplace_back(cell->id(), cell);
    std::sort(keyed.begin(), keyed.end(), [](const auto &a, const auto &b) {
      return a.first < b.first;
    });
    std::vector<Iterator> cells;
    cells.reserve(keyed.size());
    for (const auto &k : keyed)
      cells.push_back(k.second);
    return cells;
  }

  template std::vector<typename DoFHandler<2>::active_cell_iterator>
  canonical_cell_order(const DoFHandler<2> &);
  template std::vector<typename DoFHandler<3>::active_cell_iterator>
  canonical_cell_order(const DoFHandler<3> &);
} // namespace Fidus
