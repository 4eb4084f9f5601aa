#include <cmath>
#include <fidus/contact/contact_error.h>
#include <fidus/core/input_error.h>
#include <fidus/particles/orientation.h>
#include <fidus/simulation/simulation.h>
#include <sstream>

// The stages of the time loop between the predicted velocities and the
// new positions: the sub-grid lubrication, the projection onto the
// admissible set K, and the move.

namespace Fidus
{
  template <int dim>
  const std::vector<RunState::Vec3> &
  Simulation<dim>::correct(PredictedVelocities &p,
                           const double         dt,
                           const bool           trial)
  {
    // A trial (a trapezoidal pass placing its solve) starts from the glue
    // and warm start of the beginning of the step, and leaves them so.
    std::vector<Contact::GlueState::Entry> glue;
    if (trial)
      glue = projector.glue_state().entries();
    add_lubrication(p, dt, trial);
    // The tangential lubrication also changes how the particles turn, and
    // friction in the projection turns them further.
    w_corrected = lubrication ? w_lubricated : p.w;
    project_onto_admissible_set(lubrication ? u_lubricated : p.u,
                                p.middle,
                                dt,
                                trial);
    if (trial)
      projector.restore_glue(glue);
    return u_corrected;
  }



  template <int dim>
  void
  Simulation<dim>::add_lubrication(const PredictedVelocities &p,
                                   const double               dt,
                                   const bool                 trial)
  {
    if (!lubrication)
      return;
    TimerOutput::Scope scope(*timer, "lubrication");
    const unsigned int next = state.step + 1;
    // The walls slide with the shear rate at which the prediction is
    // given, that of the middle of the step. Without it they stood still:
    // in a dense 2D suspension their tangential lubrication braked every
    // disc next to them, and the suspension's lubrication stress came out
    // negative (doc/lubrication.md).
    if (lubrication_in_fluid)
      {
        // The fluid solved the sub-grid resistance with the flow, so the
        // predicted velocities already hold it.
        u_lubricated       = p.u;
        w_lubricated       = p.w;
        record.lubrication = fluid_lubrication;
        if (!trial && prm.contact.model == ContactModel::none)
          check_lubricated_gaps(dt);
        return;
      }
    const double rate = shear(state.time + 0.5 * dt);
    lubrication->set_wall_velocity(
      [this, rate](const Contact::Wall &wall, const Contact::Vec3 &point) {
        return box.wall_velocity(wall, point, rate);
      });
    try
      {
        record.lubrication = lubrication->correct(state.X,
                                                  prm.particles.radii,
                                                  p.u,
                                                  p.w,
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
    if (trial)
      return;
    const Contact::LubricationStatistics &ls = record.lubrication;
    if (!ls.converged)
      {
        std::ostringstream m;
        m << "the lubrication correction at step " << next
          << " did not converge: relative residual " << ls.residual << " after "
          << ls.iterations << " CG iterations";
        warnings.warn("lubrication not converged", m.str(), next, ls.residual);
      }
    // A contact model holds the gap itself.
    if (prm.contact.model == ContactModel::none)
      check_lubricated_gaps(dt);
  }



  template <int dim>
  void
  Simulation<dim>::check_lubricated_gaps(const double dt)
  {
    // The positions move explicitly (X += dt u): a gap that the corrected
    // velocities take past zero within the step stays crossed, and without
    // a contact model nothing stops the pair there (doc/lubrication.md,
    // "Stability"). Say so, rather than let the pair overlap silently.
    const unsigned int next = state.step + 1;
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
  Simulation<dim>::project_onto_admissible_set(
    const std::vector<RunState::Vec3> &u,
    std::vector<RunState::Vec3>       &middle,
    const double                       dt,
    const bool                         trial)
  {
    TimerOutput::Scope scope(*timer, "contact");
    const unsigned int next = state.step + 1;
    try
      {
        // Only glued rows take the middle's normals, and the rows glued
        // are those of the start of the step: without any, the middle
        // changes nothing and one projection is enough.
        Contact::ProjectionStatistics &cst = record.projection;
        if (middle.empty() || projector.n_glued() == 0)
          cst = project(u, nullptr, dt);
        else
          cst = project_with_normals_at_middle(u, middle, dt);
        state.totals.max_contact_iterations =
          std::max(state.totals.max_contact_iterations, cst.iterations);
        if (!cst.converged && !trial)
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
    const std::vector<RunState::Vec3> &u,
    std::vector<RunState::Vec3>       &middle,
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
    const std::vector<RunState::Vec3> w_start = w_corrected;
    double                            length  = 0.;
    for (const double a : prm.particles.radii)
      length = std::max(length, a);
    Contact::ProjectionStatistics cst;
    for (unsigned int repetition = 0;; ++repetition)
      {
        cst           = project(u, &middle, dt);
        double change = 0.;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double mid = state.X[i][d] + 0.5 * dt * u_corrected[i][d];
              change           = std::max(change, std::abs(mid - middle[i][d]));
              middle[i][d]     = mid;
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
        w_corrected = w_start;
      }
  }



  template <int dim>
  Contact::ProjectionStatistics
  Simulation<dim>::project(const std::vector<RunState::Vec3> &u,
                           const std::vector<RunState::Vec3> *middle,
                           const double                       dt)
  {
    // Friction turns the particles: w_corrected goes in as the predicted
    // rotations and comes out corrected. Without friction the rotations
    // are not the projection's business, and the call is the seed's.
    if (contact_settings.friction > 0.)
      {
        // The walls slide with the shear rate of the middle of the step,
        // at which the prediction is given (as in add_lubrication()).
        const double rate = shear(state.time + 0.5 * dt);
        projector.set_wall_velocity(
          [this, rate](const Contact::Wall &wall, const Contact::Vec3 &point) {
            return box.wall_velocity(wall, point, rate);
          });
        const std::vector<RunState::Vec3> w = w_corrected;
        return projector.project(state.X,
                                 prm.particles.radii,
                                 u,
                                 w,
                                 dt,
                                 u_corrected,
                                 w_corrected,
                                 middle);
      }
    if (middle == nullptr)
      return projector.project(state.X,
                               prm.particles.radii,
                               u,
                               dt,
                               u_corrected);
    return projector
      .project(state.X, prm.particles.radii, u, dt, u_corrected, *middle);
  }



  template <int dim>
  void
  Simulation<dim>::advance_particles(const double dt)
  {
    RunState &s = state;
    for (unsigned int i = 0; i < n; ++i)
      {
        for (unsigned int d = 0; d < dim; ++d)
          s.X[i][d] += dt * u_corrected[i][d];
        if (dim == 2)
          s.angle[i] += dt * w_corrected[i][2];
        else
          turn_orientation(s.quaternion[i], w_corrected[i], dt);
      }
    predicted.middle.clear();
    s.U_old          = s.U;
    s.W_old          = s.W;
    s.shear_rate_old = s.shear_rate;
    s.dt_old         = dt;
    s.t_old          = s.time;
    s.have_history   = true;
    s.time += dt;
    ++s.step;

    // A particle whose centre crossed a periodic face comes back through
    // the opposite face; the solid indicator keeps images of particles
    // that straddle it, the contact module works with the minimum image.
    box.wrap(s.X);
    for (unsigned int i = 0; i < n; ++i)
      check_inside_box(i);
  }



  template <int dim>
  void
  Simulation<dim>::check_inside_box(const unsigned int i) const
  {
    const RunState &s = state;
    // After a projection that did not converge (a warning), what it left
    // is tolerated as in the next projection's input.
    const double tol = projector.tolerated_overlap();
    for (unsigned int d = 0; d < dim; ++d)
      if (!box.is_periodic[d] &&
          (s.X[i][d] - prm.particles.radii[i] < box.lo[d] - tol ||
           s.X[i][d] + prm.particles.radii[i] > box.hi[d] + tol))
        {
          const bool low     = s.X[i][d] - prm.particles.radii[i] < box.lo[d];
          const char axis[3] = {'x', 'y', 'z'};
          std::ostringstream m;
          m << "particle " << i << " reached the box face " << axis[d] << " = "
            << (low ? box.lo[d] : box.hi[d]) << " at step " << s.step
            << ", t = " << s.time << " (centre " << s.X[i][d] << ", radius "
            << prm.particles.radii[i] << "): ";
          const ContactModel model = prm.contact.model;
          if (box.is_wall_axis[d])
            {
              m << "it crossed a wall (Contact/Walls = "
                << (prm.contact.walls ? "true" : "false")
                << ", Contact/Model = "
                << (model == ContactModel::none      ? "none" :
                    model == ContactModel::inelastic ? "inelastic" :
                                                       "gluey")
                << ")";
              // With walls in the contact model only a projection that
              // stopped short of its tolerance lets a particle through.
              if (prm.contact.walls && model != ContactModel::none)
                m << "; a contact projection that did not converge (see the "
                     "warnings above) leaves overlaps";
            }
          else
            m << "it left through an in/outflow face";
          m << "; output up to step " << s.step - 1 << " is written";
          throw RunError(m.str());
        }
  }



  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Fidus
