// Cut-cell blocks in the GMG smoother (Fluid/Linear solver/Multigrid
// smoother blocks = cut cells, CellBlockPreconditioner). Checks, on 1 and 2
// ranks:
// - each block is the assembled velocity matrix restricted to the free DoFs
//   of its cut cell: W^{-1} A_KK W^{-1} times the stored inverse is the
//   identity to 1e-9, in 2D and 3D, on adaptive meshes whose hanging nodes
//   reach the periodic faces (the assembled matrix comes from deal.II's
//   MatrixFreeTools::compute_matrix, an independent assembly path); on 2
//   ranks this includes the rows that the ghost cells' element matrices
//   complete;
// - the preconditioner is symmetric (relative 1e-12) and positive;
// - in the solver: the exact 3D inclusion at r = 1e4 needs at most 0.6
//   times the FGMRES iterations per Uzawa solve of point Jacobi (measured
//   0.47 at level 3 on 1 and 2 ranks; on 2 ranks 0.67 before the ghost
//   cells completed the rows), and the particle velocity changes by at most
//   1e-7;
// - Rigid-body correction = auto is off with GMG in 3D and on elsewhere
//   (doc/preconditioners.md), and true/false override it.

#include "../fidus_test.h"
#include "summary_tools.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>
#include <fidus/core/parameters.h>
#include <fidus/fluid/fictitious_domain/cell_block_preconditioner.h>
#include <fidus/simulation/simulation.h>

using namespace dealii;
using namespace FidusTest;

/// Distance to the particle at (0.97, 0.5, ...) with radius 0.2, periodic in
/// x (the particle crosses x = 1).
template <int dim>
double
distance(const Point<dim> &x)
{
  Point<dim> c;
  for (unsigned int d = 0; d < dim; ++d)
    c[d] = 0.5;
  c[0]       = 0.97;
  double dx0 = x[0] - c[0];
  dx0 -= std::round(dx0);
  double d2 = dx0 * dx0;
  for (unsigned int d = 1; d < dim; ++d)
    d2 += (x[d] - c[d]) * (x[d] - c[d]);
  return std::sqrt(d2) - 0.2;
}

/**
 * Over the cut-cell blocks of @p blocks: the largest |W A_KK W B_K - I|
 * relative to the single-precision rounding of B_K (A = @p matrix, W the
 * square roots of the multiplicities), and the largest multiplicity.
 */
template <int dim>
std::pair<double, double>
block_errors(const Fidus::CellBlockPreconditioner<dim, 2> &blocks,
             const TrilinosWrappers::SparseMatrix         &matrix,
             const Utilities::MPI::Partitioner            &partitioner)
{
  double worst = 0., largest_multiplicity = 0.;
  for (unsigned int b = 0; b < blocks.n_blocks(); ++b)
    {
      const auto         local   = blocks.block_indices(b);
      const auto         inverse = blocks.block_inverse(b);
      const unsigned int n       = local.size();
      FullMatrix<double> weighted(n, n), product(n, n);
      for (unsigned int p = 0; p < n; ++p)
        for (unsigned int q = 0; q < n; ++q)
          weighted(p, q) = matrix.el(partitioner.local_to_global(local[p]),
                                     partitioner.local_to_global(local[q])) *
                           std::sqrt(double(blocks.multiplicity()[local[p]]) *
                                     blocks.multiplicity()[local[q]]);
      weighted.mmult(product, inverse);
      // The inverses are stored in single precision: each entry within
      // its rounding, 2^-24 relative, so that |A B - I| is bounded by
      // 2^-24 |A| |B| (maximum-row-sum norms); a wrong inverse is off by
      // far more.
      const double rounding =
        std::ldexp(1., -24) * weighted.linfty_norm() * inverse.linfty_norm();
      for (unsigned int p = 0; p < n; ++p)
        for (unsigned int q = 0; q < n; ++q)
          worst =
            std::max(worst, std::abs(product(p, q) - (p == q)) / rounding);
      for (const unsigned int i : local)
        largest_multiplicity =
          std::max<double>(largest_multiplicity, blocks.multiplicity()[i]);
    }
  return {worst, largest_multiplicity};
}



