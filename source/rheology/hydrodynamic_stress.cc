#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>
#include <fidus/rheology/hydrodynamic_stress.h>
#include <fidus/rheology/plane_strain.h>
#include <limits>
#include <map>

namespace Fidus
{
  namespace
  {
    /// A dim x dim symmetric tensor in the top-left block of a 3 x 3 one.
    template <int dim>
    SymmetricTensor<2, 3>
    embed(const SymmetricTensor<2, dim> &t)
    {
      SymmetricTensor<2, 3> r;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          r[i][j] = t[i][j];
      return r;
    }

    /// Append the 6 independent entries of @p t to @p v at @p offset.
    void
    add_to(std::vector<double>         &v,
           const std::size_t            offset,
           const SymmetricTensor<2, 3> &t,
           const double                 weight)
    {
      for (unsigned int k = 0; k < 6; ++k)
        v[offset + k] +=
          weight * t[SymmetricTensor<2, 3>::unrolled_to_component_indices(k)];
    }

    SymmetricTensor<2, 3>
    read_from(const std::vector<double> &v, const std::size_t offset)
    {
      SymmetricTensor<2, 3> t;
      for (unsigned int k = 0; k < 6; ++k)
        t[SymmetricTensor<2, 3>::unrolled_to_component_indices(k)] =
          v[offset + k];
      return t;
    }


    /// The box (its faces are the walls): the smallest and largest vertex
    /// coordinates over all ranks.
    template <int dim>
    std::pair<Point<dim>, Point<dim>>
    global_box_bounds(const StokesSolver<dim> &solver, const MPI_Comm comm)
    {
      // The box (its faces are the walls).
      Point<dim> box_lo, box_hi;
      for (unsigned int d = 0; d < dim; ++d)
        {
          box_lo[d] = std::numeric_limits<double>::max();
          box_hi[d] = -std::numeric_limits<double>::max();
        }
      for (const auto &cell : solver.get_cells())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < dim; ++d)
            {
              box_lo[d] = std::min(box_lo[d], cell->vertex(v)[d]);
              box_hi[d] = std::max(box_hi[d], cell->vertex(v)[d]);
            }
      for (unsigned int d = 0; d < dim; ++d)
        {
          box_lo[d] = Utilities::MPI::min(box_lo[d], comm);
          box_hi[d] = Utilities::MPI::max(box_hi[d], comm);
        }
      return {box_lo, box_hi};
    }



    /// The fields of one cell at its quadrature points, and its candidate
    /// particles; reused from cell to cell.
    template <int dim>
    struct CellFields
    {
      explicit CellFields(const unsigned int n_q)
        : p(n_q)
        , e_u(n_q)
        , e_lambda(n_q)
        , sigma(n_q)
      {}

      std::vector<double>                  p;
      std::vector<SymmetricTensor<2, dim>> e_u, e_lambda;
      std::vector<SymmetricTensor<2, dim>> sigma;
      std::vector<unsigned int>            cands;
    };



