// ElementSparsity (the cut element's sparsity pattern): on Taylor-Hood
// meshes with hanging nodes, boundary values and periodic faces, in 2D and
// 3D, the pattern of the cells' DoF lists (each cell's list extended by
// extra unknowns past the mesh's, as a cut cell is by its particle's rigid
// unknowns, and unions of two neighbours' lists, as a ghost-penalty face's)
// against deal.II's: a DynamicSparsityPattern filled by
// AffineConstraints::add_entries_local_to_global with
// keep_constrained_entries, copied into a SparsityPattern. The two must
// hold the same entries, row by row. The rows are built in several ranges
// (more than the threads), so the ranges' seams are crossed. Then built
// again with each row keeping all its columns, those flagged (every third
// column), or its diagonal alone (i mod 3 = 0, 1, 2): deal.II's rows
// filtered alike, and the diagonal in every row. The rows' weights
// (row_weights(), by which the cut element splits its rows among the ranks)
// lie between each touched row's length and that times the number of
// elements touching it, and equal hand-counted sums on three elements.

#include "../fidus_test.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>
#include <fidus/fluid/cut_element/element_sparsity.h>
#include <set>

using namespace dealii;
using namespace FidusTest;

namespace
{
  /// The Taylor-Hood mesh of the test: periodic in x, hanging nodes in
  /// the middle, inhomogeneous velocities on y = 0 and y = 1.
  template <int dim>
  struct Mesh
  {
    Triangulation<dim>        tria;
    const FESystem<dim>       fe{FE_Q<dim>(2), dim, FE_Q<dim>(1), 1};
    DoFHandler<dim>           dof_handler;
    AffineConstraints<double> constraints;

    Mesh();
  };

  template <int dim>
  Mesh<dim>::Mesh()
  {
    GridGenerator::hyper_cube(tria, 0., 1., true);
    // Periodic in x, before any refinement.
    std::vector<
      GridTools::PeriodicFacePair<typename Triangulation<dim>::cell_iterator>>
      pairs;
    GridTools::collect_periodic_faces(tria, 0, 1, 0, pairs);
    tria.add_periodicity(pairs);
    tria.refine_global(2);
    // Hanging nodes: refine the cells near the centre twice more (two
    // levels meet, away from the periodic faces).
    Point<dim> middle;
    for (unsigned int d = 0; d < dim; ++d)
      middle[d] = 0.5;
    for (const double radius : {0.3, 0.2})
      {
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->center().distance(middle) < radius)
            cell->set_refine_flag();
        tria.execute_coarsening_and_refinement();
      }

