#include "output_columns.h"

#include <algorithm>
#include <cmath>
#include <deal.II/base/mpi.h>
#include <fidus/contact/contact_error.h>
#include <fidus/core/input_error.h>
#include <fidus/mesh/box_mesh.h>
#include <fidus/particles/rigid_motion.h>
#include <fidus/simulation/simulation.h>
#include <fidus/simulation/stop_request.h>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

namespace Fidus
{
  using Vec3 = RunState::Vec3;

  namespace
  {
    Contact::Settings
    contact_settings_of(const Parameters &prm, const unsigned int dim)
    {
      double a_min = 1.;
      if (!prm.radii.empty())
        a_min = *std::min_element(prm.radii.begin(), prm.radii.end());
      Contact::Settings cs;
      cs.dimension         = dim;
      cs.model             = prm.contact_model == ContactModel::none ?
                               Contact::Model::none :
                             prm.contact_model == ContactModel::inelastic ?
                               Contact::Model::inelastic :
                               Contact::Model::gluey;
      cs.solver            = prm.dual_solver == "projected gradient" ?
                               Contact::DualSolver::projected_gradient :
                             prm.dual_solver == "accelerated projected gradient" ?
                               Contact::DualSolver::accelerated_projected_gradient :
                               Contact::DualSolver::projected_gauss_seidel;
      cs.tolerance         = prm.contact_tolerance * a_min;
      cs.alert_distance    = prm.alert_distance * a_min;
      cs.overlap_tolerance = 2. * cs.tolerance;
      return cs;
    }

    /**
     * Run @p work and make a failure there stop every rank: rank 0's
     * message is shared and every rank throws it as a RunError headed by
     * @p what. Work that only rank 0 does (files of the output directory)
     * would otherwise fail on rank 0 alone and leave the other ranks
     * waiting in their next collective call.
     */
    template <typename F>
    void
    failure_stops_every_rank(const MPI_Comm     comm,
                             const std::string &what,
                             F                &&work)
    {
      std::string error;
      try
        {
          work();
        }
      catch (const std::exception &e)
        {
          error = e.what();
        }
      error = Utilities::MPI::broadcast(comm, error, 0);
      if (!error.empty())
        throw RunError(what + ": " + error);
    }

    /**
     * The speed an external force alone gives a particle, the largest over
     * the particles: |F| / (6 pi eta a) for a sphere (Stokes) and
     * |F| / (4 pi eta) for a disc (the 2D drag has no free-space value;
     * 4 pi eta is its size at a few radii from walls). A scale for the
     * Uzawa stop, not a prediction; 0 without forces.
     */
    double
    forced_velocity_scale(const Parameters &prm)
    {
      double u = 0.;
      for (unsigned int i = 0; i < prm.external_forces.size(); ++i)
        {
          double f2 = 0.;
          for (const double c : prm.external_forces[i])
            f2 += c * c;
          const double drag =
            prm.dimension == 3 ?
              6. * M_PI * prm.viscosity *
                prm.radii[std::min<std::size_t>(i, prm.radii.size() - 1)] :
              4. * M_PI * prm.viscosity;
          u = std::max(u, std::sqrt(f2) / drag);
        }
      return u;
    }

  } // namespace