template <int dim>
void
check_blocks()
{
  const MPI_Comm                            comm = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::hyper_cube(tria, 0., 1., true);
  std::vector<
    GridTools::PeriodicFacePair<typename Triangulation<dim>::cell_iterator>>
    faces;
  GridTools::collect_periodic_faces(tria, 0, 1, 0, faces);
  tria.add_periodicity(faces);
  tria.refine_global(dim == 2 ? 3 : 2);
  // Refine the cells the particle's surface cuts, twice: hanging nodes, also
  // on the periodic faces.
  for (unsigned int step = 0; step < 2; ++step)
    {
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() &&
            std::abs(distance(cell->center())) < 0.9 * cell->diameter())
          cell->set_refine_flag();
      tria.execute_coarsening_and_refinement();
    }

  DoFHandler<dim> dofs(tria);
  dofs.distribute_dofs(FESystem<dim>(FE_Q<dim>(2), dim));
  IndexSet relevant;
  DoFTools::extract_locally_relevant_dofs(dofs, relevant);
  AffineConstraints<double> constraints(relevant);
  DoFTools::make_hanging_node_constraints(dofs, constraints);
  DoFTools::make_periodicity_constraints(dofs, 0, 1, 0, constraints);
  for (types::boundary_id id = 2; id < 2 * dim; ++id)
    VectorTools::interpolate_boundary_values(MappingQ1<dim>(),
                                             dofs,
                                             id,
                                             Functions::ZeroFunction<dim>(dim),
                                             constraints);
  constraints.close();

  using Operator = Fidus::VelocityOperator<dim, 2>;
  typename MatrixFree<dim, double>::AdditionalData data;
  data.tasks_parallel_scheme = MatrixFree<dim, double>::AdditionalData::none;
  data.mapping_update_flags =
    update_gradients | update_JxW_values | update_quadrature_points;
  auto mf = std::make_shared<MatrixFree<dim, double>>();
  mf->reinit(MappingQ1<dim>(), dofs, constraints, QGauss<1>(3), data);
  Operator op;
  op.initialize(mf);
  {
    typename Operator::Evaluator phi(*mf);
    op.viscosity.reinit(mf->n_cell_batches(), phi.n_q_points);
    for (unsigned int batch = 0; batch < mf->n_cell_batches(); ++batch)
      {
        phi.reinit(batch);
        for (unsigned int q = 0; q < phi.n_q_points; ++q)
          for (unsigned int lane = 0; lane < VectorizedArray<double>::size();
               ++lane)
            {
              Point<dim> x;
              for (unsigned int d = 0; d < dim; ++d)
                x[d] = phi.quadrature_point(q)[d][lane];
              op.viscosity(batch, q)[lane] = distance(x) < 0. ? 1e4 : 1.;
            }
      }
  }
  op.compute_diagonal();
  Fidus::CellBlockPreconditioner<dim, 2> blocks;
  // The ghost cells' viscosity completes the rows at the partition
  // boundary (on 2 ranks); the check below then covers those rows too.
  blocks.initialize(op,
                    dofs,
                    constraints,
                    Fidus::SmootherBlocks::cut_cells,
                    [](const typename DoFHandler<dim>::active_cell_iterator &,
                       const FEValues<dim> &fe_values,
                       std::vector<double> &eta) {
                      eta.resize(fe_values.n_quadrature_points);
                      for (unsigned int q = 0; q < eta.size(); ++q)
                        eta[q] = distance(fe_values.quadrature_point(q)) < 0. ?
                                   1e4 :
                                   1.;
                    });

  TrilinosWrappers::SparsityPattern pattern(dofs.locally_owned_dofs(), comm);
  DoFTools::make_sparsity_pattern(dofs, pattern, constraints);
  pattern.compress();
  TrilinosWrappers::SparseMatrix matrix;
  matrix.reinit(pattern);
  op.compute_matrix(constraints, matrix);

  typename Operator::VectorType v, w, pv, pw;
  op.initialize_dof_vector(v);
  const auto &partitioner = v.get_partitioner();
  const auto [worst, largest_multiplicity] =
    block_errors(blocks, matrix, *partitioner);
  const std::string name = std::to_string(dim) + "D: ";
  check_range(name + "cut-cell blocks on all ranks",
              Utilities::MPI::sum(blocks.n_blocks(), comm),
              dim == 2 ? 8 : 20,
              1e6);
  check_range(name + "largest number of blocks holding a DoF",
              Utilities::MPI::max(largest_multiplicity, comm),
              2,
              1e3);
  check_range(name + "max |W^-1 A_KK W^-1 B_K - I| / (2^-24 |W^-1 A_KK W^-1| "
                     "|B_K|) over the blocks (single-precision inverses)",
              Utilities::MPI::max(worst, comm),
              0.,
              1.);

  // Symmetry and positivity of the whole preconditioner.
  op.initialize_dof_vector(w);
  op.initialize_dof_vector(pv);
  op.initialize_dof_vector(pw);
  for (const auto i : dofs.locally_owned_dofs())
    if (!constraints.is_constrained(i))
      {
        v[i] = std::sin(1.3 * i + 0.7);
        w[i] = std::cos(0.37 * i) + 0.2;
      }
  blocks.vmult(pv, v);
  blocks.vmult(pw, w);
  check_range(name + "|v.Pw - w.Pv| / (|v| |Pw|)",
              std::abs(v * pw - w * pv) / (v.l2_norm() * pw.l2_norm()),
              0.,
              1e-12);
  check_range(name + "v.Pv / (|v| |Pv|)",
              v * pv / (v.l2_norm() * pv.l2_norm()),
              1e-8,
              1.);
}

