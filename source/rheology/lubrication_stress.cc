#include <fidus/contact/vector_operations.h>
#include <fidus/rheology/lubrication_stress.h>

namespace Fidus
{
  namespace
  {
    using Contact::Vec3;

    /// The part of a sliding gap's first moment that the bond's force
    /// across its length leaves out. The tangential load on a particle is
    /// the shear on its surface at the gap plus a part F_p from the gap
    /// pressure on the curved surface (LubricationCorrection's class
    /// documentation). A pressure acts along the surface normal, so its
    /// first moment about the centre is symmetric and puts a F_p whole into
    /// sym(n (x) F_p) twice, where the force across the length counts it
    /// once; the shear's moment a n (x) s is counted right. The shear is
    /// read back from the bond's torque, T = a n_k x s (n_k from the centre
    /// to the gap). Zero for two equal discs sliding with equal rotations,
    /// about a third of a disc's stresslet next to a sliding wall
    /// (doc/history/cut_element_lubrication.md).
    void
    add_gap_pressure_moment(const Contact::LubricationBond             &b,
                            std::vector<dealii::SymmetricTensor<2, 3>> &s)
    {
      const bool pair = b.j != Contact::LubricationBond::no_particle;
      const auto add  = [&](const std::size_t k,
                           const double      a,
                           const double      side,
                           const Vec3       &force,
                           const Vec3       &torque) {
        if (!(a > 0.))
          return;
        Vec3 n, f_p;
        for (unsigned int d = 0; d < 3; ++d)
          n[d] = side * b.n[d];
        const Vec3 shear = Contact::cross(torque, n);
        for (unsigned int d = 0; d < 3; ++d)
          f_p[d] = force[d] - shear[d] / a;
        const double f_n = Contact::dot(f_p, n);
        for (unsigned int d = 0; d < 3; ++d)
          f_p[d] -= f_n * n[d];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            s[k][i][j] += 0.5 * a * (n[i] * f_p[j] + n[j] * f_p[i]);
      };
      Vec3 on_i;
      for (unsigned int d = 0; d < 3; ++d)
        on_i[d] = -b.tangential_force[d];
      add(b.i, b.a_i, 1., on_i, b.torque_i);
      if (pair)
        add(b.j, b.a_j, -1., b.tangential_force, b.torque_j);
    }
  } // namespace



  dealii::SymmetricTensor<2, 3>
  lubrication_stress(const std::vector<Contact::LubricationBond> &bonds,
                     const double                                 volume)
  {
    std::size_t n = 0;
    for (const Contact::LubricationBond &b : bonds)
      {
        n = std::max<std::size_t>(n, b.i + 1);
        if (b.j != Contact::LubricationBond::no_particle)
          n = std::max<std::size_t>(n, b.j + 1);
      }
    dealii::SymmetricTensor<2, 3> sigma;
    for (const auto &s : lubrication_stresslets(bonds, n))
      sigma += s;
    return sigma / volume;
  }



  std::vector<dealii::SymmetricTensor<2, 3>>
  lubrication_stresslets(const std::vector<Contact::LubricationBond> &bonds,
                         const std::size_t n_particles)
  {
    std::vector<dealii::SymmetricTensor<2, 3>> s(n_particles);
    for (const Contact::LubricationBond &b : bonds)
      {
        const bool   pair  = b.j != Contact::LubricationBond::no_particle;
        const double share = pair ? 0.5 : 1.;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            {
              // The bond's force on j, normal and tangential, acting across
              // the length of the bond.
              const double t = -share * b.length *
                               (b.force * b.n[i] * b.n[j] +
                                0.5 * (b.n[i] * b.tangential_force[j] +
                                       b.n[j] * b.tangential_force[i]));
              s[b.i][i][j] += t;
              if (pair)
                s[b.j][i][j] += t;
            }
        add_gap_pressure_moment(b, s);
      }
    return s;
  }
} // namespace Fidus
