#include <algorithm>
#include <cmath>
#include <deal.II/base/mpi.h>
#include <fidus/contact/pair_search.h>
#include <fidus/core/input_error.h>
#include <fidus/core/memory_budget.h>
#include <fidus/fluid/cut_element/cut_element_model.h>
#include <fidus/fluid/cut_element/cut_stokes_inclusion.h>
#include <fidus/lubrication/lubrication_correction.h>
#include <fidus/rheology/plane_strain.h>
#include <fidus/simulation/run_summary.h>
#include <iostream>
#include <limits>
#include <sstream>

namespace Fidus
{
  using namespace dealii;

  template <int dim>
  CutElementModel<dim>::CutElementModel(const Parameters       &parameters,
                                        const BoxGeometry<dim> &box_geometry,
                                        TimerOutput            &timer_output,
                                        WarningLog             &warning_log)
    : prm(parameters)
    , box(box_geometry)
    , timer(timer_output)
    , warnings(warning_log)
    , n(parameters.n_particles())
    , unit(box_geometry.smallest_side)
  {
    // In units of the shortest side; a side that is a whole multiple of it
    // is made exactly that multiple, so that its coarse cells are cubes.
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double ratio = (box.hi[d] - box.lo[d]) / unit;
        const double whole = std::round(ratio);
        box_sides.push_back(std::abs(ratio - whole) <= 1e-9 * ratio ? whole :
                                                                      ratio);
      }
    // On more than one rank the iterative solve splits the system, its
    // multigrid and its iterations among the ranks; on one machine one rank
    // with the machine's cores as threads splits the same work as well, and
    // holds less (each rank keeps the whole mesh, a few per cent of its
    // memory, and the libraries). Said once when 'auto' chose it and all
    // ranks share one machine: across machines, ranks are how a run gets
    // more memory (a solver set by hand is the user's call).
    const unsigned int ranks  = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    const std::string &solver = prm.cut_element.linear_solver;
    if (dim == 3 && ranks > 1 && (solver == "auto" || solver == "automatic") &&
        ranks_on_this_machine(MPI_COMM_WORLD) == ranks)
      warnings.warn(
        "cut element: 3D on many ranks",
        "the cut element runs on " + std::to_string(ranks) +
          " MPI ranks of one machine: its iterative solve splits the "
          "system, its multigrid and its iterations among them, but one "
          "rank with the machine's cores as threads splits them as well, "
          "as fast or faster, and holds less in all (the paper's 3D pair "
          "0.01 a apart on a 2-core machine: 12.7 s and 1.77 GB per rank "
          "on 2 ranks against 11.2 s and 2.19 GB on one, per solve; "
          "doc/theory/cut_element_solvers.md): run fidus on one rank, or "
          "set 'Fluid/Cut linear solver' by hand to keep the ranks without "
          "this warning",
        0,
        ranks);
  }



  template <int dim>
  std::vector<double>
  CutElementModel<dim>::fluid_radii(const std::vector<Vec3> &X,
                                    const SolveLabel        &label) const
  {
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
        const double a = prm.particles.radii[i];
        for (unsigned int d = 0; d < dim; ++d)
          if (!box.is_periodic[d])
            {
              const double wall =
                std::min(X[i][d] - box.lo[d], box.hi[d] - X[i][d]) - a;
              shrink[i] =
                std::max(shrink[i], prm.cut_element.minimum_gap * a - wall);
              overlap = std::max(overlap, -wall / a);
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
            const double b   = prm.particles.radii[j];
            const double gap = std::sqrt(d2) - a - b;
            const double cut_by =
              0.5 * (prm.cut_element.minimum_gap * std::min(a, b) - gap);
            shrink[i] = std::max(shrink[i], cut_by);
            shrink[j] = std::max(shrink[j], cut_by);
            overlap   = std::max(overlap, -gap / std::min(a, b));
          }
      }
    if (overlap > 0.)
      warnings.warn("cut element: overlap",
                    label.where +
                      ": particles overlap each other or the box by up to " +
                      std::to_string(overlap) +
                      " radii; the cut element's fluid saw them with "
                      "radii reduced to leave Fluid/Cut minimum gap",
                    label.step,
                    overlap);
    std::vector<double> radii(n);
    for (unsigned int i = 0; i < n; ++i)
      radii[i] = prm.particles.radii[i] - std::max(0., shrink[i]);
    return radii;
  }



  template <int dim>
  typename CutElementModel<dim>::Statistics
  CutElementModel<dim>::rigid_velocities(const std::vector<Vec3> &X,
                                         const double             g,
                                         const SolveLabel        &label,
                                         std::vector<Vec3>       &U,
                                         std::vector<Vec3>       &W)
  {
    TimerOutput::Scope scope(timer, "fluid");
    using Cut = CutStokesInclusion<dim>;
    typename Cut::Settings s;
    s.boundary =
      prm.domain.boundary_condition == BoundaryCondition::sliding_walls ?
        Cut::Boundary::sliding_walls :
        Cut::Boundary::linear_shear;
    s.shear_rate = g;
    s.viscosity  = prm.fluid.viscosity;
    s.box_sides  = box_sides;
    // The fields are kept for output, and as the next solve's start with
    // the iterative solver (keeping costs a second DoF numbering of the
    // mesh, small beside the solve).
    const bool warm_start = !prm.cut_element.direct_solver(dim) &&
                            prm.cut_element.initial_guess == "previous solve";
    s.keep_fields   = prm.output.field_output_interval > 0 || warm_start;
    s.initial_guess = warm_start ? last_fields : nullptr;
    s.memory_limit  = prm.fictitious_domain.memory_per_rank;
    s.communicator  = MPI_COMM_WORLD;
    s.global_level  = prm.refinement.minimum_level;
    s.band_levels = prm.refinement.maximum_level - prm.refinement.minimum_level;
    s.gap_cells   = prm.cut_element.gap_cells;
    s.nitsche     = prm.cut_element.nitsche;
    s.iterative_tolerance = prm.cut_element.linear_tolerance;
    s.ghost_velocity      = prm.cut_element.ghost_velocity;
    s.ghost_pressure      = prm.cut_element.ghost_pressure;
    s.linear_solver       = prm.cut_element.linear_solver == "direct" ?
                              Cut::LinearSolver::direct :
                            prm.cut_element.linear_solver == "iterative" ?
                              Cut::LinearSolver::iterative :
                              Cut::LinearSolver::automatic;
    // A pair's cut cells away from its gap are as coarse as the Maximum
    // level, where 4 Gauss points per direction leave a quadrature error
    // of 1e-4 in the velocities at level 5 (a = 1.6 cells), seen as a
    // broken point symmetry of the paper's pair; 8 points take it to 1e-7
    // (doc/cut_element.md). 2D affords it; 3D keeps 4.
    s.quadrature_points = dim == 2 ? 8 : 4;

    const std::vector<double> radii = fluid_radii(X, label);
    s.particles.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        // In the solver's units: lengths over the unit, forces over its
        // power dim - 1 (a force is viscosity x velocity x length^(dim-2)).
        auto &P = s.particles[i];
        for (unsigned int d = 0; d < dim; ++d)
          P.center[d] = (X[i][d] - box.lo[d]) / unit;
        P.radius = radii[i] / unit;
        if (!prm.particles.external_forces.empty())
          for (unsigned int d = 0; d < dim; ++d)
            P.force[d] =
              prm.particles.external_forces[i][d] / std::pow(unit, dim - 1);
      }

    typename Cut::Result r;
    try
      {
        s.couplings = subgrid_couplings(X, radii);
        r           = Cut::solve(s);
      }
    catch (const std::exception &e)
      {
        throw RunError(label.where +
                       ": the cut finite element failed: " + e.what());
      }
    if (prm.output.verbosity == Verbosity::verbose)
      print_stages(r);
    Statistics stats;
    stats.n_cells = last_cells = r.n_cells;
    stats.n_dofs = last_dofs = r.n_dofs;
    // The iterative solver's FGMRES iterations (0 when solved directly)
    // go to the linear_iterations column.
    stats.linear_iterations = r.n_iterations;
    // A direct solve that lost accuracy gives no error: its residual is
    // checked (an iterative one that does not converge throws). The
    // residual is that of the unscaled system, which FGMRES's tolerance
    // (on the scaled one) bounds only up to the scaling: an iterative
    // solve is given a hundred times its tolerance.
    const double bound =
      r.iterative ? std::max(1e-8, 100. * prm.cut_element.linear_tolerance) :
                    1e-8;
    if (!(r.residual < bound))
      {
        std::ostringstream m;
        m << label.where << ": the linear solve's relative residual is "
          << r.residual << " > " << bound;
        warnings.warn("cut element: inaccurate solve",
                      m.str(),
                      label.step,
                      r.residual);
      }
    for (unsigned int i = 0; i < n; ++i)
      {
        U[i] = {{0., 0., 0.}};
        for (unsigned int d = 0; d < dim; ++d)
          U[i][d] = unit * r.velocity[i][d];
        for (unsigned int d = 0; d < 3; ++d)
          W[i][d] = r.angular_velocity[i][d];
      }

    // The stress in the form of HydrodynamicStress (doc/rheology.md):
    // Sigma = -<p>_f I + 2 eta <e(u)> + (1/V) sum S_a over the box,
    // where <e(u)> is the boundary's shear, since the velocity is rigid
    // in the particles. In plane strain the zz stresslet is half the
    // in-plane trace (with_plane_strain_zz()). Between sliding walls the
    // walls' stress sigma e_y is measured too (entries (a, y)), as the
    // fictitious domain's is; with linear shear it is not (NaN).
    using Tensor3      = typename HydrodynamicStress<dim>::Tensor3;
    Stress &h          = last_stress;
    h                  = Stress();
    const double scale = std::pow(unit, dim);
    h.volume           = scale;
    for (unsigned int d = 0; d < dim; ++d)
      h.volume *= box_sides[d];
    h.fluid_pressure         = r.fluid_pressure;
    h.solid_fraction         = 1. - scale * r.fluid_volume / h.volume;
    h.mean_strain_rate[0][1] = 0.5 * g;
    for (unsigned int i = 0; i < n; ++i)
      {
        Tensor3 S;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = a; b < dim; ++b)
            S[a][b] = scale * r.stresslets[i][a][b];
        if (dim == 2)
          S = with_plane_strain_zz(S);
        h.stresslets.push_back(S);
        h.particle += S / h.volume;
      }
    h.total = -h.fluid_pressure * unit_symmetric_tensor<3>() +
              2. * prm.fluid.viscosity * h.mean_strain_rate + h.particle;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        h.wall[a][b] = std::numeric_limits<double>::quiet_NaN();
    if (s.boundary == Cut::Boundary::sliding_walls)
      for (unsigned int a = 0; a < dim; ++a)
        h.wall[a][1] = r.top_wall_stress[a];
    solved_shear_rate = g;
    last_fields       = r.fields;
    return stats;
  }



  template <int dim>
  void
  CutElementModel<dim>::print_stages(
    const typename CutStokesInclusion<dim>::Result &r) const
  {
    // Every rank has the same figures (the first one's clock).
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;
    const auto &t = r.stage_seconds;
    std::cout << "    cut element: " << r.n_dofs << " unknowns (" << r.n_entries
              << " matrix entries), " << r.n_cells << " cells ("
              << r.n_cut_cells << " cut), "
              << (r.iterative ? "FGMRES " + std::to_string(r.n_iterations) :
                                std::string("direct"))
              << ", residual " << r.residual << "; s: mesh " << t.mesh
              << ", DoFs and pattern " << t.dofs << ", assembly " << t.assembly
              << ", solve " << t.solve;
    if (r.iterative)
      std::cout << " (of which FGMRES " << t.fgmres
                << ", from a start at the relative residual "
                << r.initial_residual << "; set-up: blocks " << t.blocks
                << ", pressure " << t.pressure << ", velocity " << t.velocity
                << ")";
    std::cout << ", measure " << t.measure << ", all " << r.seconds
              << std::endl;
  }



  template <int dim>
  typename CutElementModel<dim>::Stress
  CutElementModel<dim>::hydrodynamic_stress(const double shear_rate)
  {
    Stress s = last_stress;
    if (shear_rate != solved_shear_rate)
      s.scale(shear_rate / solved_shear_rate);
    return s;
  }



  template <int dim>
  double
  CutElementModel<dim>::cfl_length() const
  {
    return box.h_finest;
  }



  template <int dim>
  bool
  CutElementModel<dim>::resolves_gap_flow() const
  {
    return true;
  }



  template <int dim>
  void
  CutElementModel<dim>::set_subgrid_lubrication(
    Contact::LubricationCorrection *correction)
  {
    subgrid = correction;
  }



  template <int dim>
  std::vector<typename CutStokesInclusion<dim>::RigidCoupling>
  CutElementModel<dim>::subgrid_couplings(
    const std::vector<Vec3>   &X,
    const std::vector<double> &fluid) const
  {
    std::vector<typename CutStokesInclusion<dim>::RigidCoupling> couplings;
    if (subgrid == nullptr)
      return couplings;
    // A bond's loads (F_i, T_i, F_j, T_j) are linear in the generalised
    // velocities (U_i, w_i, U_j, w_j) but for a wall's own motion: the
    // matrix is minus the loads of unit velocities, the load that of zero
    // velocities. The solver's rigid unknowns of a particle are U, then
    // omega (omega_z in 2D), in its units: velocities over the unit,
    // forces over its power dim - 1, torques over its power dim.
    constexpr unsigned int        n_rigid = dim * (dim + 1) / 2;
    const std::array<unsigned, 6> component =
      dim == 2 ? std::array<unsigned, 6>{{0, 1, 5, 0, 0, 0}} :
                 std::array<unsigned, 6>{{0, 1, 2, 3, 4, 5}};
    const auto length_power = [&](const unsigned int k) {
      return k < dim ? 1 : 0;
    };
    const auto load_power = [&](const unsigned int k) {
      return k < dim ? int(dim) - 1 : int(dim);
    };
    for (const Contact::LubricationBond &b :
         subgrid->find_bonds(X, prm.particles.radii, fluid))
      {
        typename CutStokesInclusion<dim>::RigidCoupling c;
        c.owners.push_back(b.i);
        if (b.j != Contact::LubricationBond::no_particle)
          c.owners.push_back(b.j);
        const unsigned int m    = c.owners.size() * n_rigid;
        const auto         full = [&](const unsigned int k) {
          return 6 * (k / n_rigid) + component[k % n_rigid];
        };
        c.matrix.assign(m, std::vector<double>(m, 0.));
        c.load.assign(m, 0.);
        const std::array<double, 12> rest =
          subgrid->subgrid_loads(b, std::array<double, 12>{}, true);
        for (unsigned int k = 0; k < m; ++k)
          c.load[k] = rest[full(k)] / std::pow(unit, load_power(k % n_rigid));
        for (unsigned int l = 0; l < m; ++l)
          {
            std::array<double, 12> v{};
            v[full(l)] = 1.;
            const std::array<double, 12> f =
              subgrid->subgrid_loads(b, v, false);
            for (unsigned int k = 0; k < m; ++k)
              c.matrix[k][l] =
                -f[full(k)] *
                std::pow(unit,
                         length_power(l % n_rigid) - load_power(k % n_rigid));
          }
        couplings.push_back(std::move(c));
      }
    return couplings;
  }



  template <int dim>
  double
  CutElementModel<dim>::resolved_gap_fraction() const
  {
    // The mesh resolves every gap down to Fluid/Cut minimum gap, and the
    // fluid sees narrower ones at that gap (radii shrunk): that is the
    // resistance the fluid carries for them.
    return prm.cut_element.minimum_gap;
  }



  template <int dim>
  void
  CutElementModel<dim>::add_to_summary(RunSummary &s) const
  {
    s.n_cells = last_cells;
    s.n_dofs  = last_dofs;
  }



  template class CutElementModel<2>;
  template class CutElementModel<3>;
} // namespace Fidus
