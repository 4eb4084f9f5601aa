// The entries of the subsection Particles: positions given, read from a file
// or placed by the generator, radii and external forces.

#include <algorithm>
#include <cmath>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>
#include <fidus/contact/contact_error.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/mesh/domain_parameters.h>
#include <fidus/particles/particle_generator.h>
#include <fidus/particles/particle_parameters.h>
#include <fstream>
#include <limits>
#include <sstream>

namespace Fidus
{
  using namespace dealii;

  void
  ParticleParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Particles");
    prm.declare_entry("Radius",
                      "0.05",
                      Patterns::Anything(),
                      "Particle radius [length], > 0: one value for all "
                      "particles or one per particle, comma separated.");
    prm.declare_entry("Positions",
                      "",
                      Patterns::Anything(),
                      "Centres [length], particles separated by ';', "
                      "coordinates by ',', e.g. '0.451, 0.51; 0.549, 0.49'.");
    prm.declare_entry(
      "External force",
      "",
      Patterns::Anything(),
      "Force [force, per unit length in 2D] on the particles, e.g. "
      "gravity minus buoyancy: one vector 'fx, fy[, fz]' for every "
      "particle, or one per particle separated by ';'. Empty: force-free "
      "particles (the seed's scenes). In the fictitious domain it acts as a uniform "
      "force density over each particle's solid, so the fluid carries it "
      "to the walls; the cut element applies it to each particle's rigid "
      "motion; the stress output assumes force-free particles "
      "(doc/fluid.md). Free-draining particles (undisturbed shear) move "
      "at F over their isolated drag, 6 pi eta a (4 pi eta per unit "
      "length in 2D). Not with the exact rigid inclusion.");
    prm.declare_entry("Positions file",
                      "",
                      Patterns::Anything(),
                      "Alternative to 'Positions': a text file with one "
                      "particle per line, 'x y [z] [radius]' ('#' starts a "
                      "comment). Relative to the parameter file.");
    prm.leave_subsection();
    prm.enter_subsection("Particles");
    prm.enter_subsection("Generator");
    prm.declare_entry(
      "Number of particles",
      "0",
      Patterns::Integer(0),
      "Particles to place at random without overlap, instead of "
      "'Positions' (which must then be empty); 0: use 'Fraction'. At "
      "most one of the two may be > 0; both 0: no generator.");
    prm.declare_entry(
      "Fraction",
      "0",
      Patterns::Double(0., 1.),
      "Area fraction (2D) or volume fraction (3D) of the region to fill; "
      "the number of particles follows. Below 0.9069 (2D) and 0.7405 "
      "(3D), the densest packings; random packings jam near 0.84 "
      "(bidisperse discs) and 0.64 (spheres). Reached by growing the "
      "particles from a tenth of the fraction while pushing overlapping "
      "pairs apart; 0.6 (2D) and 0.5 (3D) take about a second for 1e5 "
      "particles (contrib/benchmarks/particle_generator.sh).");
    prm.declare_entry(
      "Radii",
      "",
      Patterns::Anything(),
      "Radii [length], comma separated: one value (monodisperse), two "
      "(bidisperse, e.g. 'a, 1.4 a' in 2D, where equal discs "
      "crystallise) or more (polydisperse). Empty: 'Particles/Radius'.");
    prm.declare_entry("Radius weights",
                      "",
                      Patterns::Anything(),
                      "Number fractions of 'Radii', one per radius, "
                      "summing to 1; empty: equal fractions.");
    prm.declare_entry("Region lower left",
                      "",
                      Patterns::Anything(),
                      "Lower corner of the region to fill [length], one "
                      "coordinate per dimension; empty: the box.");
    prm.declare_entry(
      "Region upper right",
      "",
      Patterns::Anything(),
      "Upper corner of the region to fill [length]; empty: the box. "
      "Along a periodic axis of 'sliding walls' the region is periodic "
      "when it spans the box.");
    prm.declare_entry(
      "Minimum separation",
      "0",
      Patterns::Double(0.),
      "Smallest gap between particles, and between a particle and a "
      "non-periodic face of the region, relative to the smallest "
      "radius, >= 0.");
    prm.declare_entry("Seed",
                      "1",
                      Patterns::Integer(0),
                      "Seed of the random numbers: the same parameters "
                      "and seed give the same particles.");
    prm.declare_entry("Maximum iterations",
                      "20000",
                      Patterns::Integer(1),
                      "Cap on the relaxation sweeps of the generator; a "
                      "jammed growth stops earlier with an error naming "
                      "the fraction reached.");
    prm.leave_subsection();
    prm.leave_subsection();
  }



  namespace
  {
    using ParameterParsing::parse_numbers;
    using ParameterParsing::parse_point;

    /// Particles: the positions, given or from a file (relative to
    /// @p input_name), with the file's radii in @p file_radii.
    void
    parse_positions(ParameterHandler    &prm,
                    ParticleParameters  &p,
                    const unsigned int   dim,
                    const std::string   &input_name,
                    std::vector<double> &file_radii)
    {
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
                    ParticleParameters        &p,
                    const unsigned int         dim,
                    const DomainParameters    &domain,
                    const std::vector<double> &given_radii,
                    std::vector<double>       &file_radii)
    {
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
          g.lower         = domain.lower_left;
          g.upper         = domain.upper_right;
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
              if (g.lower[d] < domain.lower_left[d] ||
                  g.upper[d] > domain.upper_right[d])
                throw InputError(
                  "entries 'Particles/Generator/Region lower left' and "
                  "'Region upper right' give a region that leaves the box "
                  "along axis " +
                  std::to_string(d) + "; allowed: a region inside the box");
              // Periodic where the box is ('sliding walls': all axes but y)
              // and the region spans it.
              g.periodic[d] =
                domain.boundary_condition == BoundaryCondition::sliding_walls &&
                d != 1 && g.lower[d] == domain.lower_left[d] &&
                g.upper[d] == domain.upper_right[d];
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
                           ParticleParameters        &p,
                           const unsigned int         dim,
                           const std::vector<double> &given_radii,
                           const std::vector<double> &file_radii)
    {
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

  } // namespace



  void
  ParticleParameters::parse(ParameterHandler       &prm,
                            const unsigned int      dim,
                            const DomainParameters &domain,
                            const std::string      &input_name)
  {
    prm.enter_subsection("Particles");
    {
      const std::vector<double> given_radii =
        parse_numbers(prm.get("Radius"), "Particles/Radius");
      std::vector<double> file_radii;
      parse_positions(prm, *this, dim, input_name, file_radii);
      parse_generator(prm, *this, dim, domain, given_radii, file_radii);
      parse_radii_and_forces(prm, *this, dim, given_radii, file_radii);
    }
    prm.leave_subsection();
  }
} // namespace Fidus
