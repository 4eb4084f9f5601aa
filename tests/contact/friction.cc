// Coulomb friction in the projection (doc/theory/contact.md, "Friction"),
// checked against exact answers and against the definitions of the law,
// written here independently of the solver:
//
// 1. A sphere pressed onto a wall by a force F in a shear flow (the
//    free-draining case of issue 49, with the resistance metric 6 pi eta a,
//    8 pi eta a^3): it rolls without slip (v = 5/7 rate a, omega = -5/7
//    rate) when mu F >= 12/7 pi eta rate a^2, and otherwise slides with
//    v = rate a - mu F / (6 pi eta a), omega = -rate/2 - mu F /
//    (8 pi eta a^2). Both sides of the threshold, and mu = 0.
// 2. Two spheres pressed together across a shear flow: with a large mu the
//    contact does not slip; with mu = 0 the result is the frictionless
//    projection, bit for bit, and the rotations are untouched.
// 3. Random dense packings, 2D and 3D, squeezed and sheared with random
//    spins, for several steps with mu = 0.5, until about one active contact
//    per particle: every contact satisfies lambda_n >= 0 (unglued),
//    |lambda_t| <= mu lambda_n, normal complementarity, no slip where the
//    impulse is inside the cone, a sliding impulse opposite to the slip and
//    on the rim, non-negative dissipation, and the force and torque balance
//    of every particle, each to the solver's tolerance.

#include "test_tools.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fidus/contact/contact_projector.h>

using namespace Fidus::Contact;

namespace
{
  /// Measured numbers go to a file beside the output, which compares only
  /// the checks (iteration counts may differ with the compiler).
  std::FILE *
  log()
  {
    static std::FILE *file = std::fopen("statistics.txt", "w");
    return file;
  }

  Vec3
  cross(const Vec3 &x, const Vec3 &y)
  {
    return Vec3{{x[1] * y[2] - x[2] * y[1],
                 x[2] * y[0] - x[0] * y[2],
                 x[0] * y[1] - x[1] * y[0]}};
  }

  double
  dot(const Vec3 &x, const Vec3 &y)
  {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  }

  double
  norm(const Vec3 &x)
  {
    return std::sqrt(dot(x, x));
  }

  /// Sphere on the wall y = 0, sheared at @p rate, pushed down by @p force.
  void
  sphere_on_wall(const double mu, const double force, Vec3 &u, Vec3 &w)
  {
    const double eta = 1., a = 0.5, rate = 2.;
    Settings     settings;
    settings.dimension = 3;
    settings.model     = Model::inelastic;
    settings.friction  = mu;
    settings.tolerance = 1e-13;
    ContactProjector projector(settings);
    Wall             wall;
    wall.axis     = 1;
    wall.position = 0.;
    wall.side     = 1;
    projector.set_walls({wall});
    projector.set_weights({6. * M_PI * eta * a});
    projector.set_rotational_weights({8. * M_PI * eta * a * a * a});
    // Free-draining prediction: the flow's velocity at the centre plus
    // F / (6 pi eta a), the flow's half vorticity.
    const std::vector<Vec3> x{{{0., a, 0.}}};
    const std::vector<Vec3> u_star{
      {{rate * a, -force / (6. * M_PI * eta * a), 0.}}};
    const std::vector<Vec3> w_star{{{0., 0., -0.5 * rate}}};
    std::vector<Vec3>       uc, wc;
    const auto st = projector.project(x, {a}, u_star, w_star, 0.01, uc, wc);
    TestTools::check("sphere on a wall, mu = " + std::to_string(mu) +
                       ": converged",
                     st.converged);
    u = uc[0];
    w = wc[0];
  }

