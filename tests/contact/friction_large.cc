// The Coulomb conditions of contact/friction (tests/contact/cone_check.h) on
// the largest packings the issue asks for: 10^4 discs and 10^4 spheres at
// the density of the smaller ones, squeezed and sheared with random spins,
// mu = 0.5, inelastic: the discs for 40 projections, as far as
// contact/friction squeezes its 2000 (about 0.6 active contacts per disc),
// the spheres for 8 (squeezed as far as contact/friction's 1000, over 30
// projections, the 3D projections take up to 2500 sweeps at this size and
// the test ten minutes: doc/history/contact.md). Every
// contact of every projection satisfies lambda_n >= 0, |lambda_t| <= mu
// lambda_n, normal complementarity, no slip inside the cone, a sliding
// impulse on the rim and against the slip, non-negative dissipation, and
// every particle's force and torque balance, each to the solver's tolerance.

#include "cone_check.h"

int
main()
{
  // Measured numbers go to a file beside the output, which compares only
  // the checks (iteration counts may differ with the compiler).
  std::FILE *log = std::fopen("statistics.txt", "w");
  try
    {
      for (const unsigned dim : {2u, 3u})
        ConeCheck::check_squeezed_packing(dim,
                                          10000,
                                          Fidus::Contact::Model::inelastic,
                                          dim == 2 ? 40 : 8,
                                          log);
    }
  catch (const Fidus::Contact::ContactError &e)
    {
      std::printf("ContactError: %s\n", e.what());
      return 1;
    }
  std::fclose(log);
  return TestTools::failures() != 0;
}
