// The checks of a scene as a whole, once every entry is read: values in
// range, particles inside the box and apart, the combinations a model
// refuses. Each problem is one InputError naming the entry, the value and
// what is allowed.

#include <algorithm>
#include <cmath>
#include <deal.II/base/utilities.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameters.h>
#include <limits>
#include <numeric>
#include <sstream>

namespace Fidus
{
  using namespace dealii;

  namespace
  {
    std::string
    format_point(const std::array<double, 3> &x, const unsigned int dim)
    {
      std::ostringstream s;
      s << "(";
      for (unsigned int d = 0; d < dim; ++d)
        s << (d ? ", " : "") << x[d];
      s << ")";
      return s.str();
    }



    /// Every particle inside the box (its centre, along periodic axes).
    void
    check_inside_box(const Parameters &p)
    {
      const unsigned int dim     = p.dimension;
      const char         axis[3] = {'x', 'y', 'z'};
      // Every particle strictly inside the box; in the periodic directions of
      // 'sliding walls' (all but y) the centre must be in the box, the
      // particle may straddle the face.
      for (unsigned int i = 0; i < p.particles.positions.size(); ++i)
        for (unsigned int d = 0; d < dim; ++d)
          if (p.domain.boundary_condition == BoundaryCondition::sliding_walls &&
              d != 1)
            {
              if (p.particles.positions[i][d] < p.domain.lower_left[d] ||
                  p.particles.positions[i][d] >= p.domain.upper_right[d])
                {
                  std::ostringstream s;
                  s << "entry 'Particles/Positions': particle " << i << " at "
                    << format_point(p.particles.positions[i], dim)
                    << " has its centre outside the periodic direction "
                    << axis[d] << "; allowed: " << p.domain.lower_left[d]
                    << " <= " << axis[d] << " < " << p.domain.upper_right[d];
                  throw InputError(s.str());
                }
            }
          else
            {
              const double lo =
                p.particles.positions[i][d] - p.particles.radii[i];
              const double hi =
                p.particles.positions[i][d] + p.particles.radii[i];
              if (lo < p.domain.lower_left[d] || hi > p.domain.upper_right[d])
                {
                  const bool         low = lo < p.domain.lower_left[d];
                  std::ostringstream s;
                  s << "entry 'Particles/Positions': particle " << i << " at "
                    << format_point(p.particles.positions[i], dim)
                    << " with radius " << p.particles.radii[i]
                    << " cuts or lies outside the box face " << axis[d] << " = "
                    << (low ? p.domain.lower_left[d] : p.domain.upper_right[d])
                    << "; allowed: every particle inside the box (Domain/Lower "
                       "left, Domain/Upper right)";
                  throw InputError(s.str());
                }
            }
    }



