// The contact stress of a projection (Fidus::contact_stress) against hand
// computations: Sigma_c = -(zeta / V) sum_k lambda_k l_k e_k (x) e_k.
// - Two touching discs (radius 0.1) driven into each other at speed 1,
//   inelastic: both stop, lambda = 1, branch 0.2, so Sigma_xx = -0.2 zeta/V
//   (compression, positive particle pressure) and nothing else.
// - The same pair, gluey, pulled apart on the next step: the glue holds
//   (lambda = -1), Sigma_xx = +0.2 zeta/V (tension).
// - A disc pushed into the lower wall at speed 1: lambda = 1, branch = the
//   radius, Sigma_yy = -0.1 zeta/V.
// - Pairs in the alert band that do not push contribute nothing.
// - Per particle (contact_stresslets): the stresslets add up to V Sigma_c,
//   and particles 0 and 1 (symmetric in every case) carry equal parts.
// - Sub-grid lubrication (lubrication_stresslets): two discs closing head-on
//   along x, a third one closing on the lower wall, a fourth far away. The
//   pair's bond (force f > 0, branch l = centre distance) gives each disc
//   -f l / 2 in xx, the wall bond gives its disc -f l in yy (l = the
//   radius), the far disc nothing; the shares add up to V Sigma_l.

#include "../fidus_test.h"

#include <fidus/contact/contact_projector.h>
#include <fidus/lubrication/lubrication_correction.h>
#include <fidus/rheology/contact_stress.h>
#include <fidus/rheology/lubrication_stress.h>

using namespace FidusTest;
using Fidus::Contact::Vec3;

namespace
{
  constexpr double zeta = 2., volume = 0.5;

  /// Check max_ij |Sigma_c,ij - expected_ij| <= 1e-9 for the rows of the
  /// projector's last projection.
  void
  check_stress(const std::string                      &what,
               const Fidus::Contact::ContactProjector &projector,
               const std::vector<double>              &radii,
               const dealii::SymmetricTensor<2, 3>    &expected)
  {
    const auto s =
      Fidus::contact_stress(projector.constraints(), radii, zeta, volume);
    double d = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        d = std::max(d, std::abs(s[i][j] - expected[i][j]));
    check_range(what + ": max |Sigma_c - expected|", d, 0., 1e-9);

    // Per particle: the stresslets add up to V Sigma_c, and particles 0
    // and 1, placed symmetrically in every case, carry equal parts.
    const auto per =
      Fidus::contact_stresslets(projector.constraints(), radii, zeta);
    dealii::SymmetricTensor<2, 3> sum;
    for (const auto &t : per)
      sum += t;
    double e = 0., share = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          e     = std::max(e, std::abs(sum[i][j] / volume - expected[i][j]));
          share = std::max(share, std::abs(per[0][i][j] - per[1][i][j]));
        }
    check_range(what + ": max |sum_i S_i / V - expected|", e, 0., 1e-9);
    check_range(what + ": max |S_0 - S_1|", share, 0., 1e-12);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  Fidus::Contact::Settings settings;
  settings.dimension        = 2;
  settings.model            = Fidus::Contact::Model::gluey;
  settings.alert_distance   = 0.05;
  std::vector<double> radii = {0.1, 0.1, 0.1};
  // Particle 2 sits far away, inside the alert band of nobody.
  std::vector<Vec3> x = {{{0.4, 0.5, 0.}}, {{0.6, 0.5, 0.}}, {{2., 2., 0.}}};
  std::vector<Vec3> u;

  for (const auto model :
       {Fidus::Contact::Model::inelastic, Fidus::Contact::Model::gluey})
    {
      settings.model = model;
      Fidus::Contact::ContactProjector projector(settings);
      const std::string                name =
        model == Fidus::Contact::Model::gluey ? "gluey" : "inelastic";
      projector.project(x,
                        radii,
                        {{{1., 0., 0.}}, {{-1., 0., 0.}}, {{0., 0., 0.}}},
                        0.01,
                        u);
      dealii::SymmetricTensor<2, 3> expected;
      expected[0][0] = -zeta * 0.2 / volume;
      check_stress(name + " pair pushed together", projector, radii, expected);
      if (model != Fidus::Contact::Model::gluey)
        continue;
      projector.project(x,
                        radii,
                        {{{-1., 0., 0.}}, {{1., 0., 0.}}, {{0., 0., 0.}}},
                        0.01,
                        u);
      expected[0][0] = zeta * 0.2 / volume;
      check_stress("gluey pair pulled apart", projector, radii, expected);
    }

