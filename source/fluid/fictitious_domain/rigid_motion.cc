#include <cmath>
#include <deal.II/base/mpi.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/fictitious_domain/rigid_motion.h>

namespace Fidus
{
  namespace
  {
    /**
     * Stop the run where the rigid fit cannot determine a rotation. @p s
     * holds a particle's sums (volume V at 0, J at 7..15, c = int r at
     * 16..18); the rotation is fitted through the second moment of the
     * integrated points about their centroid, J - (|c|^2 I - c c^T) / V.
     * A small particle on a coarse mesh (its solid retracted by 'Solid
     * retraction') can hold so few points, so close together, that this
     * moment vanishes about some axis, and the fit then returns an
     * unbounded rotation (measured: 1e14 for spheres of radius 0.04 at
     * h = 0.0625, with a bounded flow). A resolved ball, or the quarter or
     * more of one that the fit uses, keeps its smallest moment well above
     * 1e-3 of its largest.
     */
    void
    check_rotation_determined(const double      *s,
                              const unsigned int i,
                              const double       radius)
    {
      const double         *c  = &s[16];
      const double          cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
      SymmetricTensor<2, 3> J;
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = a; b < 3; ++b)
          J[a][b] =
            s[7 + 3 * a + b] - ((a == b ? cc : 0.) - c[a] * c[b]) / s[0];
      const auto lambda = eigenvalues(J); // descending
      if (!(lambda[2] > 1e-3 * lambda[0]))
        throw RunError(
          "particle " + std::to_string(i) +
          " holds too few quadrature points to fit a rigid rotation: its "
          "solid, a ball of radius " +
          std::to_string(radius) +
          " (after 'Fluid/Solid retraction'), is too small for the mesh "
          "(raise 'Mesh refinement/Maximum level', or lower 'Fluid/Solid "
          "retraction')");
    }
  } // namespace

  template <int dim>
  std::vector<RigidMotion>
  compute_rigid_motions(
    const DoFHandler<dim> &dof_handler,
    const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells,
    const TrilinosWrappers::MPI::BlockVector                          &solution,
    const SolidIndicator<dim>                                         &solid,
    const Quadrature<dim>   &quadrature,
    const std::vector<bool> *excluded_cells)
  {
    const unsigned int n = solid.n_particles();
    // Per particle: volume, int u (3), int r x u (3), J (9), int r (3);
    // over the whole solid, then over the solid outside excluded cells.
    constexpr unsigned int           stride = 19;
    std::vector<double>              sums(2 * n * stride, 0.);
    FEValues<dim>                    fe_values(dof_handler.get_fe(),
                            quadrature,
                            update_values | update_quadrature_points |
                              update_JxW_values);
    const FEValuesExtractors::Vector velocities(0);
    std::vector<Tensor<1, dim>>      u(quadrature.size());
    std::vector<unsigned int>        cands;

    for (const auto &cell : cells)
      if (cell->is_locally_owned())
        {
          const bool held =
            !(excluded_cells && (*excluded_cells)[cell->active_cell_index()]);
          solid.candidates(cell->center(), 0.5 * cell->diameter(), cands);
          if (cands.empty())
            continue;
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(solution, u);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Point<dim> &x   = fe_values.quadrature_point(q);
              int               k   = -1;
              const double      phi = solid.fraction(x, cands, k);
              if (phi == 0.)
                continue;
              // A periodic image adds to its particle, with the lever arm
              // taken from the image's centre. A smoothed solid weighs each
              // point by its solid fraction.
              const double JxW = phi * fe_values.JxW(q);
              for (unsigned int part = 0; part < (held ? 2u : 1u); ++part)
                {
                  double *s    = &sums[(part * n + solid.owner(k)) * stride];
                  double  r[3] = {0, 0, 0}, v[3] = {0, 0, 0};
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      r[d] = x[d] - solid.center(k)[d];
                      v[d] = u[q][d];
                    }
                  s[0] += JxW;
                  for (unsigned int d = 0; d < 3; ++d)
                    s[1 + d] += v[d] * JxW;
                  s[4] += (r[1] * v[2] - r[2] * v[1]) * JxW;
                  s[5] += (r[2] * v[0] - r[0] * v[2]) * JxW;
                  s[6] += (r[0] * v[1] - r[1] * v[0]) * JxW;
                  const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
                  for (unsigned int a = 0; a < 3; ++a)
                    for (unsigned int b = 0; b < 3; ++b)
                      s[7 + 3 * a + b] +=
                        ((a == b ? r2 : 0.) - r[a] * r[b]) * JxW;
                  for (unsigned int d = 0; d < 3; ++d)
                    s[16 + d] += r[d] * JxW;
                }
            }
        }
    Utilities::MPI::sum(sums, dof_handler.get_communicator(), sums);

    std::vector<RigidMotion> motions(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        // The fit over the held solid, unless excluded cells leave less
        // than a quarter of the particle (a particle packed in on all
        // sides): then over all of it, as without exclusion.
        const double *all  = &sums[i * stride];
        const double *held = &sums[(n + i) * stride];
        const double *s    = held[0] >= 0.25 * all[0] ? held : all;
        if (!(s[0] > 0.))
          throw RunError("particle " + std::to_string(i) +
                         " contains no quadrature point: the mesh is too "
                         "coarse for its radius " +
                         std::to_string(solid.radius(i)) +
                         " (raise 'Mesh refinement/Maximum level')");
        if (dim == 3)
          check_rotation_determined(s, i, solid.radius(i));
        motions[i].volume = s[0];
        // Normal equations of min int |u - U - omega x r|^2 over the
        // integrated part of the particle: with c = int r,
        //   V U - c x omega = int u,   c x U + J omega = int r x u.
        // c vanishes for a whole particle up to quadrature; it does not when
        // cells are excluded (shared cells), where the two decouple no more.
        FullMatrix<double> A(6, 6);
        Vector<double>     b(6), x(6);
        const double      *c           = &s[16];
        const double       cross[3][3] = {{0, -c[2], c[1]},
                                          {c[2], 0, -c[0]},
                                          {-c[1], c[0], 0}};
        for (unsigned int a = 0; a < 3; ++a)
          {
            A(a, a)  = s[0];
            b(a)     = s[1 + a];
            b(3 + a) = s[4 + a];
            for (unsigned int e = 0; e < 3; ++e)
              {
                A(a, 3 + e)     = -cross[a][e];
                A(3 + a, e)     = cross[a][e];
                A(3 + a, 3 + e) = s[7 + 3 * a + e];
              }
          }
        // 2D: the unknowns are U_x, U_y and omega_z.
        const std::vector<unsigned int> unknowns =
          dim == 2 ? std::vector<unsigned int>{0, 1, 5} :
                     std::vector<unsigned int>{0, 1, 2, 3, 4, 5};
        const unsigned int m = unknowns.size();
        FullMatrix<double> Ar(m, m);
        Vector<double>     br(m), xr(m);
        for (unsigned int a = 0; a < m; ++a)
          {
            br(a) = b(unknowns[a]);
            for (unsigned int e = 0; e < m; ++e)
              Ar(a, e) = A(unknowns[a], unknowns[e]);
          }
        Ar.gauss_jordan();
        Ar.vmult(xr, br);
        for (unsigned int a = 0; a < m; ++a)
          x(unknowns[a]) = xr(a);
        for (unsigned int d = 0; d < 3; ++d)
          {
            motions[i].velocity[d] = d < dim ? x(d) : 0.;
            motions[i].omega[d]    = x(3 + d);
          }
        for (unsigned int d = 0; d < 3; ++d)
          if (!std::isfinite(motions[i].velocity[d]) ||
              !std::isfinite(motions[i].omega[d]))
            throw RunError("the rigid velocity of particle " +
                           std::to_string(i) + " is not finite (NaN)");
      }
    return motions;
  }

  template std::vector<RigidMotion>
  compute_rigid_motions(
    const DoFHandler<2> &,
    const std::vector<DoFHandler<2>::active_cell_iterator> &,
    const TrilinosWrappers::MPI::BlockVector &,
    const SolidIndicator<2> &,
    const Quadrature<2> &,
    const std::vector<bool> *);
  template std::vector<RigidMotion>
  compute_rigid_motions(
    const DoFHandler<3> &,
    const std::vector<DoFHandler<3>::active_cell_iterator> &,
    const TrilinosWrappers::MPI::BlockVector &,
    const SolidIndicator<3> &,
    const Quadrature<3> &,
    const std::vector<bool> *);
} // namespace Fidus
