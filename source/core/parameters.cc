#include <algorithm>
#include <cmath>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>
#include <fidus/contact/contact_error.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameters.h>
#include <fidus/particles/particle_generator.h>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <numeric>
#include <sstream>

namespace Fidus
{
  using namespace dealii;

  namespace
  {
    /// Parse a comma-separated list of numbers; throw naming @p entry.
    std::vector<double>
    parse_numbers(const std::string &text, const std::string &entry)
    {
      std::vector<double> values;
      for (const std::string &item : Utilities::split_string_list(text, ','))
        {
          if (item.empty())
            continue;
          std::size_t end = 0;
          double      v   = 0;
          try
            {
              v = std::stod(item, &end);
            }
          catch (...)
            {
              end = 0;
            }
          if (end != item.size() || !std::isfinite(v))
            throw InputError("entry '" + entry + "' has the value '" + text +
                             "': '" + item +
                             "' is not a finite number; allowed: a "
                             "comma-separated list of numbers");
          values.push_back(v);
        }
      return values;
    }

    /// An entry that is 'auto' (then @p auto_value) or one number for which
    /// @p valid holds (any number if it is empty); otherwise throw one
    /// message naming @p entry, its value and @p allowed.
    double
    number_or_auto(const std::string                 &value,
                   const std::string                 &entry,
                   const double                       auto_value,
                   const std::string                 &allowed,
                   const std::function<bool(double)> &valid = {})
    {
      const std::string text = Utilities::trim(value);
      if (text == "auto")
        return auto_value;
      std::vector<double> v;
      try
        {
          v = parse_numbers(text, entry);
        }
      catch (const InputError &)
        {
          v.clear();
        }
      if (v.size() != 1 || (valid && !valid(v[0])))
        throw InputError("entry '" + entry + "' has the value '" + text +
                         "'; allowed: " + allowed);
      return v[0];
    }

    std::array<double, 3>
    parse_point(const std::string &text,
                const std::string &entry,
                const unsigned int dim)
    {
      const std::vector<double> v = parse_numbers(text, entry);
      if (v.size() != dim)
        throw InputError(
          "entry '" + entry + "' has the value '" + text + "' with " +
          std::to_string(v.size()) + " coordinates; allowed: exactly " +
          std::to_string(dim) +
          " coordinates (Dimension = " + std::to_string(dim) + ")");
      std::array<double, 3> x = {{0., 0., 0.}};
      std::copy(v.begin(), v.end(), x.begin());
      return x;
    }
  } // namespace



  namespace
  {
    /// The message of a deal.II exception without its source location.
    std::string
    clean_message(const std::exception &e)
    {
      std::string       what = e.what();
      const std::string key  = "Additional information:";
      const auto        pos  = what.find(key);
      if (pos != std::string::npos)
        what = what.substr(pos + key.size());
      const auto stack = what.find("Stacktrace:");
      if (stack != std::string::npos)
        what = what.substr(0, stack);
      // Collapse the line breaks and indentation of the deal.II format.
      std::string out;
      bool        space = false;
      for (const char c : what)
        if (c == '\n' || c == ' ' || c == '\t')
          space = !out.empty();
        else
          {
            if (space)
              out += ' ';
            out += c;
            space = false;
          }
      while (!out.empty() && (out.back() == '-' || out.back() == ' '))
        out.pop_back();
      return out;
    }

    Parameters
    read_from(ParameterHandler  &prm,
              const std::string &name,
              const std::string &text,
              const bool         from_file,
              std::ostream      *used)
    {
      Parameters::declare(prm);
      try
        {
          if (from_file)
            {
              std::ifstream in(name);
              if (!in)
                throw InputError("cannot read the parameter file '" + name +
                                 "'");
              if (name.size() > 5 && name.substr(name.size() - 5) == ".json")
                prm.parse_input_from_json(in);
              else
                prm.parse_input(name);
            }
          else
            prm.parse_input_from_string(text);
        }
      catch (const InputError &)
        {
          throw;
        }
      catch (const std::exception &e)
        {
          throw InputError(clean_message(e));
        }
      Parameters p;
      p.parse(prm, name);
      if (used)
        prm.print_parameters(*used, ParameterHandler::ShortPRM);
      return p;
    }
  } // namespace



  Parameters
  read_parameters(const std::string &filename, std::ostream *used)
  {
    ParameterHandler prm;
    return read_from(prm, filename, "", true, used);
  }



