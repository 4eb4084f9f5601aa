#include "output_columns.h"

#include <algorithm>
#include <cmath>
#include <deal.II/base/mpi.h>
#include <fidus/core/input_error.h>
#include <fidus/core/memory_usage.h>
#include <fidus/fluid/fluid_model_factory.h>
#include <fidus/particles/isolated_drag.h>
#include <fidus/simulation/simulation.h>
#include <fidus/simulation/stop_request.h>
#include <fidus/time_stepping/adams_bashforth.h>
#include <fidus/time_stepping/trapezoidal_scheme.h>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

// The time loop, its set-up and the choice of the time step.

namespace Fidus
{
  namespace
  {
    /// The contact library's settings, its tolerances relative to the
    /// smallest radius.
    Contact::Settings
    contact_settings_of(const Parameters &prm, const unsigned int dim)
    {
      double a_min = 1.;
      if (!prm.particles.radii.empty())
        a_min = *std::min_element(prm.particles.radii.begin(),
                                  prm.particles.radii.end());
      return prm.contact.settings(dim, a_min);
    }



    /// The time scheme Time stepping/Scheme names.
    template <int dim>
    std::unique_ptr<TimeScheme<dim>>
    create_time_scheme(const Parameters       &prm,
                       const ShearRate        &shear,
                       const BoxGeometry<dim> &box)
    {
      const bool forced = !prm.particles.external_forces.empty();
      if (prm.time_stepping.scheme == TimeSchemeType::trapezoidal)
        return std::make_unique<TrapezoidalScheme<dim>>(
          shear,
          box,
          forced,
          prm.domain.boundary_condition !=
            BoundaryCondition::exact_rigid_inclusion,
          prm.time_stepping.trapezoidal_iterations);
      return std::make_unique<AdamsBashforth2<dim>>(shear, forced);
    }



    /// The sub-grid lubrication of Fluid/Lubrication correction (null when
    /// off), with what the fluid model @p fluid resolves of a gap.
    template <int dim>
    std::unique_ptr<Contact::LubricationCorrection>
    create_lubrication(const Parameters       &prm,
                       const BoxGeometry<dim> &box,
                       const FluidModel<dim>  &fluid)
    {
      if (!prm.lubrication.enabled)
        return nullptr;
      Contact::LubricationSettings ls =
        prm.lubrication.settings(dim,
                                 prm.finest_cell_size(),
                                 prm.fluid.viscosity,
                                 prm.contact.roughness,
                                 prm.contact.drag_coefficient,
                                 fluid.resolves_gap_flow());
      ls.resolved_gap_fraction = fluid.resolved_gap_fraction();
      auto lubrication = std::make_unique<Contact::LubricationCorrection>(ls);
      lubrication->set_walls(box.walls);
      lubrication->set_periodicity(box.periods);
      // The force density is spread over each particle's solid, so the
      // fluid solve is driven by the whole force.
      lubrication->set_external_forces(prm.particles.external_forces);
      return lubrication;
    }
  } // namespace



