// The Coulomb conditions of contact/friction (tests/contact/cone_check.h) on
// the largest packings the issue asks for: 10^4 discs and 10^4 spheres at
// the density of the smaller ones, squeezed and sheared with random spins
// for 8 projections (fewer contacts per particle than contact/friction's 30
// to 40: squeezed that far, the Gauss-Seidel takes minutes at this size,
// doc/theory/contact.md), mu = 0.5, inelastic. Every
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
                                          8,
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