  Parameters
  read_parameters_from_string(const std::string &text)
  {
    ParameterHandler prm;
    return read_from(prm, "", text, false, nullptr);
  }



  namespace
  {
    /// Domain: the box, its boundary condition and the shear rate.
    void
    parse_domain(ParameterHandler &prm, Parameters &p)
    {
      const unsigned int dim = p.dimension;
      prm.enter_subsection("Domain");
      {
        p.lower_left =
          parse_point(prm.get("Lower left"), "Domain/Lower left", dim);
        p.upper_right =
          parse_point(prm.get("Upper right"), "Domain/Upper right", dim);
        const std::string bc = prm.get("Boundary condition");
        p.boundary_condition =
          bc == "linear shear"  ? BoundaryCondition::linear_shear :
          bc == "sliding walls" ? BoundaryCondition::sliding_walls :
          bc == "cavity"        ? BoundaryCondition::cavity :
                                  BoundaryCondition::exact_rigid_inclusion;
        p.shear_rate = prm.get("Shear rate");
      }
      prm.leave_subsection();
    }



    /// Fluid, but for its linear solver: the model and its entries; the
    /// 'auto' of Shared cells and Reuse multiplier depends on the contact
    /// model and is decided by Parameters::parse().
    void
    parse_fluid(ParameterHandler &prm,
                Parameters       &p,
                std::string      &shared_cells_choice,
                std::string      &reuse_choice)
    {
      const unsigned int dim   = p.dimension;
      const std::string  model = prm.get("Model");
      p.fluid_model =
        model == "fictitious domain" ? FluidModelType::fictitious_domain :
        model == "undisturbed shear" ? FluidModelType::undisturbed_shear :
                                       FluidModelType::cut_finite_element;
      p.cut_minimum_gap       = prm.get_double("Cut minimum gap");
      p.cut_gap_cells         = prm.get_double("Cut gap cells");
      p.cut_linear_solver     = prm.get("Cut linear solver");
      p.viscosity             = prm.get_double("Viscosity");
      p.penalty_factor        = prm.get_double("Penalty factor");
      p.velocity_degree       = prm.get_integer("Velocity degree");
      p.rigidity_per_particle = prm.get("Rigidity measure") == "particle";
      // auto: the single particle's work-precision optimum in each measure
      // (doc/uzawa.md, "Rigidity per particle").
      p.rigidity_tolerance =
        number_or_auto(prm.get("Rigidity tolerance"),
                       "Fluid/Rigidity tolerance",
                       p.rigidity_per_particle ? 5e-3 : 1e-3,
                       "auto or a number in (0, 1)",
                       [](const double v) { return v > 0. && v < 1.; });
      p.rigid_velocity_tolerance = prm.get_double("Rigid velocity tolerance");
      p.sliver_threshold         = prm.get_double("Sliver threshold");
      p.max_uzawa_iterations     = prm.get_integer("Maximum Uzawa iterations");
      reuse_choice               = prm.get("Reuse multiplier");
      shared_cells_choice        = prm.get("Shared cells");
      p.solid_retraction         = prm.get_double("Solid retraction");
      p.solid_smoothing          = prm.get_double("Solid smoothing");
      p.lubrication              = prm.get_bool("Lubrication correction");
      // An entry that is 'auto' (then {auto_pairs, auto_walls}), one gap
      // in cells for both, or two: the particle pairs' and the walls'.
      const auto pair_and_wall_ranges = [&](const std::string &entry,
                                            const double       auto_pairs,
                                            const double       auto_walls) {
        const std::string text = Utilities::trim(prm.get(entry));
        if (text == "auto")
          return std::vector<double>{auto_pairs, auto_walls};
        const std::vector<double> v = parse_numbers(text, "Fluid/" + entry);
        if (v.empty() || v.size() > 2)
          throw InputError("entry 'Fluid/" + entry + "' has the value '" +
                           text +
                           "'; allowed: auto, one gap in finest cell sizes "
                           "> 0 (particle pairs and walls), or two "
                           "(particle pairs, walls)");
        return std::vector<double>{v[0], v.back()};
      };
      // The 3D values and the 2D walls' and pairs' squeeze ranges are the
      // fraction of a cell down to which the mesh carries a pushed
      // particle's squeeze (doc/lubrication.md).
      const std::vector<double> squeeze =
        pair_and_wall_ranges("Lubrication range",
                             dim == 3 ? 0.3 : 0.65,
                             dim == 3 ? 0.2 : 0.33);
      p.lubrication_range      = squeeze[0];
      p.lubrication_wall_range = squeeze[1];
      // An entry that is 'auto' (then auto_value) or one gap in cells.
      const auto gap_or_auto = [&](const std::string &entry,
                                   const double       auto_value) {
        return number_or_auto(prm.get(entry),
                              "Fluid/" + entry,
                              auto_value,
                              "auto or one gap in finest cell sizes > 0");
      };
      const std::vector<double> tangential =
        pair_and_wall_ranges("Lubrication tangential range",
                             p.lubrication_range,
                             dim == 3 ? p.lubrication_wall_range : 1.);
      p.lubrication_tangential_range      = tangential[0];
      p.lubrication_wall_tangential_range = tangential[1];
      // 2 in 2D: the range with which a lubricated pair in shear does not
      // overlap at any level. A held pair would want 0.7-1, but that
      // changes the dense scene's viscosity by a third, with no reference
      // for it yet (doc/lubrication_2d.md, "Two discs held in shear").
      p.lubrication_flow_range =
        gap_or_auto("Lubrication flow range", dim == 3 ? 0.45 : 2.);
      p.lubrication_tangential = prm.get_bool("Lubrication tangential terms");
    }