    dof_handler.reinit(tria);
    dof_handler.distribute_dofs(fe);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    std::vector<
      GridTools::PeriodicFacePair<typename DoFHandler<dim>::cell_iterator>>
      dof_pairs;
    GridTools::collect_periodic_faces(dof_handler, 0, 1, 0, dof_pairs);
    DoFTools::make_periodicity_constraints<dim, dim>(dof_pairs, constraints);
    // Inhomogeneous velocities on y = 0 and y = 1.
    const FEValuesExtractors::Vector velocity(0);
    for (const types::boundary_id b : {2, 3})
      VectorTools::interpolate_boundary_values(
        dof_handler,
        b,
        Functions::ConstantFunction<dim>(1., dim + 1),
        constraints,
        fe.component_mask(velocity));
    constraints.close();
  }

  /// The elements: each cell's DoFs (every third with a group of extra
  /// unknowns past the mesh's, four groups of six), each cell's union with
  /// its active neighbour across face 1, and two groups together; added
  /// to @p elements and, through the constraints, to @p dsp. @p touches
  /// counts the elements that touch each row: through its unconstrained
  /// DoFs and the DoFs its constrained ones hang from, and its constrained
  /// ones.
  template <int dim>
  void
  add_elements(const Mesh<dim>           &mesh,
               const unsigned int         n_fluid,
               DynamicSparsityPattern    &dsp,
               Fidus::ElementSparsity    &elements,
               std::vector<unsigned int> &touches)
  {
    const AffineConstraints<double> &constraints = mesh.constraints;
    const auto add = [&](const std::vector<types::global_dof_index> &list) {
      constraints.add_entries_local_to_global(list, dsp, true);
      elements.add_element(list);
      std::set<types::global_dof_index> touched;
      for (const auto j : list)
        {
          touched.insert(j);
          if (const auto *entries = constraints.get_constraint_entries(j))
            for (const auto &entry : *entries)
              touched.insert(entry.first);
        }
      for (const auto j : touched)
        ++touches[j];
    };
    std::vector<types::global_dof_index> dofs(mesh.fe.n_dofs_per_cell()),
      neighbour_dofs(mesh.fe.n_dofs_per_cell()), list;
    unsigned int k = 0;
    for (const auto &cell : mesh.dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        list = dofs;
        // Every third cell takes a group of extra unknowns.
        if (k++ % 3 == 0)
          for (unsigned int e = 0; e < 6; ++e)
            list.push_back(n_fluid + 6 * (k % 4) + e);
        add(list);
        // The union with the neighbour across face 1, where it is active.
        if (!cell->at_boundary(1) && cell->neighbor(1)->is_active())
          {
            cell->neighbor(1)->get_dof_indices(neighbour_dofs);
            list = dofs;
            for (const auto j : neighbour_dofs)
              if (std::find(dofs.begin(), dofs.end(), j) == dofs.end())
                list.push_back(j);
            add(list);
          }
      }
    // Two groups coupled with each other.
    list.clear();
    for (unsigned int e = 0; e < 12; ++e)
      list.push_back(n_fluid + e);
    add(list);
  }

  /// The rows' weights: at least each touched row's length (every list
  /// merged into the row is in it), at most that many times its length
  /// (each list is no longer than the row), and the row's length where
  /// one element touches it.
  void
  check_weights(const std::string               &name,
                const Fidus::ElementSparsity    &elements,
                const Fidus::RowPattern         &built,
                const std::vector<unsigned int> &touches)
  {
    const std::vector<std::size_t> weight = elements.row_weights();
    unsigned int                   below = 0, above = 0, inexact = 0;
    for (unsigned int i = 0; i < touches.size(); ++i)
      if (touches[i] > 0)
        {
          below += weight[i] < built.row_length(i);
          above += weight[i] > touches[i] * built.row_length(i);
          inexact += touches[i] == 1 && weight[i] != built.row_length(i);
        }
    check_range(name + ": touched rows whose weight is below their length",
                below,
                0,
                0);
    check_range(name + ": touched rows whose weight is above their "
                       "touches times their length",
                above,
                0,
                0);
    check_range(name + ": rows of one element whose weight is not their "
                       "length",
                inexact,
                0,
                0);
  }

  /// Built with each row keeping all its columns, those flagged (every
  /// third column), or its diagonal alone (i mod 3 = 0, 1, 2): deal.II's
  /// rows (@p expected) filtered alike, and the diagonal in every row.
  void
  check_kept(const std::string            &name,
             const Fidus::ElementSparsity &elements,
             const SparsityPattern        &expected)
  {
    const unsigned int n = expected.n_rows();
    using Keep           = Fidus::ElementSparsity::Keep;
    std::vector<Keep> keep(n);
    std::vector<bool> flagged(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        keep[i]    = i % 3 == 0 ? Keep::all :
                     i % 3 == 1 ? Keep::flagged :
                                  Keep::diagonal;
        flagged[i] = i % 3 == 2;
      }
    Fidus::RowPattern kept;
    elements.build(kept, keep, flagged);
    unsigned int differing_kept = 0, without_diagonal = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        std::vector<unsigned int> a, b;
        for (auto it = expected.begin(i); it != expected.end(i); ++it)
          if (it->column() == i || keep[i] == Keep::all ||
              (keep[i] == Keep::flagged && flagged[it->column()]))
            a.push_back(it->column());
        for (auto it = kept.begin(i); it != kept.end(i); ++it)
          b.push_back(it->column());
        without_diagonal += !kept.exists(i, i);
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        differing_kept += (a != b);
      }
    check_range(name + ": rows kept in part whose columns differ",
                differing_kept,
                0,
                0);
    check_range(name + ": rows kept in part without their diagonal",
                without_diagonal,
                0,
                0);
  }

  template <int dim>
  void
  check(const std::string &name)
  {
    const Mesh<dim>    mesh;
    const unsigned int n_fluid = mesh.dof_handler.n_dofs(), n_extra = 24,
                       n = n_fluid + n_extra;
    DynamicSparsityPattern    dsp(n, n);
    Fidus::ElementSparsity    elements(n, mesh.constraints);
    std::vector<unsigned int> touches(n, 0);
    add_elements(mesh, n_fluid, dsp, elements, touches);

    SparsityPattern   expected;
    Fidus::RowPattern built;
    expected.copy_from(dsp);
    elements.build(built);
    unsigned int differing_rows = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        std::vector<unsigned int> a, b;
        for (auto it = expected.begin(i); it != expected.end(i); ++it)
          a.push_back(it->column());
        for (auto it = built.begin(i); it != built.end(i); ++it)
          b.push_back(it->column());
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        differing_rows += (a != b);
      }
    check_range(name + ": rows", built.n_rows(), n, n);
    check_weights(name, elements, built, touches);
    check_range(name + ": rows whose columns differ from deal.II's",
                differing_rows,
                0,
                0);
    check_range(name + ": entries, relative to deal.II's",
                double(built.n_nonzero_elements()) /
                  expected.n_nonzero_elements(),
                1.,
                1.);
    check_kept(name, elements, expected);
    check_range(name + ": constrained DoFs (some of each kind)",
                mesh.constraints.n_constraints() > n_fluid / 20 ? 1 : 0,
                1,
                1);
  }

  // Three elements without constraints, {0, 1, 2}, {2, 3} and {4}, on
  // eight unknowns: each row's weight is the sum of the sizes of the
  // elements that hold it.
  void
  check_weights_by_hand()
  {
    AffineConstraints<double> none;
    none.close();
    Fidus::ElementSparsity elements(8, none);
    elements.add_element({0, 1, 2});
    elements.add_element({2, 3});
    elements.add_element({4});
    const std::vector<std::size_t> weight   = elements.row_weights();
    const std::vector<std::size_t> expected = {3, 3, 5, 2, 1, 0, 0, 0};
    unsigned int                   wrong    = 0;
    for (unsigned int i = 0; i < 8; ++i)
      wrong += weight[i] != expected[i];
    check_range("three elements by hand: rows of another weight", wrong, 0, 0);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_weights_by_hand();
  check<2>("2D");
  check<3>("3D");
  return exit_code();
}
