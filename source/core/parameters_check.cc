// The checks of a scene as a whole, once every entry is read: values in
// range, particles inside the box and apart, the combinations a model
// refuses. Each problem is one InputError naming the entry, the value and
// what is allowed.

#include <algorithm>
#include <cmath>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameters.h>
#include <iostream>
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
      for (unsigned int i = 0; i < p.positions.size(); ++i)
        for (unsigned int d = 0; d < dim; ++d)
          if (p.boundary_condition == BoundaryCondition::sliding_walls &&
              d != 1)
            {
              if (p.positions[i][d] < p.lower_left[d] ||
                  p.positions[i][d] >= p.upper_right[d])
                {
                  std::ostringstream s;
                  s << "entry 'Particles/Positions': particle " << i << " at "
                    << format_point(p.positions[i], dim)
                    << " has its centre outside the periodic direction "
                    << axis[d] << "; allowed: " << p.lower_left[d]
                    << " <= " << axis[d] << " < " << p.upper_right[d];
                  throw InputError(s.str());
                }
            }
          else
            {
              const double lo = p.positions[i][d] - p.radii[i];
              const double hi = p.positions[i][d] + p.radii[i];
              if (lo < p.lower_left[d] || hi > p.upper_right[d])
                {
                  const bool         low = lo < p.lower_left[d];
                  std::ostringstream s;
                  s << "entry 'Particles/Positions': particle " << i << " at "
                    << format_point(p.positions[i], dim) << " with radius "
                    << p.radii[i] << " cuts or lies outside the box face "
                    << axis[d] << " = "
                    << (low ? p.lower_left[d] : p.upper_right[d])
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
      if (p.positions.size() > 1)
        {
          const bool periodic =
            p.boundary_condition == BoundaryCondition::sliding_walls;
          const auto gap_between = [&](const unsigned int i,
                                       const unsigned int j) {
            double dist2 = 0;
            for (unsigned int d = 0; d < dim; ++d)
              {
                double dx = p.positions[j][d] - p.positions[i][d];
                if (periodic && d != 1)
                  {
                    const double period = p.upper_right[d] - p.lower_left[d];
                    dx -= period * std::round(dx / period);
                  }
                dist2 += dx * dx;
              }
            return std::sqrt(dist2) - p.radii[i] - p.radii[j];
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

          std::vector<unsigned int> order(p.positions.size());
          std::iota(order.begin(), order.end(), 0u);
          std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) {
            return p.positions[a][0] < p.positions[b][0];
          });
          const double max_radius =
            *std::max_element(p.radii.begin(), p.radii.end());
          for (unsigned int k = 0; k < order.size(); ++k)
            for (unsigned int l = k + 1; l < order.size(); ++l)
              {
                const unsigned int i = order[k], j = order[l];
                if (p.positions[j][0] - p.positions[i][0] > 2 * max_radius)
                  break;
                const double gap = gap_between(i, j);
                if (gap < 0.)
                  report(i, j, gap);
              }
          if (periodic)
            for (unsigned int k = 0;
                 k < order.size() &&
                 p.positions[order[k]][0] < p.lower_left[0] + 2 * max_radius;
                 ++k)
              for (unsigned int l = order.size();
                   l-- > k + 1 && p.positions[order[l]][0] >
                                    p.upper_right[0] - 2 * max_radius;)
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
    const unsigned int dim     = dimension;
    const char         axis[3] = {'x', 'y', 'z'};

    auto require_positive = [](const double v, const std::string &entry) {
      if (!(v > 0.))
        throw InputError("entry '" + entry + "' has the value " +
                         std::to_string(v) + "; allowed: a value > 0");
    };
    require_positive(viscosity, "Fluid/Viscosity");
    require_positive(time_step, "Time stepping/Time step");
    require_positive(cfl_number, "Time stepping/CFL number");
    require_positive(maximum_time_step, "Time stepping/Maximum time step");
    require_positive(interface_band, "Mesh refinement/Interface band");
    require_positive(rigidity_tolerance, "Fluid/Rigidity tolerance");
    require_positive(linear_tolerance, "Fluid/Linear solver/Tolerance");

    // The exact inclusion's boundary data are those of a force-free
    // particle. Free-draining particles take a force over their isolated
    // drag (UndisturbedShearModel).
    if (!external_forces.empty() &&
        boundary_condition == BoundaryCondition::exact_rigid_inclusion)
      throw InputError(
        "entry 'Particles/External force' is set with 'Domain/Boundary "
        "condition = exact rigid inclusion'; allowed: external forces with "
        "any other boundary condition");

    if (fluid_model == FluidModelType::cut_finite_element)
      check_cut_finite_element();

    if (!(penalty_factor > 1.))
      throw InputError("entry 'Fluid/Penalty factor' has the value " +
                       std::to_string(penalty_factor) +
                       "; allowed: a value > 1 (the solid must be more "
                       "viscous than the fluid)");

    for (unsigned int d = 0; d < dim; ++d)
      if (!(upper_right[d] > lower_left[d]))
        throw InputError(std::string("entries 'Domain/Lower left' and "
                                     "'Domain/Upper right' give an empty "
                                     "box in ") +
                         axis[d] + ": " + std::to_string(lower_left[d]) +
                         " >= " + std::to_string(upper_right[d]) +
                         "; allowed: lower < upper in every direction");

    // The parser reports syntax errors on std::cerr itself; silence it so
    // that the user sees one message only.
    std::ostringstream    swallowed;
    std::streambuf *const cerr_buffer = std::cerr.rdbuf(swallowed.rdbuf());
    struct RestoreCerr
    {
      std::streambuf *buffer;
      ~RestoreCerr()
      {
        std::cerr.rdbuf(buffer);
      }
    } restore{cerr_buffer};
    try
      {
        FunctionParser<1> f(1);
        f.initialize("x,t", shear_rate, {}, true);
        f.set_time(0.);
        const double v = f.value(Point<1>());
        (void)v;
      }
    catch (...)
      {
        throw InputError("entry 'Domain/Shear rate' has the value '" +
                         shear_rate +
                         "', which is not a valid expression; allowed: a "
                         "muparser expression in t, e.g. 't < 10 ? 1 : -1'");
      }

    if (minimum_level > initial_global_refinement ||
        initial_global_refinement > maximum_level)
      throw InputError(
        "entries 'Mesh refinement/Minimum level' = " +
        std::to_string(minimum_level) + ", 'Initial global refinement' = " +
        std::to_string(initial_global_refinement) +
        ", 'Maximum level' = " + std::to_string(maximum_level) +
        "; allowed: Minimum level <= Initial global refinement <= Maximum "
        "level");

    if (boundary_condition == BoundaryCondition::exact_rigid_inclusion &&
        positions.size() != 1)
      throw InputError("entry 'Domain/Boundary condition' is 'exact rigid "
                       "inclusion' with " +
                       std::to_string(positions.size()) +
                       " particles; allowed: exactly one particle");
    if (boundary_condition == BoundaryCondition::exact_rigid_inclusion &&
        fluid_model != FluidModelType::fictitious_domain)
      throw InputError("entry 'Fluid/Model' is 'undisturbed shear' with the "
                       "'exact rigid inclusion' scene; allowed: 'fictitious "
                       "domain'");

    check_inside_box(*this);
    check_no_overlap(*this);

    // Friction and rough contact act at contacts, which 'none' does not
    // have: they would do nothing.
    if (contact_model == ContactModel::none && friction_coefficient > 0.)
      throw InputError("entry 'Contact/Friction coefficient' has the value " +
                       std::to_string(friction_coefficient) +
                       " with 'Contact/Model = none', which has no contacts; "
                       "allowed: 0, or the model 'inelastic' or 'gluey'");
    if (contact_model == ContactModel::none && rough_contact)
      throw InputError("entry 'Contact/Rough contact' is true with "
                       "'Contact/Model = none', which has no contacts; "
                       "allowed: false, or the model 'inelastic' or 'gluey'");

    const auto require_gap = [&](const std::string &entry, const double gap) {
      if (lubrication && !(gap > 0.))
        {
          std::ostringstream m;
          m << "entry 'Fluid/" << entry << "' has the value " << gap
            << "; allowed: a gap in finest cell sizes > 0 when 'Fluid/"
            << "Lubrication correction' is true";
          throw InputError(m.str());
        }
    };
    require_gap("Lubrication range", lubrication_range);
    require_gap("Lubrication range", lubrication_wall_range);
    require_gap("Lubrication flow range", lubrication_flow_range);
    require_gap("Lubrication tangential range", lubrication_tangential_range);
    require_gap("Lubrication tangential range",
                lubrication_wall_tangential_range);

    // The held solid, radius a - c h at the finest cell size h, must exist.
    if (fluid_model == FluidModelType::fictitious_domain)
      {
        const double h = finest_cell_size();
        for (unsigned int i = 0; i < radii.size(); ++i)
          if (radii[i] - solid_retraction * h <= 0.)
            {
              std::ostringstream m;
              m << "entry 'Fluid/Solid retraction' has the value "
                << solid_retraction << ", which leaves particle " << i
                << " (radius " << radii[i] << ") no solid at the finest cell "
                << "size " << h << "; allowed: values below radius / finest "
                << "cell size = " << radii[i] / h;
              throw InputError(m.str());
            }
      }
  }


  void
  Parameters::check_cut_finite_element() const
  {
    const std::string model = "'Fluid/Model = cut finite element'";
    if (boundary_condition != BoundaryCondition::linear_shear &&
        boundary_condition != BoundaryCondition::sliding_walls)
      throw InputError("entry 'Domain/Boundary condition' is not 'linear "
                       "shear' or 'sliding walls' with " +
                       model +
                       "; allowed: 'linear shear' or 'sliding walls' (the "
                       "cut element's box has the shear's velocity on "
                       "every face, or on the walls y = 0, 1 with the other "
                       "faces periodic)");
    for (unsigned int d = 0; d < dimension; ++d)
      if (lower_left[d] != 0. || upper_right[d] != 1.)
        {
          std::ostringstream m;
          m << "entries 'Domain/Lower left' and 'Domain/Upper right' give "
            << lower_left[d] << " to " << upper_right[d] << " in "
            << "xyz"[d] << " with " << model
            << "; allowed: the unit box, 0 to 1 in every direction";
          throw InputError(m.str());
        }
    if (!(cut_minimum_gap > 0.))
      throw InputError("entry 'Fluid/Cut minimum gap' has the value " +
                       std::to_string(cut_minimum_gap) +
                       "; allowed: a value > 0 (the cut element cannot "
                       "solve touching particles)");
    if (lubrication)
      throw InputError("entry 'Fluid/Lubrication correction' is true with " +
                       model +
                       "; allowed: false (the cut element resolves the "
                       "gaps down to Fluid/Cut minimum gap)");
    if (field_output_interval > 0)
      throw InputError("entry 'Output/Field output interval' is " +
                       std::to_string(field_output_interval) + " with " +
                       model +
                       "; allowed: 0 (the cut element writes no fields "
                       "yet)");
  }
} // namespace Fidus