    /// Fluid/Linear solver, with its 'auto' rules (direct in 2D, GMG in
    /// 3D, the rigid-body correction).
    void
    parse_linear_solver(ParameterHandler &prm, Parameters &p)
    {
      const unsigned int dim = p.dimension;
      prm.enter_subsection("Linear solver");
      p.linear_tolerance          = prm.get_double("Tolerance");
      p.inexact_uzawa_factor      = prm.get_double("Inexact Uzawa factor");
      p.max_cheap_iterations      = prm.get_integer("Maximum cheap iterations");
      p.max_linear_iterations     = prm.get_integer("Maximum iterations");
      p.amg_aggregation_threshold = prm.get_double("AMG aggregation threshold");
      p.amg_smoother_sweeps       = prm.get_integer("AMG smoother sweeps");
      p.amg_smoother_type         = prm.get("AMG smoother type");
      // Method auto: direct in 2D (doc/fluid.md, "A direct solver for
      // 2D"), unless a preconditioner was chosen by name, which asks for
      // FGMRES; and FGMRES above a million unknowns, where the
      // factorisation takes more than twice FGMRES's memory and no less
      // time.
      const std::string method         = prm.get("Method");
      const std::string preconditioner = prm.get("Preconditioner");
      p.direct_max_unknowns =
        method == "direct" ? std::numeric_limits<unsigned long long>::max() :
        method == "auto" && dim == 2 && preconditioner == "auto" ? 1000000ULL :
                                                                   0ULL;
      // Preconditioner auto: the faster one per dimension as measured
      // (doc/preconditioners.md): GMG in 3D, AMG in 2D and for degrees
      // the GMG does not have.
      p.geometric_multigrid =
        preconditioner == "GMG" ||
        (preconditioner == "auto" && dim == 3 && p.velocity_degree <= 3);
      p.mg_smoother_degree     = prm.get_integer("Multigrid smoother degree");
      p.mg_viscosity_averaging = prm.get("Multigrid viscosity averaging");
      p.mg_smoother_blocks     = prm.get("Multigrid smoother blocks");
      // auto: off where measured not to pay (GMG in 3D with its Galerkin
      // levels and cut-cell blocks; doc/preconditioners.md).
      const std::string correction = prm.get("Rigid-body correction");
      p.rigid_body_correction =
        correction == "true" ||
        (correction == "auto" && !(p.geometric_multigrid && dim == 3));
      p.matrix_free_velocity_block = prm.get_bool("Matrix-free velocity block");
      if (p.geometric_multigrid && p.velocity_degree > 3)
        throw InputError(
          "entry 'Fluid/Linear solver/Preconditioner' has the value 'GMG' "
          "with 'Fluid/Velocity degree' = " +
          std::to_string(p.velocity_degree) +
          "; allowed: GMG with Velocity degree 2 or 3, or Preconditioner = "
          "AMG");
      prm.leave_subsection();
    }



