// Periodic directions of the contact projector (minimum-image convention),
// as in the `sliding walls' box: periodic in x (and z in 3D), walls in y.
//
// a. Translation invariance: a few approaching particles, some straddling
//    the periodic face(s), give the same corrected velocities (1e-12) as the
//    same configuration shifted by half a period (nothing straddles), and as
//    the same configuration given with unwrapped positions (some particles
//    moved by whole periods), and as with the R-tree pair search, over many
//    steps with glue building up and being pulled apart, for inelastic and
//    gluey, in 2D and 3D.
// b. A random dense periodic packing (200 discs, area fraction 0.5) squeezed
//    towards the periodic face and towards mid-height: every projection
//    converges and satisfies the KKT conditions, no minimum-image gap
//    (brute force) is below -tolerance after any step, contacts across the
//    periodic face carry load, and minimum_gap() with periods agrees with
//    the brute force.
// c. Bad periods throw ContactError with a message that names the problem.
// d. The pair search (cell list and R-tree) finds each pair exactly once
//    with its minimum image, as brute force does, also with only one or two
//    cells along a periodic direction and unwrapped positions.
//
// Only OK/FAILED lines are printed; the numbers behind a check only if it
// fails.

#include "kkt_check.h"
#include "test_tools.h"

#include <algorithm>
#include <cmath>
#include <fidus/contact/contact_driver.h>
#include <fidus/contact/pair_search.h>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>

using namespace Fidus::Contact;

namespace
{
  using Periods = std::array<double, 3>;

  double
  minimum_image(const double dx, const double L)
  {
    return L > 0. ? dx - L * std::round(dx / L) : dx;
  }

  /// Minimum-image distance |X_j - X_i|, written here from the definition.
  double
  distance(const unsigned dim, const Periods &L, const Vec3 &xi, const Vec3 &xj)
  {
    double r2 = 0.;
    for (unsigned d = 0; d < dim; ++d)
      {
        const double dx = minimum_image(xj[d] - xi[d], L[d]);
        r2 += dx * dx;
      }
    return std::sqrt(r2);
  }

  /// Wrap into [0, L) in the periodic directions.
  void
  wrap(const unsigned dim, const Periods &L, std::vector<Vec3> &x)
  {
    for (auto &p : x)
      for (unsigned d = 0; d < dim; ++d)
        if (L[d] > 0.)
          {
            p[d] -= L[d] * std::floor(p[d] / L[d]);
            if (p[d] >= L[d])
              p[d] -= L[d];
          }
  }

  /// Smallest minimum-image gap over all pairs and walls (O(N^2)).
  double
  brute_force_min_gap(const unsigned             dim,
                      const Periods             &L,
                      const std::vector<Vec3>   &x,
                      const std::vector<double> &a,
                      const std::vector<Wall>   &walls)
  {
    double g = 1e300;
    for (std::size_t i = 0; i < x.size(); ++i)
      {
        for (std::size_t j = i + 1; j < x.size(); ++j)
          g = std::min(g, distance(dim, L, x[i], x[j]) - a[i] - a[j]);
        for (const auto &w : walls)
          g = std::min(g, w.side * (x[i][w.axis] - w.position) - a[i]);
      }
    return g;
  }

  std::string
  model_name(const Model m)
  {
    return m == Model::gluey ? "gluey" : "inelastic";
  }