    /// Adds the cell's stress, strain rate, fluid pressure and volumes to
    /// the box sums @p box and the particle sums @p part; leaves the stress
    /// at the quadrature points in @p f.sigma for the wall residual.
    template <int dim>
    void
    integrate_cell(const StokesSolver<dim>                              &solver,
                   const SolidIndicator<dim>                            &solid,
                   const typename DoFHandler<dim>::active_cell_iterator &cell,
                   FEValues<dim>       &fe_values,
                   CellFields<dim>     &f,
                   std::vector<double> &box,
                   std::vector<double> &part)
    {
      using Tensor3                           = SymmetricTensor<2, 3>;
      const double                     eta_f  = solver.get_settings().viscosity;
      const auto                      &shared = solver.get_shared_cells();
      const auto                      &solution = solver.get_solution();
      const unsigned int               n_q      = fe_values.n_quadrature_points;
      const FEValuesExtractors::Vector velocities(0);
      const FEValuesExtractors::Scalar pressure(dim);

      fe_values.reinit(cell);
      fe_values[pressure].get_function_values(solution, f.p);
      fe_values[velocities].get_function_symmetric_gradients(solution, f.e_u);
      solid.candidates(cell->center(), 0.5 * cell->diameter(), f.cands);
      // The same rule as the assembly (StokesSolver::viscosity_at() and
      // the multiplier load): r eta_f and lambda on the solid of cells
      // that are not shared; shared cells are fluid.
      const bool held = !f.cands.empty() && !shared[cell->active_cell_index()];
      if (held)
        fe_values[velocities].get_function_symmetric_gradients(
          solver.get_multiplier(),
          f.e_lambda);
      for (unsigned int q = 0; q < n_q; ++q)
        {
          int          entry = -1;
          const double phi =
            f.cands.empty() ?
              0. :
              solid.fraction(fe_values.quadrature_point(q), f.cands, entry);
          const bool inside = phi > 0.;
          // As the assembly mixes a smoothed solid's viscosity and
          // weighs its multiplier (phi = 1 or 0 for a sharp solid).
          const double eta = held ? solver.solid_viscosity(eta_f, phi) : eta_f;
          f.sigma[q]       = 2. * eta * f.e_u[q];
          for (unsigned int d = 0; d < dim; ++d)
            f.sigma[q][d][d] -= f.p[q];
          if (inside && held)
            f.sigma[q] += phi * f.e_lambda[q];

          Tensor3 s3 = embed<dim>(f.sigma[q]);
          if (dim == 2)
            s3[2][2] = -f.p[q]; // plane strain
          const Tensor3 e3  = embed<dim>(f.e_u[q]);
          const double  JxW = fe_values.JxW(q);
          add_to(box, 0, s3, JxW);
          add_to(box, 6, e3, JxW);
          box[14] += JxW;
          // A smoothed solid splits the point between particle and fluid.
          if (inside)
            {
              const std::size_t o = 13 * std::size_t(solid.owner(entry));
              add_to(part, o, s3, phi * JxW);
              add_to(part, o + 6, e3, phi * JxW);
              part[o + 12] += phi * JxW;
            }
          if (phi < 1.)
            {
              box[12] += f.p[q] * (1. - phi) * JxW;
              box[13] += (1. - phi) * JxW;
            }
        }
    }



    /// Whether @p cell is close enough to a wall of a direction in
    /// @p wall_directions for its residual to reach a wall DoF.
    template <int dim>
    bool
    near_a_wall(const typename DoFHandler<dim>::active_cell_iterator &cell,
                const std::vector<unsigned int> &wall_directions,
                const Point<dim>                &box_lo,
                const Point<dim>                &box_hi)
    {
      // The residual of the wall DoFs: the cells that touch a wall, and
      // the finer cells next to a coarser wall cell, whose hanging nodes
      // pass part of their residual on to the coarse cell's wall DoFs.
      // Such a cell is at most two of its own sizes from the wall (one
      // level of difference across faces and edges); three is safe.
      bool near_wall = false;
      for (const unsigned int b : wall_directions)
        {
          double lo = cell->vertex(0)[b], hi = lo;
          for (const unsigned int v : cell->vertex_indices())
            {
              lo = std::min(lo, cell->vertex(v)[b]);
              hi = std::max(hi, cell->vertex(v)[b]);
            }
          if (std::min(lo - box_lo[b], box_hi[b] - hi) <= 3. * (hi - lo))
            near_wall = true;
        }
      return near_wall;
    }



    /// The residual of the momentum equation at the DoFs with imposed
    /// velocity, with what the cells need to add to it.
    template <int dim>
    struct WallResidual
    {
      WallResidual(const StokesSolver<dim> &solver, const MPI_Comm comm)
        : constraints(solver.get_conforming_constraints())
        , support(solver.get_fe(),
                  Quadrature<dim>(solver.get_fe().get_unit_support_points()),
                  update_quadrature_points)
        , dofs(solver.get_fe().n_dofs_per_cell())
        , cell_residual(solver.get_fe().n_dofs_per_cell())
      {
        // Writable ghost entries: cells of this rank add to the wall DoFs of
        // others.
        residual.reinit(solver.get_dof_handler().locally_owned_dofs(),
                        constraints.get_local_lines(),
                        comm,
                        true);
      }

