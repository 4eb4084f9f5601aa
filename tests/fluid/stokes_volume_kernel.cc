// StokesVolumeKernel, the cut element's volume terms formed from the
// scalar Q2 functions' derivatives (G G^T) instead of from every shape
// function's strain, on the fluid part of a cell cut by a ball (the
// quadrature the cut element integrates on), in 2D and 3D:
//  - against the textbook double loop over the Taylor-Hood functions,
//    2 eta eps_i : eps_j - div_i q_j - q_i div_j and q_i q_j / eta: within
//    1e-13 of the largest entry;
//  - rigid motions a + omega x r make no viscous force and no divergence:
//    the matrix times them within 1e-12 of |matrix| |motion|;
//  - the linear shear u = (y, 0, ...) has the energy u^T K u = eta |fluid|
//    (eps : eps = 1/2), |fluid| the quadrature's volume: within 1e-12;
//  - an element that is not Q2^dim-Q1 is refused by name.
// The ball leaves 0.05 to 0.95 of the cell fluid (a cut cell).

#include "../fidus_test.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_cartesian.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/non_matching/quadrature_generator.h>
#include <fidus/fluid/cut_element/cut_level_set.h>
#include <fidus/fluid/cut_element/stokes_volume_kernel.h>

using namespace dealii;
using namespace FidusTest;

namespace
{
  /// The volume terms and the pressure mass / eta by the double loop over
  /// the Taylor-Hood functions, as a textbook writes them; returns the
  /// quadrature's volume.
  template <int dim>
  double
  textbook_matrices(const FEValues<dim> &fe_values,
                    const double         eta,
                    FullMatrix<double>  &reference,
                    FullMatrix<double>  &reference_pressure)
  {
    const auto                      &fe = fe_values.get_fe();
    const unsigned int               n  = fe.n_dofs_per_cell();
    const FEValuesExtractors::Vector velocity(0);
    const FEValuesExtractors::Scalar pressure(dim);
    std::vector<unsigned int>        pressures;
    for (unsigned int i = 0; i < n; ++i)
      if (fe.system_to_component_index(i).first == dim)
        pressures.push_back(i);
    reference.reinit(n, n);
    reference_pressure.reinit(pressures.size(), pressures.size());
    double volume = 0.;
    for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
      {
        const double JxW = fe_values.JxW(q);
        volume += JxW;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            reference(i, j) +=
              (2. * eta *
                 (fe_values[velocity].symmetric_gradient(i, q) *
                  fe_values[velocity].symmetric_gradient(j, q)) -
               fe_values[velocity].divergence(i, q) *
                 fe_values[pressure].value(j, q) -
               fe_values[pressure].value(i, q) *
                 fe_values[velocity].divergence(j, q)) *
              JxW;
        for (unsigned int a = 0; a < pressures.size(); ++a)
          for (unsigned int b = 0; b < pressures.size(); ++b)
            reference_pressure(a, b) += fe_values.shape_value(pressures[a], q) *
                                        fe_values.shape_value(pressures[b], q) *
                                        JxW / eta;
      }
    return volume;
  }