    /// No two particles overlap (nearest periodic images).
    void
    check_no_overlap(const Parameters &p)
    {
      const unsigned int dim = p.dimension;
      // No two particles overlap: sweep along x so that the check stays
      // O(N log N) for large suspensions. With 'sliding walls', x and z are
      // periodic: distances use the nearest periodic image, and pairs across
      // the x faces (which the sweep does not see) are checked separately.
      if (p.particles.positions.size() > 1)
        {
          const bool periodic =
            p.domain.boundary_condition == BoundaryCondition::sliding_walls;
          const auto gap_between = [&](const unsigned int i,
                                       const unsigned int j) {
            double dist2 = 0;
            for (unsigned int d = 0; d < dim; ++d)
              {
                double dx =
                  p.particles.positions[j][d] - p.particles.positions[i][d];
                if (periodic && d != 1)
                  {
                    const double period =
                      p.domain.upper_right[d] - p.domain.lower_left[d];
                    dx -= period * std::round(dx / period);
                  }
                dist2 += dx * dx;
              }
            return std::sqrt(dist2) - p.particles.radii[i] -
                   p.particles.radii[j];
          };
          const auto report =
            [&](const unsigned int i, const unsigned int j, const double gap) {
              std::ostringstream s;
              s << "entry 'Particles/Positions': particles " << std::min(i, j)
                << " and " << std::max(i, j) << " overlap by " << -gap;
              if (periodic)
                s << " (nearest periodic image; 'sliding walls' is periodic in "
                     "x"
                  << (dim == 3 ? " and z" : "") << ")";
              s << "; allowed: non-overlapping particles (gap >= 0)";
              throw InputError(s.str());
            };

          std::vector<unsigned int> order(p.particles.positions.size());
          std::iota(order.begin(), order.end(), 0u);
          std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) {
            return p.particles.positions[a][0] < p.particles.positions[b][0];
          });
          const double max_radius = *std::max_element(p.particles.radii.begin(),
                                                      p.particles.radii.end());
          for (unsigned int k = 0; k < order.size(); ++k)
            for (unsigned int l = k + 1; l < order.size(); ++l)
              {
                const unsigned int i = order[k], j = order[l];
                if (p.particles.positions[j][0] - p.particles.positions[i][0] >
                    2 * max_radius)
                  break;
                const double gap = gap_between(i, j);
                if (gap < 0.)
                  report(i, j, gap);
              }
          if (periodic)
            for (unsigned int k = 0;
                 k < order.size() && p.particles.positions[order[k]][0] <
                                       p.domain.lower_left[0] + 2 * max_radius;
                 ++k)
              for (unsigned int l = order.size();
                   l-- > k + 1 && p.particles.positions[order[l]][0] >
                                    p.domain.upper_right[0] - 2 * max_radius;)
                {
                  const double gap = gap_between(order[k], order[l]);
                  if (gap < 0.)
                    report(order[k], order[l], gap);
                }
        }
    }
  } // namespace



  void
  Parameters::check_scene() const
  {
    // Each module's own entries first, in the order of the file.
    fluid.check();
    time_stepping.check();
    refinement.check();
    fictitious_domain.check();
    domain.check(dimension);
    contact.check();
    lubrication.check();

    // The exact inclusion's boundary data are those of a force-free
    // particle. Free-draining particles take a force over their isolated
    // drag (UndisturbedShearModel).
    if (!particles.external_forces.empty() &&
        domain.boundary_condition == BoundaryCondition::exact_rigid_inclusion)
      throw InputError(
        "entry 'Particles/External force' is set with 'Domain/Boundary "
        "condition = exact rigid inclusion'; allowed: external forces with "
        "any other boundary condition");

    if (fluid.model == FluidModelType::cut_finite_element)
      cut_element.check(*this);
    else
      cut_element.check_unused(
        fluid.model == FluidModelType::fictitious_domain ? "fictitious domain" :
                                                           "undisturbed shear");

    if (domain.boundary_condition == BoundaryCondition::exact_rigid_inclusion &&
        particles.positions.size() != 1)
      throw InputError("entry 'Domain/Boundary condition' is 'exact rigid "
                       "inclusion' with " +
                       std::to_string(particles.positions.size()) +
                       " particles; allowed: exactly one particle");
    if (domain.boundary_condition == BoundaryCondition::exact_rigid_inclusion &&
        fluid.model != FluidModelType::fictitious_domain)
      throw InputError("entry 'Fluid/Model' is 'undisturbed shear' with the "
                       "'exact rigid inclusion' scene; allowed: 'fictitious "
                       "domain'");

    // Free-draining particles have no flow to solve the bonds with.
    if (fluid.model == FluidModelType::undisturbed_shear &&
        lubrication.coupling == LubricationParameters::Coupling::with_the_flow)
      throw InputError("entry 'Fluid/Lubrication coupling' has the value "
                       "'with the flow' with 'Fluid/Model = undisturbed "
                       "shear', which solves no flow; allowed: auto, after "
                       "the solve");

    // Solved with the flow, the bonds act at the gaps of the solve.
    if (fluid.model == FluidModelType::fictitious_domain &&
        lubrication.coupling ==
          LubricationParameters::Coupling::with_the_flow &&
        lubrication.gap_in_time != Contact::GapInTime::start)
      throw InputError("entry 'Fluid/Lubrication gap in time' is not 'start' "
                       "with 'Fluid/Lubrication coupling = with the flow', "
                       "which solves the bonds with the flow at the gaps of "
                       "each solve; allowed: start");
    // Only the fictitious domain iterates the bonds with its solve.
    if (lubrication.coupling_tolerance != 1e-3 &&
        !(fluid.model == FluidModelType::fictitious_domain &&
          lubrication.coupling ==
            LubricationParameters::Coupling::with_the_flow))
      {
        std::ostringstream m;
        m << "entry 'Fluid/Lubrication coupling tolerance' has the value "
          << lubrication.coupling_tolerance
          << ", which only 'Fluid/Model = fictitious domain' with "
             "'Fluid/Lubrication coupling = with the flow' uses; allowed: "
             "the default 1e-3 otherwise";
        throw InputError(m.str());
      }

    check_inside_box(*this);
    check_no_overlap(*this);

    // The held solid, radius a - c h at the finest cell size h, must exist.
    if (fluid.model == FluidModelType::fictitious_domain)
      {
        const double               h     = finest_cell_size();
        const std::vector<double> &radii = particles.radii;
        const double               c     = fictitious_domain.solid_retraction;
        for (unsigned int i = 0; i < radii.size(); ++i)
          if (radii[i] - c * h <= 0.)
            {
              std::ostringstream m;
              m << "entry 'Fluid/Solid retraction' has the value " << c
                << ", which leaves particle " << i << " (radius " << radii[i]
                << ") no solid at the finest cell size " << h
                << "; allowed: values below radius / finest cell size = "
                << radii[i] / h;
              throw InputError(m.str());
            }
      }
  }
} // namespace Fidus
