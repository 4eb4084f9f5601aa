#include <fidus/rheology/lubrication_stress.h>

namespace Fidus
{
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
      }
    return s;
  }
} // namespace Fidus