  // ------------------------------------------------------------------ a.
  void
  translation_invariance(const unsigned dim, const Model model)
  {
    const double L = 1.;
    // Periodic in x (and z), walls in y at 0 and 1 (sliding in x).
    const Periods           periods{{L, 0., dim == 3 ? L : 0.}};
    const std::vector<Wall> walls   = {Wall{1, 0., 1, Vec3{{0.2, 0., 0.}}},
                                       Wall{1, 1., -1, Vec3{{-0.2, 0., 0.}}}};
    const double            a       = 0.1;
    const double            dt      = 0.01;
    const int               n_steps = 60;

    // A chain straddling x = 0 (and, in 3D, z = 0 and the corner), whose
    // ends are pushed together across the face, a particle pushed against
    // the chain obliquely and one pushed against the lower wall; the
    // velocities reverse at half time so that the glue is pulled on.
    const double        z  = dim == 3 ? 0.02 : 0.;
    std::vector<Vec3>   x0 = {Vec3{{0.04, 0.5, z}},
                              Vec3{{0.83, 0.5, z}},
                              Vec3{{0.245, 0.52, z}},
                              Vec3{{0.04, 0.73, dim == 3 ? 0.97 : 0.}},
                              Vec3{{0.9, 0.31, dim == 3 ? 0.8 : 0.}},
                              Vec3{{0.12, 0.13, dim == 3 ? 0.15 : 0.}}};
    std::vector<Vec3>   v  = {Vec3{{-0.3, 0.1, dim == 3 ? -0.2 : 0.}},
                              Vec3{{0.9, 0., dim == 3 ? 0.3 : 0.}},
                              Vec3{{-1.0, -0.1, 0.}},
                              Vec3{{0., -0.8, dim == 3 ? 0.4 : 0.}},
                              Vec3{{0.5, 0.5, dim == 3 ? 0.6 : 0.}},
                              Vec3{{0.1, -0.5, 0.}}};
    const std::size_t   n  = x0.size();
    std::vector<double> radii(n, a);
    radii[2] = 0.08;
    radii[5] = 0.11;

    // Four copies: as given (wrapped), shifted by half a period in every
    // periodic direction (wrapped), as given but with particles moved by
    // whole periods and never wrapped, and as given with the R-tree pair
    // search instead of the cell list.
    std::vector<Vec3> x_shifted = x0, x_unwrapped = x0;
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned d = 0; d < dim; ++d)
        if (periods[d] > 0.)
          {
            x_shifted[i][d] += 0.5 * L;
            x_unwrapped[i][d] += (static_cast<int>(i % 3) - 1) * L;
          }
    wrap(dim, periods, x_shifted);
    // Particles straddle the periodic faces in the first copy, none in the
    // shifted one.
    auto straddles = [&](const std::vector<Vec3> &y) {
      bool any = false;
      for (std::size_t i = 0; i < n; ++i)
        for (unsigned d = 0; d < dim; ++d)
          if (periods[d] > 0. && (y[i][d] < radii[i] || y[i][d] > L - radii[i]))
            any = true;
      return any;
    };
    const bool set_up_ok = straddles(x0) && !straddles(x_shifted);

    Settings settings;
    settings.dimension = dim;
    settings.model     = model;
    settings.tolerance = 1e-14;
    std::vector<ContactProjector> projectors(3, ContactProjector(settings));
    settings.pair_search = PairSearchMethod::rtree;
    projectors.emplace_back(settings);
    for (auto &p : projectors)
      {
        p.set_walls(walls);
        p.set_periodicity(periods);
      }
    std::vector<std::vector<Vec3>> x        = {x0, x_shifted, x_unwrapped, x0};
    const unsigned                 n_copies = x.size();

