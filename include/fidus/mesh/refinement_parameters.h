#ifndef fidus_mesh_refinement_parameters_h
#define fidus_mesh_refinement_parameters_h

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /**
   * How the adaptive mesh of the fictitious domain (and the cut element's
   * level range) is refined: the entries of the subsection Mesh refinement.
   */
  struct RefinementParameters
  {
    /// Register the entries of the subsection Mesh refinement.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back.
    void
    parse(dealii::ParameterHandler &prm);

    /// Throw an InputError if the band is not positive or the levels are
    /// not ordered.
    void
    check() const;

    unsigned int initial_global_refinement = 3;
    unsigned int minimum_level             = 3;
    unsigned int maximum_level             = 8;
    double       interface_band            = 1.;
    double       gap_refinement_distance   = 0.5;
    double       remesh_fraction           = 0.5;
  };
} // namespace Fidus

#endif