Fidus::RunSummary
run_inclusion(const std::string &blocks)
{
  std::ostringstream prm;
  prm << "set Dimension = 3\nset Output directory = run_output\n"
      << "subsection Domain\n  set Lower left = 0, 0, 0\n"
      << "  set Upper right = 1, 1, 1\n"
      << "  set Boundary condition = exact rigid inclusion\nend\n"
      << "subsection Fluid\n  set Penalty factor = 1e4\n"
      << "  subsection Linear solver\n    set Tolerance = 1e-9\n"
      << "    set Preconditioner = GMG\n"
      << "    set Multigrid smoother blocks = " << blocks << "\n  end\nend\n"
      << "subsection Particles\n  set Radius = 0.2\n"
      << "  set Positions = 0.53, 0.48, 0.51\nend\n"
      << "subsection Time stepping\n  set End time = 0\nend\n"
      << "subsection Mesh refinement\n  set Initial global refinement = 2\n"
      << "  set Minimum level = 2\n  set Maximum level = 3\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

/// Whether the rigid-body correction is on in @p dim dimensions, with the
/// Linear solver entries @p solver.
bool
correction_on(const unsigned int dim, const std::string &solver = "")
{
  std::ostringstream prm;
  prm << "set Dimension = " << dim << "\nsubsection Domain\n"
      << "  set Lower left = " << (dim == 2 ? "0, 0" : "0, 0, 0") << "\n"
      << "  set Upper right = " << (dim == 2 ? "1, 1" : "1, 1, 1") << "\n"
      << "end\nsubsection Fluid\n  subsection Linear solver\n"
      << solver << "  end\nend\n";
  return Fidus::read_parameters_from_string(prm.str())
    .fictitious_domain.rigid_body_correction;
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  check_blocks<2>();
  check_blocks<3>();

  check_range("Rigid-body correction = auto: 3D (GMG) off, 2D (AMG) on, 3D "
              "AMG on, 3D GMG with true on (1 each)",
              !correction_on(3) + correction_on(2) +
                correction_on(3, "    set Preconditioner = AMG\n") +
                correction_on(3, "    set Rigid-body correction = true\n"),
              4,
              4);

  const auto blocks = run_inclusion("cut cells");
  const auto points = run_inclusion("none");
  std::cerr << "  (FGMRES per Uzawa solve, 3D inclusion r = 1e4: blocks "
            << per_solve(blocks) << ", point Jacobi " << per_solve(points)
            << ")" << std::endl;
  check_range("3D inclusion, r = 1e4: FGMRES per solve, blocks / point Jacobi",
              per_solve(blocks) / per_solve(points),
              0.,
              0.6);
  check_range("3D inclusion: |dU|/a, |d omega|, blocks minus point Jacobi",
              difference(blocks, points, 0.2),
              0.,
              1e-7);
  return exit_code();
}
