#include "cut_stokes_solve.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/non_matching/fe_immersed_values.h>
#include <deal.II/numerics/vector_tools.h>
#include <fidus/fluid/cut_element/cut_fields.h>
#include <fidus/fluid/cut_element/cut_level_set.h>
#include <fidus/fluid/cut_element/cut_saddle_point_solver.h>
#include <fidus/fluid/fictitious_domain/rigid_mode.h>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

// The stages of CutStokesSolve after the solve: the particles' motions,
// the fluid's mean pressure and the stresslets, the walls' stress, the
// exact inclusion's errors, and the fields kept for output.

namespace Fidus
{
  template <int dim>
  void
  CutStokesSolve<dim>::read_rigid_motion()
  {
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        Tensor<1, dim> U;
        Tensor<1, 3>   omega;
        for (unsigned int d = 0; d < dim; ++d)
          U[d] = solution(n_fluid + p * n_rigid + d);
        for (unsigned int d = dim; d < n_rigid; ++d)
          omega[dim == 2 ? 2 : d - dim] = solution(n_fluid + p * n_rigid + d);
        result.velocity.push_back(U);
        result.angular_velocity.push_back(omega);
      }
  }

  template <int dim>
  void
  CutStokesSolve<dim>::measure_solution()
  {
    // What is measured on the solution, in one pass over the fluid cells
    // (a cut cell's quadratures are generated once): the fluid's mean
    // pressure, each particle's stresslet and, for the exact inclusion,
    // the velocity error.
    //
    // The stresslet comes from the traction that the particle's rigid rows
    // balance: with n the fluid's outward normal, the force on the
    // particle is -int (sigma n - gamma (u - w)), the Nitsche flux, so
    // that a force- and torque-free particle has a stresslet independent
    // of the point its moments are taken about. The pressure is fixed up to
    // a constant, which the stresslets must not see: they take it relative
    // to the fluid's mean p_m, which is known only after the pass, so the
    // pass sums the traction with the raw pressure and the moment
    // int sym((x - X) (x) n) that -p_m n adds to it.
    const auto &balls             = mesh->get_balls();
    double      pressure_integral = 0., volume = 0., error2 = 0.;
    std::vector<SymmetricTensor<2, dim>> normal_moment(particles.size());
    result.stresslets.assign(particles.size(), SymmetricTensor<2, dim>());
    Vector<double> exact_values(dim + 1);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (cell->active_fe_index() != 0)
          continue;
        const Placement &here = placed(cell);
        const auto      &P    = balls[here.ball];
        cell->get_dof_indices(dofs);
        Quadrature<dim> quadrature = q_cell;
        if (here.n_cut > 0)
          {
            generator->generate(
              CutLevelSet<dim>(cell->vertex(0),
                               cell->vertex(
                                 GeometryInfo<dim>::vertices_per_cell - 1),
                               P.center,
                               P.radius),
              unit_box);
            quadrature = generator->get_outside_quadrature();
          }
        if (quadrature.size() > 0)
          {
            FEValues<dim> fe_values(mapping,
                                    taylor_hood,
                                    quadrature,
                                    update_values | update_JxW_values |
                                      update_quadrature_points);
            fe_values.reinit(cell);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                double         p = 0.;
                Tensor<1, dim> u;
                for (unsigned int i = 0; i < n_local; ++i)
                  {
                    p += solution(dofs[i]) * fe_values[pressure].value(i, q);
                    if (exact_case)
                      u += solution(dofs[i]) * fe_values[velocity].value(i, q);
                  }
                pressure_integral += p * fe_values.JxW(q);
                volume += fe_values.JxW(q);
                if (exact_case)
                  {
                    exact->vector_value(fe_values.quadrature_point(q),
                                        exact_values);
                    for (unsigned int d = 0; d < dim; ++d)
                      u[d] -= exact_values[d];
                    error2 += u.norm_square() * fe_values.JxW(q);
                  }
              }
          }
        if (here.n_cut == 0 || generator->get_surface_quadrature().size() == 0)
          continue;
        measure_surface(cell, P, normal_moment);
      }
    result.fluid_volume   = volume;
    result.fluid_pressure = pressure_integral / volume;
    for (unsigned int k = 0; k < particles.size(); ++k)
      result.stresslets[k] -= result.fluid_pressure * normal_moment[k];
    if (exact_case)
      result.velocity_error =
        std::sqrt(error2 / volume) / (g * particles[0].radius);
  }

  template <int dim>
  void
  CutStokesSolve<dim>::measure_surface(
    const cell_iterator                  &cell,
    const Ball                           &P,
    std::vector<SymmetricTensor<2, dim>> &normal_moment)
  {
    const auto        &q_surface = generator->get_surface_quadrature();
    const unsigned int k         = P.owner;
    NonMatching::FEImmersedSurfaceValues<dim> fe_surface(mapping,
                                                         taylor_hood,
                                                         q_surface,
                                                         surface_flags);
    fe_surface.reinit(cell);
    const double gamma = s.nitsche * eta / CutMesh<dim>::shortest_side(cell);
    for (unsigned int q = 0; q < q_surface.size(); ++q)
      {
        const Tensor<1, dim>    n = -fe_surface.normal_vector(q);
        const Tensor<1, dim>    r = fe_surface.quadrature_point(q) - P.center;
        Tensor<1, dim>          u, w;
        SymmetricTensor<2, dim> strain;
        double                  p = 0.;
        for (unsigned int i = 0; i < n_local; ++i)
          {
            const double c = solution(dofs[i]);
            u += c * fe_surface[velocity].value(i, q);
            strain += c * fe_surface[velocity].symmetric_gradient(i, q);
            p += c * fe_surface[pressure].value(i, q);
          }
        for (unsigned int m = 0; m < n_rigid; ++m)
          w += solution(n_fluid + k * n_rigid + m) * rigid_mode<dim>(m, r);
        const Tensor<1, dim> t =
          -(2. * eta * (strain * n) - p * n - gamma * (u - w));
        result.stresslets[k] +=
          symmetrize(outer_product(r, t)) * fe_surface.JxW(q);
        normal_moment[k] += symmetrize(outer_product(r, n)) * fe_surface.JxW(q);
      }
  }

  template <int dim>
  void
  CutStokesSolve<dim>::make_wall_rows()
  {
    // Phi for each wall and component a: 1 at the wall's DoFs of component
    // a (both ends of the periodic wall included), the hanging DoFs
    // interpolated, which reaches the first layer of cells only.
    AffineConstraints<double> hanging;
    DoFTools::make_hanging_node_constraints(dof_handler, hanging);
    hanging.close();
    const auto &support = taylor_hood.get_unit_support_points();
    for (auto &wall : wall_phi)
      for (auto &component : wall)
        component.reinit(n_total);
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (unsigned int side = 0; side < 2; ++side)
        if (cell->active_fe_index() == 0 && cell->at_boundary(2 + side))
          {
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < n_local; ++i)
              {
                const unsigned int a =
                  taylor_hood.system_to_component_index(i).first;
                if (a < dim && std::abs(support[i][1] - side) < 1e-12)
                  wall_phi[side][a][dofs[i]] = 1.;
              }
          }
    wall_rows.assign(n_total, false);
    for (auto &wall : wall_phi)
      for (auto &component : wall)
        {
          hanging.distribute(component);
          for (unsigned int i = 0; i < n_total; ++i)
            if (component[i] != 0.)
              wall_rows[i] = true;
        }
  }

  template <int dim>
  void
  CutStokesSolve<dim>::make_wall_pattern()
  {
    // The wall rows of the system's pattern (which holds the unconstrained
    // entries, and these rows whole on every rank); the other rows get
    // their diagonal alone.
    wall_sparsity
      .fill(n_total, n_total, [&](const unsigned int i, const auto &f) {
        if (wall_rows[i])
          for (auto it = sparsity.begin(i); it != sparsity.end(i); ++it)
            f(it->column());
      });
  }

  template <int dim>
  void
  CutStokesSolve<dim>::wall_stress()
  {
    // The walls' stress, as a rheometer's walls feel it: with Phi a
    // conforming test function that is e_a on one wall and vanishes off
    // its first layer of cells (1 at the wall's DoFs of component a, both
    // ends of the periodic wall included, hanging DoFs interpolated), the
    // residual a(u, Phi) of the unconstrained rows is the wall's force
    // int sigma n . e_a whenever the equations of all other DoFs hold: the
    // same momentum balance the stresslets come from. The two agree as far
    // as the cut cells' volume and surface quadratures obey the divergence
    // theorem (int e(u) over the fluid against the surface terms): to
    // round-off for most positions, to 1e-5 of the particles' stress at
    // worst with 8 points (doc/cut_element.md, "Periodic faces").
    for (unsigned int d = 0; d < dim; ++d)
      result.top_wall_stress[d] = result.bottom_wall_stress[d] =
        periodic ? 0. : std::numeric_limits<double>::quiet_NaN();
    if (!periodic)
      return;
    Vector<double> residual(n_total);
    unconstrained.vmult(residual, solution);
    const double area = dim == 2 ? side(0) : side(0) * side(2);
    for (unsigned int side = 0; side < 2; ++side)
      for (unsigned int a = 0; a < dim; ++a)
        {
          // sigma e_y: the force on the top wall (n = e_y), minus the
          // force on the bottom one, over the wall's area.
          const double force = wall_phi[side][a] * residual / area;
          if (side == 1)
            result.top_wall_stress[a] = force;
          else
            result.bottom_wall_stress[a] = -force;
        }
    // The pressure relative to the fluid's mean, as in the stresslets:
    // a constant c in p adds -c int div Phi = -c int Phi . n.
    result.top_wall_stress[1] += result.fluid_pressure;
    result.bottom_wall_stress[1] += result.fluid_pressure;
  }

  template <int dim>
  void
  CutStokesSolve<dim>::exact_inclusion_errors()
  {
    if (!exact_case)
      return;
    // U is zero and omega = -g/2 e_z for the exact particle.
    const double a     = particles[0].radius;
    result.translation = result.velocity[0].norm() / (g * a);
    result.omega_error =
      std::abs(result.angular_velocity[0][2] + 0.5 * g) / (0.5 * g);
    // The deviatoric part: the isotropic part depends on the pressure
    // the moments are taken against, the fluid's mean here, which in a
    // box around an off-centre particle differs from the far field's
    // (zero) by O(a^2) of the pressure scale.
    SymmetricTensor<2, dim> exact_stresslet;
    exact_stresslet[0][1] = (dim == 2 ? 4. * numbers::PI * a * a :
                                        20. / 3. * numbers::PI * a * a * a) *
                            eta * 0.5 * g;
    result.stresslet_error =
      (deviator(result.stresslets[0]) - exact_stresslet).norm() /
      exact_stresslet.norm();
  }

  template <int dim>
  void
  CutStokesSolve<dim>::keep_fields()
  {
    // The solve's own DoFHandler is a member that dies with it; a second
    // one on the same mesh, with the same finite element on every cell,
    // numbers the DoFs the same way (distribute_dofs is deterministic), so
    // the fluid unknowns carry over as they are.
    auto fields = std::make_shared<CutFields<dim>>();
    fields->dof_handler =
      std::make_unique<DoFHandler<dim>>(mesh->get_triangulation());
    for (const auto &cell : fields->dof_handler->active_cell_iterators())
      cell->set_active_fe_index(placed(cell).solid ? 1 : 0);
    fields->dof_handler->distribute_dofs(fe_collection);
    if (fields->dof_handler->n_dofs() != n_fluid)
      throw std::logic_error("CutStokesSolve: the kept DoFs differ from the "
                             "solve's");
    fields->solution.reinit(n_fluid);
    fields->is_pressure.resize(n_fluid);
    for (unsigned int i = 0; i < n_fluid; ++i)
      {
        fields->solution[i]    = solution[i];
        fields->is_pressure[i] = is_pressure[i];
      }
    fields->fluid_pressure = result.fluid_pressure;
    for (unsigned int i = n_fluid; i < n_total; ++i)
      fields->rigid.push_back(solution[i]);
    fields->shear_rate   = g;
    fields->proportional = true;
    for (const auto &P : particles)
      {
        fields->proportional = fields->proportional && P.force.norm() == 0.;
        fields->centers.push_back(P.center);
      }
    // The mesh goes last: the solve's DoFHandler, still attached to it,
    // detaches when the solve ends, and the mesh lives on in the fields.
    fields->mesh  = std::move(mesh);
    result.fields = fields;
  }

  template void
  CutStokesSolve<2>::read_rigid_motion();
  template void
  CutStokesSolve<2>::measure_solution();
  template void
  CutStokesSolve<2>::make_wall_pattern();
  template void
  CutStokesSolve<2>::wall_stress();
  template void
  CutStokesSolve<2>::make_wall_rows();
  template void
  CutStokesSolve<2>::exact_inclusion_errors();
  template void
  CutStokesSolve<2>::keep_fields();
  template void
  CutStokesSolve<2>::measure_surface(const CutStokesSolve<2>::cell_iterator &,
                                     const CutStokesSolve<2>::Ball &,
                                     std::vector<SymmetricTensor<2, 2>> &);
  template void
  CutStokesSolve<3>::read_rigid_motion();
  template void
  CutStokesSolve<3>::measure_solution();
  template void
  CutStokesSolve<3>::make_wall_pattern();
  template void
  CutStokesSolve<3>::wall_stress();
  template void
  CutStokesSolve<3>::make_wall_rows();
  template void
  CutStokesSolve<3>::exact_inclusion_errors();
  template void
  CutStokesSolve<3>::keep_fields();
  template void
  CutStokesSolve<3>::measure_surface(const CutStokesSolve<3>::cell_iterator &,
                                     const CutStokesSolve<3>::Ball &,
                                     std::vector<SymmetricTensor<2, 3>> &);
} // namespace Fidus
