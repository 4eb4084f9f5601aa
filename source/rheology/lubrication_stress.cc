#include <fidus/rheology/lubrication_stress.h>

namespace Fidus
{
  dealii::SymmetricTensor<2, 3>
  lubrication_stress(const std::vector<Contact::LubricationBond> &bonds,
                     const double                                 volume)
  {
    dealii::SymmetricTensor<2, 3> sigma;
    for (const Contact::LubricationBond &b : bonds)
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          sigma[i][j] -= b.force * b.length * b.n[i] * b.n[j];
    return sigma / volume;
  }
} // namespace Fidus
