#ifndef fidus_tests_contact_cone_check_h
#define fidus_tests_contact_cone_check_h

// The Coulomb conditions checked on every contact of a projection, written
// independently of the solver, and a random dense packing squeezed and
// sheared with random spins until about one active contact per particle
// (tests contact/friction and contact/friction_large).

#include "test_tools.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fidus/contact/contact_projector.h>
#include <fidus/contact/vector_operations.h>
#include <string>

namespace ConeCheck
{
  using namespace Fidus::Contact;

  /// Largest violations of the Coulomb conditions in one projection.
  struct ConeErrors
  {
    double sign = 0., cone = 0., complementarity = 0., stick = 0., sliding = 0.,
           dissipation = 0., balance = 0.;
    unsigned int n_stick = 0, n_slide = 0;
  };

  inline ConeErrors
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

  /// @p n particles in the unit box (the density of 2000 discs or 1000
  /// spheres), squeezed towards the centre and sheared with random spins
  /// for @p steps projections with friction coefficient @p mu and the
  /// model @p model; every projection's contacts checked with
  /// check_cone().
  /// Measured numbers go to @p log.
  inline void
  check_squeezed_packing(const unsigned    dim,
                         const std::size_t n,
                         const Model       model,
                         const int         steps,
                         std::FILE        *log,
                         const double      mu = 0.5)
  {
    const double        tolerance = 1e-10, dt = 0.005;
    TestTools::Random   random(11);
    std::vector<Vec3>   x;
    std::vector<double> a;
    // The density of 2000 discs of radius 0.0075 or 1000 spheres of
    // radius 0.045 in the unit box, whatever n.
    const double radius =
      dim == 2 ? 0.0075 * std::sqrt(2000. / n) : 0.045 * std::cbrt(1000. / n);
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
    unsigned int      iterations = 0, sliding = 0, active = 0, relaxed = 0;
    // Squeezed until about one active contact per particle, the
    // density of a dense suspension's contact network (contact/friction
    // also squeezes a packing at mu = 1 to where the sweeps stall and
    // relax; contact/friction_large squeezes further).
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
        relaxed += st.relaxation < 1. ? 1 : 0;
        active = st.n_active;
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
    char mu_text[32];
    std::snprintf(mu_text, sizeof(mu_text), ", mu = %g: ", mu);
    const std::string head =
      std::to_string(dim) + "D " + std::to_string(n) + " particles, " +
      (model == Model::gluey ? "gluey" : "inelastic") + mu_text;
    std::fprintf(log,
                 "%slast step %u active, %u sliding; over %d steps %u "
                 "stuck and %u sliding contacts, at most %u sweeps, %u "
                 "relaxed\n",
                 head.c_str(),
                 active,
                 sliding,
                 steps,
                 worst.n_stick,
                 worst.n_slide,
                 iterations,
                 relaxed);
    // The tolerance bounds each contact's local correction in length
    // units; a few times it bounds what follows from it.
    const double tol = 4. * tolerance;
    TestTools::check(head + "all projections converged", converged);
    TestTools::check(head + "both stuck and sliding contacts present",
                     worst.n_stick > 100 && worst.n_slide > 100);
    TestTools::check(head + "lambda_n >= 0 on unglued rows", worst.sign <= tol);
    TestTools::check(head + "|lambda_t| <= mu lambda_n", worst.cone <= tol);
    TestTools::check(head + "normal complementarity",
                     worst.complementarity <= tol);
    TestTools::check(head + "no slip inside the cone", worst.stick <= tol);
    TestTools::check(head + "sliding impulse on the rim, against the "
                            "slip",
                     worst.sliding <= tol);
    TestTools::check(head + "dissipation >= 0", worst.dissipation <= tol);
    TestTools::check(head + "force and torque balance", worst.balance <= 1e-12);
  }
} // namespace ConeCheck

#endif