  template <int dim>
  void
  check(const std::string &name)
  {
    const double       eta = 1.7, h = 0.25;
    Triangulation<dim> tria;
    GridGenerator::hyper_cube(tria, 0.1, 0.1 + h);
    const FESystem<dim> fe(FE_Q<dim>(2), dim, FE_Q<dim>(1), 1);
    DoFHandler<dim>     dofs(tria);
    dofs.distribute_dofs(fe);
    const auto cell = dofs.begin_active();

    // The fluid outside a ball that cuts the cell near its lower corner.
    Point<dim> center;
    for (unsigned int d = 0; d < dim; ++d)
      center[d] = 0.1 + 0.3 * h - 0.07 * d * h;
    const hp::QCollection<1>              q1d(QGauss<1>(dim == 2 ? 8 : 4));
    NonMatching::QuadratureGenerator<dim> generator(q1d);
    generator.generate(Fidus::CutLevelSet<dim>(cell->vertex(0),
                                               cell->vertex((1 << dim) - 1),
                                               center,
                                               0.5 * h),
                       create_unit_bounding_box<dim>());
    const Quadrature<dim>      &quadrature = generator.get_outside_quadrature();
    const MappingCartesian<dim> mapping;
    FEValues<dim>               fe_values(mapping,
                            fe,
                            quadrature,
                            update_values | update_gradients |
                              update_JxW_values | update_quadrature_points);
    fe_values.reinit(cell);
    const unsigned int n = fe.n_dofs_per_cell();

    Fidus::StokesVolumeKernel<dim> kernel(fe);
    FullMatrix<double>             local(n + 3, n + 3),
      local_pressure((1 << dim), (1 << dim));
    kernel.add(fe_values, eta, local, local_pressure);

    // The textbook loops.
    FullMatrix<double> reference, reference_pressure;
    const double       volume =
      textbook_matrices(fe_values, eta, reference, reference_pressure);
    // The ball cuts the cell: part of it is fluid.
    check_range(name + ": the fluid's fraction of the cell",
                volume / std::pow(h, dim),
                0.05,
                0.95);
    double error = 0., largest = 0.;
    for (unsigned int i = 0; i < n + 3; ++i)
      for (unsigned int j = 0; j < n + 3; ++j)
        {
          const double expected = i < n && j < n ? reference(i, j) : 0.;
          error   = std::max(error, std::abs(local(i, j) - expected));
          largest = std::max(largest, std::abs(expected));
        }
    check_range(name + ": the volume terms against the loops, relative",
                error / largest,
                0.,
                1e-13);
    double error_p = 0., largest_p = 0.;
    for (unsigned int a = 0; a < reference_pressure.m(); ++a)
      for (unsigned int b = 0; b < reference_pressure.n(); ++b)
        {
          error_p =
            std::max(error_p,
                     std::abs(local_pressure(a, b) - reference_pressure(a, b)));
          largest_p = std::max(largest_p, std::abs(reference_pressure(a, b)));
        }
    check_range(name + ": the pressure mass against the loops, relative",
                error_p / largest_p,
                0.,
                1e-13);

    // A velocity field's nodal values (Q2 holds linear fields exactly).
    const auto nodal = [&](const auto &u) {
      Vector<double> x(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          const auto c = fe.system_to_component_index(i).first;
          if (c < dim)
            x[i] = u(
              mapping.transform_unit_to_real_cell(cell,
                                                  fe.unit_support_point(i)))[c];
        }
      return x;
    };
    FullMatrix<double> matrix(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        matrix(i, j) = local(i, j);
    double worst = 0.;
    for (unsigned int mode = 0; mode < (dim == 2 ? 3 : 6); ++mode)
      {
        const Vector<double> x = nodal([&](const Point<dim> &p) {
          Tensor<1, dim> u;
          if (mode < dim)
            u[mode] = 1.;
          else if (dim == 2)
            u[0] = -p[1], u[1] = p[0];
          else
            {
              const unsigned int a = (mode - dim + 1) % dim,
                                 b = (mode - dim + 2) % dim;
              u[a]                 = -p[b];
              u[b]                 = p[a];
            }
          return u;
        });
        Vector<double>       y(n);
        matrix.vmult(y, x);
        worst =
          std::max(worst,
                   y.linfty_norm() / (matrix.linfty_norm() * x.linfty_norm()));
      }
    check_range(name + ": rigid motions' force and divergence, relative",
                worst,
                0.,
                1e-12);
    const Vector<double> shear = nodal([](const Point<dim> &p) {
      Tensor<1, dim> u;
      u[0] = p[1];
      return u;
    });
    check_range(name + ": linear shear's energy over eta |fluid|, minus 1",
                std::abs(matrix.matrix_norm_square(shear) / (eta * volume) -
                         1.),
                0.,
                1e-12);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>("2D cut cell");
  check<3>("3D cut cell");
  try
    {
      const FESystem<2>            q1q1(FE_Q<2>(1), 2, FE_Q<2>(1), 1);
      Fidus::StokesVolumeKernel<2> kernel(q1q1);
      check_range("Q1-Q1 refused", 0., 1., 1.);
    }
  catch (const std::invalid_argument &e)
    {
      const std::string what = e.what();
      check_range("Q1-Q1 refused, by name",
                  what.find("FESystem<2>[FE_Q<2>(1)^2-FE_Q<2>(1)]") !=
                      std::string::npos ?
                    1. :
                    0.,
                  1.,
                  1.);
    }
  return exit_code();
}
