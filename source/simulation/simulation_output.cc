#include "output_columns.h"

#include <algorithm>
#include <cmath>
#include <fidus/rheology/contact_stress.h>
#include <fidus/rheology/lubrication_stress.h>
#include <fidus/rheology/plane_strain.h>
#include <fidus/simulation/progress_line.h>
#include <fidus/simulation/simulation.h>
#include <iomanip>
#include <limits>

// The stages of the time loop that measure and write: the stress, the CSV
// rows, VTU/VTP files and the progress line, the exact-solution errors.

namespace Fidus
{
  template <int dim>
  void
  Simulation<dim>::measure_stress(const double dt)
  {
    TimerOutput::Scope scope(*timer, "stress");
    // A row pairs the fluid solved at this time with the contact and
    // lubrication forces of the step that led here, which the shear rate
    // before this time drove. Where the shear rate jumps at this time (a
    // reversal 't < T ? 1 : -1'), the fluid was just solved with the new
    // rate, and dividing the old contact stress by the new rate gave a row
    // that belonged to neither side. Stokes flow is linear in the shear
    // rate, so the fluid's stress under the rate before the jump is the
    // solved one rescaled: the row then describes one instant, the end of
    // the step just before the jump, and the next row is the first of the
    // new rate. External forces add a part that does not scale, and a zero
    // rate cannot be rescaled; those rows keep the rate at this time.
    const double g_now = shear(state.time);
    double       g     = g_now;
    if (dt > 0. && g_now != 0. && prm.external_forces.empty())
      {
        const double g_before = shear(state.time - 1e-6 * dt);
        if (std::abs(g_before - g_now) >
            1e-3 * std::max(std::abs(g_before), std::abs(g_now)))
          g = g_before;
      }
    if (fictitious || cut)
      {
        // The cut element's stress comes with its last solve (its walls'
        // traction only between sliding walls, NaN otherwise).
        hydrodynamic =
          cut ? cut_stress : hydrodynamic_stress->compute(*solver, solid);
        if (g != g_now)
          hydrodynamic.scale(g / g_now);
      }
    else
      {
        // Free-draining particles carry no stress of their own: the
        // undisturbed shear flow's viscous stress.
        hydrodynamic        = typename HydrodynamicStress<dim>::Result();
        hydrodynamic.volume = 1.;
        for (unsigned int d = 0; d < dim; ++d)
          hydrodynamic.volume *= box.hi[d] - box.lo[d];
        hydrodynamic.total[0][1]            = prm.viscosity * g;
        hydrodynamic.mean_strain_rate[0][1] = 0.5 * g;
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            hydrodynamic.wall[a][b] = std::numeric_limits<double>::quiet_NaN();
        hydrodynamic.stresslets.assign(n, SymmetricTensor<2, 3>());
      }
    SymmetricTensor<2, 3> contact = contact_stress(projector.constraints(),
                                                   prm.radii,
                                                   contact_drag,
                                                   hydrodynamic.volume);
    SymmetricTensor<2, 3> lubricated =
      lubrication ?
        lubrication_stress(lubrication->bonds(), hydrodynamic.volume) :
        SymmetricTensor<2, 3>();
    // The forces between discs press on their cylinders' axial stress as
    // the resolved gap pressure does (with_plane_strain_zz()).
    if (dim == 2)
      {
        contact    = with_plane_strain_zz(contact);
        lubricated = with_plane_strain_zz(lubricated);
      }
    stress = SuspensionStress::combine(hydrodynamic.total,
                                       hydrodynamic.particle,
                                       hydrodynamic.wall[0][1],
                                       contact,
                                       prm.viscosity,
                                       g,
                                       dim,
                                       lubricated);
  }