    /// Particles: the positions, given or from a file (relative to
    /// @p input_name), with the file's radii in @p file_radii.
    void
    parse_positions(ParameterHandler    &prm,
                    Parameters          &p,
                    const std::string   &input_name,
                    std::vector<double> &file_radii)
    {
      const unsigned int dim           = p.dimension;
      p.positions_file                 = prm.get("Positions file");
      const std::string positions_text = prm.get("Positions");
      p.positions.clear();

      if (!p.positions_file.empty() && !Utilities::trim(positions_text).empty())
        throw InputError("entries 'Particles/Positions' and 'Particles/"
                         "Positions file' are both set; allowed: one of them");

      if (!p.positions_file.empty())
        {
          std::string path = p.positions_file;
          if (path[0] != '/')
            {
              const auto slash = input_name.find_last_of('/');
              if (slash != std::string::npos)
                path = input_name.substr(0, slash + 1) + path;
            }
          std::ifstream in(path);
          if (!in)
            throw InputError(
              "entry 'Particles/Positions file' has the value '" +
              p.positions_file + "': the file '" + path +
              "' cannot be read; allowed: a readable text "
              "file with lines 'x y [z] [radius]'");
          std::string  line;
          unsigned int line_no = 0;
          while (std::getline(in, line))
            {
              ++line_no;
              const auto hash = line.find('#');
              if (hash != std::string::npos)
                line.erase(hash);
              std::istringstream  s(line);
              std::vector<double> v;
              std::string         word;
              while (s >> word)
                {
                  std::size_t end = 0;
                  double      x   = 0;
                  try
                    {
                      x = std::stod(word, &end);
                    }
                  catch (...)
                    {
                      end = 0;
                    }
                  if (end != word.size() || !std::isfinite(x))
                    throw InputError("entry 'Particles/Positions file': line " +
                                     std::to_string(line_no) + " of '" + path +
                                     "' has '" + word +
                                     "', which is not a finite number");
                  v.push_back(x);
                }
              if (v.empty())
                continue;
              if (v.size() != dim && v.size() != dim + 1)
                throw InputError("entry 'Particles/Positions file': line " +
                                 std::to_string(line_no) + " of '" + path +
                                 "' has " + std::to_string(v.size()) +
                                 " numbers; allowed: " + std::to_string(dim) +
                                 " coordinates, optionally followed "
                                 "by a radius");
              std::array<double, 3> x = {{0., 0., 0.}};
              std::copy(v.begin(), v.begin() + dim, x.begin());
              p.positions.push_back(x);
              if (v.size() == dim + 1)
                file_radii.push_back(v[dim]);
            }
          if (!file_radii.empty() && file_radii.size() != p.positions.size())
            throw InputError("entry 'Particles/Positions file': '" + path +
                             "' gives a radius on some lines only; allowed: "
                             "a radius on every line or on none");
        }
      else
        {
          for (const std::string &item :
               Utilities::split_string_list(positions_text, ';'))
            if (!item.empty())
              p.positions.push_back(
                parse_point(item, "Particles/Positions", dim));
        }
    }



    /// Particles/Generator: places the particles when asked to, their
    /// radii in @p file_radii.
    void
    parse_generator(ParameterHandler          &prm,
                    Parameters                &p,
                    const std::vector<double> &given_radii,
                    std::vector<double>       &file_radii)
    {
      const unsigned int dim = p.dimension;
      prm.enter_subsection("Generator");
      const unsigned int generator_count =
        prm.get_integer("Number of particles");
      const double generator_fraction = prm.get_double("Fraction");
      if (generator_count > 0 || generator_fraction > 0.)
        {
          if (!p.positions.empty())
            throw InputError("entries 'Particles/Generator' and 'Particles/" +
                             std::string(p.positions_file.empty() ?
                                           "Positions" :
                                           "Positions file") +
                             "' are both set; allowed: one of them");
          if (generator_count > 0 && generator_fraction > 0.)
            throw InputError("entries 'Particles/Generator/Number of "
                             "particles' (" +
                             std::to_string(generator_count) +
                             ") and 'Particles/Generator/Fraction' (" +
                             std::to_string(generator_fraction) +
                             ") are both set; allowed: one of them");
          Contact::GeneratorSettings g;
          g.dimension       = dim;
          g.n_particles     = generator_count;
          g.target_fraction = generator_fraction;
          g.radii_values =
            parse_numbers(prm.get("Radii"), "Particles/Generator/Radii");
          if (g.radii_values.empty())
            g.radii_values = given_radii;
          g.radii_weights = parse_numbers(prm.get("Radius weights"),
                                          "Particles/Generator/Radius weights");
          g.lower         = p.lower_left;
          g.upper         = p.upper_right;
          if (!Utilities::trim(prm.get("Region lower left")).empty())
            g.lower = parse_point(prm.get("Region lower left"),
                                  "Particles/Generator/Region lower left",
                                  dim);
          if (!Utilities::trim(prm.get("Region upper right")).empty())
            g.upper = parse_point(prm.get("Region upper right"),
                                  "Particles/Generator/Region upper right",
                                  dim);
          for (unsigned int d = 0; d < dim; ++d)
            {
              if (g.lower[d] < p.lower_left[d] || g.upper[d] > p.upper_right[d])
                throw InputError(
                  "entries 'Particles/Generator/Region lower left' and "
                  "'Region upper right' give a region that leaves the box "
                  "along axis " +
                  std::to_string(d) + "; allowed: a region inside the box");
              // Periodic where the box is ('sliding walls': all axes but y)
              // and the region spans it.
              g.periodic[d] =
                p.boundary_condition == BoundaryCondition::sliding_walls &&
                d != 1 && g.lower[d] == p.lower_left[d] &&
                g.upper[d] == p.upper_right[d];
            }
          double a_min = std::numeric_limits<double>::max();
          for (const double a : g.radii_values)
            a_min = std::min(a_min, a);
          g.min_separation = prm.get_double("Minimum separation") *
                             (g.radii_values.empty() ? 0. : a_min);
          g.seed           = prm.get_integer("Seed");
          g.max_iterations = prm.get_integer("Maximum iterations");
          try
            {
              const Contact::GeneratedParticles placed =
                Contact::ParticleGenerator::generate(g);
              p.positions = placed.positions;
              file_radii  = placed.radii;
            }
          catch (const Contact::ContactError &e)
            {
              throw InputError(std::string("entry 'Particles/Generator': ") +
                               e.what());
            }
        }
      prm.leave_subsection();
    }



