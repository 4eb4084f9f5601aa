// Benchmark of the contact projection (not a test): time per projection and
// dual iterations for one configuration and one or all dual solvers, with the
// pair search timed separately (cell list and R-tree).
//
// Usage: fidus_contact_benchmark DIM N PHI SOLVER [STEPS]
//   DIM 2 or 3, N particles, PHI volume (area) fraction, SOLVER one of
//   pg, apg, pgs, pgs_subspace, all; STEPS projections to average (default 3).
//
// Configuration: equal radii a = 1 on a jittered lattice (triangular in 2D,
// FCC in 3D) at volume fraction PHI: random sequential addition cannot reach
// 0.5 in 3D. Each particle moves by at most its share of the lattice gap, so
// the start has no overlap. Predicted velocities are random in the unit ball
// plus a weak converging part, with dt max|u*| = a/2, so that a large share
// of the pairs collide in one step. Each step moves the particles with the
// corrected velocities, so steps after the first are warm started.
// Model: gluey (equalities and inequalities); tolerance 1e-9 a.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fidus/contact/contact_projector.h>
#include <fidus/contact/pair_search.h>
#include <string>
#include <vector>

using namespace Fidus::Contact;

namespace
{
  /// Portable uniform random numbers (xorshift64*).
  class Random
  {
  public:
    explicit Random(std::uint64_t seed)
      : state(seed * 2685821657736338717ull + 1)
    {}
    double
    uniform(double lo, double hi)
    {
      state ^= state >> 12;
      state ^= state << 25;
      state ^= state >> 27;
      return lo +
             (hi - lo) *
               static_cast<double>((state * 2685821657736338717ull) >> 11) *
               0x1.0p-53;
    }

  private:
    std::uint64_t state;
  };

  /// Jittered lattice of n unit particles at fraction phi; returns box size.
  double
  lattice(const unsigned     dim,
          const std::size_t  n,
          const double       phi,
          Random            &random,
          std::vector<Vec3> &x)
  {
    const double      pi = 3.14159265358979323846;
    std::vector<Vec3> basis;
    Vec3              cell_size;
    double            d_nn;
    if (dim == 2)
      {
        // Triangular lattice: rectangular cell of two sites, d x sqrt(3) d.
        const double d = std::sqrt(2. * pi / (std::sqrt(3.) * phi));
        cell_size      = {{d, std::sqrt(3.) * d, 0.}};
        basis          = {Vec3{{0., 0., 0.}},
                          Vec3{{0.5 * d, 0.5 * std::sqrt(3.) * d, 0.}}};
        d_nn           = d;
      }
    else
      {
        // FCC: cubic cell of four sites.
        const double s = std::cbrt(4. * 4. / 3. * pi / phi);
        cell_size      = {{s, s, s}};
        basis          = {Vec3{{0., 0., 0.}},
                          Vec3{{0.5 * s, 0.5 * s, 0.}},
                          Vec3{{0.5 * s, 0., 0.5 * s}},
                          Vec3{{0., 0.5 * s, 0.5 * s}}};
        d_nn           = s / std::sqrt(2.);
      }
    const std::size_t cells_needed = (n + basis.size() - 1) / basis.size();
    const auto        m            = static_cast<std::size_t>(
      std::ceil(std::pow(static_cast<double>(cells_needed), 1. / dim)));
    const double jitter = 0.5 * (d_nn - 2.) * 0.999;
    x.clear();
    for (std::size_t k = 0; k < (dim == 3 ? m : 1) && x.size() < n; ++k)
      for (std::size_t j = 0; j < m && x.size() < n; ++j)
        for (std::size_t i = 0; i < m && x.size() < n; ++i)
          for (const auto &b : basis)
            {
              if (x.size() == n)
                break;
              Vec3 p{{i * cell_size[0] + b[0],
                      j * cell_size[1] + b[1],
                      k * cell_size[2] + b[2]}};
              // Uniform in the ball of radius jitter (rejection).
              Vec3   v;
              double r2;
              do
                {
                  r2 = 0.;
                  for (unsigned d = 0; d < 3; ++d)
                    {
                      v[d] = d < dim ? random.uniform(-1., 1.) : 0.;
                      r2 += v[d] * v[d];
                    }
              } while (r2 > 1.);
              for (unsigned d = 0; d < dim; ++d)
                p[d] += jitter * v[d];
              x.push_back(p);
            }
    return m * cell_size[0];
  }

  double
  now()
  {
    return std::chrono::duration<double>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
  }
} // namespace

