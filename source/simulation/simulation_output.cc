#include "output_columns.h"

#include <algorithm>
#include <cmath>
#include <fidus/contact/pair_search.h>
#include <fidus/rheology/contact_stress.h>
#include <fidus/rheology/lubrication_stress.h>
#include <fidus/rheology/plane_strain.h>
#include <fidus/simulation/progress_line.h>
#include <fidus/simulation/simulation.h>
#include <iomanip>
#include <limits>

// The stages of the time loop that measure and write: the stress, the CSV
// rows, VTU/VTP files and the progress line.

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
    if (dt > 0. && g_now != 0. && prm.particles.external_forces.empty())
      {
        const double g_before = shear(state.time - 1e-6 * dt);
        if (std::abs(g_before - g_now) >
            1e-3 * std::max(std::abs(g_before), std::abs(g_now)))
          g = g_before;
      }
    record.hydrodynamic                = fluid->hydrodynamic_stress(g);
    const auto           &hydrodynamic = record.hydrodynamic;
    SymmetricTensor<2, 3> contact      = contact_stress(projector.constraints(),
                                                   prm.particles.radii,
                                                   contact_drag,
                                                   hydrodynamic.volume);
    SymmetricTensor<2, 3> lubricated =
      lubrication ?
        lubrication_stress(lubrication->bonds(), hydrodynamic.volume) :
        SymmetricTensor<2, 3>();
    // Solved with the flow, the bonds' forces are those of the solve at
    // this time, linear in its rate like the fluid's stress: rescaled with
    // it (after the solve they are the step's, driven by the rate before).
    record.lubrication_scale =
      lubrication_in_fluid && g != g_now ? g / g_now : 1.;
    lubricated *= record.lubrication_scale;
    // The forces between discs press on their cylinders' axial stress as
    // the resolved gap pressure does (with_plane_strain_zz()).
    if (dim == 2)
      {
        contact    = with_plane_strain_zz(contact);
        lubricated = with_plane_strain_zz(lubricated);
      }
    record.stress = SuspensionStress::combine(hydrodynamic.total,
                                              hydrodynamic.particle,
                                              hydrodynamic.wall[0][1],
                                              contact,
                                              prm.fluid.viscosity,
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
    if (s.step % prm.output.particle_csv_interval == 0)
      write_particle_rows();

    double gap = std::numeric_limits<double>::infinity();
    if (n > 0)
      gap = Contact::ContactProjector::minimum_gap(s.X,
                                                   prm.particles.radii,
                                                   box.walls,
                                                   dim,
                                                   n <= 200 ?
                                                     1e3 * box.smallest_side :
                                                     4. * box.a_max,
                                                   box.periods);
    const Statistics &fs     = record.fluid;
    RunTotals        &totals = state.totals;
    totals.min_gap           = std::min(totals.min_gap, gap);
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
                   std::sqrt(d2) /
                     (prm.particles.radii[0] + prm.particles.radii[1]));
      }
    totals.max_uzawa_iterations =
      std::max(totals.max_uzawa_iterations, fs.uzawa_iterations);
    totals.max_linear_iterations =
      std::max(totals.max_linear_iterations, fs.linear_iterations);
    totals.max_rigidity_residual =
      std::max(totals.max_rigidity_residual, fs.rigidity_residual);
    totals.max_shared_cells =
      std::max(totals.max_shared_cells, fs.shared_cells);
    totals.max_shared_residual =
      std::max(totals.max_shared_residual, fs.shared_residual);

    const Contact::ProjectionStatistics &cst = record.projection;
    std::vector<double>                  row = {double(s.step),
                                                s.time,
                                                dt,
                                                double(fs.n_cells),
                                                double(fs.n_dofs),
                                                double(fs.uzawa_iterations),
                                                double(fs.linear_iterations),
                                                fs.rigidity_residual,
                               std::isfinite(gap) ? gap : 0.,
                                                double(cst.n_active),
                                                double(cst.n_glued),
                                                elapsed_wall_seconds(),
                                                double(fs.remeshed),
                                                double(cst.iterations),
                                                double(fs.shared_cells),
                                                fs.shared_residual};
    for (const double v : record.stress.values())
      row.push_back(v);
    row.push_back(
      double(record.lubrication.n_pairs + record.lubrication.n_wall_pairs));
    row.push_back(fs.rigid_velocity_change);
    row.push_back(fs.particle_rigidity_residual);
    row.push_back(double(cst.n_sliding));
    statistics_csv->write_row(row);

    fluid->write_fields(s.step, s.time);
    if (prm.output.particle_output_interval > 0 &&
        s.step % prm.output.particle_output_interval == 0)
      particle_output->write(s.step,
                             s.time,
                             s.X,
                             prm.particles.radii,
                             s.U,
                             s.W,
                             projector.glued_count_per_particle(n));
    write_progress_line(dt, gap);
  }



  template <int dim>
  void
  Simulation<dim>::write_particle_rows()
  {
    const RunState                    &s = state;
    std::vector<SymmetricTensor<2, 3>> contact =
      contact_stresslets(projector.constraints(),
                         prm.particles.radii,
                         contact_drag);
    std::vector<SymmetricTensor<2, 3>> lubricated =
      lubrication ? lubrication_stresslets(lubrication->bonds(), n) :
                    std::vector<SymmetricTensor<2, 3>>(n);
    for (SymmetricTensor<2, 3> &l : lubricated)
      l *= record.lubrication_scale;
    if (dim == 2)
      for (unsigned int i = 0; i < n; ++i)
        {
          contact[i]    = with_plane_strain_zz(contact[i]);
          lubricated[i] = with_plane_strain_zz(lubricated[i]);
        }
    for (unsigned int i = 0; i < n; ++i)
      {
        const SymmetricTensor<2, 3> &h = record.hydrodynamic.stresslets[i];
        const SymmetricTensor<2, 3> &c = contact[i];
        const SymmetricTensor<2, 3> &l = lubricated[i];
        const bool moved = u_corrected.size() == n && w_corrected.size() == n;
        const RunState::Vec3  zero{{0., 0., 0.}};
        const RunState::Vec3 &u = moved ? u_corrected[i] : zero;
        const RunState::Vec3 &w = moved ? w_corrected[i] : zero;
        std::array<double, 4> q{{1., 0., 0., 0.}};
        if (dim == 2 && i < s.angle.size())
          q = {
            {std::cos(0.5 * s.angle[i]), 0., 0., std::sin(0.5 * s.angle[i])}};
        else if (dim == 3 && i < s.quaternion.size())
          q = s.quaternion[i];
        particles_csv->write_row({double(s.step),
                                  s.time,
                                  double(i),
                                  s.X[i][0],
                                  s.X[i][1],
                                  s.X[i][2],
                                  s.U[i][0],
                                  s.U[i][1],
                                  s.U[i][2],
                                  s.W[i][0],
                                  s.W[i][1],
                                  s.W[i][2],
                                  prm.particles.radii[i],
                                  h[0][0],
                                  h[0][1],
                                  h[0][2],
                                  h[1][1],
                                  h[1][2],
                                  h[2][2],
                                  c[0][0],
                                  c[0][1],
                                  c[0][2],
                                  c[1][1],
                                  c[1][2],
                                  c[2][2],
                                  l[0][0],
                                  l[0][1],
                                  l[0][2],
                                  l[1][1],
                                  l[1][2],
                                  l[2][2],
                                  u[0],
                                  u[1],
                                  u[2],
                                  w[0],
                                  w[1],
                                  w[2],
                                  q[0],
                                  q[1],
                                  q[2],
                                  q[3]});
      }
  }



  template <int dim>
  void
  Simulation<dim>::write_progress_line(const double dt, const double gap)
  {
    // Every 'Progress interval' steps, or by wall clock (the first and the
    // last step always).
    const RunState &s   = state;
    const double    now = wall_clock.wall_time();
    const bool      due =
      prm.output.progress_interval > 0 ?
             s.step % prm.output.progress_interval == 0 :
             last_progress_wall < 0. ||
          now - last_progress_wall >= prm.output.progress_wall_interval;
    if (!due && !finished())
      return;
    last_progress_wall   = now;
    const Statistics &fs = record.fluid;
    ProgressLine      line;
    line.step               = s.step;
    line.time               = s.time;
    line.dt                 = dt;
    line.gap                = std::isfinite(gap) ? gap : 0.;
    line.cells              = fs.n_cells;
    line.uzawa              = fs.uzawa_iterations;
    line.fgmres             = fs.linear_iterations;
    line.rigidity_residual  = fs.rigidity_residual;
    line.shared             = fs.shared_cells;
    line.active             = record.projection.n_active;
    line.glued              = record.projection.n_glued;
    line.relative_viscosity = record.stress.relative_viscosity;
    line.eta                = s.time > 0 ? elapsed_wall_seconds() / s.time *
                              (prm.time_stepping.end_time - s.time) :
                                           0.;
    pcout << line.text() << std::endl;
  }



  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Fidus
