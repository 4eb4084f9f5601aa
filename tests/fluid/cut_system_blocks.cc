// CutSystemBlocks (the cut element's system assembled directly into the
// blocks of its iterative solver) against the same system assembled into
// one deal.II SparseMatrix. A Taylor-Hood Q2-Q1 system on a 2D and a 3D
// mesh with hanging nodes (the unknowns of both kinds interleaved, as the
// cut element numbers them), an imposed velocity on the boundary, and two
// "particles" whose rigid unknowns, numbered after the fluid's, couple to
// some cells; every cell adds a pseudo-random local matrix through the
// constraints, and single entries are added between the rigid unknowns.
// Both must hold the same numbers, to the bit (the same additions in the
// same order): every entry of the matrix but B's (the pressure rows'
// columns of velocities and rigid unknowns, which the blocks leave to B^T's
// transpose) found in its block at its place, no entry more in the blocks,
// the same diagonal, the same right-hand side.

#include "../fidus_test.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/affine_constraints.templates.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <fidus/fluid/cut_element/cut_system_blocks.h>
#include <random>

using namespace dealii;
using namespace FidusTest;
using Fidus::CutSystemBlocks;

namespace
{
  template <int dim>
  void
  check(const unsigned int refinements)
  {
    const std::string  name = std::to_string(dim) + "D";
    Triangulation<dim> mesh;
    GridGenerator::hyper_cube(mesh);
    mesh.refine_global(refinements);
    mesh.begin_active()->set_refine_flag();
    mesh.execute_coarsening_and_refinement();
    const FESystem<dim> fe(FE_Q<dim>(2), dim, FE_Q<dim>(1), 1);
    DoFHandler<dim>     dofs(mesh);
    dofs.distribute_dofs(fe);
    const unsigned int n_fluid = dofs.n_dofs(), n_rigid = dim * (dim + 1) / 2,
                       n_total = n_fluid + 2 * n_rigid;

    AffineConstraints<double> constraints;
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    const FEValuesExtractors::Vector velocity(0);
    VectorTools::interpolate_boundary_values(
      dofs,
      0,
      Functions::ConstantFunction<dim>(0.7, dim + 1),
      constraints,
      fe.component_mask(velocity));
    constraints.close();

    // Cell c couples to the rigid unknowns of particle c % 3 (none for 2).
    std::vector<std::vector<types::global_dof_index>> cell_dofs;
    std::vector<types::global_dof_index>              local(fe.dofs_per_cell);
    for (const auto &cell : dofs.active_cell_iterators())
      {
        cell->get_dof_indices(local);
        const unsigned int p = cell_dofs.size() % 3;
        if (p < 2)
          for (unsigned int k = 0; k < n_rigid; ++k)
            local.push_back(n_fluid + p * n_rigid + k);
        cell_dofs.push_back(local);
        local.resize(fe.dofs_per_cell);
      }
    DynamicSparsityPattern dsp(n_total, n_total);
    for (const auto &d : cell_dofs)
      constraints.add_entries_local_to_global(d, dsp);
    for (unsigned int i = n_fluid; i < n_total; ++i)
      for (unsigned int j = n_fluid; j < n_total; ++j)
        dsp.add(i, j);
    SparsityPattern pattern;
    pattern.copy_from(dsp);

    std::vector<unsigned char> kind(n_total, 2);
    for (const auto &cell : dofs.active_cell_iterators())
      {
        cell->get_dof_indices(local);
        for (unsigned int k = 0; k < fe.dofs_per_cell; ++k)
          kind[local[k]] = fe.system_to_component_index(k).first == dim;
      }
    unsigned int interleaved = 0;
    for (unsigned int i = 1; i < n_fluid; ++i)
      interleaved += kind[i] != kind[i - 1];

    SparseMatrix<double> matrix(pattern);
    CutSystemBlocks      blocks;
    blocks.reinit(pattern, kind);
    Vector<double> rhs_matrix(n_total), rhs_blocks(n_total);
    std::mt19937   random(dim);
    std::uniform_real_distribution<double> value(-1., 1.);
    for (const auto &d : cell_dofs)
      {
        FullMatrix<double> m(d.size(), d.size());
        Vector<double>     load(d.size());
        for (unsigned int i = 0; i < d.size(); ++i)
          {
            load[i] = value(random);
            for (unsigned int j = 0; j < d.size(); ++j)
              m(i, j) = value(random);
          }
        constraints.distribute_local_to_global(m, load, d, matrix, rhs_matrix);
        constraints.distribute_local_to_global(m, load, d, blocks, rhs_blocks);
      }
    for (unsigned int i = n_fluid; i < n_total; ++i)
      for (unsigned int j = n_fluid; j < n_total; ++j)
        {
          const double v = value(random);
          matrix.add(i, j, v);
          blocks.add(i, j, v);
        }

    // Every entry of the matrix at its place in its block, and no more.
    unsigned int wrong = 0, diagonal = 0, visited = 0;
    std::size_t  entries = 0, in_b = 0;
    for (unsigned int i = 0; i < n_total; ++i)
      {
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
          {
            const unsigned int j  = it->column();
            const bool         kp = kind[i] == 1, jp = kind[j] == 1;
            if (kp && !jp)
              {
                ++in_b;
                continue;
              }
            const auto &b = kp ? blocks.p : (jp ? blocks.bt : blocks.k);
            wrong += b.el(blocks.local[i], blocks.local[j]) != it->value();
            ++entries;
          }
        diagonal += blocks.diag_element(i) != matrix.diag_element(i);
        blocks.for_row(i, [&](const unsigned int j, const double v) {
          visited += v == matrix.el(i, j);
        });
      }
    const std::size_t in_blocks = blocks.k.n_nonzero_elements() +
                                  blocks.bt.n_nonzero_elements() +
                                  blocks.p.n_nonzero_elements();
    rhs_blocks -= rhs_matrix;

    check_range(name + ": kind changes along the fluid's numbering (some)",
                interleaved > 2,
                1,
                1);
    check_range(name + ": constrained unknowns (some)",
                constraints.n_constraints() > 0,
                1,
                1);
    check_range(name + ": B's entries, left out (some)", in_b > 0, 1, 1);
    check_range(name + ": entries that differ from the matrix's", wrong, 0, 0);
    check_range(name + ": diagonal entries that differ", diagonal, 0, 0);
    check_range(name + ": entries in the blocks, relative to the matrix's",
                double(in_blocks) / entries,
                1.,
                1.);
    check_range(name + ": row entries for_row() visits with the matrix's value,"
                       " relative to the matrix's entries",
                double(visited) / entries,
                1.,
                1.);
    check_range(name + ": |right-hand side difference|",
                rhs_blocks.linfty_norm(),
                0.,
                0.);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>(2);
  check<3>(1);
  return exit_code();
}
