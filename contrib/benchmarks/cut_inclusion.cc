// The exact rigid inclusion with the cut finite element (CutStokesInclusion):
// for N seeded positions of a particle of radius a in the middle of the unit
// box and each level, prints the largest and mean omega error and |U|/(g a),
// the velocity's L2 error over the fluid, and the cost. See
// contrib/benchmarks/cut_inclusion.sh.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <deal.II/base/mpi.h>
#include <fidus/fluid/cut_stokes_inclusion.h>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
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
      "max |U|/(g a) | mean |U|/(g a) | velocity L2 error | unknowns "
      "(mean) | cut cells (mean) | wall s (mean) | largest residual |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const unsigned int level : levels)
      {
        double mw = 0., sw = 0., mu = 0., su = 0., mv = 0., h = 0., t = 0.,
               mr   = 0.;
        double dofs = 0., cut = 0.;
        for (const auto &c : centers)
          {
            typename Fidus::CutStokesInclusion<dim>::Settings s;
            s.center       = c;
            s.radius       = a;
            s.global_level = level - band_levels;
            s.band_levels  = band_levels;
            if (const char *v = std::getenv("NITSCHE"))
              s.nitsche = std::atof(v);
            if (const char *v = std::getenv("GHOST_VELOCITY"))
              s.ghost_velocity = std::atof(v);
            if (const char *v = std::getenv("GHOST_PRESSURE"))
              s.ghost_pressure = std::atof(v);
            const auto r = Fidus::CutStokesInclusion<dim>::solve(s);
            mw           = std::max(mw, r.omega_error);
            sw += r.omega_error;
            mu = std::max(mu, r.translation);
            su += r.translation;
            mv = std::max(mv, r.velocity_error);
            mr = std::max(mr, r.residual);
            h  = r.h;
            t += r.seconds;
            dofs += r.n_dofs;
            cut += r.n_cut_cells;
          }
        std::printf("| %u | %.3f | %.2e | %.2e | %.2e | %.2e | %.2e | %.0f | "
                    "%.0f | %.2f | %.1e |\n",
                    level,
                    h / a,
                    mw,
                    sw / n,
                    mu,
                    su / n,
                    mv,
                    dofs / n,
                    cut / n,
                    t / n,
                    mr);
        std::fflush(stdout);
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
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
