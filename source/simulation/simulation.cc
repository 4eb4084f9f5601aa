#include <algorithm>
#include <cmath>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <fidus/contact/contact_error.h>
#include <fidus/contact/contact_projector.h>
#include <fidus/core/input_error.h>
#include <fidus/core/shear_rate.h>
#include <fidus/core/warning_log.h>
#include <fidus/fluid/boundary_velocity.h>
#include <fidus/fluid/exact_rigid_inclusion.h>
#include <fidus/fluid/stokes_solver.h>
#include <fidus/io/csv_writer.h>
#include <fidus/io/field_output.h>
#include <fidus/io/particle_output.h>
#include <fidus/mesh/box_mesh.h>
#include <fidus/mesh/mesh_refiner.h>
#include <fidus/particles/rigid_motion.h>
#include <fidus/particles/solid_indicator.h>
#include <fidus/simulation/simulation.h>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <memory>
#include <sstream>

namespace Fidus
{
  using Vec3 = std::array<double, 3>;

  namespace
  {
    Contact::Model
    contact_model(const ContactModel m)
    {
      return m == ContactModel::none      ? Contact::Model::none :
             m == ContactModel::inelastic ? Contact::Model::inelastic :
                                            Contact::Model::gluey;
    }

    Contact::DualSolver
    dual_solver(const std::string &name)
    {
      return name == "projected gradient" ?
               Contact::DualSolver::projected_gradient :
             name == "accelerated projected gradient" ?
               Contact::DualSolver::accelerated_projected_gradient :
               Contact::DualSolver::projected_gauss_seidel;
    }

    std::string
    format_time(const double seconds)
    {
      std::ostringstream s;
      const long         t = std::lround(seconds);
      if (t >= 3600)
        s << t / 3600 << "h" << std::setw(2) << std::setfill('0')
          << (t % 3600) / 60 << "m";
      else if (t >= 60)
        s << t / 60 << "m" << std::setw(2) << std::setfill('0') << t % 60
          << "s";
      else
        s << std::fixed << std::setprecision(1) << seconds << "s";
      return s.str();
    }
  } // namespace



  template <int dim>
  Simulation<dim>::Simulation(const Parameters &parameters)
    : prm(parameters)
  {}



  template <int dim>
  RunSummary
  Simulation<dim>::run()
  {
    const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    ConditionalOStream pcout(std::cout,
                             root && prm.verbosity != Verbosity::quiet);
    // The timer is destroyed before an error propagates, so that it neither
    // communicates nor prints while the run stops.
    auto timer = std::make_unique<TimerOutput>(MPI_COMM_WORLD,
                                               pcout,
                                               TimerOutput::never,
                                               TimerOutput::wall_times);
    try
      {
        const RunSummary summary = run_steps(*timer);
        if (prm.verbosity != Verbosity::quiet)
          timer->print_summary();
        return summary;
      }
    catch (...)
      {
        timer.reset();
        throw;
      }
  }



