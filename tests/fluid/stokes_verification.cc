// Verification of the Stokes core without particles:
//  1. linear shear (validation.md case 1) in 2D and 3D: the exact field lies
//     in the Q2/Q1 space, so the error is at round-off on any mesh (here an
//     adapted mesh with hanging nodes);
//  2. a manufactured solution with a smooth variable viscosity (a tanh jump
//     from 1 to 10) in 2D (case 2): rates ~3 (u, L2), ~2 (u, H1), ~2 (p, L2)
//     under uniform refinement.
// Both with the ML AMG and with the geometric multigrid (global coarsening,
// matrix-free velocity block) as the velocity preconditioner: the answer
// must not depend on the preconditioner, so the same bounds hold for both.
// The convergence table goes to measured_values.txt.

#include "../fidus_test.h"

#include <deal.II/base/function.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fstream>

using namespace dealii;
using namespace FidusTest;

template <int dim>
class LinearShear : public Function<dim>
{
public:
  LinearShear()
    : Function<dim>(dim + 1)
  {}
  double
  value(const Point<dim> &p, const unsigned int c) const override
  {
    return c == 0 ? p[1] - 0.5 : 0.;
  }
  Tensor<1, dim>
  gradient(const Point<dim> &, const unsigned int c) const override
  {
    Tensor<1, dim> g;
    if (c == 0)
      g[1] = 1.;
    return g;
  }
};

// Manufactured solution: u = curl of psi = sin^2(pi x) sin^2(pi y),
// p = sin(pi x) cos(pi y), eta = 1 + 4.5 (1 + tanh((x + y - 1) / 0.1)).
namespace MMS
{
  const double pi = numbers::PI;
  double
  S(double x)
  {
    return std::pow(std::sin(pi * x), 2);
  }
  double
  S1(double x)
  {
    return pi * std::sin(2 * pi * x);
  }
  double
  S2(double x)
  {
    return 2 * pi * pi * std::cos(2 * pi * x);
  }
  double
  S3(double x)
  {
    return -4 * pi * pi * pi * std::sin(2 * pi * x);
  }
  double
  eta(const Point<2> &p)
  {
    return 1. + 4.5 * (1. + std::tanh((p[0] + p[1] - 1.) / 0.1));
  }
  Tensor<1, 2>
  grad_eta(const Point<2> &p)
  {
    const double c = std::cosh((p[0] + p[1] - 1.) / 0.1);
    const double d = 4.5 / 0.1 / (c * c);
    return Tensor<1, 2>({d, d});
  }
} // namespace MMS

class MmsSolution : public Function<2>
{
public:
  MmsSolution()
    : Function<2>(3)
  {}
  double
  value(const Point<2> &p, const unsigned int c) const override
  {
    using namespace MMS;
    const double x = p[0], y = p[1];
    if (c == 0)
      return S(x) * S1(y);
    if (c == 1)
      return -S1(x) * S(y);
    return std::sin(pi * x) * std::cos(pi * y);
  }
  Tensor<1, 2>
  gradient(const Point<2> &p, const unsigned int c) const override
  {
    using namespace MMS;
    const double x = p[0], y = p[1];
    if (c == 0)
      return Tensor<1, 2>({S1(x) * S1(y), S(x) * S2(y)});
    if (c == 1)
      return Tensor<1, 2>({-S2(x) * S(y), -S1(x) * S1(y)});
    return Tensor<1, 2>({pi * std::cos(pi * x) * std::cos(pi * y),
                         -pi * std::sin(pi * x) * std::sin(pi * y)});
  }
};

class MmsForce : public Function<2>
{
public:
  MmsForce()
    : Function<2>(3)
  {}
  // f = -div(2 eta e(u)) + grad p = -eta lap u - 2 e(u) grad eta + grad p
  // for a divergence-free u.
  void
  vector_value(const Point<2> &p, Vector<double> &f) const override
  {
    using namespace MMS;
    const double       x = p[0], y = p[1];
    const double       lap[2] = {S2(x) * S1(y) + S(x) * S3(y),
                                 -S3(x) * S(y) - S1(x) * S2(y)};
    MmsSolution        u;
    const Tensor<1, 2> gu0 = u.gradient(p, 0), gu1 = u.gradient(p, 1),
                       gp      = u.gradient(p, 2);
    const double       e[2][2] = {{gu0[0], 0.5 * (gu0[1] + gu1[0])},
                                  {0.5 * (gu0[1] + gu1[0]), gu1[1]}};
    const Tensor<1, 2> ge      = grad_eta(p);
    for (unsigned int d = 0; d < 2; ++d)
      f[d] = -eta(p) * lap[d] - 2 * (e[d][0] * ge[0] + e[d][1] * ge[1]) + gp[d];
    f[2] = 0;
  }
};