    /// Particles: one radius per particle, the external forces.
    void
    parse_radii_and_forces(ParameterHandler          &prm,
                           Parameters                &p,
                           const std::vector<double> &given_radii,
                           const std::vector<double> &file_radii)
    {
      const unsigned int dim = p.dimension;
      if (!file_radii.empty())
        p.radii = file_radii;
      else if (given_radii.size() == 1)
        p.radii.assign(p.positions.size(), given_radii[0]);
      else if (given_radii.size() == p.positions.size() && !p.positions.empty())
        p.radii = given_radii;
      else
        throw InputError("entry 'Particles/Radius' has " +
                         std::to_string(given_radii.size()) + " values for " +
                         std::to_string(p.positions.size()) +
                         " particles; allowed: one value for all particles or "
                         "one per particle");
      for (unsigned int i = 0; i < p.radii.size(); ++i)
        if (!(p.radii[i] > 0.))
          throw InputError("entry 'Particles/Radius' has the value " +
                           std::to_string(p.radii[i]) + " for particle " +
                           std::to_string(i) + "; allowed: a radius > 0");

      p.external_forces.clear();
      const std::string forces_text = prm.get("External force");
      std::vector<std::array<double, 3>> forces;
      for (const std::string &item :
           Utilities::split_string_list(forces_text, ';'))
        if (!item.empty())
          forces.push_back(parse_point(item, "Particles/External force", dim));
      if (forces.size() == 1)
        p.external_forces.assign(p.positions.size(), forces[0]);
      else if (forces.size() == p.positions.size())
        p.external_forces = forces;
      else if (!forces.empty())
        throw InputError("entry 'Particles/External force' has " +
                         std::to_string(forces.size()) + " forces for " +
                         std::to_string(p.positions.size()) +
                         " particles; allowed: one force for all particles "
                         "or one per particle, separated by ';'");
      bool any_force = false;
      for (const auto &f : p.external_forces)
        for (const double c : f)
          any_force = any_force || c != 0.;
      if (!any_force)
        p.external_forces.clear();
    }



    /// Contact: the model and its projection.
    void
    parse_contact(ParameterHandler &prm, Parameters &p)
    {
      prm.enter_subsection("Contact");
      {
        const std::string m    = prm.get("Model");
        p.contact_model        = m == "none"      ? ContactModel::none :
                                 m == "inelastic" ? ContactModel::inelastic :
                                                    ContactModel::gluey;
        p.walls                = prm.get_bool("Walls");
        p.contact_tolerance    = prm.get_double("Tolerance");
        p.dual_solver          = prm.get("Dual solver");
        p.alert_distance       = prm.get_double("Alert distance");
        p.drag_coefficient     = prm.get_double("Drag coefficient");
        p.roughness            = prm.get_double("Roughness");
        p.rough_contact        = prm.get_bool("Rough contact");
        p.friction_coefficient = prm.get_double("Friction coefficient");
      }
      prm.leave_subsection();
    }



