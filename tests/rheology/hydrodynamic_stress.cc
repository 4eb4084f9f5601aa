// The hydrodynamic stress of the suspension (HydrodynamicStress), on 1 and 2
// MPI ranks, against known answers, on direct solves of the penalised Stokes
// problem (2D, two discs):
// - a rigid-body rotation of the whole box (the boundary turns it): every
//   stresslet, the deviatoric box stress and the mean strain rate vanish;
// - a linear shear imposed on the whole boundary: the stress from the
//   walls' consistent residual equals the volume average of the stress in
//   all four components (xx, xy, yx, yy) to the linear solver's tolerance
//   (on a mesh with hanging nodes at the walls),
//   the mean strain rate is the imposed one, and the box stress splits
//   exactly as -<p>_f I + 2 eta_f <e(u)> + (1/V) sum_a S_a.

#include "../fidus_test.h"

#include <deal.II/base/function.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fidus/rheology/hydrodynamic_stress.h>

using namespace FidusTest;
using namespace dealii;

/// u = (a y' + b x', c x' + d y') about the box centre, p = 0.
class LinearVelocity : public Function<2>
{
public:
  LinearVelocity(const double a, const double b, const double c, const double d)
    : Function<2>(3)
    , g{{a, b, c, d}}
  {}
  double
  value(const Point<2> &x, const unsigned int component) const override
  {
    const double xs = x[0] - 0.5, ys = x[1] - 0.5;
    if (component == 0)
      return g[0] * ys + g[1] * xs;
    if (component == 1)
      return g[2] * xs + g[3] * ys;
    return 0.;
  }

private:
  std::array<double, 4> g;
};

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
  GridGenerator::hyper_cube(tria, 0., 1., true);
  tria.refine_global(5);
  Fidus::StokesSolver<2>::Settings settings;
  settings.rigidity_tolerance = 1e-5;
  settings.linear_tolerance   = 1e-10;
  Fidus::StokesSolver<2> solver(tria, settings);
  solver.setup_dofs({}, {0, 1, 2, 3});

  Fidus::SolidIndicator<2> solid;
  solid.reinit({{{0.3, 0.4, 0.}}, {{0.68, 0.62, 0.}}},
               {0.12, 0.1},
               Point<2>(0., 0.),
               Point<2>(1., 1.));
  const Fidus::HydrodynamicStress<2> stress({0, 1, 2, 3});

  // Rigid rotation with angular velocity 1: no stress at all.
  solver.solve(solid, LinearVelocity(-1., 0., 1., 0.));
  auto   r       = stress.compute(solver, solid);
  double largest = 0.;
  for (const auto &s : r.stresslets)
    largest = std::max(largest, s.norm());
  // Zero up to the solver's tolerance (1e-10), which the solid viscosity
  // r eta_f = 1e3 eta_f multiplies; scale: a disc's stresslet in shear,
  // 2 pi eta gamma_dot a^2.
  check_range("rotation: largest |S_a| / (2 pi eta omega a^2)",
              largest / (2. * numbers::PI * 0.12 * 0.12),
              0.,
              1e-5);
  check_range("rotation: |dev Sigma| / (eta omega)",
              deviator(r.total).norm(),
              0.,
              1e-6);
  check_range("rotation: |<e(u)>| / omega",
              r.mean_strain_rate.norm(),
              0.,
              1e-8);

  // Linear shear u = (y', 0) on the whole boundary (shear rate 1), on a
  // mesh with hanging nodes where it meets the walls (a finer patch at the
  // lower-left corner): hanging nodes pass residual to coarse wall DoFs.
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->center()[0] < 0.45 && cell->center()[1] < 0.3)
      cell->set_refine_flag();
  tria.execute_coarsening_and_refinement();
  solver.setup_dofs({}, {0, 1, 2, 3});
  solver.solve(solid, LinearVelocity(1., 0., 0., 0.));
  r               = stress.compute(solver, solid);
  double mismatch = 0.;
  for (unsigned int a = 0; a < 2; ++a)
    for (unsigned int b = 0; b < 2; ++b)
      mismatch = std::max(mismatch, std::abs(r.wall[a][b] - r.total[a][b]));
  check_range("shear: max |wall stress - volume-averaged stress| / Sigma_xy",
              mismatch / r.total[0][1],
              0.,
              1e-6);
  check_range("shear: <e(u)>_xy (imposed 1/2)",
              r.mean_strain_rate[0][1],
              0.5 - 1e-10,
              0.5 + 1e-10);
  SymmetricTensor<2, 3> split = 2. * r.mean_strain_rate + r.particle;
  for (unsigned int d = 0; d < 3; ++d)
    split[d][d] -= r.fluid_pressure;
  check_range("shear: |Sigma - (-<p>_f I + 2 eta <e> + Sigma_p)| / Sigma_xy",
              (r.total - split).norm() / r.total[0][1],
              0.,
              1e-10);
  // Two rigid discs make the box stiffer than the fluid (eta_r > 1).
  check_range("shear: Sigma_xy / (eta gamma_dot)", r.total[0][1], 1., 2.);
  return exit_code();
}
