// The exact rigid inclusion with the cut finite element (CutStokesInclusion):
// for N seeded positions of a particle of radius a in the middle of the unit
// box and each level, prints the largest and mean omega error and |U|/(g a),
// the velocity's L2 error over the fluid, the stresslet's error, and the
// cost. See
// contrib/benchmarks/cut_inclusion.sh.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deal.II/base/mpi.h>
#include <fidus/fluid/cut_element/cut_stokes_inclusion.h>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  /// PAIR_ANGLE in the environment: a held pair's line of centres that
  /// many degrees below the x axis (default 45, the compressional axis
  /// of the shear), in radians.
  double
  pair_angle()
  {
    const char *v = std::getenv("PAIR_ANGLE");
    return (v ? std::atof(v) : 45.) * M_PI / 180.;
  }

  /// LINEAR_SOLVER = direct | iterative in the environment (default: the
  /// solver's choice), ITERATIVE_TOLERANCE its tolerance,
  /// VELOCITY_PRECONDITIONER = amg | multigrid, CUT_CELL_BLOCKS = 0 for
  /// the multigrid's smoother without cut-cell blocks, SMOOTHER_DEGREE its
  /// products per smoothing, SEPARATE_COMPONENTS = 0 | 1 for its levels
  /// built from the full velocity block or from its components separated
  /// (default: separated in 3D, full in 2D), GAP_LAPLACIAN the weight of the
  /// thin gaps' pressure Laplacian (0: the pressure mass alone), GAP_THRESHOLD
  /// its region in reduced radii, NITSCHE, GHOST_VELOCITY and GHOST_PRESSURE
  /// the discretisation's penalties (default: the solver's).
  template <int dim>
  void
  set_linear_solver(typename Fidus::CutStokesInclusion<dim>::Settings &s)
  {
    using Solver = typename Fidus::CutStokesInclusion<dim>::LinearSolver;
    if (const char *v = std::getenv("LINEAR_SOLVER"))
      s.linear_solver = std::string(v) == "direct"    ? Solver::direct :
                        std::string(v) == "iterative" ? Solver::iterative :
                                                        Solver::automatic;
    if (const char *v = std::getenv("ITERATIVE_TOLERANCE"))
      s.iterative_tolerance = std::atof(v);
    using Velocity =
      typename Fidus::CutStokesInclusion<dim>::VelocityPreconditioner;
    if (const char *v = std::getenv("VELOCITY_PRECONDITIONER"))
      s.velocity_preconditioner =
        std::string(v) == "amg" ? Velocity::amg : Velocity::multigrid;
    if (const char *v = std::getenv("GAP_LAPLACIAN"))
      s.gap_laplacian = std::atof(v);
    if (const char *v = std::getenv("GAP_THRESHOLD"))
      s.gap_threshold = std::atof(v);
    if (const char *v = std::getenv("CUT_CELL_BLOCKS"))
      s.cut_cell_blocks = std::string(v) != "0";
    if (const char *v = std::getenv("SEPARATE_COMPONENTS"))
      s.separate_components = std::string(v) != "0";
    if (const char *v = std::getenv("SMOOTHER_DEGREE"))
      s.smoother_degree = std::atoi(v);
    if (const char *v = std::getenv("NITSCHE"))
      s.nitsche = std::atof(v);
    if (const char *v = std::getenv("GHOST_VELOCITY"))
      s.ghost_velocity = std::atof(v);
    if (const char *v = std::getenv("GHOST_PRESSURE"))
      s.ghost_pressure = std::atof(v);
  }

  template <int dim>
  void
  sweep(const double                     a,
        const std::vector<unsigned int> &levels,
        const unsigned int               n,
        const unsigned int               band_levels)
  {
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> middle(0.4, 0.6);
    std::vector<dealii::Point<dim>>        centers(n);
    for (auto &c : centers)
      for (unsigned int d = 0; d < dim; ++d)
        c[d] = middle(random);
    std::printf(
      "| level | finest h / a | max omega error | mean omega error | "
      "max |U|/(g a) | mean |U|/(g a) | velocity L2 error | max stresslet "
      "error | unknowns (mean) | cut cells (mean) | wall s (mean) | largest "
      "residual | FGMRES (mean) | CG of W (mean) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const unsigned int level : levels)
      {
        double mw = 0., sw = 0., mu = 0., su = 0., mv = 0., h = 0., t = 0.,
               mr = 0., ms = 0.;
        double dofs = 0., cut = 0., iterations = 0., setup = 0.;
        for (const auto &c : centers)
          {
            typename Fidus::CutStokesInclusion<dim>::Settings s;
            s.particles    = {{c, a, dealii::Tensor<1, dim>()}};
            s.global_level = level - band_levels;
            s.band_levels  = band_levels;
            if (const char *v = std::getenv("QUADRATURE_POINTS"))
              s.quadrature_points = std::atoi(v);
            set_linear_solver<dim>(s);
            const auto r = Fidus::CutStokesInclusion<dim>::solve(s);
            iterations += r.n_iterations;
            setup += r.n_setup_iterations;
            mw = std::max(mw, r.omega_error);
            sw += r.omega_error;
            mu = std::max(mu, r.translation);
            su += r.translation;
            mv = std::max(mv, r.velocity_error);
            mr = std::max(mr, r.residual);
            ms = std::max(ms, r.stresslet_error);
            h  = r.h;
            t += r.seconds;
            dofs += r.n_dofs;
            cut += r.n_cut_cells;
          }
        std::printf("| %u | %.3f | %.2e | %.2e | %.2e | %.2e | %.2e | %.2e | "
                    "%.0f | %.0f | %.2f | %.1e | %.1f | %.1f |\n",
                    level,
                    h / a,
                    mw,
                    sw / n,
                    mu,
                    su / n,
                    mv,
                    ms,
                    dofs / n,
                    cut / n,
                    t / n,
                    mr,
                    iterations / n,
                    setup / n);
        std::fflush(stdout);
      }
  }

  /// Two discs of radius a, gap h, for each gap h/a and level:
  /// - pushed (held = false): at 0.5 -/+ (a + h/2) on y = 1/2, pushed
  ///   together by forces +/-1 in the box at rest; the speed printed is
  ///   half their closing speed;
  /// - held (held = true): force-free on the compressional axis of the
  ///   linear shear g (y - 1/2) e_x (g = 1), line of centres at -45 degrees
  ///   through the box centre; the speed printed is their closing speed
  ///   -n . (U_1 - U_0) divided by the undisturbed one, d / 2.
  /// Both scenes are point-symmetric about the box centre, so U_0 + U_1
  /// vanishes.
  void
  two_discs(const bool                       held,
            const double                     a,
            const std::vector<unsigned int> &levels,
            const std::vector<double>       &gaps,
            const unsigned int               band_levels)
  {
    using Solver = Fidus::CutStokesInclusion<2>;
    std::printf(
      "| h/a | level | a / cell | %s | unknowns | cut cells | gap "
      "refinements | wall s | FGMRES | residual | U_0 + U_1 | omega_0 |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      held ? "closing speed / undisturbed" : "approach speed");
    for (const double gap : gaps)
      for (const unsigned int level : levels)
        {
          const double         d = 2. * a + gap * a;
          dealii::Tensor<1, 2> n; // from disc 0 to disc 1
          const double         angle = pair_angle();
          n[0]                       = held ? std::cos(angle) : 1.;
          n[1]                       = held ? -std::sin(angle) : 0.;
          const dealii::Point<2> middle(0.5, 0.5);
          const auto             force = held ? 0. * n : n;
          Solver::Settings       s;
          s.particles    = {{middle - 0.5 * d * n, a, force},
                            {middle + 0.5 * d * n, a, -force}};
          s.boundary     = Solver::Boundary::linear_shear;
          s.shear_rate   = held ? 1. : 0.;
          s.global_level = level - band_levels;
          s.band_levels  = band_levels;
          if (const char *v = std::getenv("GAP_CELLS"))
            s.gap_cells = std::atof(v);
          if (const char *v = std::getenv("QUADRATURE_POINTS"))
            s.quadrature_points = std::atoi(v);
          set_linear_solver<2>(s);
          const auto   r       = Solver::solve(s);
          const double closing = -n * (r.velocity[1] - r.velocity[0]);
          std::printf("| %g | %u | %.1f | %.6e | %u | %u | %u | %.2f | %u | "
                      "%.1e | %.1e | %.1e |\n",
                      gap,
                      level,
                      a * (1 << level),
                      held ? closing / (0.5 * d) : 0.5 * closing,
                      r.n_dofs,
                      r.n_cut_cells,
                      r.n_gap_refinements,
                      r.seconds,
                      r.n_iterations,
                      r.residual,
                      (r.velocity[0] + r.velocity[1]).norm(),
                      r.angular_velocity[0][2]);
          std::fflush(stdout);
        }
  }

  /// Two force-free spheres of radius a, gap h, held on the compressional
  /// axis of the linear shear g (y - 1/2) e_x (g = 1), line of centres at
  /// -45 degrees in the plane z = 1/2 through the box centre, as the paper's
  /// 3D pair near its closest approach; the gap refined with GAP_CELLS
  /// cells across (default 1). Prints the closing speed divided by the
  /// undisturbed one and the cost of the solve.
  void
  held_spheres(const double                     a,
               const std::vector<unsigned int> &levels,
               const std::vector<double>       &gaps,
               const unsigned int               band_levels)
  {
    using Solver = Fidus::CutStokesInclusion<3>;
    std::printf("| gap / a | level | unknowns | cells | gap refinements | "
                "closing speed / undisturbed | wall s | FGMRES | CG of W | "
                "residual |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (const double gap : gaps)
      for (const unsigned int level : levels)
        {
          const double         d = 2. * a + gap * a;
          dealii::Tensor<1, 3> n;
          const double         angle = pair_angle();
          n[0]                       = std::cos(angle);
          n[1]                       = -std::sin(angle);
          const dealii::Point<3> middle(0.5, 0.5, 0.5);
          Solver::Settings       s;
          s.particles    = {{middle - 0.5 * d * n, a, 0. * n},
                            {middle + 0.5 * d * n, a, 0. * n}};
          s.boundary     = Solver::Boundary::linear_shear;
          s.global_level = level - band_levels;
          s.band_levels  = band_levels;
          s.gap_cells    = 1.;
          if (const char *v = std::getenv("GAP_CELLS"))
            s.gap_cells = std::atof(v);
          set_linear_solver<3>(s);
          const auto   r       = Solver::solve(s);
          const double closing = -n * (r.velocity[1] - r.velocity[0]);
          std::printf("| %g | %u | %u | %u | %u | %.6f | %.1f | %u | %u | "
                      "%.1e |\n",
                      gap,
                      level,
                      r.n_dofs,
                      r.n_cells,
                      r.n_gap_refinements,
                      closing / (0.5 * d),
                      r.seconds,
                      r.n_iterations,
                      r.n_setup_iterations,
                      r.residual);
          std::fflush(stdout);
        }
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // cut_inclusion pair|held <a> "<levels>" "<gaps / a>" <band levels>
  if (argc > 1 &&
      (std::string(argv[1]) == "pair" || std::string(argv[1]) == "held"))
    {
      std::vector<unsigned int> levels;
      std::vector<double>       gaps;
      std::istringstream        in_levels(argc > 3 ? argv[3] : "4 5");
      for (unsigned int l; in_levels >> l;)
        levels.push_back(l);
      std::istringstream in_gaps(argc > 4 ? argv[4] : "0.5 0.2 0.1 0.05");
      for (double g; in_gaps >> g;)
        gaps.push_back(g);
      two_discs(std::string(argv[1]) == "held",
                argc > 2 ? std::atof(argv[2]) : 0.1,
                levels,
                gaps,
                argc > 5 ? std::atoi(argv[5]) : 0);
      return 0;
    }
  // cut_inclusion held3d <a> "<levels>" "<gaps / a>" <levels above 2>
  if (argc > 1 && std::string(argv[1]) == "held3d")
    {
      std::vector<unsigned int> levels;
      std::vector<double>       gaps;
      std::istringstream        in_levels(argc > 3 ? argv[3] : "4");
      for (unsigned int l; in_levels >> l;)
        levels.push_back(l);
      std::istringstream in_gaps(argc > 4 ? argv[4] : "0.2 0.05");
      for (double g; in_gaps >> g;)
        gaps.push_back(g);
      held_spheres(argc > 2 ? std::atof(argv[2]) : 0.05,
                   levels,
                   gaps,
                   argc > 5 ? std::atoi(argv[5]) : 2);
      return 0;
    }
  // cut_inclusion <dim> <a> "<levels>" <N> <band levels>
  const unsigned int        dim = argc > 1 ? std::atoi(argv[1]) : 2;
  const double              a   = argc > 2 ? std::atof(argv[2]) : 0.1;
  std::vector<unsigned int> levels;
  std::istringstream        in(argc > 3 ? argv[3] : "4 5 6");
  for (unsigned int l; in >> l;)
    levels.push_back(l);
  const unsigned int n    = argc > 4 ? std::atoi(argv[4]) : 6;
  const unsigned int band = argc > 5 ? std::atoi(argv[5]) : 0;
  if (dim == 3)
    sweep<3>(a, levels, n, band);
  else
    sweep<2>(a, levels, n, band);
}