    /// Time stepping.
    void
    parse_time_stepping(ParameterHandler &prm, Parameters &p)
    {
      prm.enter_subsection("Time stepping");
      {
        p.end_time               = prm.get_double("End time");
        p.time_step              = prm.get_double("Time step");
        p.adaptive_time_step     = prm.get_bool("Adaptive time step");
        p.cfl_number             = prm.get_double("CFL number");
        p.maximum_time_step      = prm.get_double("Maximum time step");
        p.gap_step_fraction      = prm.get_double("Gap step fraction");
        p.gap_step_floor         = prm.get_double("Gap step floor");
        p.time_scheme            = prm.get("Scheme") == "trapezoidal" ?
                                     TimeSchemeType::trapezoidal :
                                     TimeSchemeType::ab2;
        p.trapezoidal_iterations = prm.get_integer("Trapezoidal iterations");
      }
      prm.leave_subsection();
    }



    /// Mesh refinement.
    void
    parse_mesh_refinement(ParameterHandler &prm, Parameters &p)
    {
      prm.enter_subsection("Mesh refinement");
      {
        p.initial_global_refinement =
          prm.get_integer("Initial global refinement");
        p.minimum_level           = prm.get_integer("Minimum level");
        p.maximum_level           = prm.get_integer("Maximum level");
        p.interface_band          = prm.get_double("Interface band");
        p.gap_refinement_distance = prm.get_double("Gap refinement distance");
        p.remesh_fraction         = prm.get_double("Remesh fraction");
      }
      prm.leave_subsection();
    }



    /// Output.
    void
    parse_output(ParameterHandler &prm, Parameters &p)
    {
      prm.enter_subsection("Output");
      {
        p.field_output_interval = prm.get_integer("Field output interval");
        p.particle_output_interval =
          prm.get_integer("Particle output interval");
        p.particle_csv_interval    = prm.get_integer("Particle CSV interval");
        p.progress_interval        = prm.get_integer("Progress interval");
        p.progress_wall_interval   = prm.get_double("Progress wall interval");
        p.checkpoint_interval      = prm.get_integer("Checkpoint interval");
        p.checkpoint_wall_interval = prm.get_double("Checkpoint wall interval");
        const std::string v        = prm.get("Verbosity");
        p.verbosity                = v == "quiet"  ? Verbosity::quiet :
                                     v == "normal" ? Verbosity::normal :
                                                     Verbosity::verbose;
      }
      prm.leave_subsection();
    }



  } // namespace



  void
  Parameters::parse(ParameterHandler &prm, const std::string &input_name)
  {
    dimension        = prm.get_integer("Dimension");
    output_directory = prm.get("Output directory");

    // Fluid entries whose 'auto' depends on the contact model, read below.
    std::string shared_cells_choice, reuse_choice;
    parse_domain(prm, *this);

    prm.enter_subsection("Fluid");
    parse_fluid(prm, *this, shared_cells_choice, reuse_choice);
    parse_linear_solver(prm, *this);
    prm.leave_subsection();

    prm.enter_subsection("Particles");
    {
      const std::vector<double> given_radii =
        parse_numbers(prm.get("Radius"), "Particles/Radius");
      std::vector<double> file_radii;
      parse_positions(prm, *this, input_name, file_radii);
      parse_generator(prm, *this, given_radii, file_radii);
      parse_radii_and_forces(prm, *this, given_radii, file_radii);
    }
    prm.leave_subsection();

    parse_contact(prm, *this);

    // The 'auto' choices of the fluid depend on the contact model: a pair
    // closer than a cell is released where something else keeps it apart.
    release_shared_cells =
      shared_cells_choice == "auto" ?
        contact_model != ContactModel::none || lubrication :
        shared_cells_choice == "fluid";
    reuse_multiplier =
      reuse_choice == "auto" ? !release_shared_cells : reuse_choice == "true";

    parse_time_stepping(prm, *this);
    parse_mesh_refinement(prm, *this);
    parse_output(prm, *this);

    check_scene();
  }



  double
  Parameters::smallest_side() const
  {
    double side = upper_right[0] - lower_left[0];
    for (unsigned int d = 1; d < dimension; ++d)
      side = std::min(side, upper_right[d] - lower_left[d]);
    return side;
  }



  double
  Parameters::finest_cell_size() const
  {
    return smallest_side() / std::pow(2., maximum_level);
  }
} // namespace Fidus
