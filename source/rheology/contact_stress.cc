#include <fidus/rheology/contact_stress.h>

namespace Fidus
{
  dealii::SymmetricTensor<2, 3>
  contact_stress(const Contact::ConstraintSystem &rows,
                 const std::vector<double>       &radii,
                 const double                     drag,
                 const double                     volume)
  {
    // The particles' shares add up to every row's whole contribution.
    dealii::SymmetricTensor<2, 3> sigma;
    for (const auto &s : contact_stresslets(rows, radii, drag))
      sigma += s;
    return sigma / volume;
  }



  std::vector<dealii::SymmetricTensor<2, 3>>
  contact_stresslets(const Contact::ConstraintSystem &rows,
                     const std::vector<double>       &radii,
                     const double                     drag)
  {
    const std::size_t                          n = radii.size();
    std::vector<dealii::SymmetricTensor<2, 3>> s(n);
    for (std::size_t k = 0; k < rows.size(); ++k)
      {
        const double lambda = rows.lambda(k);
        // The friction force (zero without friction) has no trace but adds
        // to the shear stress and the normal-stress differences.
        const Contact::Vec3 &t  = rows.tangential_impulse(k);
        const bool has_friction = t[0] != 0. || t[1] != 0. || t[2] != 0.;
        if (lambda == 0. && !has_friction)
          continue;
        const std::uint32_t bodies[2] = {rows.first(k), rows.second(k)};
        double              branch    = rows.gap(k);
        unsigned int        particles = 0;
        for (const std::uint32_t body : bodies)
          if (body < n)
            {
              branch += radii[body];
              ++particles;
            }
        const auto &e = rows.normal(k);
        for (const std::uint32_t body : bodies)
          if (body < n)
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = i; j < 3; ++j)
                {
                  s[body][i][j] -=
                    drag * lambda * branch * e[i] * e[j] / particles;
                  if (has_friction)
                    s[body][i][j] -= drag * branch * 0.5 *
                                     (e[i] * t[j] + t[i] * e[j]) / particles;
                }
      }
    return s;
  }
} // namespace Fidus
