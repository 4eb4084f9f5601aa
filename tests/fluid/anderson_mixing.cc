// Anderson acceleration (AndersonMixing) on a linear fixed-point iteration
// with known answers, the Uzawa loop's situation in miniature:
// x <- G(x) = x + rho (b - S x) with S symmetric positive semi-definite of
// size n = 6 whose eigenvalues spread over [0.05, 1] (plain iteration with
// rho = 1 contracts the slowest mode by 0.95 per step) and one null
// direction z, which b does not load and the inner product ignores (as
// the rigid motions that the Uzawa multiplier accumulates without
// loading anything). Checked:
//
// - depth 0 is the plain iteration: weights 1 on the newest, the same
//   iterates to the last bit;
// - weights sum to 1, and combined_norm() of the weights is the norm of
//   the combined residual computed from the vectors;
// - with depth n - 1 (the whole history of the n - 1 modes that the
//   inner product sees), the residual falls below 1e-6 of the first in
//   at most n iterations, as GMRES would; the plain iteration needs 410
//   (counted from the modes' contraction) to 1e-10;
// - with depth 2, fewer iterations than plain to 1e-8;
// - two parallel residuals (a singular Gram matrix) give finite weights.

#include "../fidus_test.h"

#include <cmath>
#include <deal.II/base/mpi.h>
#include <deque>
#include <fidus/fluid/fictitious_domain/anderson_mixing.h>
#include <iostream>
#include <string>
#include <vector>

using namespace FidusTest;
using Fidus::AndersonMixing;

namespace
{
  void
  check(const std::string &what, const bool ok)
  {
    if (!ok)
      ++failures();
    if (root())
      std::cout << what << ": " << (ok ? "OK" : "FAILED") << std::endl;
  }

  constexpr unsigned int n = 6;
  using Vec                = std::vector<double>;

  /// An orthonormal basis (a fixed rotation of the unit vectors): the
  /// last is the null direction z.
  std::vector<Vec>
  basis()
  {
    std::vector<Vec> q(n, Vec(n, 0.));
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        q[i][j] = std::cos(0.7 * (i + 1) * (j + 0.5) + 0.3 * i);
    // Gram-Schmidt.
    for (unsigned int i = 0; i < n; ++i)
      {
        for (unsigned int k = 0; k < i; ++k)
          {
            double d = 0.;
            for (unsigned int j = 0; j < n; ++j)
              d += q[i][j] * q[k][j];
            for (unsigned int j = 0; j < n; ++j)
              q[i][j] -= d * q[k][j];
          }
        double s = 0.;
        for (const double v : q[i])
          s += v * v;
        for (double &v : q[i])
          v /= std::sqrt(s);
      }
    return q;
  }

  struct Problem
  {
    std::vector<Vec> q = basis();
    Vec eigenvalues{0.05, 0.12, 0.3, 0.55, 1., 0.}; // the last: null
    Vec b;

    Problem()
      : b(n, 0.)
    {
      for (unsigned int i = 0; i + 1 < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          b[j] += (1. + i) * q[i][j];
    }

    /// f(x) = G(x) - x = b - S x.
    Vec
    residual(const Vec &x) const
    {
      Vec f = b;
      for (unsigned int i = 0; i < n; ++i)
        {
          double c = 0.;
          for (unsigned int j = 0; j < n; ++j)
            c += q[i][j] * x[j];
          for (unsigned int j = 0; j < n; ++j)
            f[j] -= eigenvalues[i] * c * q[i][j];
        }
      return f;
    }

    /// The inner product that does not see z.
    double
    product(const Vec &u, const Vec &v) const
    {
      double s = 0.;
      for (unsigned int i = 0; i + 1 < n; ++i)
        {
          double cu = 0., cv = 0.;
          for (unsigned int j = 0; j < n; ++j)
            {
              cu += q[i][j] * u[j];
              cv += q[i][j] * v[j];
            }
          s += cu * cv;
        }
      return s;
    }
  };

  struct Run
  {
    unsigned int     iterations           = 0;
    double           final_ratio          = 0.;
    double           largest_weight_error = 0.;
    double           largest_norm_error   = 0.;
    std::vector<Vec> iterates;
  };