  template <int dim>
  Simulation<dim>::Simulation(const Parameters                &parameters,
                              const Checkpoint::ResumePoint   *resume_point,
                              std::unique_ptr<FluidModel<dim>> fluid_model)
    : prm(parameters)
    , resume(resume_point)
    , comm(MPI_COMM_WORLD)
    , root(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    , pcout(std::cout, root && parameters.output.verbosity != Verbosity::quiet)
    , timer(std::make_unique<TimerOutput>(MPI_COMM_WORLD,
                                          pcout,
                                          TimerOutput::never,
                                          TimerOutput::wall_times))
    , warnings(std::cerr, root)
    , box(parameters)
    , shear(parameters.domain.shear_rate)
    , n(parameters.n_particles())
    , fluid(fluid_model ? std::move(fluid_model) :
                          create_fluid_model<dim>(parameters,
                                                  box,
                                                  resume_point != nullptr,
                                                  *timer,
                                                  warnings))
    , scheme(create_time_scheme<dim>(parameters, shear, box))
    , contact_settings(contact_settings_of(parameters, dim))
    , projector(contact_settings)
    , lubrication(create_lubrication<dim>(parameters, box, *fluid))
  {
    projector.set_walls(box.walls);
    projector.set_periodicity(box.periods);
    if (parameters.time_stepping.gap_step_fraction > 0.)
      gap_step = std::make_unique<GapTimeStep>(
        parameters.time_stepping.gap_step_fraction,
        parameters.time_stepping.gap_step_floor,
        dim,
        box.walls,
        box.periods);
    if (lubrication && fluid->solves_subgrid_lubrication())
      {
        fluid->set_subgrid_lubrication(lubrication.get());
        lubrication_in_fluid = true;
      }
    // 'Lubrication coupling = auto' chooses by the scene: say which.
    if (lubrication)
      {
        std::ostringstream line;
        line << "lubrication correction "
             << (lubrication_in_fluid ? "solved with the flow" :
                                        "after the solve")
             << " (the particles fill " << std::setprecision(3)
             << 100. * parameters.particle_volume_fraction()
             << " % of the box)";
        pcout << line.str() << std::endl;
      }
    // A contact correction u - u* is a velocity; the force that gives it to
    // an isolated particle is its drag (doc/rheology.md).
    double mean_radius = 0.;
    for (const double a : parameters.particles.radii)
      mean_radius +=
        a / std::max<std::size_t>(1, parameters.particles.radii.size());
    contact_drag =
      parameters.contact.drag_coefficient > 0. ?
        parameters.contact.drag_coefficient :
        isolated_drag(dim, parameters.fluid.viscosity, mean_radius);
    // With friction the projection's metric is each particle's isolated
    // resistance relative to that of the mean radius (so that a multiplier
    // times contact_drag is still a force): 6 pi eta a and 8 pi eta a^3 for
    // a sphere, 4 pi eta and 4 pi eta a^2 for a disc (the projector's
    // default rotational weights). Without friction the seed's unit
    // weights stay, and every result with them.
    if (parameters.contact.friction_coefficient > 0. && dim == 3)
      {
        std::vector<double> weights(n);
        for (unsigned int i = 0; i < n; ++i)
          weights[i] = parameters.particles.radii[i] / mean_radius;
        projector.set_weights(weights);
      }

    if (root)
      std::filesystem::create_directories(prm.output_directory);
    MPI_Barrier(comm);
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
            scheme->predict(state, dt, *this, predicted);
            correct(predicted, dt, false);
            advance_particles(dt);
            record.fluid     = scheme->velocities_after_step(state, *this);
            state.shear_rate = shear(state.time);
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
    if (prm.output.verbosity != Verbosity::quiet)
      timer->print_summary();
    RunSummary s = summary();
    s.peak_memory_per_rank =
      Utilities::MPI::max(double(MemoryUsage::peak_bytes()), comm);
    if (s.peak_memory_per_rank > 0.)
      pcout << "peak memory per rank: "
            << MemoryUsage::format(s.peak_memory_per_rank)
            << " (the largest of " << Utilities::MPI::n_mpi_processes(comm)
            << ")" << std::endl;
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
    state.initialise(prm.particles.positions);
    fluid->open_field_output(prm.output_directory, nullptr);
    // The files are opened once the first solve is done: a run stopped
    // there (a mesh that does not fit in memory, a solve that does not
    // converge) leaves no empty CSV files behind.
    record.fluid     = solve_at_current_positions();
    state.shear_rate = shear(state.time);
    particles_csv =
      std::make_unique<CsvWriter>(prm.output_directory + "/particles.csv",
                                  OutputColumns::particle_columns(),
                                  root);
    statistics_csv =
      std::make_unique<CsvWriter>(prm.output_directory + "/statistics.csv",
                                  OutputColumns::statistics_columns(),
                                  root);
    particle_output = std::make_unique<ParticleOutput>(
      prm.output_directory,
      root && prm.output.particle_output_interval > 0);
    measure_stress(0.);
    write_output(0.);
  }



  template <int dim>
  bool
  Simulation<dim>::finished() const
  {
    return state.time >= prm.time_stepping.end_time * (1. - 1e-12);
  }



  template <int dim>
  double
  Simulation<dim>::choose_time_step() const
  {
    double dt = prm.time_stepping.time_step;
    if (prm.time_stepping.adaptive_time_step)
      {
        double umax = 0;
        for (const auto &v : state.U)
          umax =
            std::max(umax, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
        const double h = fluid->cfl_length();
        dt = umax > 0 ? std::min(prm.time_stepping.maximum_time_step,
                                 prm.time_stepping.cfl_number * h / umax) :
                        prm.time_stepping.maximum_time_step;
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
               ->limit(state.X,
                       prm.particles.radii,
                       state.U,
                       dt,
                       &projector.glue_state())
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
    const double remaining = prm.time_stepping.end_time - state.time;
    return dt <= remaining * (1. + 1e-9) ? dt : remaining;
  }



  template <int dim>
  typename Simulation<dim>::Statistics
  Simulation<dim>::solve_at(const std::vector<Vec3> &X,
                            const double             g,
                            const SolveLabel        &label,
                            std::vector<Vec3>       &U,
                            std::vector<Vec3>       &W)
  {
    // The sub-grid lubrication solved with the flow sees the walls move
    // with the rate of this solve, and its bonds' forces are those of the
    // velocities solved.
    if (lubrication_in_fluid)
      lubrication->set_wall_velocity(
        [this, g](const Contact::Wall &wall, const Contact::Vec3 &point) {
          return box.wall_velocity(wall, point, g);
        });
    const Statistics stats = fluid->rigid_velocities(X, g, label, U, W);
    if (lubrication_in_fluid)
      fluid_lubrication = lubrication->measure(U, W);
    if (!stats.converged)
      ++state.totals.uzawa_failures;
    return stats;
  }



  template <int dim>
  typename Simulation<dim>::Statistics
  Simulation<dim>::solve_at_current_positions()
  {
    return solve_at(state.X,
                    shear(state.time),
                    {state.step,
                     "step " + std::to_string(state.step) +
                       ", t = " + std::to_string(state.time)},
                    state.U,
                    state.W);
  }



  template <int dim>
  double
  Simulation<dim>::elapsed_wall_seconds() const
  {
    return state.wall_seconds_before + wall_clock.wall_time();
  }



  template <int dim>
  RunSummary
  Simulation<dim>::summary() const
  {
    RunSummary s;
    fluid->add_to_summary(s);
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
    s.wall_seconds            = elapsed_wall_seconds();
    s.stop_signal             = stop_signal;
    s.stress                  = record.stress;
    const auto &h             = record.hydrodynamic;
    s.solid_fraction          = h.solid_fraction;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        {
          s.hydrodynamic_stress[3 * a + b] = h.total[a][b];
          s.wall_stress[3 * a + b]         = h.wall[a][b];
          s.mean_strain_rate[3 * a + b]    = h.mean_strain_rate[a][b];
        }
    for (const auto &t : h.stresslets)
      s.stresslets.push_back(
        {{t[0][0], t[0][1], t[0][2], t[1][1], t[1][2], t[2][2]}});
    return s;
  }



  namespace
  {
    template <int dim>
    RunSummary
    run_in_dimension(const Parameters              &parameters,
                     const Checkpoint::ResumePoint *resume,
                     const std::string             &used_parameters)
    {
      // Constructed first: a scene the fluid model refuses writes nothing.
      Simulation<dim> simulation(parameters, resume);
      if (!used_parameters.empty() &&
          Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        {
          std::ofstream out(parameters.output_directory +
                            "/used_parameters.prm");
          out << used_parameters;
        }
      return simulation.run();
    }
  } // namespace



  RunSummary
  run_simulation(const Parameters              &parameters,
                 const Checkpoint::ResumePoint *resume,
                 const std::string             &used_parameters)
  {
    if (parameters.dimension == 2)
      return run_in_dimension<2>(parameters, resume, used_parameters);
    return run_in_dimension<3>(parameters, resume, used_parameters);
  }

  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Fidus