  void
  check_sphere_on_wall()
  {
    const double eta = 1., a = 0.5, rate = 2., force = 1.;
    const double threshold = 12. * M_PI * eta * rate * a * a / 7.; // mu F
    Vec3         u, w;
    for (const double factor : {1.2, 0.8, 0.})
      {
        const double mu = factor * threshold / force;
        sphere_on_wall(mu, force, u, w);
        double v, omega;
        if (factor >= 1.)
          {
            v     = 5. / 7. * rate * a;
            omega = -5. / 7. * rate;
          }
        else
          {
            v     = rate * a - mu * force / (6. * M_PI * eta * a);
            omega = -0.5 * rate - mu * force / (8. * M_PI * eta * a * a);
          }
        char line[200];
        std::snprintf(line,
                      sizeof(line),
                      "sphere on a wall, mu F = %.1f x threshold: v = %.6f "
                      "(exact %.6f), omega = %.6f (exact %.6f), normal "
                      "velocity %.1e",
                      factor,
                      u[0],
                      v,
                      w[2],
                      omega,
                      u[1]);
        std::fprintf(log(), "%s\n", line);
        char what[100];
        std::snprintf(what,
                      sizeof(what),
                      "sphere on a wall, mu F = %.1f x threshold: exact v "
                      "and omega, no normal velocity",
                      factor);
        TestTools::check(what,
                         std::abs(u[0] - v) < 1e-10 &&
                           std::abs(w[2] - omega) < 1e-10 &&
                           std::abs(u[1]) < 1e-10 && std::abs(u[2]) < 1e-14 &&
                           std::abs(w[0]) + std::abs(w[1]) < 1e-14);
      }
  }

  void
  check_pair()
  {
    // Two touching spheres on a line inclined in a shear flow, pressed
    // together by opposite forces: their contact points slide past each
    // other without friction.
    const double            a = 0.5, rate = 1., dt = 0.01;
    const Vec3              e{{std::cos(-M_PI / 9.), std::sin(-M_PI / 9.), 0.}};
    const std::vector<Vec3> x{{{-a * e[0], -a * e[1], 0.}},
                              {{a * e[0], a * e[1], 0.}}};
    std::vector<Vec3>       u_star(2), w_star(2, Vec3{{0., 0., -0.5 * rate}});
    for (unsigned i = 0; i < 2; ++i)
      {
        const double push = i == 0 ? 0.3 : -0.3;
        for (unsigned d = 0; d < 3; ++d)
          u_star[i][d] = push * e[d];
        u_star[i][0] += rate * x[i][1];
      }
    Settings settings;
    settings.dimension = 3;
    settings.model     = Model::inelastic;
    settings.tolerance = 1e-13;

    std::vector<Vec3> u0, uf, wf;
    {
      ContactProjector frictionless(settings);
      frictionless.project(x, {a, a}, u_star, dt, u0);
      ContactProjector with_rotations(settings);
      with_rotations.project(x, {a, a}, u_star, w_star, dt, uf, wf);
      TestTools::check("pair, mu = 0: velocities bit-identical to the "
                       "frictionless projection, rotations untouched",
                       u0 == uf && wf == w_star);
    }
    settings.friction = 100.;
    ContactProjector rough(settings);
    const auto       st = rough.project(x, {a, a}, u_star, w_star, dt, uf, wf);
    Vec3             slip, before;
    for (unsigned d = 0; d < 3; ++d)
      {
        const Vec3 wa = cross(wf[0], e), wb = cross(wf[1], e);
        slip[d]       = uf[1][d] - a * wb[d] - uf[0][d] - a * wa[d];
        const Vec3 sa = cross(w_star[0], e), sb = cross(w_star[1], e);
        before[d] = u_star[1][d] - a * sb[d] - u_star[0][d] - a * sa[d];
      }
    const double slip_n = dot(slip, e);
    for (unsigned d = 0; d < 3; ++d)
      slip[d] -= slip_n * e[d];
    const double before_n = dot(before, e);
    for (unsigned d = 0; d < 3; ++d)
      before[d] -= before_n * e[d];
    std::fprintf(log(),
                 "pair, mu = 100: tangential slip %.1e (%.3f without "
                 "friction), normal %.1e, %u sliding\n",
                 norm(slip),
                 norm(before),
                 slip_n,
                 st.n_sliding);
    TestTools::check("pair, mu = 100: no slip at the contact, no normal "
                     "velocity",
                     st.converged && norm(slip) < 1e-10 &&
                       std::abs(slip_n) < 1e-10 && st.n_sliding == 0);
  }

  /// Largest violations of the Coulomb conditions in one projection.
  struct ConeErrors
  {
    double sign = 0., cone = 0., complementarity = 0., stick = 0., sliding = 0.,
           dissipation = 0., balance = 0.;
    unsigned int n_stick = 0, n_slide = 0;
  };