  /// Iterate with Anderson of @p depth until |f| < tol |f_0| or 2000
  /// iterations.
  Run
  iterate(const Problem &p, const unsigned int depth, const double tol)
  {
    Run             run;
    AndersonMixing  mixing(depth);
    std::deque<Vec> xs, fs;
    Vec             x(n, 0.);
    // Start with a component along z: it must not matter.
    for (unsigned int j = 0; j < n; ++j)
      x[j] = 3. * p.q[n - 1][j];
    const double f0 = std::sqrt(p.product(p.residual(x), p.residual(x)));
    for (unsigned int k = 0; k < 2000; ++k)
      {
        const Vec f = p.residual(x);
        run.iterates.push_back(x);
        run.iterations  = k;
        run.final_ratio = std::sqrt(p.product(f, f)) / f0;
        if (run.final_ratio < tol)
          break;
        if (mixing.size() == depth + 1)
          {
            mixing.drop_oldest();
            xs.pop_front();
            fs.pop_front();
          }
        Vec products;
        for (const Vec &g : fs)
          products.push_back(p.product(f, g));
        products.push_back(p.product(f, f));
        mixing.push(products);
        xs.push_back(x);
        fs.push_back(f);
        const Vec alpha = mixing.weights();
        double    sum   = 0.;
        for (const double a : alpha)
          sum += a;
        run.largest_weight_error =
          std::max(run.largest_weight_error, std::abs(sum - 1.));
        Vec combined(n, 0.), next(n, 0.);
        for (unsigned int i = 0; i < alpha.size(); ++i)
          for (unsigned int j = 0; j < n; ++j)
            {
              combined[j] += alpha[i] * fs[i][j];
              next[j] += alpha[i] * (xs[i][j] + fs[i][j]);
            }
        const double direct = std::sqrt(p.product(combined, combined));
        run.largest_norm_error =
          std::max(run.largest_norm_error,
                   std::abs(direct - mixing.combined_norm(alpha)) / f0);
        x = next;
      }
    return run;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const Problem                            p;

  std::cout << "a. depth 0 is the plain iteration" << std::endl;
  {
    const Run run = iterate(p, 0, 1e-10);
    Vec       x(n, 0.);
    for (unsigned int j = 0; j < n; ++j)
      x[j] = 3. * p.q[n - 1][j];
    bool same = true;
    for (const Vec &y : run.iterates)
      {
        for (unsigned int j = 0; j < n; ++j)
          same = same && y[j] == x[j];
        const Vec f = p.residual(x);
        for (unsigned int j = 0; j < n; ++j)
          x[j] += f[j];
      }
    check("iterates identical to x + (b - S x)", same);
    // Mode i of the residual is (1 + i) (1 - s_i)^k: the first k at which
    // their norm falls below 1e-10 of the first, counted directly.
    unsigned int expected = 0;
    for (;; ++expected)
      {
        double s2 = 0., f2 = 0.;
        for (unsigned int i = 0; i + 1 < n; ++i)
          {
            s2 +=
              std::pow((1. + i) * std::pow(1. - p.eigenvalues[i], expected), 2);
            f2 += (1. + i) * (1. + i);
          }
        if (std::sqrt(s2 / f2) < 1e-10)
          break;
      }
    check("iterations to 1e-10 as the modes' own contraction gives",
          run.iterations == expected);
  }

  std::cout << "b. weights and the combined norm" << std::endl;
  {
    const Run run = iterate(p, 3, 1e-10);
    check_range("largest |sum alpha - 1|", run.largest_weight_error, 0., 1e-12);
    check_range("largest |combined_norm - direct| / |f_0|",
                run.largest_norm_error,
                0.,
                1e-10);
  }

  std::cout << "c. the whole history: GMRES's count" << std::endl;
  {
    // In exact arithmetic the residual vanishes at iteration 6 (GMRES ends
    // after 5 steps on the 5 modes the inner product sees; Anderson's
    // iterate is G of GMRES's). The weights come from the normal equations
    // of the Gram matrix, whose round-off limits the accuracy of the last
    // combination to about 1e-8 of the first residual, hence 1e-6 here.
    const Run run = iterate(p, n - 1, 1e-6);
    check_range("iterations to 1e-6 with depth 5 (5 seen modes + 1)",
                run.iterations,
                1,
                n);
  }

  std::cout << "d. a short history still helps" << std::endl;
  {
    const Run plain         = iterate(p, 0, 1e-8);
    const Run short_history = iterate(p, 2, 1e-8);
    check("depth 2 needs fewer iterations than plain to 1e-8",
          short_history.iterations < plain.iterations);
  }

  std::cout << "e. parallel residuals" << std::endl;
  {
    AndersonMixing mixing(2);
    mixing.push({4.});
    mixing.push({8., 16.}); // f_1 = 2 f_0
    const Vec alpha = mixing.weights();
    check("finite weights", std::isfinite(alpha[0]) && std::isfinite(alpha[1]));
    check_range("their sum", alpha[0] + alpha[1], 1. - 1e-12, 1. + 1e-12);
  }
  return exit_code();
}