  template <int dim>
  RunSummary
  Simulation<dim>::run_steps(TimerOutput &timer)
  {
    const MPI_Comm     comm = MPI_COMM_WORLD;
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    const bool         root = rank == 0;
    ConditionalOStream pcout(std::cout,
                             root && prm.verbosity != Verbosity::quiet);
    Timer              wall_clock;

    if (root)
      std::filesystem::create_directories(prm.output_directory);
    MPI_Barrier(comm);

    const bool fictitious = prm.fluid_model == FluidModel::fictitious_domain;
    const unsigned int n  = prm.n_particles();
    ShearRate          shear(prm.shear_rate);
    Point<dim>         lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] = prm.lower_left[d];
        hi[d] = prm.upper_right[d];
      }
    const double y_mid = 0.5 * (lo[1] + hi[1]);
    double       a_min = std::numeric_limits<double>::max(), a_max = 0;
    for (const double a : prm.radii)
      {
        a_min = std::min(a_min, a);
        a_max = std::max(a_max, a);
      }
    if (n == 0)
      a_min = a_max = 1.; // only scales tolerances then

    // Which faces are periodic, walls, or in/outflow (numerics section 1).
    std::vector<unsigned int> periodic;
    if (prm.boundary_condition == BoundaryCondition::sliding_walls)
      for (unsigned int d = 0; d < dim; ++d)
        if (d != 1)
          periodic.push_back(d);
    std::array<bool, dim> is_periodic = {};
    for (const unsigned int d : periodic)
      is_periodic[d] = true;
    std::set<types::boundary_id> dirichlet_ids;
    for (unsigned int d = 0; d < dim; ++d)
      if (std::find(periodic.begin(), periodic.end(), d) == periodic.end())
        {
          dirichlet_ids.insert(2 * d);
          dirichlet_ids.insert(2 * d + 1);
        }
    // A face is a wall if the imposed velocity has no normal component:
    // the y faces always; x and z faces for the cavity; z faces in linear
    // shear (u = g (y - y_mid) e_x is tangential there).
    std::vector<bool> is_wall_axis(dim, false);
    if (prm.boundary_condition != BoundaryCondition::exact_rigid_inclusion)
      for (unsigned int d = 0; d < dim; ++d)
        is_wall_axis[d] =
          d == 1 || prm.boundary_condition == BoundaryCondition::cavity ||
          (prm.boundary_condition == BoundaryCondition::linear_shear && d == 2);
    std::vector<Contact::Wall> walls;
    if (prm.walls)
      for (unsigned int d = 0; d < dim; ++d)
        if (is_wall_axis[d])
          for (const int side : {1, -1})
            {
              Contact::Wall w;
              w.axis     = d;
              w.side     = side;
              w.position = side > 0 ? lo[d] : hi[d];
              walls.push_back(w);
            }

    // Contact module.
    Contact::Settings cs;
    cs.dimension         = dim;
    cs.model             = contact_model(prm.contact_model);
    cs.solver            = dual_solver(prm.dual_solver);
    cs.tolerance         = prm.contact_tolerance * a_min;
    cs.alert_distance    = prm.alert_distance * a_min;
    cs.overlap_tolerance = 2. * cs.tolerance;
    Contact::ContactProjector projector(cs);
    projector.set_walls(walls);
    std::array<double, 3> periods = {{0., 0., 0.}};
    for (const unsigned int d : periodic)
      periods[d] = hi[d] - lo[d];
    projector.set_periodicity(periods);

    // Fluid: mesh, solver, refinement.
    std::unique_ptr<parallel::distributed::Triangulation<dim>> tria;
    std::unique_ptr<StokesSolver<dim>>                         solver;
    std::unique_ptr<MeshRefiner<dim>>                          refiner;
    std::unique_ptr<FieldOutput<dim>>                          field_output;
    BoundaryVelocity<dim> boundary(prm.boundary_condition, lo[1], hi[1]);
    std::unique_ptr<ExactRigidInclusion<dim>> exact;
    double                                    smallest_side = hi[0] - lo[0];
    for (unsigned int d = 1; d < dim; ++d)
      smallest_side = std::min(smallest_side, hi[d] - lo[d]);
    const double h_finest = smallest_side / std::pow(2., prm.maximum_level);
    if (fictitious)
      {
        tria = std::make_unique<parallel::distributed::Triangulation<dim>>(
          comm,
          typename Triangulation<dim>::MeshSmoothing(
            Triangulation<dim>::smoothing_on_refinement |
            Triangulation<dim>::smoothing_on_coarsening));
        create_box_mesh(*tria, lo, hi, periodic, prm.initial_global_refinement);
        typename StokesSolver<dim>::Settings ss;
        ss.degree                    = prm.velocity_degree;
        ss.viscosity                 = prm.viscosity;
        ss.penalty_factor            = prm.penalty_factor;
        ss.rigidity_tolerance        = prm.rigidity_tolerance;
        ss.max_uzawa_iterations      = prm.max_uzawa_iterations;
        ss.linear_tolerance          = prm.linear_tolerance;
        ss.max_cheap_iterations      = prm.max_cheap_iterations;
        ss.max_linear_iterations     = prm.max_linear_iterations;
        ss.amg_aggregation_threshold = prm.amg_aggregation_threshold;
        ss.amg_smoother_sweeps       = prm.amg_smoother_sweeps;
        ss.amg_smoother_type         = prm.amg_smoother_type;
        ss.reuse_multiplier          = prm.reuse_multiplier;
        ss.verbose                   = prm.verbosity == Verbosity::verbose;
        solver = std::make_unique<StokesSolver<dim>>(*tria, ss);
        typename MeshRefiner<dim>::Settings ms;
        ms.minimum_level = prm.minimum_level;
        ms.maximum_level = prm.maximum_level;
        ms.band          = prm.interface_band;
        ms.gap_distance  = prm.gap_refinement_distance;
        refiner          = std::make_unique<MeshRefiner<dim>>(ms);
        if (prm.field_output_interval > 0)
          field_output =
            std::make_unique<FieldOutput<dim>>(prm.output_directory);
        if (prm.boundary_condition == BoundaryCondition::exact_rigid_inclusion)
          {
            Point<dim> c;
            for (unsigned int d = 0; d < dim; ++d)
              c[d] = prm.positions[0][d];
            exact = std::make_unique<ExactRigidInclusion<dim>>(c,
                                                               prm.radii[0],
                                                               shear(0.),
                                                               prm.viscosity);
          }
      }

    // Output files.
    CsvWriter      particles_csv(prm.output_directory + "/particles.csv",
                            {"step",
                                  "time",
                                  "id",
                                  "x",
                                  "y",
                                  "z",
                                  "ux",
                                  "uy",
                                  "uz",
                                  "omega_x",
                                  "omega_y",
                                  "omega_z",
                                  "radius"},
                            root);
    CsvWriter      statistics_csv(prm.output_directory + "/statistics.csv",
                             {"step",
                                   "time",
                                   "dt",
                                   "cells",
                                   "dofs",
                                   "uzawa_iterations",
                                   "linear_iterations",
                                   "rigidity_residual",
                                   "min_gap",
                                   "active_contacts",
                                   "glued_contacts",
                                   "wall_seconds",
                                   "remeshed",
                                   "contact_iterations"},
                             root);
    ParticleOutput particle_output(prm.output_directory,
                                   root && prm.particle_output_interval > 0);

    // Particle state.
    std::vector<Vec3>   X = prm.positions;
    std::vector<Vec3>   U(n), U_old(n), W(n), W_old(n), u_star(n), u(n);
    std::vector<double> angle(n, 0.);
    std::vector<std::array<double, 4>> quaternion(n, {{1., 0., 0., 0.}});
    std::vector<Vec3>                  X_at_remesh = X;
    bool                               mesh_ready  = false;
    SolidIndicator<dim>                solid;

    RunSummary summary;
    summary.min_gap                 = std::numeric_limits<double>::max();
    summary.min_normalised_distance = std::numeric_limits<double>::max();

    typename StokesSolver<dim>::Statistics fluid_stats;
    bool                                   remeshed = false;
    // Step counter; the fluid predictor's warnings name it.
    unsigned int step = 0;
    // Repeated warnings are written in full the first ten times per kind,
    // then counted (see WarningLog).
    WarningLog warnings(std::cerr, root);

    // Fluid predictor at the current state: U, W at positions X, time t.
    auto compute_velocities = [&](const double t) {
      fluid_stats = typename StokesSolver<dim>::Statistics();
      remeshed    = false;
      if (!fictitious)
        {
          const double g = shear(t);
          for (unsigned int i = 0; i < n; ++i)
            {
              U[i] = {{g * (X[i][1] - y_mid), 0., 0.}};
              W[i] = {{0., 0., -0.5 * g}};
            }
          return;
        }
      solid.reinit(X, prm.radii, lo, hi, is_periodic);
      {
        TimerOutput::Scope scope(timer, "mesh");
        double             moved = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            double d2 = 0;
            for (unsigned int d = 0; d < dim; ++d)
              d2 += std::pow(X[i][d] - X_at_remesh[i][d], 2);
            moved = std::max(moved, std::sqrt(d2));
          }
        // Skip remeshing while no particle has left a fraction of the
        // refined band: the mesh still resolves every surface.
        if (!mesh_ready ||
            moved > prm.remesh_fraction * prm.interface_band * h_finest)
          {
            const unsigned int changes = refiner->adapt(*tria, solid);
            if (changes > 0 || !mesh_ready)
              {
                solver->setup_dofs(periodic, dirichlet_ids);
                remeshed = true;
              }
            X_at_remesh = X;
            mesh_ready  = true;
          }
      }
      {
        TimerOutput::Scope scope(timer, "fluid");
        boundary.set_shear_rate(shear(t));
        fluid_stats =
          solver->solve(solid,
                        exact ? static_cast<const Function<dim> &>(*exact) :
                                boundary);
        if (!fluid_stats.uzawa_converged)
          {
            ++summary.uzawa_failures;
            std::ostringstream m;
            m << "step " << step << ", t = " << t
              << ": the Uzawa loop stopped after "
              << fluid_stats.uzawa_iterations
              << (fluid_stats.uzawa_iterations == 1 ? " iteration" :
                                                      " iterations")
              << " at rigidity residual " << fluid_stats.rigidity_residual
              << " > " << prm.rigidity_tolerance
              << (fluid_stats.uzawa_stalled ?
                    " (no progress in the last iteration; "
                    "Fluid/Rigidity tolerance)" :
                    " (Fluid/Maximum Uzawa iterations)");
            warnings.warn("rigidity not reached",
                          m.str(),
                          step,
                          fluid_stats.rigidity_residual);
          }
      }
      {
        TimerOutput::Scope             scope(timer, "rigid motion");
        const std::vector<RigidMotion> motions =
          compute_rigid_motions(solver->get_dof_handler(),
                                solver->get_solution(),
                                solid,
                                solver->get_quadrature());
        for (unsigned int i = 0; i < n; ++i)
          {
            U[i] = motions[i].velocity;
            W[i] = motions[i].omega;
          }
      }
    };

    auto min_gap_of = [&](const std::vector<Vec3> &x) {
      if (n == 0)
        return std::numeric_limits<double>::infinity();
      const double search = n <= 200 ? 1e3 * smallest_side : 4. * a_max;
      return Contact::ContactProjector::minimum_gap(x,
                                                    prm.radii,
                                                    walls,
                                                    dim,
                                                    search,
                                                    periods);
    };

    unsigned int n_active = 0, n_glued = 0, contact_iterations = 0;
    auto         write_step = [&](const unsigned int step,
                          const double       t,
                          const double       dt) {
      TimerOutput::Scope scope(timer, "output");
      for (unsigned int i = 0; i < n; ++i)
        particles_csv.write_row({double(step),
                                 t,
                                 double(i),
                                 X[i][0],
                                 X[i][1],
                                 X[i][2],
                                 U[i][0],
                                 U[i][1],
                                 U[i][2],
                                 W[i][0],
                                 W[i][1],
                                 W[i][2],
                                 prm.radii[i]});
      const double gap = min_gap_of(X);
      summary.min_gap  = std::min(summary.min_gap, gap);
      if (n >= 2)
        {
          double d2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            d2 += std::pow(Contact::PairSearch::minimum_image(X[1][d] - X[0][d],
                                                              periods[d]),
                           2);
          summary.min_normalised_distance =
            std::min(summary.min_normalised_distance,
                     std::sqrt(d2) / (prm.radii[0] + prm.radii[1]));
        }
      const double cells =
        fictitious ? double(tria->n_global_active_cells()) : 0.;
      const double dofs = fictitious ? double(solver->n_dofs()) : 0.;
      statistics_csv.write_row({double(step),
                                t,
                                dt,
                                cells,
                                dofs,
                                double(fluid_stats.uzawa_iterations),
                                double(fluid_stats.linear_iterations),
                                fluid_stats.rigidity_residual,
                                std::isfinite(gap) ? gap : 0.,
                                double(n_active),
                                double(n_glued),
                                wall_clock.wall_time(),
                                double(remeshed),
                                double(contact_iterations)});
      summary.max_uzawa_iterations =
        std::max(summary.max_uzawa_iterations, fluid_stats.uzawa_iterations);
      summary.max_linear_iterations =
        std::max(summary.max_linear_iterations, fluid_stats.linear_iterations);
      summary.max_rigidity_residual =
        std::max(summary.max_rigidity_residual, fluid_stats.rigidity_residual);
      summary.n_cells = cells;
      summary.n_dofs  = dofs;
      if (field_output && step % prm.field_output_interval == 0)
        field_output->write(*solver, solid, step, t);
      if (prm.particle_output_interval > 0 &&
          step % prm.particle_output_interval == 0)
        particle_output.write(step,
                              t,
                              X,
                              prm.radii,
                              U,
                              W,
                              projector.glued_count_per_particle(n));
      if (step % prm.progress_interval == 0)
        {
          const double elapsed = wall_clock.wall_time();
          const double eta = t > 0 ? elapsed / t * (prm.end_time - t) : 0.;
          pcout << "step " << std::setw(6) << step << "  t = " << std::fixed
                << std::setprecision(4) << t << "  dt = " << std::scientific
                << std::setprecision(2) << dt
                << "  gap = " << (std::isfinite(gap) ? gap : 0.)
                << std::defaultfloat;
          if (fictitious)
            pcout << "  cells " << tria->n_global_active_cells() << "  Uzawa "
                  << fluid_stats.uzawa_iterations << "  FGMRES "
                  << fluid_stats.linear_iterations << "  rigidity "
                  << std::scientific << std::setprecision(1)
                  << fluid_stats.rigidity_residual << std::defaultfloat;
          pcout << "  contacts " << n_active << "/" << n_glued << "  ETA "
                << format_time(eta) << std::endl;
        }
    };

    // Step 0: the initial state.
    double t = 0.;
    compute_velocities(t);
    write_step(step, t, 0.);

    if (exact)
      {
        const auto   errors = solver->compute_errors(*exact, solid, true);
        const double g      = shear(0.);
        double       werr = 0, uerr = 0;
        for (unsigned int d = 0; d < 3; ++d)
          {
            const double w_exact = d == 2 ? -0.5 * g : 0.;
            werr += std::pow(W[0][d] - w_exact, 2);
            uerr += std::pow(U[0][d], 2);
          }
        summary.u_l2_error  = errors.u_l2;
        summary.u_h1_error  = errors.u_h1;
        summary.u_l2_norm   = errors.u_l2_norm;
        summary.omega_error = std::sqrt(werr) / std::abs(0.5 * g);
        summary.translation_error =
          std::sqrt(uerr) / std::abs(g * prm.radii[0]);
        pcout << std::scientific << std::setprecision(4)
              << "exact rigid inclusion: cells " << summary.n_cells << ", dofs "
              << summary.n_dofs << ", L2 error of u (fluid) " << errors.u_l2
              << ", L2 norm of exact u (fluid) " << errors.u_l2_norm
              << ", H1 error of u (fluid) " << errors.u_h1
              << ", relative omega error " << summary.omega_error
              << ", |U|/(g a) " << summary.translation_error
              << std::defaultfloat << std::endl;
      }

    double dt_old = 0., t_old = 0.;
    bool   have_history = false;
    while (t < prm.end_time * (1. - 1e-12))
      {
        // Time step (numerics section 5).
        double dt = prm.time_step;
        if (prm.adaptive_time_step)
          {
            double umax = 0;
            for (const auto &v : U)
              umax =
                std::max(umax,
                         std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
            const double h = fictitious ? h_finest : a_min;
            dt             = umax > 0 ?
                               std::min(prm.maximum_time_step, prm.cfl_number * h / umax) :
                               prm.maximum_time_step;
          }
        dt = std::min(dt, prm.end_time - t);

        // AB2 extrapolation of the hydrodynamic velocities. The Stokes
        // problem is quasi-static and linear in the boundary data, so U is
        // the shear rate times a field that depends on the positions only.
        // Extrapolating U / shear and multiplying by the shear rate at the
        // middle of the step is the same formula for a constant shear rate,
        // and stays exact when the shear rate jumps at a step boundary (a
        // reversal 't < T ? 1 : -1'), where plain AB2 would make one step
        // with -2U: an O(dt) error that breaks the reversibility of Stokes
        // flow, which is what the contact models are meant to keep.
        const double      beta   = have_history ? dt / (2. * dt_old) : 0.;
        const double      g_now  = shear(t);
        const double      g_old  = have_history ? shear(t_old) : g_now;
        const double      g_mid  = shear(t + 0.5 * dt);
        const bool        scaled = std::abs(g_now) > 0. && std::abs(g_old) > 0.;
        const double      c_now  = scaled ? g_mid / g_now : 1.;
        const double      c_old  = scaled ? g_mid / g_old : 1.;
        std::vector<Vec3> w_star(n);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            {
              u_star[i][d] =
                (1. + beta) * c_now * U[i][d] - beta * c_old * U_old[i][d];
              w_star[i][d] =
                (1. + beta) * c_now * W[i][d] - beta * c_old * W_old[i][d];
            }

        // Contact: projection onto K.
        {
          TimerOutput::Scope scope(timer, "contact");
          try
            {
              const Contact::ProjectionStatistics cst =
                projector.project(X, prm.radii, u_star, dt, u);
              n_active           = cst.n_active;
              n_glued            = cst.n_glued;
              contact_iterations = cst.iterations;
              summary.max_contact_iterations =
                std::max(summary.max_contact_iterations, cst.iterations);
              if (!cst.converged)
                {
                  ++summary.contact_failures;
                  std::ostringstream m;
                  m << "the contact projection at step " << step + 1
                    << " did not converge: constraint violation "
                    << cst.residual << " > " << cs.tolerance << " after "
                    << cst.iterations << " iterations";
                  warnings.warn("contact projection not converged",
                                m.str(),
                                step + 1,
                                cst.residual);
                }
            }
          catch (const Contact::ContactError &e)
            {
              throw RunError(std::string(e.what()) + " (at step " +
                             std::to_string(step + 1) +
                             ", t = " + std::to_string(t) + ")");
            }
        }

        // Displacement and orientation.
        for (unsigned int i = 0; i < n; ++i)
          {
            for (unsigned int d = 0; d < dim; ++d)
              X[i][d] += dt * u[i][d];
            if (dim == 2)
              angle[i] += dt * w_star[i][2];
            else
              {
                // q <- q + dt/2 (0, w) q, renormalised.
                auto        &q  = quaternion[i];
                const double wx = w_star[i][0], wy = w_star[i][1],
                             wz                = w_star[i][2];
                const std::array<double, 4> dq = {
                  {-wx * q[1] - wy * q[2] - wz * q[3],
                   wx * q[0] + wy * q[3] - wz * q[2],
                   -wx * q[3] + wy * q[0] + wz * q[1],
                   wx * q[2] - wy * q[1] + wz * q[0]}};
                double norm = 0;
                for (unsigned int k = 0; k < 4; ++k)
                  {
                    q[k] += 0.5 * dt * dq[k];
                    norm += q[k] * q[k];
                  }
                for (unsigned int k = 0; k < 4; ++k)
                  q[k] /= std::sqrt(norm);
              }
          }
        U_old        = U;
        W_old        = W;
        dt_old       = dt;
        t_old        = t;
        have_history = true;
        t += dt;
        ++step;

        // A particle whose centre crossed a periodic face comes back
        // through the opposite face; the solid indicator keeps images of
        // particles that straddle it, the contact module works with the
        // minimum image.
        for (unsigned int i = 0; i < n; ++i)
          for (const unsigned int d : periodic)
            {
              const double L = hi[d] - lo[d];
              if (X[i][d] < lo[d])
                X[i][d] += L;
              else if (X[i][d] >= hi[d])
                X[i][d] -= L;
            }

        // A particle that reaches a face where it cannot stay stops the run.
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < dim; ++d)
            if (is_periodic[d])
              continue;
            else if (X[i][d] - prm.radii[i] < lo[d] - cs.overlap_tolerance ||
                     X[i][d] + prm.radii[i] > hi[d] + cs.overlap_tolerance)
              {
                const bool         low     = X[i][d] - prm.radii[i] < lo[d];
                const char         axis[3] = {'x', 'y', 'z'};
                std::ostringstream s;
                s << "particle " << i << " reached the box face " << axis[d]
                  << " = " << (low ? lo[d] : hi[d]) << " at step " << step
                  << ", t = " << t << " (centre " << X[i][d] << ", radius "
                  << prm.radii[i] << "): ";
                if (is_wall_axis[d])
                  s << "it crossed a wall (Contact/Walls = "
                    << (prm.walls ? "true" : "false") << ", Contact/Model "
                    << (prm.contact_model == ContactModel::none ? "none" : "")
                    << ")";
                else
                  s << "it left through an in/outflow face";
                s << "; output up to step " << step - 1 << " is written";
                throw RunError(s.str());
              }

        compute_velocities(t);
        write_step(step, t, dt);
      }

    warnings.summary();
    summary.n_steps      = step;
    summary.final_time   = t;
    summary.positions    = X;
    summary.velocities   = U;
    summary.omegas       = W;
    summary.wall_seconds = wall_clock.wall_time();
    return summary;
  }



  RunSummary
  run_simulation(const Parameters &parameters)
  {
    if (parameters.dimension == 2)
      return Simulation<2>(parameters).run();
    return Simulation<3>(parameters).run();
  }

  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Fidus