  ConeErrors
  check_cone(const ContactProjector    &projector,
             const std::vector<double> &a,
             const std::vector<Vec3>   &u_star,
             const std::vector<Vec3>   &w_star,
             const std::vector<Vec3>   &u,
             const std::vector<Vec3>   &w,
             const double               mu,
             const double               dt)
  {
    // All weights are the defaults: w = 1, j = 4/3 a^2 (3D) or a^2 (2D).
    const unsigned    dim   = projector.get_settings().dimension;
    const double      ratio = dim == 3 ? 4. / 3. : 1.;
    const auto       &rows  = projector.constraints();
    const std::size_t n     = u.size();
    std::vector<Vec3> force(n, Vec3{{0., 0., 0.}}),
      torque(n, Vec3{{0., 0., 0.}});
    ConeErrors errors;
    for (std::size_t k = 0; k < rows.size(); ++k)
      {
        const std::uint32_t ia = rows.first(k), ib = rows.second(k);
        const Vec3         &e  = rows.normal(k);
        const double        ln = rows.lambda(k);
        const Vec3         &lt = rows.tangential_impulse(k);
        const double        la = ia < n ? a[ia] : 0., lb = a[ib];
        // Contact-point velocities (walls stand still here).
        Vec3 va{{0., 0., 0.}}, vb;
        if (ia < n)
          {
            const Vec3 r = cross(w[ia], e);
            for (unsigned d = 0; d < 3; ++d)
              va[d] = u[ia][d] + la * r[d];
          }
        const Vec3 r = cross(w[ib], e);
        for (unsigned d = 0; d < 3; ++d)
          vb[d] = u[ib][d] - lb * r[d];
        Vec3 v;
        for (unsigned d = 0; d < 3; ++d)
          v[d] = vb[d] - va[d];
        const double c = rows.gap(k) + dt * dot(v, e); // length units
        Vec3         vt;
        for (unsigned d = 0; d < 3; ++d)
          vt[d] = v[d] - dot(v, e) * e[d];
        // Impulses in length units (times dt), like the tolerance.
        const double lt_norm = norm(lt);
        if (!rows.glued(k))
          {
            errors.sign = std::max(errors.sign, -dt * ln);
            errors.complementarity =
              std::max(errors.complementarity, std::min(dt * ln, std::abs(c)));
          }
        errors.cone =
          std::max(errors.cone, dt * (lt_norm - mu * std::max(ln, 0.)));
        // The slip along the impulse (dissipation lambda_t . v_t >= 0).
        if (lt_norm > 0.)
          errors.dissipation =
            std::max(errors.dissipation, dt * dot(lt, vt) / lt_norm);
        if (lt_norm < mu * ln * (1. - 1e-6))
          {
            ++errors.n_stick;
            errors.stick = std::max(errors.stick, dt * norm(vt));
          }
        else if (ln > 0. && norm(vt) > 0.)
          {
            ++errors.n_slide;
            // The slip must be -s lambda_t / |lambda_t| with s >= 0.
            Vec3 off;
            for (unsigned d = 0; d < 3; ++d)
              off[d] = vt[d] + norm(vt) * lt[d] / lt_norm;
            errors.sliding = std::max(errors.sliding, dt * norm(off));
          }
        // Force and torque on each particle.
        Vec3 f;
        for (unsigned d = 0; d < 3; ++d)
          f[d] = ln * e[d] + lt[d];
        const Vec3 t_b = cross(Vec3{{-lb * e[0], -lb * e[1], -lb * e[2]}}, f);
        for (unsigned d = 0; d < 3; ++d)
          {
            force[ib][d] += f[d];
            torque[ib][d] += t_b[d];
          }
        if (ia < n)
          {
            const Vec3 t_a = cross(Vec3{{la * e[0], la * e[1], la * e[2]}}, f);
            for (unsigned d = 0; d < 3; ++d)
              {
                force[ia][d] -= f[d];
                torque[ia][d] -= t_a[d];
              }
          }
      }
    // u = u* + F / w, omega = omega* + T / j: the particle's resistance
    // balances the contact force and torque.
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned d = 0; d < 3; ++d)
        {
          const double j = ratio * a[i] * a[i];
          errors.balance = std::max(
            {errors.balance,
             dt * std::abs(u[i][d] - u_star[i][d] - force[i][d]),
             dt * a[i] * std::abs(j * (w[i][d] - w_star[i][d]) - torque[i][d]) /
               j});
        }
    return errors;
  }

  void
  check_packings()
  {
    const double tolerance = 1e-10, mu = 0.5, dt = 0.005;
    for (const unsigned dim : {2u, 3u})
      for (const Model model : {Model::inelastic, Model::gluey})
        {
          TestTools::Random   random(11);
          std::vector<Vec3>   x;
          std::vector<double> a;
          const std::size_t   n      = dim == 2 ? 2000 : 1000;
          const double        radius = dim == 2 ? 0.0075 : 0.045;
          TestTools::random_packing(random,
                                    dim,
                                    n,
                                    0.8 * radius,
                                    1.2 * radius,
                                    0.,
                                    1.,
                                    0.,
                                    x,
                                    a);
          Settings settings;
          settings.dimension = dim;
          settings.model     = model;
          settings.friction  = mu;
          settings.tolerance = tolerance;
          ContactProjector  projector(settings);
          ConeErrors        worst;
          std::vector<Vec3> u_star(n), w_star(n), u, w;
          bool              converged  = true;
          unsigned int      iterations = 0, sliding = 0, active = 0;
          // Squeezed until about one active contact per particle, the
          // density of a dense suspension's contact network. (Squeezed
          // further, to more contacts than particles, a few projections
          // stall in clusters of stuck contacts: doc/theory/contact.md.)
          const int steps = dim == 2 ? 40 : 30;
          for (int step = 0; step < steps; ++step)
            {
              // Squeezed towards the centre and sheared, with random spins.
              for (std::size_t i = 0; i < n; ++i)
                {
                  for (unsigned d = 0; d < 3; ++d)
                    {
                      u_star[i][d] = d < dim ? -(x[i][d] - 0.5) : 0.;
                      w_star[i][d] = 0.;
                    }
                  u_star[i][0] += 2. * (x[i][1] - 0.5);
                  w_star[i][2] = random.uniform(-3., 3.);
                  if (dim == 3)
                    {
                      w_star[i][0] = random.uniform(-3., 3.);
                      w_star[i][1] = random.uniform(-3., 3.);
                    }
                }
              const auto st = projector.project(x, a, u_star, w_star, dt, u, w);
              converged     = converged && st.converged;
              iterations    = std::max(iterations, st.iterations);
              sliding       = st.n_sliding;
              active        = st.n_active;
              const ConeErrors e =
                check_cone(projector, a, u_star, w_star, u, w, mu, dt);
              worst.sign = std::max(worst.sign, e.sign);
              worst.cone = std::max(worst.cone, e.cone);
              worst.complementarity =
                std::max(worst.complementarity, e.complementarity);
              worst.stick       = std::max(worst.stick, e.stick);
              worst.sliding     = std::max(worst.sliding, e.sliding);
              worst.dissipation = std::max(worst.dissipation, e.dissipation);
              worst.balance     = std::max(worst.balance, e.balance);
              worst.n_stick += e.n_stick;
              worst.n_slide += e.n_slide;
              for (std::size_t i = 0; i < n; ++i)
                for (unsigned d = 0; d < dim; ++d)
                  x[i][d] += dt * u[i][d];
            }
          const std::string head =
            std::to_string(dim) + "D " + std::to_string(n) + " particles, " +
            (model == Model::gluey ? "gluey" : "inelastic") + ", mu = 0.5: ";
          std::fprintf(log(),
                       "%slast step %u active, %u sliding; over %d steps %u "
                       "stuck and %u sliding contacts, at most %u sweeps\n",
                       head.c_str(),
                       active,
                       sliding,
                       steps,
                       worst.n_stick,
                       worst.n_slide,
                       iterations);
          // The tolerance bounds each contact's local correction in length
          // units; a few times it bounds what follows from it.
          const double tol = 4. * tolerance;
          TestTools::check(head + "all projections converged", converged);
          TestTools::check(head + "both stuck and sliding contacts present",
                           worst.n_stick > 100 && worst.n_slide > 100);
          TestTools::check(head + "lambda_n >= 0 on unglued rows",
                           worst.sign <= tol);
          TestTools::check(head + "|lambda_t| <= mu lambda_n",
                           worst.cone <= tol);
          TestTools::check(head + "normal complementarity",
                           worst.complementarity <= tol);
          TestTools::check(head + "no slip inside the cone",
                           worst.stick <= tol);
          TestTools::check(head + "sliding impulse on the rim, against the "
                                  "slip",
                           worst.sliding <= tol);
          TestTools::check(head + "dissipation >= 0", worst.dissipation <= tol);
          TestTools::check(head + "force and torque balance",
                           worst.balance <= 1e-12);
        }
  }
} // namespace

int
main()
{
  try
    {
      check_sphere_on_wall();
      check_pair();
      check_packings();
    }
  catch (const ContactError &e)
    {
      std::printf("ContactError: %s\n", e.what());
      return 1;
    }
  return TestTools::failures() != 0;
}