  template <int dim>
  Simulation<dim>::Simulation(const Parameters              &parameters,
                              const Checkpoint::ResumePoint *resume_point)
    : prm(parameters)
    , resume(resume_point)
    , comm(MPI_COMM_WORLD)
    , root(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    , pcout(std::cout, root && parameters.verbosity != Verbosity::quiet)
    , timer(std::make_unique<TimerOutput>(MPI_COMM_WORLD,
                                          pcout,
                                          TimerOutput::never,
                                          TimerOutput::wall_times))
    , box(parameters)
    , shear(parameters.shear_rate)
    , fictitious(parameters.fluid_model == FluidModel::fictitious_domain)
    , cut(parameters.fluid_model == FluidModel::cut_finite_element)
    , n(parameters.n_particles())
    , contact_settings(contact_settings_of(parameters, dim))
    , projector(contact_settings)
    , boundary(parameters.boundary_condition, box.lo[1], box.hi[1])
    , warnings(std::cerr, root)
  {
    projector.set_walls(box.walls);
    projector.set_periodicity(box.periods);
    if (parameters.gap_step_fraction > 0.)
      gap_step = std::make_unique<GapTimeStep>(parameters.gap_step_fraction,
                                               parameters.gap_step_floor,
                                               dim,
                                               box.walls,
                                               box.periods);
    // A contact correction u - u* is a velocity; the force that gives it to
    // an isolated particle is its Stokes drag (doc/rheology.md).
    double mean_radius = 0.;
    for (const double a : parameters.radii)
      mean_radius += a / std::max<std::size_t>(1, parameters.radii.size());
    contact_drag =
      parameters.drag_coefficient > 0. ?
        parameters.drag_coefficient :
        (dim == 3 ? 6. * numbers::PI * parameters.viscosity * mean_radius :
                    4. * numbers::PI * parameters.viscosity);

    if (parameters.lubrication)
      {
        Contact::LubricationSettings ls;
        ls.dimension = dim;
        ls.viscosity = parameters.viscosity;
        ls.range = parameters.lubrication_range * parameters.finest_cell_size();
        ls.wall_range =
          parameters.lubrication_wall_range * parameters.finest_cell_size();
        ls.flow_range =
          parameters.lubrication_flow_range * parameters.finest_cell_size();
        ls.tangential_range = parameters.lubrication_tangential_range *
                              parameters.finest_cell_size();
        ls.tangential_wall_range =
          parameters.lubrication_wall_tangential_range *
          parameters.finest_cell_size();
        ls.roughness        = parameters.roughness;
        ls.nothing_resolved = !fictitious;
        ls.drag             = parameters.drag_coefficient;
        ls.tangential       = parameters.lubrication_tangential;
        lubrication = std::make_unique<Contact::LubricationCorrection>(ls);
        lubrication->set_walls(box.walls);
        lubrication->set_periodicity(box.periods);
        // The force density is spread over each particle's solid, so the
        // fluid solve is driven by the whole force.
        lubrication->set_external_forces(parameters.external_forces);
      }

    solid_radii = parameters.radii;
    for (double &a : solid_radii)
      a -= parameters.solid_retraction * box.h_finest;
    solid.set_smoothing_width(parameters.solid_smoothing * box.h_finest);

    if (root)
      std::filesystem::create_directories(prm.output_directory);
    MPI_Barrier(comm);

    if (!fictitious)
      return;
    tria = std::make_unique<parallel::distributed::Triangulation<dim>>(
      comm,
      typename Triangulation<dim>::MeshSmoothing(
        Triangulation<dim>::smoothing_on_refinement |
        Triangulation<dim>::smoothing_on_coarsening));
    // A checkpoint's forest is loaded onto the coarse mesh; a new run
    // starts from the globally refined one.
    create_box_mesh(*tria,
                    box.lo,
                    box.hi,
                    box.periodic,
                    resume ? 0 : prm.initial_global_refinement);

    typename StokesSolver<dim>::Settings ss;
    ss.degree                     = prm.velocity_degree;
    ss.viscosity                  = prm.viscosity;
    ss.penalty_factor             = prm.penalty_factor;
    ss.rigidity_tolerance         = prm.rigidity_tolerance;
    ss.rigidity_per_particle      = prm.rigidity_per_particle;
    ss.rigid_velocity_tolerance   = prm.rigid_velocity_tolerance;
    ss.forced_velocity_scale      = forced_velocity_scale(prm);
    ss.sliver_threshold           = prm.sliver_threshold;
    ss.max_uzawa_iterations       = prm.max_uzawa_iterations;
    ss.linear_tolerance           = prm.linear_tolerance;
    ss.inexact_uzawa_factor       = prm.inexact_uzawa_factor;
    ss.max_cheap_iterations       = prm.max_cheap_iterations;
    ss.max_linear_iterations      = prm.max_linear_iterations;
    ss.amg_aggregation_threshold  = prm.amg_aggregation_threshold;
    ss.amg_smoother_sweeps        = prm.amg_smoother_sweeps;
    ss.amg_smoother_type          = prm.amg_smoother_type;
    ss.direct_max_unknowns        = prm.direct_max_unknowns;
    ss.geometric_multigrid        = prm.geometric_multigrid;
    ss.mg_smoother_degree         = prm.mg_smoother_degree;
    ss.mg_viscosity_averaging     = prm.mg_viscosity_averaging;
    ss.mg_smoother_blocks         = prm.mg_smoother_blocks;
    ss.rigid_body_correction      = prm.rigid_body_correction;
    ss.matrix_free_velocity_block = prm.matrix_free_velocity_block;
    ss.reuse_multiplier           = prm.reuse_multiplier;
    ss.release_shared_cells       = prm.release_shared_cells;
    ss.verbose                    = prm.verbosity == Verbosity::verbose;
    solver = std::make_unique<StokesSolver<dim>>(*tria, ss);
    hydrodynamic_stress =
      std::make_unique<HydrodynamicStress<dim>>(box.dirichlet_ids);

    typename MeshRefiner<dim>::Settings ms;
    ms.minimum_level = prm.minimum_level;
    ms.maximum_level = prm.maximum_level;
    ms.band          = prm.interface_band;
    ms.gap_distance  = prm.gap_refinement_distance;
    refiner          = std::make_unique<MeshRefiner<dim>>(ms);

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
    if (!prm.external_forces.empty())
      external_force =
        std::make_unique<ParticleForceDensity<dim>>(solid, prm.external_forces);
  }



  template <int dim>
  Simulation<dim>::~Simulation() = default;



  template <int dim>
  RunSummary
  Simulation<dim>::run()
  {
    // SIGTERM / SIGINT / SIGUSR1 finish the step and checkpoint.
    const StopRequest stop_request;
    try
      {
        if (resume)
          resume_from_checkpoint();
        else
          start();

        while (!finished())
          {
            const double dt = choose_time_step();
            extrapolate_velocities(dt);
            average_with_end_of_step_velocities(dt);
            add_lubrication(dt);
            project_onto_admissible_set(dt);
            advance_particles(dt);
            predict_velocities();
            measure_stress(dt);
            write_output(dt);
            if (checkpoint_or_stop())
              break;
          }
      }
    catch (...)
      {
        // The timer is destroyed before the error propagates, so that it
        // neither communicates nor prints while the run stops.
        timer.reset();
        throw;
      }

    warnings.summary();
    if (prm.verbosity != Verbosity::quiet)
      timer->print_summary();

    RunSummary s              = exact_errors;
    s.n_steps                 = state.step;
    s.final_time              = state.time;
    s.positions               = state.X;
    s.velocities              = state.U;
    s.omegas                  = state.W;
    s.min_gap                 = state.totals.min_gap;
    s.min_normalised_distance = state.totals.min_normalised_distance;
    s.max_uzawa_iterations    = state.totals.max_uzawa_iterations;
    s.max_linear_iterations   = state.totals.max_linear_iterations;
    s.max_rigidity_residual   = state.totals.max_rigidity_residual;
    s.uzawa_failures          = state.totals.uzawa_failures;
    s.contact_failures        = state.totals.contact_failures;
    s.max_contact_iterations  = state.totals.max_contact_iterations;
    s.max_shared_cells        = state.totals.max_shared_cells;
    s.max_shared_residual     = state.totals.max_shared_residual;
    s.n_cells = fictitious ? tria->n_global_active_cells() : cut_cells;
    s.n_dofs  = fictitious ? solver->n_dofs() : cut_dofs;
    s.multigrid_galerkin_defect =
      fictitious ? solver->multigrid_galerkin_defect() : 0.;
    s.wall_seconds   = elapsed_wall_seconds();
    s.stop_signal    = stop_signal;
    s.stress         = stress;
    s.solid_fraction = hydrodynamic.solid_fraction;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        {
          s.hydrodynamic_stress[3 * a + b] = hydrodynamic.total[a][b];
          s.wall_stress[3 * a + b]         = hydrodynamic.wall[a][b];
          s.mean_strain_rate[3 * a + b] = hydrodynamic.mean_strain_rate[a][b];
        }
    for (const auto &t : hydrodynamic.stresslets)
      s.stresslets.push_back(
        {{t[0][0], t[0][1], t[0][2], t[1][1], t[1][2], t[2][2]}});
    return s;
  }



  template <int dim>
  void
  Simulation<dim>::start()
  {
    // A new run rewrites the CSV files of this Output directory, so a
    // checkpoint of an earlier run there no longer matches them: remove it,
    // so that '--resume' cannot continue the old run into the new files.
    if (root)
      for (const auto &entry :
           std::filesystem::directory_iterator(prm.output_directory))
        if (entry.path().filename().string().rfind("checkpoint-", 0) == 0)
          {
            std::error_code ignored;
            std::filesystem::remove_all(entry.path(), ignored);
          }
    state.initialise(prm.positions);
    particles_csv =
      std::make_unique<CsvWriter>(prm.output_directory + "/particles.csv",
                                  OutputColumns::particle_columns(),
                                  root);
    statistics_csv =
      std::make_unique<CsvWriter>(prm.output_directory + "/statistics.csv",
                                  OutputColumns::statistics_columns(),
                                  root);
    particle_output =
      std::make_unique<ParticleOutput>(prm.output_directory,
                                       root &&
                                         prm.particle_output_interval > 0);
    if (fictitious && prm.field_output_interval > 0)
      field_output = std::make_unique<FieldOutput<dim>>(prm.output_directory);

    predict_velocities();
    measure_stress(0.);
    write_output(0.);
    if (exact)
      report_exact_solution_errors();
  }



  template <int dim>
  void
  Simulation<dim>::resume_from_checkpoint()
  {
    state = resume->state;
    warnings.restore(state.warnings);
    projector.restore_glue(state.glue);
    if (fictitious)
      {
        TimerOutput::Scope scope(*timer, "checkpoint");
        tria->load(Checkpoint::mesh_file(resume->folder));
        solver->load_from_checkpoint(box.periodic,
                                     box.dirichlet_ids,
                                     state.multiplier_valid);
      }
    // Rows and collection entries after the checkpoint's step are dropped:
    // those steps are computed again. Rank 0 rewrites the files; a problem
    // there (a damaged CSV file) stops every rank.
    failure_stops_every_rank(comm, "resuming from " + resume->folder, [&]() {
      particles_csv =
        std::make_unique<CsvWriter>(prm.output_directory + "/particles.csv",
                                    OutputColumns::particle_columns(),
                                    root,
                                    state.step);
      statistics_csv =
        std::make_unique<CsvWriter>(prm.output_directory + "/statistics.csv",
                                    OutputColumns::statistics_columns(),
                                    root,
                                    state.step);
      particle_output =
        std::make_unique<ParticleOutput>(prm.output_directory,
                                         root &&
                                           prm.particle_output_interval > 0);
      particle_output->resume(state.step);
      if (fictitious && prm.field_output_interval > 0)
        {
          field_output =
            std::make_unique<FieldOutput<dim>>(prm.output_directory);
          field_output->resume(state.step, root);
        }
    });
    pcout << "fidus: resumed from " << resume->folder << " at step "
          << state.step << ", t = " << state.time << ", on "
          << Utilities::MPI::n_mpi_processes(comm)
          << (Utilities::MPI::n_mpi_processes(comm) == 1 ? " rank" : " ranks")
          << std::endl;
  }



  template <int dim>
  bool
  Simulation<dim>::finished() const
  {
    return state.time >= prm.end_time * (1. - 1e-12);
  }



  template <int dim>
  double
  Simulation<dim>::choose_time_step() const
  {
    double dt = prm.time_step;
    if (prm.adaptive_time_step)
      {
        double umax = 0;
        for (const auto &v : state.U)
          umax =
            std::max(umax, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
        const double h = fictitious || cut ? box.h_finest : box.a_min;
        dt             = umax > 0 ?
                           std::min(prm.maximum_time_step, prm.cfl_number * h / umax) :
                           prm.maximum_time_step;
      }
    if (gap_step)
      {
        // The fluid's velocities, not the lubricated ones: below the mesh
        // scale they close a gap up to 20 times faster than the
        // correction lets the pair move, and that margin is what keeps a
        // lubricated pair without a contact model from overlapping once
        // its gap is below the floor, where nothing limits the step. With
        // the lubricated velocities the steps were 3 to 6 times fewer,
        // and such a pair overlapped (doc/results.md).
        dt = gap_step
               ->limit(state.X, prm.radii, state.U, dt, &projector.glue_state())
               .dt;
        // AB2 extrapolates with dt / (2 dt_old): a step that more than
        // doubles after a closest approach would weigh the old velocities
        // by more than one and amplify their difference.
        if (state.have_history)
          dt = std::min(dt, 2. * state.dt_old);
      }
    // The last step ends at the End time. A remainder that differs from
    // the step only by round-off (an End time that is a multiple of a fixed
    // step) is taken as the full step, so that a run makes the same steps
    // as a longer one, and one resumed with a later End time continues
    // bit-identically.
    const double remaining = prm.end_time - state.time;
    return dt <= remaining * (1. + 1e-9) ? dt : remaining;
  }



  template <int dim>
  void
  Simulation<dim>::add_lubrication(const double dt)
  {
    if (!lubrication)
      return;
    TimerOutput::Scope scope(*timer, "lubrication");
    const unsigned int next = state.step + 1;
    // The walls slide with the shear rate at which u_star is given, that of
    // the middle of the step (extrapolate_velocities()). Without it they
    // stood still: in a dense 2D suspension their tangential lubrication
    // braked every disc next to them, and the suspension's lubrication
    // stress came out negative (doc/lubrication.md).
    const double rate = shear(state.time + 0.5 * dt);
    lubrication->set_wall_velocity(
      [this, rate](const Contact::Wall &wall, const Contact::Vec3 &point) {
        return box.wall_velocity(wall, point, rate);
      });
    try
      {
        lubrication_stats = lubrication->correct(state.X,
                                                 prm.radii,
                                                 u_star,
                                                 w_star,
                                                 u_lubricated,
                                                 w_lubricated,
                                                 dt);
      }
    catch (const Contact::ContactError &e)
      {
        throw RunError(std::string(e.what()) + " (at step " +
                       std::to_string(next) +
                       ", t = " + std::to_string(state.time) + ")");
      }
    // A trapezoidal pass's trial only places the solve; the final
    // lubrication and projection of the step report their own trouble.
    if (trial_pass)
      return;
    if (!lubrication_stats.converged)
      {
        std::ostringstream m;
        m << "the lubrication correction at step " << next
          << " did not converge: relative residual "
          << lubrication_stats.residual << " after "
          << lubrication_stats.iterations << " CG iterations";
        warnings.warn("lubrication not converged",
                      m.str(),
                      next,
                      lubrication_stats.residual);
      }

    // The positions move explicitly (X += dt u): a gap that the corrected
    // velocities take past zero within the step stays crossed, and without
    // a contact model nothing stops the pair there (doc/lubrication.md,
    // "Stability"). Say so, rather than let the pair overlap silently. A
    // contact model holds the gap itself.
    if (prm.contact_model != ContactModel::none)
      return;
    using Contact::LubricationCorrection;
    for (const Contact::LubricationBond &b : lubrication->bonds())
      {
        const bool pair = b.j != Contact::LubricationBond::no_particle;
        // A wall bond has a_j = 0.
        const double after =
          LubricationCorrection::length_after_step(b, u_lubricated, dt) -
          b.a_i - b.a_j;
        const double closing =
          LubricationCorrection::approach_speed(b, u_lubricated);
        if (b.gap > 0. && after < 0.)
          {
            std::ostringstream m;
            m << "the lubrication correction cannot hold the gap of particle "
              << b.i
              << (pair ? " and particle " + std::to_string(b.j) :
                         std::string(" and a wall"))
              << " at step " << next << ": the step of " << dt
              << " takes it from " << b.gap << " to " << after
              << " (explicit positions; Contact/Model = none lets the "
              << "particles overlap)";
            if (closing > 0.)
              m << "; a time step below " << b.gap / closing
                << " (gap / closing speed) or a contact model keeps it open";
            else
              m << "; a smaller time step or a contact model keeps it open";
            warnings.warn("lubrication gap closed in one step",
                          m.str(),
                          next,
                          -after / b.gap);
            break;
          }
      }
  }



  template <int dim>
  void
  Simulation<dim>::project_onto_admissible_set(const double dt)
  {
    TimerOutput::Scope scope(*timer, "contact");
    const unsigned int next = state.step + 1;
    try
      {
        const std::vector<RunState::Vec3> &predicted =
          lubrication ? u_lubricated : u_star;
        // Only glued rows take the middle's normals, and the rows glued
        // are those of the start of the step: without any, the middle
        // changes nothing and one projection is enough.
        Contact::ProjectionStatistics cst;
        if (X_mid.empty() || projector.n_glued() == 0)
          cst =
            projector.project(state.X, prm.radii, predicted, dt, u_corrected);
        else
          cst = project_with_normals_at_middle(predicted, dt);
        n_active           = cst.n_active;
        n_glued            = cst.n_glued;
        contact_iterations = cst.iterations;
        state.totals.max_contact_iterations =
          std::max(state.totals.max_contact_iterations, cst.iterations);
        if (!cst.converged && !trial_pass)
          {
            ++state.totals.contact_failures;
            std::ostringstream m;
            m << "the contact projection at step " << next
              << " did not converge: constraint violation " << cst.residual
              << " > " << contact_settings.tolerance << " after "
              << cst.iterations << " iterations";
            warnings.warn("contact projection not converged",
                          m.str(),
                          next,
                          cst.residual);
          }
      }
    catch (const Contact::ContactError &e)
      {
        throw RunError(std::string(e.what()) + " (at step " +
                       std::to_string(next) +
                       ", t = " + std::to_string(state.time) + ")");
      }
  }



  template <int dim>
  Contact::ProjectionStatistics
  Simulation<dim>::project_with_normals_at_middle(
    const std::vector<RunState::Vec3> &predicted,
    const double                       dt)
  {
    // A glued pair keeps its distance exactly when its row's normal is the
    // line of centres at the exact middle of the step
    // (ContactProjector::project). That middle depends on the corrected
    // velocities, so the projection is repeated from the glue of the start
    // of the step, each time with the middle the last one reached. The
    // distance error is about |change of the middle| dt |u_j - u_i| / |d|,
    // and each repetition multiplies the change by about dt |u_j - u_i| /
    // |d|, a small number: the estimate of the trapezoidal pass is already
    // O(dt^3) off, and two or three repetitions take it to round-off.
    const std::vector<Contact::GlueState::Entry> glue =
      projector.glue_state().entries();
    double length = 0.;
    for (const double a : prm.radii)
      length = std::max(length, a);
    Contact::ProjectionStatistics cst;
    for (unsigned int repetition = 0;; ++repetition)
      {
        cst = projector
                .project(state.X, prm.radii, predicted, dt, u_corrected, X_mid);
        double change = 0.;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double mid = state.X[i][d] + 0.5 * dt * u_corrected[i][d];
              change           = std::max(change, std::abs(mid - X_mid[i][d]));
              X_mid[i][d]      = mid;
            }
        if (change <= 1e-13 * length)
          return cst;
        if (repetition == 20)
          {
            std::ostringstream m;
            m << "the glued pairs' normals at the middle of step "
              << state.step + 1 << " did not settle: the middle still moved by "
              << change << " after " << repetition + 1
              << " projections (glued distances may drift by about that "
                 "much times dt |u_j - u_i| / |d|)";
            warnings.warn("glued normals not settled",
                          m.str(),
                          state.step + 1,
                          change / length);
            return cst;
          }
        projector.restore_glue(glue);
      }
  }



  template <int dim>
  void
  Simulation<dim>::advance_particles(const double dt)
  {
    RunState &s = state;
    // The tangential lubrication also changes how the particles turn.
    const std::vector<RunState::Vec3> &w_turn =
      lubrication ? w_lubricated : w_star;
    for (unsigned int i = 0; i < n; ++i)
      {
        for (unsigned int d = 0; d < dim; ++d)
          s.X[i][d] += dt * u_corrected[i][d];
        if (dim == 2)
          s.angle[i] += dt * w_turn[i][2];
        else
          {
            // q <- q + dt/2 (0, w) q, renormalised.
            auto        &q  = s.quaternion[i];
            const double wx = w_turn[i][0], wy = w_turn[i][1],
                         wz                = w_turn[i][2];
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
    X_mid.clear();
    s.U_old        = s.U;
    s.W_old        = s.W;
    s.dt_old       = dt;
    s.t_old        = s.time;
    s.have_history = true;
    s.time += dt;
    ++s.step;

    // A particle whose centre crossed a periodic face comes back through
    // the opposite face; the solid indicator keeps images of particles
    // that straddle it, the contact module works with the minimum image.
    box.wrap(s.X);

    // A particle that reaches a face where it cannot stay stops the run.
    const double tol = contact_settings.overlap_tolerance;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int d = 0; d < dim; ++d)
        if (!box.is_periodic[d] &&
            (s.X[i][d] - prm.radii[i] < box.lo[d] - tol ||
             s.X[i][d] + prm.radii[i] > box.hi[d] + tol))
          {
            const bool         low     = s.X[i][d] - prm.radii[i] < box.lo[d];
            const char         axis[3] = {'x', 'y', 'z'};
            std::ostringstream m;
            m << "particle " << i << " reached the box face " << axis[d]
              << " = " << (low ? box.lo[d] : box.hi[d]) << " at step " << s.step
              << ", t = " << s.time << " (centre " << s.X[i][d] << ", radius "
              << prm.radii[i] << "): ";
            if (box.is_wall_axis[d])
              m << "it crossed a wall (Contact/Walls = "
                << (prm.walls ? "true" : "false") << ", Contact/Model "
                << (prm.contact_model == ContactModel::none ? "none" : "")
                << ")";
            else
              m << "it left through an in/outflow face";
            m << "; output up to step " << s.step - 1 << " is written";
            throw RunError(m.str());
          }
  }



  template <int dim>
  bool
  Simulation<dim>::checkpoint_or_stop()
  {
    // One collective decision: the largest signal number any rank received
    // (a batch system signals every rank, a user perhaps one), and the
    // wall-clock interval measured on rank 0.
    int local[2] = {StopRequest::signal_received(), 0};
    if (root && prm.checkpoint_wall_interval > 0 &&
        wall_clock.wall_time() - last_checkpoint_wall >=
          prm.checkpoint_wall_interval)
      local[1] = 1;
    int global[2] = {0, 0};
    MPI_Allreduce(local, global, 2, MPI_INT, MPI_MAX, comm);

    const bool checkpoints_on =
      prm.checkpoint_interval > 0 || prm.checkpoint_wall_interval > 0;
    const bool due = global[0] != 0 || global[1] != 0 ||
                     (prm.checkpoint_interval > 0 &&
                      state.step % prm.checkpoint_interval == 0) ||
                     (checkpoints_on && finished());
    if (due)
      {
        write_checkpoint();
        // A signal that came while the checkpoint was written stops the run
        // now: this step is saved, and another step might not fit in the
        // grace period a batch system gives.
        if (global[0] == 0)
          global[0] = Utilities::MPI::max(StopRequest::signal_received(), comm);
      }
    if (global[0] == 0)
      return false;

    stop_signal = global[0];
    if (root)
      std::cerr << "fidus: " << StopRequest::name(stop_signal)
                << " received: stopped after step " << state.step
                << ", t = " << state.time << ", with a checkpoint in "
                << Checkpoint::folder(prm.output_directory, state.step)
                << "; continue with 'fidus --resume' and the same parameter "
                   "file"
                << std::endl;
    return true;
  }



  template <int dim>
  void
  Simulation<dim>::write_checkpoint()
  {
    Timer             clock;
    const std::string temporary =
      Checkpoint::temporary_folder(prm.output_directory, state.step);
    const std::string final_folder =
      Checkpoint::folder(prm.output_directory, state.step);
    // Rank 0 makes the folder; a failure (disk full, permissions) stops
    // every rank, not rank 0 alone.
    const std::string failed = "writing the checkpoint of step " +
                               std::to_string(state.step) + " failed";
    failure_stops_every_rank(comm, failed, [&]() {
      if (root)
        {
          std::filesystem::remove_all(temporary);
          std::filesystem::create_directories(temporary);
        }
    });

    TimerOutput::Scope scope(*timer, "checkpoint");
    if (fictitious)
      {
        solver->prepare_for_checkpoint();
        tria->save(Checkpoint::mesh_file(temporary));
        solver->finish_checkpoint();
      }
    MPI_Barrier(comm);

    RunState saved            = state;
    saved.multiplier_valid    = fictitious && solver->multiplier_is_valid();
    saved.glue                = projector.glue_state().entries();
    saved.warnings            = warnings.get_tallies();
    saved.wall_seconds_before = elapsed_wall_seconds();
    unsigned long long bytes  = 0;
    failure_stops_every_rank(comm, failed, [&]() {
      if (root)
        bytes = Checkpoint::commit(temporary,
                                   final_folder,
                                   prm,
                                   saved,
                                   Utilities::MPI::n_mpi_processes(comm));
    });
    bytes                = Utilities::MPI::broadcast(comm, bytes, 0);
    last_checkpoint_wall = wall_clock.wall_time();
    pcout << "checkpoint " << final_folder << ": " << bytes << " bytes, "
          << std::fixed << std::setprecision(3) << clock.wall_time() << " s"
          << std::defaultfloat << std::endl;
  }



  template <int dim>
  double
  Simulation<dim>::elapsed_wall_seconds() const
  {
    return state.wall_seconds_before + wall_clock.wall_time();
  }



  RunSummary
  run_simulation(const Parameters              &parameters,
                 const Checkpoint::ResumePoint *resume)
  {
    if (parameters.dimension == 2)
      return Simulation<2>(parameters, resume).run();
    return Simulation<3>(parameters, resume).run();
  }

  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Fidus