  // A disc touching the lower wall y = 0, pushed into it; a second disc in
  // the alert band of the first, moving along with it.
  settings.model = Fidus::Contact::Model::inelastic;
  Fidus::Contact::ContactProjector projector(settings);
  Fidus::Contact::Wall             wall;
  wall.axis     = 1;
  wall.position = 0.;
  wall.side     = 1;
  projector.set_walls({wall});
  x     = {{{0.5, 0.1, 0.}}, {{0.72, 0.1, 0.}}};
  radii = {0.1, 0.1};
  projector.project(x, radii, {{{0., -1., 0.}}, {{0., -1., 0.}}}, 0.01, u);
  dealii::SymmetricTensor<2, 3> expected;
  expected[1][1] = -2. * zeta * 0.1 / volume;
  check_stress("two discs pushed into the wall", projector, radii, expected);

  {
    Fidus::Contact::LubricationSettings ls;
    ls.dimension = 2;
    ls.range     = 0.02;
    Fidus::Contact::LubricationCorrection lub(ls);
    lub.set_walls({wall});
    const std::vector<Vec3>   xl     = {{{0.4, 0.5, 0.}},
                                        {{0.605, 0.5, 0.}},
                                        {{0.8, 0.11, 0.}},
                                        {{2., 2., 0.}}};
    const std::vector<double> rl     = {0.1, 0.1, 0.1, 0.1};
    const std::vector<Vec3>   u_star = {{{1., 0., 0.}},
                                        {{-1., 0., 0.}},
                                        {{0., -1., 0.}},
                                        {{0., 0., 0.}}};
    std::vector<Vec3>         ul;
    lub.correct(xl, rl, u_star, ul);
    const auto &bonds  = lub.bonds();
    double      f_pair = 0., l_pair = 0., f_wall = 0., l_wall = 0.;
    for (const auto &b : bonds)
      if (b.j == Fidus::Contact::LubricationBond::no_particle)
        {
          f_wall = b.force;
          l_wall = b.length;
        }
      else
        {
          f_pair = b.force;
          l_pair = b.length;
        }
    check_range("lubrication: bonds (one pair, one wall)",
                double(bonds.size()),
                2.,
                2.);
    check_range("lubrication: closing pair and wall push apart (min force)",
                std::min(f_pair, f_wall),
                1e-12,
                1e12);
    check_range("lubrication: pair branch length / 0.205",
                l_pair / 0.205,
                1. - 1e-12,
                1. + 1e-12);
    check_range("lubrication: wall branch length / 0.11",
                l_wall / 0.11,
                1. - 1e-12,
                1. + 1e-12);
    const auto shares = Fidus::lubrication_stresslets(bonds, 4);
    std::vector<dealii::SymmetricTensor<2, 3>> hand(4);
    hand[0][0][0] = hand[1][0][0]   = -0.5 * f_pair * l_pair;
    hand[2][1][1]                   = -f_wall * l_wall;
    double                        d = 0.;
    dealii::SymmetricTensor<2, 3> sum;
    for (unsigned int p = 0; p < 4; ++p)
      {
        d = std::max(d, (shares[p] - hand[p]).norm());
        sum += shares[p];
      }
    check_range("lubrication: max |S_i - hand| / (f l)",
                d / (f_pair * l_pair),
                0.,
                1e-12);
    check_range(
      "lubrication: |sum_i S_i / V - Sigma_l| / |Sigma_l|",
      (sum / volume - Fidus::lubrication_stress(bonds, volume)).norm() /
        Fidus::lubrication_stress(bonds, volume).norm(),
      0.,
      1e-12);
  }
  return exit_code();
}
