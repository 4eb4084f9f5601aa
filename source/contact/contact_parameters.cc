// The entries of the subsection Contact.

#include <deal.II/base/parameter_handler.h>
#include <fidus/contact/contact_parameters.h>
#include <fidus/core/input_error.h>

namespace Fidus
{
  using namespace dealii;

  void
  ContactParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry("Model",
                      "gluey",
                      Patterns::Selection("none|inelastic|gluey"),
                      "Projection of the particle velocities: 'none' (no "
                      "correction, overlaps possible), 'inelastic' (no "
                      "overlap), 'gluey' (no overlap, glued pairs keep "
                      "their gap until the compressive impulse is paid "
                      "back).");
    prm.declare_entry("Walls",
                      "true",
                      Patterns::Bool(),
                      "Faces whose imposed velocity has no normal component "
                      "take part in contact.");
    prm.declare_entry("Tolerance",
                      "1e-9",
                      Patterns::Double(0., 1e-2),
                      "Allowed constraint violation relative to the "
                      "smallest radius.");
    prm.declare_entry("Dual solver",
                      "projected Gauss-Seidel",
                      Patterns::Selection(
                        "projected gradient|accelerated projected "
                        "gradient|projected Gauss-Seidel"),
                      "Algorithm for the multipliers of the projection.");
    prm.declare_entry(
      "Maximum iterations",
      std::to_string(Contact::Settings().max_iterations),
      Patterns::Integer(1),
      "Iterations of the dual solver (sweeps of Gauss-Seidel) after which "
      "a projection that has not reached 'Tolerance' stops. The run goes "
      "on: the overlap it leaves, at most its residual, is accepted and "
      "pushed apart by the next projection, and the step is counted in "
      "the run's contact failures (doc/theory/contact.md). Needs a "
      "contact model other than 'none'; >= 1.");
    prm.declare_entry("Alert distance",
                      "0.1",
                      Patterns::Double(0.),
                      "Pairs closer than this gap, relative to the "
                      "smallest radius, enter the constraints (never less "
                      "than a safe multiple of dt * max |u|), >= 0.");
    prm.declare_entry(
      "Roughness",
      "5e-3",
      Patterns::Double(0., 1.),
      "Asperity height relative to the smaller radius of a pair (the "
      "radius for a wall): with 'Fluid/Lubrication correction', gaps "
      "below it count as this gap, so that the squeeze resistance stays "
      "finite and the contact model takes over. Between 0 and 1.");
    prm.declare_entry(
      "Rough contact",
      "false",
      Patterns::Bool(),
      "Whether the contact model holds the gaps at the roughness "
      "(Contact/Roughness times the smaller radius; the radius for a "
      "wall) rather than at zero, as asperities would: the contact model "
      "then takes over at the gap where the lubrication correction "
      "stops growing. Needs a contact model other than 'none'.");
    prm.declare_entry(
      "Friction coefficient",
      "0",
      Patterns::Double(0.),
      "Coulomb friction coefficient mu of every contact, between "
      "particles and with walls: a contact's tangential force is at most "
      "mu times its normal force, opposes the slip when it slides and "
      "stops the slip when it can. The projection then corrects the "
      "rotations too (doc/theory/contact.md, 'Friction'). 0: "
      "frictionless. Needs a contact model other than 'none'; >= 0.");
    prm.declare_entry(
      "Drag coefficient",
      "0",
      Patterns::Double(0.),
      "Force per unit velocity that turns the contact correction "
      "u - u* of a particle into a contact force, for the contact "
      "stress in statistics.csv (the projection itself does not use "
      "it), and the drag of a particle in the lubrication correction; "
      "0: the Stokes drag of an isolated particle, 6 pi eta a in 3D "
      "(a: the mean radius for the stress, each particle's own in the "
      "lubrication) and 4 pi eta per unit length in 2D. "
      ">= 0.");
    prm.leave_subsection();
  }



  void
  ContactParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    {
      const std::string m  = prm.get("Model");
      model                = m == "none"      ? ContactModel::none :
                             m == "inelastic" ? ContactModel::inelastic :
                                                ContactModel::gluey;
      walls                = prm.get_bool("Walls");
      tolerance            = prm.get_double("Tolerance");
      dual_solver          = prm.get("Dual solver");
      max_iterations       = prm.get_integer("Maximum iterations");
      alert_distance       = prm.get_double("Alert distance");
      drag_coefficient     = prm.get_double("Drag coefficient");
      roughness            = prm.get_double("Roughness");
      rough_contact        = prm.get_bool("Rough contact");
      friction_coefficient = prm.get_double("Friction coefficient");
    }
    prm.leave_subsection();
  }



  void
  ContactParameters::check() const
  {
    // Friction and rough contact act at contacts, which 'none' does not
    // have: they would do nothing.
    if (model == ContactModel::none && friction_coefficient > 0.)
      throw InputError("entry 'Contact/Friction coefficient' has the value " +
                       std::to_string(friction_coefficient) +
                       " with 'Contact/Model = none', which has no contacts; "
                       "allowed: 0, or the model 'inelastic' or 'gluey'");
    // The contact library's own limit is the entry's default.
    const unsigned int default_iterations = Contact::Settings().max_iterations;
    if (model == ContactModel::none && max_iterations != default_iterations)
      throw InputError("entry 'Contact/Maximum iterations' has the value " +
                       std::to_string(max_iterations) +
                       " with 'Contact/Model = none', which projects "
                       "nothing; allowed: the default " +
                       std::to_string(default_iterations) +
                       ", or the model 'inelastic' or 'gluey'");
    if (model == ContactModel::none && rough_contact)
      throw InputError("entry 'Contact/Rough contact' is true with "
                       "'Contact/Model = none', which has no contacts; "
                       "allowed: false, or the model 'inelastic' or 'gluey'");
  }



  Contact::Settings
  ContactParameters::settings(const unsigned int dim,
                              const double       smallest_radius) const
  {
    Contact::Settings cs;
    cs.dimension         = dim;
    cs.model             = model == ContactModel::none ? Contact::Model::none :
                           model == ContactModel::inelastic ? Contact::Model::inelastic :
                                                              Contact::Model::gluey;
    cs.solver            = dual_solver == "projected gradient" ?
                             Contact::DualSolver::projected_gradient :
                           dual_solver == "accelerated projected gradient" ?
                             Contact::DualSolver::accelerated_projected_gradient :
                             Contact::DualSolver::projected_gauss_seidel;
    cs.tolerance         = tolerance * smallest_radius;
    cs.alert_distance    = alert_distance * smallest_radius;
    cs.overlap_tolerance = 2. * cs.tolerance;
    cs.friction          = friction_coefficient;
    cs.max_iterations    = max_iterations;
    cs.contact_distance  = rough_contact ? roughness : 0.;
    return cs;
  }
} // namespace Fidus