int
main(int argc, char **argv)
{
  if (argc < 5)
    {
      std::fprintf(stderr,
                   "usage: %s DIM N PHI pg|apg|pgs|pgs_subspace|all [STEPS] "
                   "[FRICTION]\n",
                   argv[0]);
      return 1;
    }
  const unsigned    dim   = std::atoi(argv[1]);
  const std::size_t n     = std::atol(argv[2]);
  const double      phi   = std::atof(argv[3]);
  const std::string which = argv[4];
  const int         steps = argc > 5 ? std::atoi(argv[5]) : 3;
  // Coulomb friction (non-smooth Gauss-Seidel on translations and
  // rotations, whatever the solver named); the predicted rotations are
  // random, of the size of the predicted velocities over a radius.
  const double mu = argc > 6 ? std::atof(argv[6]) : 0.;

  std::vector<std::pair<std::string, DualSolver>> solvers;
  if (which == "pg" || which == "all")
    solvers.emplace_back("pg", DualSolver::projected_gradient);
  if (which == "apg" || which == "all")
    solvers.emplace_back("apg", DualSolver::accelerated_projected_gradient);
  if (which == "pgs" || which == "all")
    solvers.emplace_back("pgs", DualSolver::projected_gauss_seidel);
  if (which == "pgs_subspace" || which == "all")
    solvers.emplace_back("pgs_subspace",
                         DualSolver::projected_gauss_seidel_subspace);

  Random                         random(12345 + dim);
  std::vector<Vec3>              x0;
  const double                   box = lattice(dim, n, phi, random, x0);
  std::vector<double>            radii(n, 1.);
  const double                   dt = 0.5; // dt max|u*| = a / 2
  std::vector<std::vector<Vec3>> predicted(steps, std::vector<Vec3>(n));
  std::vector<std::vector<Vec3>> rotation(
    steps,
    std::vector<Vec3>(n, Vec3{{0., 0., 0.}}));
  Random spin(777); // own sequence: the frictionless inputs stay as they were
  for (auto &w : rotation)
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned d = (dim == 3 ? 0 : 2); d < 3; ++d)
        w[i][d] = spin.uniform(-1., 1.);
  for (auto &u : predicted)
    for (std::size_t i = 0; i < n; ++i)
      {
        double r2;
        do
          {
            r2 = 0.;
            for (unsigned d = 0; d < 3; ++d)
              {
                u[i][d] = d < dim ? random.uniform(-1., 1.) : 0.;
                r2 += u[i][d] * u[i][d];
              }
        } while (r2 > 1.);
        for (unsigned d = 0; d < dim; ++d)
          u[i][d] = 0.8 * u[i][d] - 0.2 * (x0[i][d] - 0.5 * box) / box;
      }

  // Pair search alone, at the alert distance the projector uses (3 dt max|u*|).
  double      search_time[2];
  std::size_t n_pairs = 0;
  for (int method = 0; method < 2; ++method)
    {
      PairSearch                    search(dim,
                        method == 0 ? PairSearchMethod::cell_list :
                                                         PairSearchMethod::rtree);
      std::vector<PairSearch::Pair> pairs;
      search.find_pairs(x0, radii, 1.5, pairs); // warm up memory
      const double start = now();
      const int    reps  = 3;
      for (int r = 0; r < reps; ++r)
        search.find_pairs(x0, radii, 1.5, pairs);
      search_time[method] = (now() - start) / reps;
      n_pairs             = pairs.size();
    }

  for (const auto &[name, solver] : solvers)
    {
      Settings settings;
      settings.dimension      = dim;
      settings.model          = Model::gluey;
      settings.solver         = solver;
      settings.tolerance      = 1e-9;
      settings.max_iterations = 20000;
      settings.friction       = mu;
      ContactProjector  projector(settings);
      std::vector<Vec3> x     = x0, u, w;
      double            total = 0., solve = 0., search = 0., residual = 0.;
      unsigned long     iterations = 0, rows = 0, active = 0;
      bool              converged = true;
      for (int s = 0; s < steps; ++s)
        {
          const double start = now();
          const auto   st =
            mu > 0. ?
                projector.project(x, radii, predicted[s], rotation[s], dt, u, w) :
                projector.project(x, radii, predicted[s], dt, u);
          total += now() - start;
          solve += st.solve_seconds;
          search += st.search_seconds;
          iterations += st.iterations;
          rows += st.n_constraints;
          active += st.n_active;
          residual  = std::max(residual, st.residual);
          converged = converged && st.converged;
          for (std::size_t i = 0; i < n; ++i)
            for (unsigned d = 0; d < dim; ++d)
              x[i][d] += dt * u[i][d];
        }
      std::printf("%uD %7zu %.1f %-13s rows %8lu active %8lu pairs %8zu "
                  "iterations %7.1f projection %8.4f s (search %7.4f solve "
                  "%8.4f) cell-list %7.4f s R-tree %7.4f s residual %.1e%s\n",
                  dim,
                  n,
                  phi,
                  name.c_str(),
                  rows / steps,
                  active / steps,
                  n_pairs,
                  static_cast<double>(iterations) / steps,
                  total / steps,
                  search / steps,
                  solve / steps,
                  search_time[0],
                  search_time[1],
                  residual,
                  converged ? "" : " NOT CONVERGED");
      std::fflush(stdout);
    }
  return 0;
}
