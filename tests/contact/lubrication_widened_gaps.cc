// The bonds of the sub-grid correction solved with the cut element
// (LubricationCorrection::find_bonds() with a resolved gap fraction h_s):
// a fluid that sees particles shrunk (fluid radii) carries each gap at its
// own width between the shrunk radii, so every gap the shrinking widens
// gets a bond, resolved at the fluid's radii and width, up to half the
// smaller radius (doc/theory/lubrication.md, "With the cut finite
// element"). Five spheres of radius 0.1 on a line 0.3 a above a wall, h_s
// = 0.05: A and B 0.005 a apart (both shrunk by 0.0225 a, as the cut
// element shrinks them), B and C 0.15 a apart, C and D 0.6 a, E 0.55 a
// before A. Checked against the resistance formulas:
// - without fluid radii, or with fluid radii equal to the radii: only
//   A-B, resolved at h_s with the true radii;
// - with the shrunk radii: A-B resolved at h_s, B-C at its fluid width
//   0.195 a, A and B to the wall at 0.3225 a, each at the fluid's radii;
//   no bond for C-D, E-A (beyond half a radius) nor C, D, E to the wall
//   (not shrunk, above h_s).

#include "test_tools.h"

#include <cmath>
#include <fidus/lubrication/lubrication_correction.h>
#include <iostream>
#include <string>
#include <vector>

using namespace Fidus::Contact;
using TestTools::check;

namespace
{
  constexpr double a = 0.1, h_s = 0.05, eta = 1.;

  LubricationCorrection
  correction()
  {
    LubricationSettings s;
    s.dimension             = 3;
    s.viscosity             = eta;
    s.range                 = h_s * a;
    s.resolved_gap_fraction = h_s;
    s.roughness             = 1e-4;
    s.tangential            = true;
    LubricationCorrection c(s);
    Wall                  wall;
    wall.axis     = 1;
    wall.position = 0.;
    wall.side     = 1;
    c.set_walls({wall});
    return c;
  }

  /// The bond of particles @p i and @p j (j = no_particle: the wall), or
  /// nullptr.
  const LubricationBond *
  find(const std::vector<LubricationBond> &bonds,
       const std::uint32_t                 i,
       const std::uint32_t                 j)
  {
    for (const LubricationBond &b : bonds)
      if ((b.i == i && b.j == j) || (b.i == j && b.j == i))
        return &b;
    return nullptr;
  }

  bool
  close(const double x, const double y)
  {
    return std::abs(x - y) <= 1e-12 * std::abs(y);
  }

  /// Bond @p b's resolved resistances are those of radii @p ri, @p rj at
  /// the gap @p g, its true ones those of its radii at its gap.
  void
  check_bond(const std::string     &what,
             const LubricationBond *b,
             const double           ri,
             const double           rj,
             const double           g)
  {
    const bool found = b != nullptr;
    check(what + ": a bond", found);
    if (!found)
      return;
    check(what + ": true squeeze at the true gap",
          close(b->r_true,
                LubricationCorrection::squeeze_resistance(3,
                                                          eta,
                                                          b->a_i,
                                                          b->a_j,
                                                          b->gap)));
    check(what + ": resolved squeeze at the fluid's radii and width",
          close(b->r_resolved,
                LubricationCorrection::squeeze_resistance(3, eta, ri, rj, g)));
    check(
      what + ": resolved sliding at the fluid's radii and width",
      close(
        b->t_resolved,
        LubricationCorrection::tangential_resistance(3, eta, ri, rj, g, g)));
    check(what + ": the true resistance exceeds the resolved one",
          b->r_true > b->r_resolved && b->t_true > b->t_resolved);
  }
} // namespace

int
main()
{
  // E, A, B, C, D along x, 0.3 a above the wall y = 0.
  const double      y       = 1.3 * a;
  const double      gaps[4] = {0.55 * a, 0.005 * a, 0.15 * a, 0.6 * a};
  std::vector<Vec3> X{{{0.2, y, 0.5}}};
  for (const double g : gaps)
    X.push_back({{X.back()[0] + 2. * a + g, y, 0.5}});
  const std::uint32_t E = 0, A = 1, B = 2, C = 3, D = 4,
                      wall = LubricationBond::no_particle;
  const std::vector<double> radii(5, a);
  const double              s     = 0.5 * (h_s * a - gaps[1]);
  std::vector<double>       fluid = radii;
  fluid[A] -= s;
  fluid[B] -= s;

  LubricationCorrection plain = correction();
  const auto            bonds = plain.find_bonds(X, radii);
  check("without fluid radii: one bond", bonds.size() == 1);
  check_bond("without fluid radii: A-B", find(bonds, A, B), a, a, h_s * a);
  LubricationCorrection same       = correction();
  const auto            same_bonds = same.find_bonds(X, radii, radii);
  check("fluid radii equal to the radii: the same bond",
        same_bonds.size() == 1 &&
          same_bonds[0].r_resolved == bonds[0].r_resolved &&
          same_bonds[0].t_resolved == bonds[0].t_resolved);

  LubricationCorrection shrunk  = correction();
  const auto            widened = shrunk.find_bonds(X, radii, fluid);
  std::cout << "with the shrunk radii: " << widened.size() << " bonds"
            << std::endl;
  check_bond("A-B", find(widened, A, B), fluid[A], fluid[B], h_s * a);
  check_bond("B-C, widened", find(widened, B, C), fluid[B], a, 0.15 * a + s);
  check_bond("A to the wall",
             find(widened, A, wall),
             fluid[A],
             0.,
             0.3 * a + s);
  check_bond("B to the wall",
             find(widened, B, wall),
             fluid[B],
             0.,
             0.3 * a + s);
  check("no other bond (C-D, E-A beyond half a radius; C, D, E to the wall)",
        widened.size() == 4 && find(widened, C, D) == nullptr &&
          find(widened, E, A) == nullptr);
  return TestTools::failures() != 0;
}
