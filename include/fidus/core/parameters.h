#ifndef fidus_core_parameters_h
#define fidus_core_parameters_h

#include <fidus/contact/contact_parameters.h>
#include <fidus/fluid/cut_element/cut_element_parameters.h>
#include <fidus/fluid/fictitious_domain/fictitious_domain_parameters.h>
#include <fidus/fluid/fluid_parameters.h>
#include <fidus/io/output_parameters.h>
#include <fidus/lubrication/lubrication_parameters.h>
#include <fidus/mesh/domain_parameters.h>
#include <fidus/mesh/refinement_parameters.h>
#include <fidus/particles/particle_parameters.h>
#include <fidus/time_stepping/time_stepping_parameters.h>
#include <ostream>
#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /**
   * All run-time parameters of a scene: the two top-level entries and one
   * struct per module, which declares, reads and checks its own entries
   * (ParameterHandler's subsections; several modules may share one, as the
   * fluid models and the lubrication correction share Fluid). Adding an
   * entry touches the module that owns it only.
   *
   * declare() registers every module's entries; parse() reads them back in
   * the order their 'auto' rules need and checks the scene as a whole
   * (particles inside the box, no overlap, what one module's settings
   * require of another's). Every problem is thrown as an InputError that
   * names the entry, the value and what is allowed. Vectors always have
   * three components and the third is zero in 2D.
   */
  struct Parameters
  {
    /// Register all entries in @p prm.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read all entries from @p prm and check the scene. @p input_name is the
    /// name of the parameter file, used to resolve a relative positions file.
    void
    parse(dealii::ParameterHandler &prm, const std::string &input_name);

    /// The shortest side of the box.
    double
    smallest_side() const;

    /// Edge of a cell at the Maximum level (the box mesh has square cells
    /// whose coarse size is the shortest side).
    double
    finest_cell_size() const;

    /// The particles' nominal volume fraction (area fraction in 2D): their
    /// volumes over the box's.
    double
    particle_volume_fraction() const;

    /// Resolve 'Fluid/Lubrication coupling = auto' for the fictitious
    /// domain from the scene (called by parse()): with the flow below
    /// LubricationParameters::dilute_fraction, where the bonds are few and
    /// a pair's closing rate needs the flow of its lubricated motion;
    /// after the solve in a dense suspension, where the coupled solves
    /// cost several times more for no measured gain in the stress.
    void
    resolve_lubrication_coupling();

    /// Check the scene as a whole (called by parse()): each module's own
    /// checks, then what involves several.
    void
    check_scene() const;

    /// Number of particles.
    unsigned int
    n_particles() const
    {
      return particles.positions.size();
    }

    /// Dimension: 2 or 3.
    unsigned int dimension = 2;
    /// Output directory.
    std::string output_directory = "output";

    DomainParameters           domain;
    FluidParameters            fluid;
    FictitiousDomainParameters fictitious_domain;
    CutElementParameters       cut_element;
    LubricationParameters      lubrication;
    ParticleParameters         particles;
    ContactParameters          contact;
    TimeSteppingParameters     time_stepping;
    RefinementParameters       refinement;
    OutputParameters           output;
  };

  /**
   * Read and check a parameter file (.prm or .json). Every problem, including
   * those the ParameterHandler finds (unknown entry, value not matching its
   * pattern), is thrown as one InputError naming the file and the entry.
   * If @p used_parameters is not null, the complete set of parameters as
   * used (defaults included) is written to it in .prm form.
   */
  Parameters
  read_parameters(const std::string &filename,
                  std::ostream      *used_parameters = nullptr);

  /// Same, from the text of a parameter file (for tests and scripts).
  Parameters
  read_parameters_from_string(const std::string &text);
} // namespace Fidus

#endif