    double       max_difference = 0., min_gap = 1e300;
    bool         converged = true, same_glue = true;
    unsigned int max_glued = 0, max_across = 0;
    double       kkt = 0.;
    for (int step = 0; step < n_steps; ++step)
      {
        std::vector<Vec3> u_star(n);
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned d = 0; d < dim; ++d)
            u_star[i][d] = (step < n_steps / 2 ? 1. : -1.) * v[i][d];
        std::vector<std::vector<Vec3>> u(n_copies);
        std::vector<unsigned int>      glued(n_copies);
        for (unsigned c = 0; c < n_copies; ++c)
          {
            const auto statistics =
              projectors[c].project(x[c], radii, u_star, dt, u[c]);
            converged = converged && statistics.converged;
            glued[c]  = statistics.n_glued;
            kkt       = std::max(
              kkt,
              KKT::check(projectors[c], walls, {}, u_star, u[c], dt).worst());
          }
        max_glued = std::max(max_glued, glued[0]);
        // Pair rows of the first copy (wrapped) that push or are glued
        // across a periodic face.
        const auto  &rows   = projectors[0].constraints();
        unsigned int across = 0;
        for (std::size_t k = 0; k < rows.size(); ++k)
          if (rows.first(k) < n && (rows.lambda(k) != 0. || rows.glued(k)))
            for (unsigned d = 0; d < dim; ++d)
              if (periods[d] > 0. &&
                  std::abs(x[0][rows.second(k)][d] - x[0][rows.first(k)][d]) >
                    0.5 * periods[d])
                {
                  ++across;
                  break;
                }
        max_across = std::max(max_across, across);
        for (unsigned c = 1; c < n_copies; ++c)
          same_glue = same_glue && glued[c] == glued[0];
        for (unsigned c = 1; c < n_copies; ++c)
          for (std::size_t i = 0; i < n; ++i)
            for (unsigned d = 0; d < 3; ++d)
              max_difference =
                std::max(max_difference, std::abs(u[c][i][d] - u[0][i][d]));
        for (unsigned c = 0; c < n_copies; ++c)
          for (std::size_t i = 0; i < n; ++i)
            for (unsigned d = 0; d < dim; ++d)
              x[c][i][d] += dt * u[c][i][d];
        wrap(dim, periods, x[0]);
        wrap(dim, periods, x[1]);
        wrap(dim, periods, x[3]);
        for (unsigned c = 0; c < n_copies; ++c)
          min_gap =
            std::min(min_gap,
                     brute_force_min_gap(dim, periods, x[c], radii, walls));
      }

    const std::string head =
      std::to_string(dim) + "D translation invariance, " + model_name(model);
    const int failures_before = TestTools::failures();
    TestTools::check(head + ": test set-up (particles straddle the periodic "
                            "face(s), none in the shifted copy)",
                     set_up_ok);
    TestTools::check(head + ": all projections converged", converged);
    TestTools::check(head + ": same corrected velocities shifted by L/2, "
                            "unwrapped and with the R-tree (1e-12)",
                     max_difference <= 1e-12);
    TestTools::check(head + ": contacts across the periodic face(s) push" +
                       (model == Model::gluey ? " or hold" : ""),
                     max_across >= 2);
    if (model == Model::gluey)
      TestTools::check(head + ": same number of glued pairs in every copy, "
                              "glue formed",
                       same_glue && max_glued >= 3);
    TestTools::check(head + ": no minimum-image gap below -1e-14",
                     min_gap >= -1e-14);
    TestTools::check(head + ": KKT within 1e-14", kkt <= 1.001e-14);
    // Numbers that would make the output unstable are printed only to
    // explain a failure.
    if (TestTools::failures() > failures_before)
      std::cout << head << ": max |u difference| " << max_difference
                << ", max glued " << max_glued << ", max across " << max_across
                << ", min gap " << min_gap << ", KKT " << kkt << std::endl;
  }



  // ------------------------------------------------------------------ b.
  /**
   * Random sequential addition of n discs in [0, L) x [0, H], periodic in x,
   * with area fraction @p phi: the radii are drawn first (uniform in
   * [0.8, 1.2] r, then scaled to the area fraction) and placed largest
   * first, each at random positions until it fits. Drawing a new radius per
   * attempt instead would favour small discs and miss the area fraction.
   */
  void
  periodic_packing(TestTools::Random   &random,
                   const std::size_t    n,
                   const double         L,
                   const double         H,
                   const double         phi,
                   std::vector<Vec3>   &x,
                   std::vector<double> &a)
  {
    const Periods periods{{L, 0., 0.}};
    a.resize(n);
    double area = 0.;
    for (auto &r : a)
      {
        r = random.uniform(0.8, 1.2);
        area += M_PI * r * r;
      }
    const double scale = std::sqrt(phi * L * H / area);
    for (auto &r : a)
      r *= scale;
    std::sort(a.begin(), a.end(), std::greater<double>());
    x.clear();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t attempt = 0;; ++attempt)
        {
          if (attempt > 1000000)
            throw std::runtime_error("periodic_packing: too dense");
          const Vec3 p{
            {random.uniform(0., L), random.uniform(a[i], H - a[i]), 0.}};
          bool free = true;
          for (std::size_t j = 0; j < i && free; ++j)
            free = distance(2, periods, p, x[j]) >= a[i] + a[j];
          if (free)
            {
              x.push_back(p);
              break;
            }
        }
  }

  void
  squeezed_periodic_packing(const Model model)
  {
    const double        tolerance = 1e-11;
    const double        L = 1., H = 1., dt = 0.005;
    const std::size_t   n       = 200;
    const int           n_steps = 100;
    const Periods       periods{{L, 0., 0.}};
    TestTools::Random   random(11);
    std::vector<Vec3>   x0;
    std::vector<double> a;
    periodic_packing(random, n, L, H, 0.5, x0, a);
    double area = 0.;
    for (const double ai : a)
      area += M_PI * ai * ai;

    const std::vector<Wall> walls = {Wall{1, 0., 1, Vec3{{0., 0., 0.}}},
                                     Wall{1, H, -1, Vec3{{0., 0., 0.}}}};
    Settings                settings;
    settings.dimension = 2;
    settings.model     = model;
    settings.tolerance = tolerance;
    // Converging towards the periodic face x = 0 = L and towards mid-height,
    // with a shear across; periodic in x, so the driver need not wrap.
    ContactDriver driver(settings, x0, a, [=](const Vec3 &p, double) {
      return Vec3{
        {-0.5 * std::sin(2. * M_PI * p[0] / L) + 0.3 * (p[1] - 0.5 * H),
         -(p[1] - 0.5 * H),
         0.}};
    });
    driver.set_walls(walls);
    driver.set_periodicity(periods);

    bool         converged = true;
    double       kkt = 0., min_gap = 1e300, gap_difference = 0.;
    unsigned int active = 0, active_across = 0, max_active_across = 0;
    for (int step = 0; step < n_steps; ++step)
      {
        const auto statistics = driver.step(dt);
        converged             = converged && statistics.converged;
        kkt                   = std::max(kkt,
                       KKT::check(driver.projector(),
                                  walls,
                                  {},
                                  driver.predicted_velocities(),
                                  driver.velocities(),
                                  dt)
                         .worst());
        // Independent check after the step: every minimum-image gap.
        const double g =
          brute_force_min_gap(2, periods, driver.positions(), a, walls);
        min_gap = std::min(min_gap, g);
        gap_difference =
          std::max(gap_difference, std::abs(driver.minimum_gap(0.1) - g));

        // Active pair rows across the periodic face: the raw difference of
        // the wrapped centres is more than half a period.
        std::vector<Vec3> xw = driver.positions();
        wrap(2, periods, xw);
        const auto &rows = driver.projector().constraints();
        active           = statistics.n_active;
        active_across    = 0;
        for (std::size_t k = 0; k < rows.size(); ++k)
          if (rows.first(k) < n && rows.lambda(k) != 0. &&
              std::abs(xw[rows.second(k)][0] - xw[rows.first(k)][0]) > 0.5 * L)
            ++active_across;
        max_active_across = std::max(max_active_across, active_across);
      }

    const std::string head =
      "2D periodic packing, 200 discs, " + model_name(model);
    const int failures_before = TestTools::failures();
    TestTools::check(head + ": area fraction 0.5",
                     std::abs(area / (L * H) - 0.5) < 1e-12);
    TestTools::check(head + ": all projections converged", converged);
    TestTools::check(head + ": KKT of every projection within 1e-11",
                     kkt <= 1.001 * tolerance);
    TestTools::check(head + ": no minimum-image gap below -1e-11 after any "
                            "step",
                     min_gap >= -tolerance);
    TestTools::check(head + ": jammed at the end (active contacts > "
                            "particles)",
                     active > n);
    TestTools::check(head + ": active contacts across the periodic face",
                     max_active_across >= 5);
    TestTools::check(head + ": minimum_gap() with periods = brute force",
                     gap_difference <= 1e-13);
    if (TestTools::failures() > failures_before)
      std::cout << head << ": area fraction " << area / (L * H) << ", min gap "
                << min_gap << ", KKT " << kkt << ", active at the end "
                << active << " (across the face " << active_across << ", max "
                << max_active_across << "), |minimum_gap - brute force| "
                << gap_difference << std::endl;
  }



  // ------------------------------------------------------------------ c.
  void
  bad_periods()
  {
    Settings settings;
    settings.dimension = 2;
    settings.model     = Model::gluey;
    // Touching discs, 0.01 apart through the other image if L = 0.41.
    const std::vector<Vec3>   x = {Vec3{{0.1, 0.5, 0.}}, Vec3{{0.3, 0.5, 0.}}};
    const std::vector<double> a(2, 0.1);
    const std::vector<Vec3>   u(2, Vec3{{0.1, 0., 0.}});
    std::vector<Vec3>         out;

    // 2 (2 a_max + d_a) = 2 (0.2 + 0.003) = 0.406 with d_a = 3 dt |u|.
    TestTools::expect_error(
      "period 0.4 < 2 (2 a_max + d_a) rejected by project()",
      [&] {
        ContactProjector p(settings);
        p.set_periodicity({{0.4, 0., 0.}});
        p.project(x, a, u, 0.01, out);
      },
      {"period 0.4 of the periodic direction x (direction 0) is too small",
       "larger than 2 (2 a_max + d_a) = 0.406",
       "a_max = 0.1",
       "ambiguous"});
    TestTools::expect_error("period too small for the alert distance rejected",
                            [&] {
                              Settings s       = settings;
                              s.alert_distance = 0.1;
                              ContactProjector p(s);
                              p.set_periodicity({{0.5, 0., 0.}});
                              p.project(x, a, u, 0.01, out);
                            },
                            {"period 0.5",
                             "larger than 2 (2 a_max + d_a) = 0.6",
                             "d_a = 0.1"});
    // The same configuration with a large enough period works.
    bool ok = true;
    try
      {
        ContactProjector p(settings);
        p.set_periodicity({{0.41, 0., 0.}});
        ok = p.project(x, a, u, 0.01, out).converged;
      }
    catch (...)
      {
        ok = false;
      }
    TestTools::check("period 0.41 > 0.406 accepted", ok);
    // Discs at x = 0.05 and 0.95 in a period of 1 are 0.1 apart through the
    // face: overlap 0.1, and the message says the gap was measured across it.
    TestTools::expect_error(
      "overlap across the periodic face names the nearest-image separation",
      [&] {
        ContactProjector p(settings);
        p.set_periodicity({{1., 0., 0.}});
        p.project({Vec3{{0.05, 0.5, 0.}}, Vec3{{0.95, 0.5, 0.}}},
                  a,
                  u,
                  0.01,
                  out);
      },
      {"particles 0 and 1",
       "overlap by 0.1",
       "across a periodic face (nearest-image separation (-0.1"});
    TestTools::expect_error(
      "minimum_gap(): period below 4 a_max rejected",
      [&] {
        ContactProjector::minimum_gap(x, a, {}, 2, 1., {{0.4, 0., 0.}});
      },
      {"minimum_gap", "period 0.4", "too small", "= 0.4"});
    TestTools::expect_error("periodic direction with a wall (walls first)",
                            [&] {
                              ContactProjector p(settings);
                              p.set_walls({Wall{0, 0., 1, Vec3{}}});
                              p.set_periodicity({{1., 0., 0.}});
                            },
                            {"direction x (direction 0) cannot be periodic",
                             "wall 0"});
    TestTools::expect_error(
      "periodic direction with a wall (periods first)",
      [&] {
        ContactProjector p(settings);
        p.set_periodicity({{1., 0., 0.}});
        p.set_walls({Wall{1, 0., 1, Vec3{}}, Wall{0, 1., -1, Vec3{}}});
      },
      {"wall 1", "axis 0 is a periodic direction"});
    TestTools::expect_error("negative period",
                            [&] {
                              ContactProjector p(settings);
                              p.set_periodicity({{-1., 0., 0.}});
                            },
                            {"period of direction x (direction 0) is -1",
                             "must be > 0"});
    TestTools::expect_error("NaN period",
                            [&] {
                              ContactProjector p(settings);
                              p.set_periodicity({{0., std::nan(""), 0.}});
                            },
                            {"period of direction y (direction 1)"});
    TestTools::expect_error("period in z in 2D",
                            [&] {
                              ContactProjector p(settings);
                              p.set_periodicity({{1., 0., 1.}});
                            },
                            {"direction z (direction 2)",
                             "does not exist in 2D"});
  }



  // ------------------------------------------------------------------ d.
  void
  pair_search(const unsigned dim)
  {
    // Periodic in x (and z). Cells are >= 2 a_max + cut-off ~ 0.04 (cut-off
    // 0) or 0.06 (cut-off 0.02) large, so along a periodic direction there
    // are many cells for L = 1, 3 or 2 for L = 0.13, 2 or 1 for L = 0.1 and
    // one for L = 0.05: the neighbour cells -1 and +1 are then the same
    // cell, or the cell itself, and a pair must still be found once.
    for (const double L : {1., 0.13, 0.1, 0.05})
      {
        TestTools::Random   random(dim + static_cast<unsigned>(100 * L));
        const Periods       periods{{L, 0., dim == 3 ? L : 0.}};
        const std::size_t   n = L == 1. ? 1500 : 300;
        std::vector<Vec3>   x(n, Vec3{{0., 0., 0.}});
        std::vector<double> a(n);
        for (std::size_t i = 0; i < n; ++i)
          {
            for (unsigned d = 0; d < dim; ++d)
              x[i][d] = random.uniform(0., periods[d] > 0. ? L : 1.);
            // Some positions are not wrapped into the box.
            if (i % 7 == 0)
              x[i][0] += (i % 2 == 0 ? 3. : -2.) * L;
            a[i] = random.uniform(0.005, 0.02);
          }
        for (const double cutoff : {0., 0.02})
          {
            std::vector<PairSearch::Pair> expected;
            for (std::uint32_t i = 0; i < n; ++i)
              for (std::uint32_t j = i + 1; j < n; ++j)
                if (distance(dim, periods, x[i], x[j]) - a[i] - a[j] < cutoff)
                  expected.emplace_back(i, j);
            for (const auto method :
                 {PairSearchMethod::cell_list, PairSearchMethod::rtree})
              {
                PairSearch search(dim, method);
                search.set_periodicity(periods);
                std::vector<PairSearch::Pair> found;
                search.find_pairs(x, a, cutoff, found);
                std::sort(found.begin(), found.end());
                const bool once =
                  std::adjacent_find(found.begin(), found.end()) == found.end();
                TestTools::check(
                  std::to_string(dim) + "D periodic pair search, " + "period " +
                    (L == 1. ? "1" : std::to_string(L).substr(0, 4)) +
                    ", cut-off " + (cutoff == 0. ? "0" : "0.02") + ", " +
                    (method == PairSearchMethod::rtree ? "R-tree" :
                                                         "cell list") +
                    ": each minimum-image pair exactly once",
                  once && found == expected && !expected.empty());
                if (found != expected)
                  std::cout << dim << "D pair search, period " << L
                            << ", cut-off " << cutoff << ": " << expected.size()
                            << " pairs expected, " << found.size() << " found"
                            << std::endl;
              }
          }
      }
  }
} // namespace



int
main()
{
  for (const unsigned dim : {2u, 3u})
    for (const Model model : {Model::inelastic, Model::gluey})
      translation_invariance(dim, model);
  for (const Model model : {Model::inelastic, Model::gluey})
    squeezed_periodic_packing(model);
  bad_periods();
  for (const unsigned dim : {2u, 3u})
    pair_search(dim);
  return TestTools::failures() == 0 ? 0 : 1;
}
