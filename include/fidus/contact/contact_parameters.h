#ifndef fidus_contact_contact_parameters_h
#define fidus_contact_contact_parameters_h

#include <fidus/contact/contact_types.h>
#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /// Contact model (numerics section 3).
  enum class ContactModel
  {
    none,
    inelastic,
    gluey
  };

  /**
   * The contact model and its projection onto the admissible set: the
   * entries of the subsection Contact. The header and the struct are free
   * of deal.II, like the contact library; declare() and parse() live in
   * the deal.II part of fidus (fidus_core).
   */
  struct ContactParameters
  {
    /// Register the entries of the subsection Contact.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back.
    void
    parse(dealii::ParameterHandler &prm);

    /// Throw an InputError for friction or rough contact with the model
    /// none, which has no contacts for them to act at.
    void
    check() const;

    /// The contact library's settings for a scene in @p dim dimensions
    /// whose smallest radius is @p smallest_radius (the tolerances are
    /// relative to it).
    Contact::Settings
    settings(const unsigned int dim, const double smallest_radius) const;

    ContactModel model       = ContactModel::gluey;
    bool         walls       = true;
    double       tolerance   = 1e-9;
    std::string  dual_solver = "projected Gauss-Seidel";
    /// Dual-solver iterations before a projection stops short of its
    /// tolerance (Contact::Settings::max_iterations).
    unsigned int max_iterations = 100000;
    double       alert_distance = 0.1;
    /// Drag coefficient zeta that turns a contact correction of velocity
    /// into a force (F = zeta (u - u*)) for the contact stress; 0: the
    /// isolated particle's Stokes drag (see doc/theory/stress.md).
    double drag_coefficient = 0.;
    /// Gaps below roughness * (smaller radius) count as that gap in the
    /// lubrication resistance.
    double roughness = 5e-3;
    /// Coulomb's mu of every contact.
    double friction_coefficient = 0.;
    /// Particles touch at a gap of roughness * (smaller radius) instead of
    /// 0.
    bool rough_contact = false;
  };
} // namespace Fidus

#endif