class MmsViscosity : public Function<2>
{
public:
  double
  value(const Point<2> &p, const unsigned int) const override
  {
    return MMS::eta(p);
  }
};

template <int dim>
void
linear_shear(const bool gmg)
{
  parallel::distributed::Triangulation<dim> tria(MPI_COMM_WORLD);
  GridGenerator::hyper_cube(tria, 0, 1, true);
  tria.refine_global(2);
  // Refine one corner twice so that the mesh has hanging nodes.
  for (unsigned int k = 0; k < 2; ++k)
    {
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->center().norm() < 0.4)
          cell->set_refine_flag();
      tria.execute_coarsening_and_refinement();
    }
  typename Fidus::StokesSolver<dim>::Settings settings;
  settings.linear_tolerance    = 1e-14;
  settings.geometric_multigrid = gmg;
  Fidus::StokesSolver<dim>     solver(tria, settings);
  std::set<types::boundary_id> ids;
  for (unsigned int b = 0; b < 2 * dim; ++b)
    ids.insert(b);
  solver.setup_dofs({}, ids);
  Fidus::SolidIndicator<dim> none;
  none.reinit({}, {}, Point<dim>(), Point<dim>());
  LinearShear<dim> exact;
  solver.solve(none, exact);
  const auto        e = solver.compute_errors(exact, none, false);
  const std::string name =
    std::to_string(dim) + "D linear shear" + (gmg ? " (GMG)" : " (AMG)");
  check_range(name + ": L2 error of u", e.u_l2, 0., 1e-10);
  check_range(name + ": H1 error of u", e.u_h1, 0., 1e-9);
  check_range(name + ": L2 error of p", e.p_l2, 0., 1e-9);
}

void
manufactured(const bool gmg)
{
  std::vector<typename Fidus::StokesSolver<2>::Errors> errors;
  std::ofstream     table("measured_values.txt", std::ios::app);
  const std::string name = gmg ? "MMS (GMG)" : "MMS (AMG)";
  table << name << ": level  dofs  |u-u_h|_L2  |u-u_h|_H1  |p-p_h|_L2\n";
  for (unsigned int level = 2; level <= 5; ++level)
    {
      parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
      GridGenerator::hyper_cube(tria, 0, 1, true);
      tria.refine_global(level);
      typename Fidus::StokesSolver<2>::Settings settings;
      settings.linear_tolerance    = 1e-12;
      settings.geometric_multigrid = gmg;
      Fidus::StokesSolver<2> solver(tria, settings);
      solver.setup_dofs({}, {0, 1, 2, 3});
      Fidus::SolidIndicator<2> none;
      none.reinit({}, {}, Point<2>(), Point<2>());
      MmsSolution  exact;
      MmsForce     force;
      MmsViscosity eta;
      solver.solve(none, exact, &force, &eta);
      errors.push_back(solver.compute_errors(exact, none, false));
      table << name << ": " << level << "  " << solver.n_dofs() << "  "
            << errors.back().u_l2 << "  " << errors.back().u_h1 << "  "
            << errors.back().p_l2 << "\n";
    }
  const unsigned int n = errors.size();
  check_range(name + ": rate of |u - u_h|_L2",
              std::log2(errors[n - 2].u_l2 / errors[n - 1].u_l2),
              2.7,
              3.5);
  check_range(name + ": rate of |u - u_h|_H1",
              std::log2(errors[n - 2].u_h1 / errors[n - 1].u_h1),
              1.8,
              2.5);
  check_range(name + ": rate of |p - p_h|_L2",
              std::log2(errors[n - 2].p_l2 / errors[n - 1].p_l2),
              1.7,
              3.5);
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const bool gmg : {false, true})
    {
      linear_shear<2>(gmg);
      linear_shear<3>(gmg);
      manufactured(gmg);
    }
  return exit_code();
}
