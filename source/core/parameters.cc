// Reading a parameter file: every module's entries, the order in which
// their 'auto' rules are resolved, and the messages of the ParameterHandler
// turned into one InputError. The modules' entries are in their own folders
// (*_parameters.cc); the checks of the scene as a whole in
// parameters_check.cc.

#include <algorithm>
#include <cmath>
#include <deal.II/base/parameter_handler.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameters.h>
#include <fidus/particles/particle_measure.h>
#include <fstream>

namespace Fidus
{
  using namespace dealii;

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



  void
  Parameters::declare(ParameterHandler &prm)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Space dimension of the scene, chosen at run time. "
                      "Allowed: 2 or 3.");
    prm.declare_entry("Output directory",
                      "output",
                      Patterns::FileName(Patterns::FileName::output),
                      "Folder for all output files (created if missing). "
                      "Relative paths are relative to the working directory.");
    DomainParameters::declare(prm);
    FluidParameters::declare(prm);
    CutElementParameters::declare(prm);
    FictitiousDomainParameters::declare(prm);
    LubricationParameters::declare(prm);
    ParticleParameters::declare(prm);
    ContactParameters::declare(prm);
    TimeSteppingParameters::declare(prm);
    RefinementParameters::declare(prm);
    OutputParameters::declare(prm);
  }



  void
  Parameters::parse(ParameterHandler &prm, const std::string &input_name)
  {
    dimension        = prm.get_integer("Dimension");
    output_directory = prm.get("Output directory");

    domain.parse(prm, dimension);
    fluid.parse(prm);
    cut_element.parse(prm);
    fictitious_domain.parse(prm, dimension, fluid.velocity_degree);
    lubrication.parse(prm, dimension, fictitious_domain.solid_retraction);
    particles.parse(prm, dimension, domain, input_name);
    contact.parse(prm);
    // A pair closer than a cell is released where something else keeps it
    // apart.
    fictitious_domain.resolve_shared_cells(
      contact.model != ContactModel::none || lubrication.enabled);
    resolve_lubrication_coupling();
    time_stepping.parse(prm);
    refinement.parse(prm);
    output.parse(prm);

    check_scene();
  }



  double
  Parameters::particle_volume_fraction() const
  {
    double box = 1.;
    for (unsigned int d = 0; d < dimension; ++d)
      box *= domain.upper_right[d] - domain.lower_left[d];
    double solid = 0.;
    for (const double r : particles.radii)
      solid += particle_measure(dimension, r);
    return solid / box;
  }



  void
  Parameters::resolve_lubrication_coupling()
  {
    using Coupling = LubricationParameters::Coupling;
    // The cut element keeps 'auto' (its only way is with the flow); the
    // coupled fictitious domain needs the gaps at the start of the step.
    if (!lubrication.enabled || lubrication.coupling != Coupling::automatic ||
        fluid.model != FluidModelType::fictitious_domain)
      return;
    const bool dilute =
      particle_volume_fraction() < LubricationParameters::dilute_fraction;
    lubrication.coupling =
      dilute && lubrication.gap_in_time == Contact::GapInTime::start ?
        Coupling::with_the_flow :
        Coupling::after_the_solve;
  }



  double
  Parameters::smallest_side() const
  {
    double side = domain.upper_right[0] - domain.lower_left[0];
    for (unsigned int d = 1; d < dimension; ++d)
      side = std::min(side, domain.upper_right[d] - domain.lower_left[d]);
    return side;
  }



  double
  Parameters::finest_cell_size() const
  {
    return smallest_side() / std::pow(2., refinement.maximum_level);
  }
} // namespace Fidus