      // The residual lives in the conforming space: hanging nodes and
      // periodicity, but no imposed velocity (the wall DoFs are where the
      // residual is wanted).
      const AffineConstraints<double> &constraints;
      // The support points of a cell's DoFs (the boundary DoFs' x_b).
      FEValues<dim>                 support;
      TrilinosWrappers::MPI::Vector residual;
      // Locally owned DoFs with imposed velocity: component and position.
      std::map<types::global_dof_index, std::pair<unsigned int, Point<dim>>>
                                           wall_dofs;
      std::vector<types::global_dof_index> dofs;
      dealii::Vector<double>               cell_residual;
    };



    /// Adds the cell's residual (the stress @p sigma against the test
    /// functions) to the wall residual, and records the wall DoFs of its
    /// faces with imposed velocity.
    template <int dim>
    void
    add_wall_residual(
      const DoFHandler<dim>                                &dof_handler,
      const std::set<types::boundary_id>                   &dirichlet_ids,
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const FEValues<dim>                                  &fe_values,
      const std::vector<SymmetricTensor<2, dim>>           &sigma,
      WallResidual<dim>                                    &w)
    {
      const FESystem<dim>             &fe            = fe_values.get_fe();
      const unsigned int               n_q           = sigma.size();
      const unsigned int               dofs_per_cell = fe.n_dofs_per_cell();
      const FEValuesExtractors::Vector velocities(0);

      w.cell_residual = 0;
      for (unsigned int q = 0; q < n_q; ++q)
        for (unsigned int k = 0; k < dofs_per_cell; ++k)
          w.cell_residual(k) +=
            (sigma[q] * fe_values[velocities].symmetric_gradient(k, q)) *
            fe_values.JxW(q);
      cell->get_dof_indices(w.dofs);
      w.constraints.distribute_local_to_global(w.cell_residual,
                                               w.dofs,
                                               w.residual);
      bool at_wall = false;
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() &&
            dirichlet_ids.count(cell->face(f)->boundary_id()) > 0)
          at_wall = true;
      if (!at_wall)
        return;
      w.support.reinit(cell);
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() &&
            dirichlet_ids.count(cell->face(f)->boundary_id()) > 0)
          for (unsigned int k = 0; k < dofs_per_cell; ++k)
            {
              const unsigned int c = fe.system_to_component_index(k).first;
              if (c < dim && fe.has_support_on_face(k, f) &&
                  dof_handler.locally_owned_dofs().is_element(w.dofs[k]) &&
                  !w.constraints.is_constrained(w.dofs[k]))
                w.wall_dofs[w.dofs[k]] = {c, w.support.quadrature_point(k)};
            }
    }



    /// The stresses from the box, particle and wall sums of all ranks.
    template <int dim>
    typename HydrodynamicStress<dim>::Result
    result_from_sums(const std::vector<double>       &box,
                     const std::vector<double>       &part,
                     const std::vector<double>       &wall,
                     const double                     eta_f,
                     const unsigned int               n,
                     const std::vector<unsigned int> &wall_directions)
    {
      using Tensor3 = SymmetricTensor<2, 3>;

      typename HydrodynamicStress<dim>::Result r;
      r.volume           = box[14];
      r.total            = read_from(box, 0) / r.volume;
      r.mean_strain_rate = read_from(box, 6) / r.volume;
      r.fluid_pressure   = box[13] > 0 ? box[12] / box[13] : 0.;
      r.solid_fraction   = 1. - box[13] / r.volume;
      r.stresslets.resize(n);
      for (unsigned int a = 0; a < n; ++a)
        {
          const std::size_t o = 13 * std::size_t(a);
          Tensor3 s = read_from(part, o) - 2. * eta_f * read_from(part, o + 6);
          for (unsigned int d = 0; d < 3; ++d)
            s[d][d] += r.fluid_pressure * part[o + 12];
          // In plane strain the solid's -p in zz is only the pressure's
          // share of its isotropic stress: inside a held particle the
          // multiplier's trace enforces div u = 0 as well, and how the two
          // split depends on the Uzawa history. The rule of every 2D
          // particle stress (with_plane_strain_zz()) does not.
          if (dim == 2)
            {
              r.total[2][2] -= s[2][2] / r.volume;
              s = with_plane_strain_zz(s);
              r.total[2][2] += s[2][2] / r.volume;
            }
          r.stresslets[a] = s;
          r.particle += s / r.volume;
        }
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          r.wall[a][b] = std::numeric_limits<double>::quiet_NaN();
      for (const unsigned int b : wall_directions)
        for (unsigned int a = 0; a < dim; ++a)
          r.wall[a][b] = wall[3 * a + b] / r.volume;
      return r;
    }
  } // namespace



  template <int dim>
  HydrodynamicStress<dim>::HydrodynamicStress(
    const std::set<types::boundary_id> &dirichlet_ids)
    : dirichlet_ids(dirichlet_ids)
  {
    for (unsigned int b = 0; b < dim; ++b)
      if (dirichlet_ids.count(2 * b) > 0 && dirichlet_ids.count(2 * b + 1) > 0)
        wall_directions.push_back(b);
  }



  template <int dim>
  typename HydrodynamicStress<dim>::Result
  HydrodynamicStress<dim>::compute(const StokesSolver<dim>   &solver,
                                   const SolidIndicator<dim> &solid) const
  {
    const DoFHandler<dim> &dof_handler = solver.get_dof_handler();
    const FESystem<dim>   &fe          = solver.get_fe();
    const auto            &settings    = solver.get_settings();
    const MPI_Comm         comm        = dof_handler.get_communicator();
    const double           eta_f       = settings.viscosity;
    const unsigned int     n           = solid.n_particles();

    const QGauss<dim> &quadrature = solver.get_quadrature();
    const unsigned int n_q        = quadrature.size();
    FEValues<dim>      fe_values(fe,
                            quadrature,
                            update_values | update_gradients |
                              update_quadrature_points | update_JxW_values);
    WallResidual<dim>  wall_residual(solver, comm);

    // Box sums: int sigma (6), int e(u) (6), int_f p, V_f, V.
    std::vector<double> box(15, 0.);
    // Per particle: int sigma (6), int e(u) (6), V_a.
    std::vector<double> part(13 * std::size_t(n), 0.);

    const auto [box_lo, box_hi] = global_box_bounds(solver, comm);

    CellFields<dim> fields(n_q);
    for (const auto &cell : solver.get_cells())
      {
        if (!cell->is_locally_owned())
          continue;
        integrate_cell(solver, solid, cell, fe_values, fields, box, part);
        if (!near_a_wall<dim>(cell, wall_directions, box_lo, box_hi))
          continue;
        add_wall_residual(dof_handler,
                          dirichlet_ids,
                          cell,
                          fe_values,
                          fields.sigma,
                          wall_residual);
      }
    wall_residual.residual.compress(VectorOperation::add);

    std::vector<double> wall(9, 0.);
    for (const auto &[j, where] : wall_residual.wall_dofs)
      for (const unsigned int b : wall_directions)
        wall[3 * where.first + b] +=
          where.second[b] * wall_residual.residual(j);

    Utilities::MPI::sum(box, comm, box);
    Utilities::MPI::sum(part, comm, part);
    Utilities::MPI::sum(wall, comm, wall);

    return result_from_sums<dim>(box, part, wall, eta_f, n, wall_directions);
  }

  template class HydrodynamicStress<2>;
  template class HydrodynamicStress<3>;
} // namespace Fidus
