#include <algorithm>
#include <cmath>
#include <fidus/contact/pair_search.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/cut_stokes_inclusion.h>
#include <fidus/particles/rigid_motion.h>
#include <fidus/rheology/plane_strain.h>
#include <fidus/simulation/simulation.h>
#include <sstream>

// The stages of the time loop that give the particles their velocities:
// the fluid solve at given positions (mesh, Stokes, rigid motion), the
// Adams-Bashforth extrapolation and the trapezoidal corrector.

namespace Fidus
{
  using Vec3 = RunState::Vec3;

  template <int dim>
  void
  Simulation<dim>::extrapolate_velocities(const double dt)
  {
    // The Stokes problem is quasi-static and linear in the boundary data,
    // so U is the shear rate times a field that depends on the positions
    // only. Extrapolating U / shear and multiplying by the shear rate at
    // the middle of the step is the same formula for a constant shear
    // rate, and stays exact when the shear rate jumps at a step boundary (a
    // reversal 't < T ? 1 : -1'), where plain AB2 would make one step with
    // -2U: an O(dt) error that breaks the reversibility of Stokes flow,
    // which is what the contact models are meant to keep.
    const RunState &s     = state;
    const double    beta  = s.have_history ? dt / (2. * s.dt_old) : 0.;
    const double    g_now = shear(s.time);
    const double    g_old = s.have_history ? shear(s.t_old) : g_now;
    const double    g_mid = shear(s.time + 0.5 * dt);
    // External forces add a part that does not scale with the shear rate.
    const bool scaled = prm.external_forces.empty() && std::abs(g_now) > 0. &&
                        std::abs(g_old) > 0.;
    const double c_now = scaled ? g_mid / g_now : 1.;
    const double c_old = scaled ? g_mid / g_old : 1.;
    u_star.resize(n);
    w_star.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          u_star[i][d] =
            (1. + beta) * c_now * s.U[i][d] - beta * c_old * s.U_old[i][d];
          w_star[i][d] =
            (1. + beta) * c_now * s.W[i][d] - beta * c_old * s.W_old[i][d];
        }
  }



  template <int dim>
  void
  Simulation<dim>::average_with_end_of_step_velocities(const double dt)
  {
    if (prm.time_scheme != TimeScheme::trapezoidal)
      return;
    // The trapezoidal rule X+ = X + dt (U(X) + U(X+)) / 2 is symmetric in
    // time: run backwards from X+ with the reversed shear, it gives back X
    // exactly. AB2 is not, and its O(dt^2) error does not cancel when the
    // shear is reversed, which is the error a reversibility experiment
    // measures (doc/results.md). X+ is found by fixed-point iteration from
    // the AB2 prediction: each pass solves the fluid at the positions the
    // current velocities reach, and averages. The contraction factor is
    // dt |grad U| / 2, so one pass (a predictor-corrector) leaves an error
    // of O(dt^4) per step. The last pass's velocities also serve as those
    // at the end of the step (predict_velocities() does not solve again):
    // they were solved O(dt^3) away from X+, which changes the next step
    // by O(dt^4) as well, and keeps the cost of one pass that of AB2.
    //
    // With the shear rate g(t), U = g V(X) at fixed positions. Both ends
    // are solved with the shear rate of their time (the end's solve is the
    // next step's start, and its stress belongs to that time) and rescaled
    // to the rate of the middle of the step, as in the AB2 extrapolation:
    // a jump of g at a step boundary (a reversal) then stays exact. A zero
    // rate at either end, external forces and the exact-inclusion scene
    // (whose boundary does not follow g) take the plain mean.
    const double g_now  = shear(state.time);
    const double g_mid  = shear(state.time + 0.5 * dt);
    const double g_end  = shear(state.time + dt);
    const bool   scaled = prm.external_forces.empty() && !exact &&
                        std::abs(g_now) > 0. && std::abs(g_end) > 0.;
    const double      c_now = scaled ? g_mid / g_now : 1.;
    const double      c_end = scaled ? g_mid / g_end : 1.;
    const std::string where = "step " + std::to_string(state.step + 1) +
                              " (trapezoidal corrector, end of the step " +
                              "from t = " + std::to_string(state.time) + ")";

    // The projections of the passes are trials: each starts from the glue
    // (and warm start) of the beginning of the step.
    const std::vector<Contact::GlueState::Entry> glue =
      projector.glue_state().entries();
    pass_stats    = typename StokesSolver<dim>::Statistics();
    pass_remeshed = false;
    std::vector<Vec3> X_end(n);
    U_end.resize(n);
    W_end.resize(n);
    for (unsigned int pass = 0; pass < prm.trapezoidal_iterations; ++pass)
      {
        trial_pass = true;
        add_lubrication(dt);
        project_onto_admissible_set(dt);
        trial_pass = false;
        projector.restore_glue(glue);
        X_mid.resize(n);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            {
              const double step = d < dim ? dt * u_corrected[i][d] : 0.;
              X_end[i][d]       = state.X[i][d] + step;
              // Not wrapped: the contact module takes minimum images of
              // separations, and a step is far shorter than a period.
              X_mid[i][d] = state.X[i][d] + 0.5 * step;
            }
        box.wrap(X_end);

        // The step's row reports the last pass's solve, with the
        // iterations of all passes and their largest rigidity residual.
        const typename StokesSolver<dim>::Statistics before = pass_stats;
        remeshed                                            = false;
        rigid_velocities_at(X_end, g_end, state.step + 1, where, U_end, W_end);
        pass_stats = fluid_stats;
        pass_stats.uzawa_iterations += before.uzawa_iterations;
        pass_stats.linear_iterations += before.linear_iterations;
        pass_stats.rigidity_residual =
          std::max(before.rigidity_residual, fluid_stats.rigidity_residual);
        pass_remeshed = pass_remeshed || remeshed;
        passes_solved = true;

        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            {
              u_star[i][d] =
                0.5 * (c_now * state.U[i][d] + c_end * U_end[i][d]);
              w_star[i][d] =
                0.5 * (c_now * state.W[i][d] + c_end * W_end[i][d]);
            }
      }
  }



  template <int dim>
  void
  Simulation<dim>::predict_velocities()
  {
    if (passes_solved)
      {
        // The trapezoidal passes of this step solved the fluid last (see
        // average_with_end_of_step_velocities()); the row reports all of
        // their iterations, and the solver's fields are those of the last.
        state.U       = U_end;
        state.W       = W_end;
        fluid_stats   = pass_stats;
        remeshed      = pass_remeshed;
        passes_solved = false;
        return;
      }
    fluid_stats = typename StokesSolver<dim>::Statistics();
    remeshed    = false;
    rigid_velocities_at(state.X,
                        shear(state.time),
                        state.step,
                        "step " + std::to_string(state.step) +
                          ", t = " + std::to_string(state.time),
                        state.U,
                        state.W);
  }



  template <int dim>
  void
  Simulation<dim>::rigid_velocities_at(const std::vector<Vec3> &X,
                                       const double             g,
                                       const unsigned int       step,
                                       const std::string       &where,
                                       std::vector<Vec3>       &U,
                                       std::vector<Vec3>       &W)
  {
    if (cut)
      {
        solve_cut_finite_element(X, g, step, where, U, W);
        return;
      }
    if (!fictitious)
      {
        // Free-draining particles: the undisturbed shear at the centre.
        for (unsigned int i = 0; i < n; ++i)
          {
            U[i] = {{g * (X[i][1] - box.y_mid), 0., 0.}};
            W[i] = {{0., 0., -0.5 * g}};
          }
        return;
      }
    solid
      .reinit(X, solid_radii, box.lo, box.hi, box.is_periodic, box.query_reach);
    refine_mesh_if_particles_moved(X);
    solve_fluid(g, step, where);
    extract_rigid_motion(U, W);
  }



  template <int dim>
  void
  Simulation<dim>::refine_mesh_if_particles_moved(const std::vector<Vec3> &X)
  {
    TimerOutput::Scope scope(*timer, "mesh");
    double             moved = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        double d2 = 0;
        for (unsigned int d = 0; d < dim; ++d)
          d2 += std::pow(Contact::PairSearch::minimum_image(
                           X[i][d] - state.X_at_remesh[i][d],
                           box.periods[d]),
                         2);
        moved = std::max(moved, std::sqrt(d2));
      }
    // Skip remeshing while no particle has left a fraction of the refined
    // band: the mesh still resolves every surface.
    if (state.mesh_ready &&
        moved <= prm.remesh_fraction * prm.interface_band * box.h_finest)
      return;
    const unsigned int changes = refiner->adapt(*tria, solid);
    if (changes > 0 || !state.mesh_ready)
      {
        solver->setup_dofs(box.periodic, box.dirichlet_ids);
        remeshed = true;
      }
    state.X_at_remesh = X;
    state.mesh_ready  = true;
  }



  template <int dim>
  void
  Simulation<dim>::solve_fluid(const double       g,
                               const unsigned int step,
                               const std::string &where)
  {
    TimerOutput::Scope scope(*timer, "fluid");
    boundary.set_shear_rate(g);
    fluid_stats =
      solver->solve(solid,
                    exact ? static_cast<const Function<dim> &>(*exact) :
                            boundary,
                    external_force.get());
    if (fluid_stats.uzawa_converged)
      return;
    ++state.totals.uzawa_failures;
    std::ostringstream m;
    m << where << ": the Uzawa loop stopped after "
      << fluid_stats.uzawa_iterations
      << (fluid_stats.uzawa_iterations == 1 ? " iteration" : " iterations")
      << " at " << (prm.rigidity_per_particle ? "per-particle " : "")
      << "rigidity residual " << fluid_stats.rigidity_residual;
    if (prm.rigid_velocity_tolerance > 0.)
      m << ", rigid velocity change " << fluid_stats.rigid_velocity_change
        << " > " << prm.rigid_velocity_tolerance
        << (fluid_stats.uzawa_stalled ?
              " (no progress in the last iteration; Fluid/Rigid velocity "
              "tolerance)" :
              " (Fluid/Maximum Uzawa iterations)");
    else
      m << " > " << prm.rigidity_tolerance
        << (fluid_stats.uzawa_stalled ?
              " (no progress in the last iteration; Fluid/Rigidity "
              "tolerance)" :
              " (Fluid/Maximum Uzawa iterations)");
    warnings.warn("rigidity not reached",
                  m.str(),
                  step,
                  fluid_stats.rigidity_residual);
  }



  template <int dim>
  void
  Simulation<dim>::solve_cut_finite_element(const std::vector<Vec3> &X,
                                            const double             g,
                                            const unsigned int       step,
                                            const std::string       &where,
                                            std::vector<Vec3>       &U,
                                            std::vector<Vec3>       &W)
  {
    TimerOutput::Scope scope(*timer, "fluid");
    using Cut = CutStokesInclusion<dim>;
    typename Cut::Settings s;
    s.boundary   = prm.boundary_condition == BoundaryCondition::sliding_walls ?
                     Cut::Boundary::sliding_walls :
                     Cut::Boundary::linear_shear;
    s.shear_rate = g;
    s.viscosity  = prm.viscosity;
    s.global_level = prm.minimum_level;
    s.band_levels  = prm.maximum_level - prm.minimum_level;
    s.gap_cells    = prm.cut_gap_cells;
    s.linear_solver =
      prm.cut_linear_solver == "direct"    ? Cut::LinearSolver::direct :
      prm.cut_linear_solver == "iterative" ? Cut::LinearSolver::iterative :
                                             Cut::LinearSolver::automatic;
    // A pair's cut cells away from its gap are as coarse as the Maximum
    // level, where 4 Gauss points per direction leave a quadrature error
    // of 1e-4 in the velocities at level 5 (a = 1.6 cells), seen as a
    // broken point symmetry of the paper's pair; 8 points take it to 1e-7
    // (doc/cut_element.md). 2D affords it; 3D keeps 4.
    s.quadrature_points = dim == 2 ? 8 : 4;

    // The cut element cannot solve touching particles, which the contact
    // models allow (gluey pairs sit at zero gap), nor overlapping ones
    // (the model 'none'). Its fluid sees each particle with a radius
    // reduced just enough that every gap is at least the minimum gap: a
    // pair at contact moves as a pair Cut minimum gap apart would, and
    // the contact model, which keeps the true radii, does the rest.
    std::vector<double> shrink(n, 0.);
    double              overlap = 0.;
    for (unsigned int i = 0; i < n; ++i)
      {
        const double a = prm.radii[i];
        for (unsigned int d = 0; d < dim; ++d)
          if (!box.is_periodic[d])
            {
              const double wall = std::min(X[i][d], 1. - X[i][d]) - a;
              shrink[i] = std::max(shrink[i], prm.cut_minimum_gap * a - wall);
              overlap   = std::max(overlap, -wall / a);
            }
        for (unsigned int j = 0; j < i; ++j)
          {
            // The nearest image along periodic axes.
            double d2 = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              d2 +=
                std::pow(Contact::PairSearch::minimum_image(X[i][d] - X[j][d],
                                                            box.periods[d]),
                         2);
            const double b   = prm.radii[j];
            const double gap = std::sqrt(d2) - a - b;
            const double cut_by =
              0.5 * (prm.cut_minimum_gap * std::min(a, b) - gap);
            shrink[i] = std::max(shrink[i], cut_by);
            shrink[j] = std::max(shrink[j], cut_by);
            overlap   = std::max(overlap, -gap / std::min(a, b));
          }
      }
    if (overlap > 0.)
      warnings.warn("cut element: overlap",
                    where +
                      ": particles overlap each other or the box by up to " +
                      std::to_string(overlap) +
                      " radii; the cut element's fluid saw them with "
                      "radii reduced to leave Fluid/Cut minimum gap",
                    step,
                    overlap);
    s.particles.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        auto &P = s.particles[i];
        for (unsigned int d = 0; d < dim; ++d)
          P.center[d] = X[i][d];
        P.radius = prm.radii[i] - std::max(0., shrink[i]);
        if (!prm.external_forces.empty())
          for (unsigned int d = 0; d < dim; ++d)
            P.force[d] = prm.external_forces[i][d];
      }

    typename Cut::Result r;
    try
      {
        r = Cut::solve(s);
      }
    catch (const std::exception &e)
      {
        throw RunError(where + ": the cut finite element failed: " + e.what());
      }
    cut_cells   = r.n_cells;
    cut_dofs    = r.n_dofs;
    fluid_stats = typename StokesSolver<dim>::Statistics();
    // The iterative solver's FGMRES iterations (0 when solved directly)
    // go to the linear_iterations column.
    fluid_stats.linear_iterations = r.n_iterations;
    // A direct solve that lost accuracy gives no error: its residual is
    // checked (an iterative one that does not converge throws).
    if (!(r.residual < 1e-8))
      warnings.warn("cut element: inaccurate solve",
                    where +
                      ": the linear solve's relative residual "
                      "is " +
                      std::to_string(r.residual) + " > 1e-8",
                    step,
                    r.residual);
    for (unsigned int i = 0; i < n; ++i)
      {
        U[i] = {{0., 0., 0.}};
        for (unsigned int d = 0; d < dim; ++d)
          U[i][d] = r.velocity[i][d];
        for (unsigned int d = 0; d < 3; ++d)
          W[i][d] = r.angular_velocity[i][d];
      }

    // The stress in the form of HydrodynamicStress (doc/rheology.md):
    // Sigma = -<p>_f I + 2 eta <e(u)> + (1/V) sum S_a over the unit box,
    // where <e(u)> is the boundary's shear, since the velocity is rigid
    // in the particles. In plane strain the zz stresslet is half the
    // in-plane trace (with_plane_strain_zz()). Between sliding walls the
    // walls' stress sigma e_y is measured too (entries (a, y)), as the
    // fictitious domain's is; with linear shear it is not (NaN).
    using Tensor3            = typename HydrodynamicStress<dim>::Tensor3;
    auto &h                  = cut_stress;
    h                        = typename HydrodynamicStress<dim>::Result();
    h.volume                 = 1.;
    h.fluid_pressure         = r.fluid_pressure;
    h.solid_fraction         = 1. - r.fluid_volume;
    h.mean_strain_rate[0][1] = 0.5 * g;
    for (unsigned int i = 0; i < n; ++i)
      {
        Tensor3 S;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = a; b < dim; ++b)
            S[a][b] = r.stresslets[i][a][b];
        if (dim == 2)
          S = with_plane_strain_zz(S);
        h.stresslets.push_back(S);
        h.particle += S / h.volume;
      }
    h.total = -h.fluid_pressure * unit_symmetric_tensor<3>() +
              2. * prm.viscosity * h.mean_strain_rate + h.particle;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        h.wall[a][b] = std::numeric_limits<double>::quiet_NaN();
    if (s.boundary == Cut::Boundary::sliding_walls)
      for (unsigned int a = 0; a < dim; ++a)
        h.wall[a][1] = r.top_wall_stress[a];
  }



  template <int dim>
  void
  Simulation<dim>::extract_rigid_motion(std::vector<Vec3> &U,
                                        std::vector<Vec3> &W)
  {
    TimerOutput::Scope             scope(*timer, "rigid motion");
    const std::vector<RigidMotion> motions =
      compute_rigid_motions(solver->get_dof_handler(),
                            solver->get_cells(),
                            solver->get_solution(),
                            solid,
                            solver->get_quadrature(),
                            &solver->get_shared_cells());
    for (unsigned int i = 0; i < n; ++i)
      {
        U[i] = motions[i].velocity;
        W[i] = motions[i].omega;
      }
  }



  template void
  Simulation<2>::extrapolate_velocities(double);
  template void
  Simulation<3>::extrapolate_velocities(double);
  template void
  Simulation<2>::average_with_end_of_step_velocities(double);
  template void
  Simulation<3>::average_with_end_of_step_velocities(double);
  template void
  Simulation<2>::predict_velocities();
  template void
  Simulation<3>::predict_velocities();
  template void
  Simulation<2>::rigid_velocities_at(const std::vector<Vec3> &,
                                     double,
                                     unsigned int,
                                     const std::string &,
                                     std::vector<Vec3> &,
                                     std::vector<Vec3> &);
  template void
  Simulation<3>::rigid_velocities_at(const std::vector<Vec3> &,
                                     double,
                                     unsigned int,
                                     const std::string &,
                                     std::vector<Vec3> &,
                                     std::vector<Vec3> &);
  template void
  Simulation<2>::refine_mesh_if_particles_moved(const std::vector<Vec3> &);
  template void
  Simulation<3>::refine_mesh_if_particles_moved(const std::vector<Vec3> &);
  template void
  Simulation<2>::solve_fluid(double, unsigned int, const std::string &);
  template void
  Simulation<3>::solve_fluid(double, unsigned int, const std::string &);
  template void
  Simulation<2>::solve_cut_finite_element(const std::vector<Vec3> &,
                                          double,
                                          unsigned int,
                                          const std::string &,
                                          std::vector<Vec3> &,
                                          std::vector<Vec3> &);
  template void
  Simulation<3>::solve_cut_finite_element(const std::vector<Vec3> &,
                                          double,
                                          unsigned int,
                                          const std::string &,
                                          std::vector<Vec3> &,
                                          std::vector<Vec3> &);
  template void
  Simulation<2>::extract_rigid_motion(std::vector<Vec3> &, std::vector<Vec3> &);
  template void
  Simulation<3>::extract_rigid_motion(std::vector<Vec3> &, std::vector<Vec3> &);
} // namespace Fidus