  template <int dim>
  void
  Simulation<dim>::write_output(const double dt)
  {
    TimerOutput::Scope scope(*timer, "output");
    const RunState    &s = state;
    if (s.step % prm.particle_csv_interval == 0)
      {
        std::vector<SymmetricTensor<2, 3>> contact =
          contact_stresslets(projector.constraints(), prm.radii, contact_drag);
        std::vector<SymmetricTensor<2, 3>> lubricated =
          lubrication ? lubrication_stresslets(lubrication->bonds(), n) :
                        std::vector<SymmetricTensor<2, 3>>(n);
        if (dim == 2)
          for (unsigned int i = 0; i < n; ++i)
            {
              contact[i]    = with_plane_strain_zz(contact[i]);
              lubricated[i] = with_plane_strain_zz(lubricated[i]);
            }
        for (unsigned int i = 0; i < n; ++i)
          {
            const SymmetricTensor<2, 3> &h = hydrodynamic.stresslets[i];
            const SymmetricTensor<2, 3> &c = contact[i];
            const SymmetricTensor<2, 3> &l = lubricated[i];
            particles_csv->write_row(
              {double(s.step), s.time,    double(i),    s.X[i][0], s.X[i][1],
               s.X[i][2],      s.U[i][0], s.U[i][1],    s.U[i][2], s.W[i][0],
               s.W[i][1],      s.W[i][2], prm.radii[i], h[0][0],   h[0][1],
               h[0][2],        h[1][1],   h[1][2],      h[2][2],   c[0][0],
               c[0][1],        c[0][2],   c[1][1],      c[1][2],   c[2][2],
               l[0][0],        l[0][1],   l[0][2],      l[1][1],   l[1][2],
               l[2][2]});
          }
      }

    double gap = std::numeric_limits<double>::infinity();
    if (n > 0)
      gap = Contact::ContactProjector::minimum_gap(s.X,
                                                   prm.radii,
                                                   box.walls,
                                                   dim,
                                                   n <= 200 ?
                                                     1e3 * box.smallest_side :
                                                     4. * box.a_max,
                                                   box.periods);
    RunTotals &totals = state.totals;
    totals.min_gap    = std::min(totals.min_gap, gap);
    if (n >= 2)
      {
        double d2 = 0;
        for (unsigned int d = 0; d < dim; ++d)
          d2 +=
            std::pow(Contact::PairSearch::minimum_image(s.X[1][d] - s.X[0][d],
                                                        box.periods[d]),
                     2);
        totals.min_normalised_distance =
          std::min(totals.min_normalised_distance,
                   std::sqrt(d2) / (prm.radii[0] + prm.radii[1]));
      }
    totals.max_uzawa_iterations =
      std::max(totals.max_uzawa_iterations, fluid_stats.uzawa_iterations);
    totals.max_linear_iterations =
      std::max(totals.max_linear_iterations, fluid_stats.linear_iterations);
    totals.max_rigidity_residual =
      std::max(totals.max_rigidity_residual, fluid_stats.rigidity_residual);
    totals.max_shared_cells =
      std::max(totals.max_shared_cells, fluid_stats.shared_cells);
    totals.max_shared_residual =
      std::max(totals.max_shared_residual, fluid_stats.shared_residual);

    const double cells =
      fictitious ? double(tria->n_global_active_cells()) : double(cut_cells);
    const double dofs =
      fictitious ? double(solver->n_dofs()) : double(cut_dofs);
    std::vector<double> row = {double(s.step),
                               s.time,
                               dt,
                               cells,
                               dofs,
                               double(fluid_stats.uzawa_iterations),
                               double(fluid_stats.linear_iterations),
                               fluid_stats.rigidity_residual,
                               std::isfinite(gap) ? gap : 0.,
                               double(n_active),
                               double(n_glued),
                               elapsed_wall_seconds(),
                               double(remeshed),
                               double(contact_iterations),
                               double(fluid_stats.shared_cells),
                               fluid_stats.shared_residual};
    for (const double v : stress.values())
      row.push_back(v);
    row.push_back(
      double(lubrication_stats.n_pairs + lubrication_stats.n_wall_pairs));
    row.push_back(fluid_stats.rigid_velocity_change);
    row.push_back(fluid_stats.particle_rigidity_residual);
    statistics_csv->write_row(row);

    if (field_output && s.step % prm.field_output_interval == 0)
      field_output->write(*solver, solid, s.step, s.time);
    if (prm.particle_output_interval > 0 &&
        s.step % prm.particle_output_interval == 0)
      particle_output->write(s.step,
                             s.time,
                             s.X,
                             prm.radii,
                             s.U,
                             s.W,
                             projector.glued_count_per_particle(n));

    // Progress: every 'Progress interval' steps, or by wall clock (the
    // first and the last step always).
    const double now = wall_clock.wall_time();
    const bool   due = prm.progress_interval > 0 ?
                         s.step % prm.progress_interval == 0 :
                         last_progress_wall < 0. ||
                         now - last_progress_wall >= prm.progress_wall_interval;
    if (due || finished())
      {
        last_progress_wall = now;
        ProgressLine line;
        line.step              = s.step;
        line.time              = s.time;
        line.dt                = dt;
        line.gap               = std::isfinite(gap) ? gap : 0.;
        line.fluid             = fictitious;
        line.cells             = fictitious ? tria->n_global_active_cells() : 0;
        line.uzawa             = fluid_stats.uzawa_iterations;
        line.fgmres            = fluid_stats.linear_iterations;
        line.rigidity_residual = fluid_stats.rigidity_residual;
        line.shared            = fluid_stats.shared_cells;
        line.active            = n_active;
        line.glued             = n_glued;
        line.eta               = s.time > 0 ?
                                   elapsed_wall_seconds() / s.time * (prm.end_time - s.time) :
                                   0.;
        pcout << line.text() << std::endl;
      }
  }



  template <int dim>
  void
  Simulation<dim>::report_exact_solution_errors()
  {
    const auto   errors = solver->compute_errors(*exact, solid, true);
    const double g      = shear(0.);
    double       werr = 0, uerr = 0;
    for (unsigned int d = 0; d < 3; ++d)
      {
        const double w_exact = d == 2 ? -0.5 * g : 0.;
        werr += std::pow(state.W[0][d] - w_exact, 2);
        uerr += std::pow(state.U[0][d], 2);
      }
    RunSummary &e       = exact_errors;
    e.u_l2_error        = errors.u_l2;
    e.u_h1_error        = errors.u_h1;
    e.u_l2_norm         = errors.u_l2_norm;
    e.omega_error       = std::sqrt(werr) / std::abs(0.5 * g);
    e.translation_error = std::sqrt(uerr) / std::abs(g * prm.radii[0]);
    pcout << std::scientific << std::setprecision(4)
          << "exact rigid inclusion: cells " << tria->n_global_active_cells()
          << ", dofs " << solver->n_dofs() << ", L2 error of u (fluid) "
          << errors.u_l2 << ", L2 norm of exact u (fluid) " << errors.u_l2_norm
          << ", H1 error of u (fluid) " << errors.u_h1
          << ", relative omega error " << e.omega_error << ", |U|/(g a) "
          << e.translation_error << std::defaultfloat << std::endl;
  }



  template void
  Simulation<2>::measure_stress(double);
  template void
  Simulation<3>::measure_stress(double);
  template void
  Simulation<2>::write_output(double);
  template void
  Simulation<3>::write_output(double);
  template void
  Simulation<2>::report_exact_solution_errors();
  template void
  Simulation<3>::report_exact_solution_errors();
} // namespace Fidus
