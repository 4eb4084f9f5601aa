// The entries of a fidus parameter file: names, defaults, patterns and the
// documentation that --print-parameters shows. Reading them back is in
// parameters.cc, checking the scene as a whole in parameters_check.cc.

#include <deal.II/base/parameter_handler.h>
#include <fidus/core/parameters.h>

namespace Fidus
{
  using namespace dealii;

  namespace
  {
    /// Domain: the box, its boundary condition and the shear rate.
    void
    declare_domain(ParameterHandler &prm)
    {
      prm.enter_subsection("Domain");
      {
        prm.declare_entry("Lower left",
                          "0, 0",
                          Patterns::Anything(),
                          "Lower-left corner of the box [length], one "
                          "coordinate per dimension, comma separated.");
        prm.declare_entry("Upper right",
                          "1, 1",
                          Patterns::Anything(),
                          "Upper-right corner of the box [length], one "
                          "coordinate per dimension; each larger than the "
                          "lower-left one.");
        prm.declare_entry(
          "Boundary condition",
          "linear shear",
          Patterns::Selection(
            "linear shear|sliding walls|cavity|exact rigid inclusion"),
          "Velocity imposed on the box. 'linear shear': u = shear rate * "
          "(y - y_mid) e_x on every face. 'sliding walls': the faces y = "
          "y_min and y = y_max move at -/+ shear rate * H/2 e_x, the other "
          "directions are periodic. 'cavity': the same moving walls, the "
          "other faces at rest. 'exact rigid inclusion': verification scene "
          "with one particle and the exact solution of a torque-free rigid "
          "particle in linear shear imposed on the box; error norms are "
          "reported.");
        prm.declare_entry("Shear rate",
                          "1",
                          Patterns::Anything(),
                          "Shear rate [1/time] as a function of the time t "
                          "(muparser syntax), e.g. 't < 10 ? 1 : -1' for a "
                          "reversal at t = 10.");
      }
      prm.leave_subsection();
    }



    /// Fluid: the model, the viscosity, the fictitious domain's penalty,
    /// rigidity and solid, the cut element's gaps.
    void
    declare_fluid_model(ParameterHandler &prm)
    {
      prm.enter_subsection("Fluid");
      {
        prm.declare_entry(
          "Model",
          "fictitious domain",
          Patterns::Selection(
            "fictitious domain|undisturbed shear|cut finite element"),
          "'fictitious domain': Stokes with penalised viscosity and a rigidity "
          "multiplier on an adaptive mesh. 'undisturbed shear': particles move "
          "with the undisturbed shear flow at their centre (no mesh, no "
          "hydrodynamic interaction). 'cut finite element': Stokes in the "
          "fluid outside the particles only, their rigid motions imposed by "
          "Nitsche's method, on a mesh built for every solve (from Mesh "
          "refinement/Minimum level to Maximum level at the surfaces, thin "
          "gaps, between particles and to the walls, further); one serial "
          "solve (Cut linear solver), in the unit box in linear shear or "
          "between sliding walls, from a pair to a dense 2D suspension "
          "(doc/cut_element.md).");
        prm.declare_entry(
          "Cut linear solver",
          "auto",
          Patterns::Selection("auto|automatic|direct|iterative"),
          "With 'cut finite element': 'direct' factorises the system (MUMPS); "
          "'iterative' runs FGMRES with a block preconditioner (a geometric "
          "multigrid V-cycle for the velocities and rigid motions) to the "
          "relative residual 1e-10; 'auto' (or 'automatic', its former "
          "name) is iterative in 3D above "
          "40000 unknowns, where the factorisation is slower and takes "
          "several GB, and direct otherwise (doc/cut_element.md, 'The "
          "iterative solver').");
        prm.declare_entry(
          "Cut minimum gap",
          "1e-4",
          Patterns::Double(0.),
          "With 'cut finite element': the fluid solve sees every gap between "
          "two particles at least this times the smaller radius, and every "
          "gap to the box this times the radius, by shrinking the radii it "
          "gives the fluid (the contact model keeps the true radii); > 0. "
          "Smaller gaps cost more refinement; down to 1e-4 the 2D squeeze "
          "follows the lubrication law (doc/cut_element.md).");
        prm.declare_entry(
          "Cut gap cells",
          "2",
          Patterns::Double(0.),
          "With 'cut finite element': the cut cells near another particle are "
          "refined until this many cells span the gap (0: only until no cell "
          "is cut by two surfaces).");
        prm.declare_entry("Viscosity",
                          "1",
                          Patterns::Double(0.),
                          "Fluid viscosity eta_f [pressure * time], > 0.");
        prm.declare_entry("Penalty factor",
                          "1000",
                          Patterns::Double(1.),
                          "r: the solid viscosity is r * eta_f; must be > 1. "
                          "It is also the augmentation of the Uzawa loop.");
        prm.declare_entry("Velocity degree",
                          "2",
                          Patterns::Integer(2, 4),
                          "Polynomial degree of the velocity (Taylor-Hood "
                          "Q(k)/Q(k-1)), 2 to 4.");
        prm.declare_entry(
          "Rigidity tolerance",
          "auto",
          Patterns::Anything(),
          "Uzawa stop: the rigidity residual of Rigidity measure below this "
          "value, in (0, 1). auto: 5e-3 with the particle measure, 1e-3 with "
          "the box measure. Both are the work-precision optimum of a single "
          "particle (doc/uzawa.md, doc/performance.md): with the default "
          "penalty factor its velocity is at the discretisation error after "
          "the first solve. Pairs closer than a cell need a tighter tolerance "
          "(the paper's scenes: doc/convergence.md).");
        prm.declare_entry(
          "Rigidity measure",
          "particle",
          Patterns::Selection("box|particle"),
          "What Rigidity tolerance bounds. particle: the largest over the "
          "particles of the rms strain rate in the particle relative to the "
          "box's rms shear rate g, max_i ||e(u)||_{L2(P_i)} / (g "
          "|P_i|^{1/2}), the same for one particle in any box. box: the "
          "strain in all of the solid relative to the strain in the whole "
          "box, ||e(u)||_{L2(solid)} / ||e(u)||_{L2(box)}, which for the same "
          "rigidity changes with the box's size and the particle count (most "
          "scenes in prm/ were calibrated in it and say so). statistics.csv "
          "has both (rigidity_residual: the chosen one; "
          "particle_rigidity_residual). doc/uzawa.md compares them.");
        prm.declare_entry(
          "Rigid velocity tolerance",
          "0",
          Patterns::Double(0.),
          "Uzawa stop on what the time loop uses instead: the particles' "
          "rigid velocities changed in the last iteration by less than this, "
          "|dU| / (g a) and |d omega| / g with g the box's rms shear rate, "
          "or the larger |dU| / U_F and a |d omega| / U_F with U_F the speed "
          "of the largest external force (|F| / (6 pi eta a) in 3D, "
          "|F| / (4 pi eta) in 2D) "
          "(column rigid_velocity_change of statistics.csv). 0 (default): "
          "stop on Rigidity tolerance. The strain left in the solid falls "
          "slowly on cut-cell slivers that barely move the particles "
          "(doc/uzawa.md).");
        prm.declare_entry(
          "Sliver threshold",
          "0",
          Patterns::Double(0., 1.),
          "Cells whose share of solid quadrature points is below this value "
          "(in [0, 1]) are held rigid by the penalty alone: the multiplier "
          "and the rigidity residual leave them out (their strain is "
          "reported in shared_residual). 0 (default): every cell that meets "
          "the solid is constrained.");
        prm.declare_entry("Maximum Uzawa iterations",
                          "50",
                          Patterns::Integer(1, 10000),
                          "Uzawa iterations per solve before a warning, >= 1.");
        prm.declare_entry(
          "Reuse multiplier",
          "auto",
          Patterns::Selection("true|false|auto"),
          "Start the Uzawa loop of a time step from the previous step's "
          "multiplier when the mesh has not changed (a warm start); otherwise "
          "from zero. auto: true with rigid shared cells, false where they "
          "are released ('Shared cells'), where the last step's multiplier "
          "is a poor start and about half the loops stalled (doc/fluid.md).");
        prm.declare_entry(
          "Solid retraction",
          "0",
          Patterns::Double(0., 1.),
          "The region held rigid for each particle is a ball of radius "
          "a - c h, with c this value and h the finest cell size: the rigid "
          "motion of a cut cell reaches into its fluid part, so that with "
          "c = 0 (the seed's model) a particle acts about half a cell larger "
          "than it is (doc/rheology.md). The contact model always uses a. "
          "Between 0 and 1; the retracted radius must stay positive.");
        prm.declare_entry(
          "Solid smoothing",
          "0",
          Patterns::Double(0., 2.),
          "Width, in finest cells, of the layer across each particle surface "
          "over which the solid fraction falls linearly from 1 to 0 "
          "(centred on the surface of the held solid). The penalty viscosity "
          "is mixed with the fluid's by that fraction, and the multiplier, "
          "the rigidity residual, the rigid projection and the stresses weigh "
          "each quadrature point by it, so that a particle's velocity changes "
          "continuously as it moves across the mesh. 0 (the seed's model) "
          "samples the solid sharply at the quadrature points. Between 0 "
          "and 2.");
      }
      prm.leave_subsection();
    }



    /// Fluid: the sub-grid lubrication and the cells two particles share.
    void
    declare_fluid_gaps(ParameterHandler &prm)
    {
      prm.enter_subsection("Fluid");
      {
        prm.declare_entry(
          "Lubrication correction",
          "false",
          Patterns::Bool(),
          "Add the squeeze resistance of the gaps the mesh cannot resolve "
          "(particle pairs and particle-wall gaps below 'Lubrication range'), "
          "implicitly in the particle velocities, minus the part the mesh "
          "carries (doc/lubrication.md). Meant with 'Shared cells = fluid', "
          "where close pairs are no longer held as one rigid doublet. false "
          "keeps the seed's model.");
        prm.declare_entry(
          "Lubrication tangential terms",
          "true",
          Patterns::Bool(),
          "With 'Lubrication correction': also correct the tangential terms "
          "of each close gap, the resistance to the two surfaces sliding past "
          "each other and to their relative rotation (singular like h^-1/2 "
          "for discs, log(1/h) for spheres), with the angular velocities "
          "among the unknowns (doc/lubrication.md). false: the normal squeeze "
          "only.");
        prm.declare_entry(
          "Lubrication range",
          "auto",
          Patterns::Anything(),
          "Gap, in finest cell sizes, below which the lubrication correction "
          "acts and above which the mesh is taken to resolve the squeeze "
          "flow, > 0. auto: between particles 0.65 in 2D and 0.3 in 3D; "
          "between a particle and a wall 0.33 in 2D and 0.2 in 3D: the "
          "fraction of a cell down to which the mesh carries the squeeze of "
          "a pushed particle (measured against exact solutions and resolved "
          "meshes in doc/lubrication.md). A number sets both; two numbers, "
          "separated by a comma, set the particle pairs' and the walls'.");
        prm.declare_entry(
          "Lubrication tangential range",
          "auto",
          Patterns::Anything(),
          "Gap, in finest cell sizes, down to which the mesh carries the "
          "tangential resistance of two surfaces sliding past each other, "
          "> 0: below it the correction adds the tangential terms of the gap. "
          "Against a wall the mesh resolves sliding less far down than the "
          "squeeze, so this may exceed 'Lubrication range'. auto: between "
          "particles the pairs' 'Lubrication range'; between a particle and "
          "a wall 1 in 2D and the walls' 'Lubrication range' in 3D. The 2D "
          "values were measured on discs pushed past each other and along a "
          "wall against a resolved mesh (doc/lubrication.md). A number sets "
          "both; two numbers, separated by a comma, set the particle pairs' "
          "and the walls'.");
        prm.declare_entry(
          "Lubrication flow range",
          "auto",
          Patterns::Anything(),
          "Gap, in finest cell sizes, whose squeeze resistance the fluid solve "
          "shows when the ambient flow, not a force, closes the gap between "
          "two particles, > 0. The mesh resists a flow-driven approach less "
          "than a force-driven one, so the correction treats the part of the "
          "fluid's velocities that 'Particles/External force' drives with "
          "'Lubrication range' and the rest with this one. auto: 0.45 in 3D, "
          "measured on two spheres held in shear against Batchelor & Green, "
          "and 2 in 2D, chosen on a lubricated pair in shear, which it keeps "
          "from overlapping at every level (two discs held in shear would "
          "want 0.7-1; doc/lubrication.md says why it stays).");
        prm.declare_entry(
          "Shared cells",
          "auto",
          Patterns::Selection("rigid|fluid|auto"),
          "Cells whose solid part lies within half a cell diameter of another "
          "particle (two particles closer than a cell, where one velocity "
          "polynomial would have to be two rigid motions). 'rigid' (the "
          "seed's model): rigid wherever there is solid; a close pair moves "
          "as one rigid doublet, which stands in for the lubrication the mesh "
          "cannot resolve, and in a dense suspension the Uzawa loop stalls. "
          "'fluid': their solid part is treated as fluid (no penalty, no "
          "rigidity multiplier), each particle keeps its rigid motion from the "
          "rest of its solid, the Uzawa loop converges, and the residual there "
          "is reported apart (statistics.csv: shared_cells, shared_residual); "
          "without a lubrication correction close pairs then approach and "
          "separate far too fast (measured in doc/fluid.md). auto: 'fluid' "
          "when a contact model ('Contact/Model' inelastic or gluey) or the "
          "lubrication correction keeps close pairs apart, 'rigid' with "
          "neither, where the rigid doublet is all that does.");
      }
      prm.leave_subsection();
    }



    /// Fluid/Linear solver: the fictitious domain's linear solver and
    /// preconditioner.
    void
    declare_linear_solver(ParameterHandler &prm)
    {
      prm.enter_subsection("Fluid");
      {
        prm.enter_subsection("Linear solver");
        {
          prm.declare_entry("Tolerance",
                            "1e-6",
                            Patterns::Double(0., 1.),
                            "FGMRES stop: residual below this value times the "
                            "norm of the right-hand side, in (0, 1).");
          prm.declare_entry(
            "Inexact Uzawa factor",
            "0",
            Patterns::Double(0., 1.),
            "Inexact Uzawa, in [0, 1]: inside the Uzawa loop, FGMRES stops at "
            "this factor times the loop's tolerance (Rigidity tolerance, or "
            "Rigid velocity tolerance when that is set), never below "
            "Tolerance. The solve predicted to be the loop's last (from its "
            "contraction so far, and the first one with Reuse multiplier = "
            "true) goes to Tolerance, and a loop that ends on an inexact solve "
            "repeats it to Tolerance: the velocity handed on always meets "
            "Tolerance. 0: every solve to Tolerance (measured in "
            "doc/uzawa.md).");
          prm.declare_entry(
            "Maximum cheap iterations",
            "1000",
            Patterns::Integer(0, 100000),
            "FGMRES iterations with the cheap preconditioner "
            "(one V-cycle per block) before switching to inner "
            "solves (CG with the V-cycle on the velocity block, "
            "CG on the pressure mass). 0: inner solves only, "
            "whose count grows much less with the penalty "
            "factor; measured faster in 3D at a penalty factor "
            "of 1e6 (doc/preconditioners.md).");
          prm.declare_entry("Maximum iterations",
                            "1000",
                            Patterns::Integer(1, 100000),
                            "FGMRES iterations with the expensive "
                            "preconditioner before failing, >= 1.");
          prm.declare_entry(
            "AMG aggregation threshold",
            "0",
            Patterns::Double(0., 1.),
            "ML aggregation threshold of the velocity AMG, in [0, 1]. 0 keeps "
            "every connection, also the weak fluid-solid ones across the "
            "viscosity jump (measured fastest, doc/fluid.md).");
          prm.declare_entry("AMG smoother sweeps",
                            "4",
                            Patterns::Integer(1, 10),
                            "Smoother sweeps of the velocity AMG.");
          prm.declare_entry(
            "AMG smoother type",
            "Chebyshev",
            Patterns::Selection("Chebyshev|symmetric Gauss-Seidel|Jacobi|ILU"),
            "Smoother of the velocity AMG (ML). Chebyshev needs no "
            "communication between the sweeps and does not depend on the "
            "number of MPI ranks. ILU (use 1 sweep) factorises each rank's "
            "block: on 1-2 ranks it needs up to 23 % fewer iterations and is up "
            "to 40 % faster in 3D for one particle, but 2.3 times slower "
            "for 24 spheres at volume fraction 0.25; being block Jacobi "
            "across ranks, it is expected to weaken on many ranks (not "
            "measured; doc/fluid.md, doc/performance.md).");
          prm.declare_entry(
            "Method",
            "auto",
            Patterns::Selection("auto|iterative|direct"),
            "How the fictitious domain's Stokes system is solved: 'iterative' "
            "runs FGMRES with the block preconditioner set below; 'direct' "
            "factorises it once per time step (MUMPS, or KLU where Trilinos "
            "has no MUMPS), so that each Uzawa iteration is one substitution; "
            "'auto': direct in 2D up to a million unknowns; iterative on "
            "larger meshes, in 3D, where the factorisation grows too fast "
            "with the mesh, and wherever Preconditioner names one (measured "
            "in doc/fluid.md, 'A direct solver for 2D').");
          prm.declare_entry(
            "Preconditioner",
            "auto",
            Patterns::Selection("auto|AMG|GMG"),
            "Velocity-block preconditioner: AMG (Trilinos ML with the rigid "
            "modes), GMG (geometric multigrid: matrix-free levels by global "
            "coarsening, Chebyshev smoothing, CG with AMG on the coarse box "
            "mesh; Velocity degree 2 or 3), or auto: the faster one as "
            "measured, GMG in 3D and AMG in 2D (doc/preconditioners.md).");
          prm.declare_entry("Multigrid smoother degree",
                            "4",
                            Patterns::Integer(1, 20),
                            "Degree of the Chebyshev smoother on each GMG "
                            "level (matrix-vector products per smoothing).");
          prm.declare_entry(
            "Multigrid smoother blocks",
            "cut cells",
            Patterns::Selection("none|cut cells"),
            "What the Chebyshev smoother of each GMG level inverts: none "
            "(point Jacobi, the diagonal), or cut cells (an exact solve on "
            "the DoFs of each cell that the particle surface cuts, additive "
            "Schwarz, and the diagonal elsewhere), which contains the local "
            "near-kernel of the penalty that point Jacobi cannot reduce: "
            "half the iterations at r = 1e3 in 3D and a count that no longer "
            "grows like r (doc/preconditioners.md).");
          prm.declare_entry(
            "Multigrid viscosity averaging",
            "galerkin",
            Patterns::Selection("none|arithmetic|harmonic|geometric|galerkin"),
            "How the viscosity (eta_f in the fluid, r eta_f in the solid) "
            "reaches the GMG levels below the finest: galerkin (no averaging: "
            "each level is the exact Galerkin product of the finest operator, "
            "so that particles smaller than a coarse cell stay in the coarse "
            "levels; measured fastest for suspensions, doc/preconditioners.md), "
            "none (the point values at each level's own quadrature points), or "
            "the arithmetic, harmonic or geometric mean over the cell. The "
            "finest level always uses the point values of the assembly.");
          prm.declare_entry(
            "Matrix-free velocity block",
            "true",
            Patterns::Bool(),
            "With Preconditioner = GMG: multiply by the velocity block with "
            "the finest multigrid level's matrix-free operator and do not "
            "assemble it (the system matrix keeps only the divergence "
            "blocks). false assembles it, as with AMG; both give the same "
            "solution. Ignored with AMG.");
          prm.declare_entry(
            "Rigid-body correction",
            "auto",
            Patterns::Selection("auto|true|false"),
            "Correct the velocity V-cycle (AMG or GMG) with the rigid motions "
            "of every particle, before and after it: each particle adds "
            "low-energy modes (its rigid motions, resisted only by the fluid "
            "around it) that one V-cycle misses, so that without the "
            "correction the FGMRES count grows with the number of particles. "
            "auto: on, except with GMG in 3D, whose Galerkin levels and "
            "cut-cell blocks keep the particles' motions, where it was measured "
            "to cost 0-17 % of the solve (doc/preconditioners.md).");
        }
        prm.leave_subsection();
      }
      prm.leave_subsection();
    }



    /// Particles: positions, radii, forces, the generator.
    void
    declare_particles(ParameterHandler &prm)
    {
      prm.enter_subsection("Particles");
      {
        prm.declare_entry("Radius",
                          "0.05",
                          Patterns::Anything(),
                          "Particle radius [length], > 0: one value for all "
                          "particles or one per particle, comma separated.");
        prm.declare_entry(
          "Positions",
          "",
          Patterns::Anything(),
          "Centres [length], particles separated by ';', "
          "coordinates by ',', e.g. '0.451, 0.51; 0.549, 0.49'.");
        prm.declare_entry(
          "External force",
          "",
          Patterns::Anything(),
          "Force [force, per unit length in 2D] on the particles, e.g. "
          "gravity minus buoyancy: one vector 'fx, fy[, fz]' for every "
          "particle, or one per particle separated by ';'. Empty: force-free "
          "particles (the seed's scenes). In the fictitious domain it acts as a uniform "
          "force density over each particle's solid, so the fluid carries it "
          "to the walls; the cut element applies it to each particle's rigid "
          "motion; the stress output assumes force-free particles "
          "(doc/fluid.md). Free-draining particles (undisturbed shear) move "
          "at F over their isolated drag, 6 pi eta a (4 pi eta per unit "
          "length in 2D). Not with the exact rigid inclusion.");
        prm.declare_entry("Positions file",
                          "",
                          Patterns::Anything(),
                          "Alternative to 'Positions': a text file with one "
                          "particle per line, 'x y [z] [radius]' ('#' starts a "
                          "comment). Relative to the parameter file.");
        prm.enter_subsection("Generator");
        {
          prm.declare_entry(
            "Number of particles",
            "0",
            Patterns::Integer(0),
            "Particles to place at random without overlap, instead of "
            "'Positions' (which must then be empty); 0: use 'Fraction'. At "
            "most one of the two may be > 0; both 0: no generator.");
          prm.declare_entry(
            "Fraction",
            "0",
            Patterns::Double(0., 1.),
            "Area fraction (2D) or volume fraction (3D) of the region to fill; "
            "the number of particles follows. Below 0.9069 (2D) and 0.7405 "
            "(3D), the densest packings; random packings jam near 0.84 "
            "(bidisperse discs) and 0.64 (spheres). Reached by growing the "
            "particles from a tenth of the fraction while pushing overlapping "
            "pairs apart; 0.6 (2D) and 0.5 (3D) take about a second for 1e5 "
            "particles (contrib/benchmarks/particle_generator.sh).");
          prm.declare_entry(
            "Radii",
            "",
            Patterns::Anything(),
            "Radii [length], comma separated: one value (monodisperse), two "
            "(bidisperse, e.g. 'a, 1.4 a' in 2D, where equal discs "
            "crystallise) or more (polydisperse). Empty: 'Particles/Radius'.");
          prm.declare_entry("Radius weights",
                            "",
                            Patterns::Anything(),
                            "Number fractions of 'Radii', one per radius, "
                            "summing to 1; empty: equal fractions.");
          prm.declare_entry("Region lower left",
                            "",
                            Patterns::Anything(),
                            "Lower corner of the region to fill [length], one "
                            "coordinate per dimension; empty: the box.");
          prm.declare_entry(
            "Region upper right",
            "",
            Patterns::Anything(),
            "Upper corner of the region to fill [length]; empty: the box. "
            "Along a periodic axis of 'sliding walls' the region is periodic "
            "when it spans the box.");
          prm.declare_entry(
            "Minimum separation",
            "0",
            Patterns::Double(0.),
            "Smallest gap between particles, and between a particle and a "
            "non-periodic face of the region, relative to the smallest "
            "radius, >= 0.");
          prm.declare_entry("Seed",
                            "1",
                            Patterns::Integer(0),
                            "Seed of the random numbers: the same parameters "
                            "and seed give the same particles.");
          prm.declare_entry("Maximum iterations",
                            "20000",
                            Patterns::Integer(1),
                            "Cap on the relaxation sweeps of the generator; a "
                            "jammed growth stops earlier with an error naming "
                            "the fraction reached.");
        }
        prm.leave_subsection();
      }
      prm.leave_subsection();
    }



    /// Contact: the contact model and its projection.
    void
    declare_contact(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        prm.declare_entry("Model",
                          "gluey",
                          Patterns::Selection("none|inelastic|gluey"),
                          "Projection of the particle velocities: 'none' (no "
                          "correction, overlaps possible), 'inelastic' (no "
                          "overlap), 'gluey' (no overlap, glued pairs keep "
                          "their gap until the compressive impulse is paid "
                          "back).");
        prm.declare_entry(
          "Walls",
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
      }
      prm.leave_subsection();
    }



    /// Time stepping: the step, the scheme, the gap step.
    void
    declare_time_stepping(ParameterHandler &prm)
    {
      prm.enter_subsection("Time stepping");
      {
        prm.declare_entry("End time",
                          "20",
                          Patterns::Double(0.),
                          "Final time [time], >= 0; 0 does one solve.");
        prm.declare_entry("Time step",
                          "0.01",
                          Patterns::Double(0.),
                          "Time step [time], > 0 (the first and, without "
                          "adaptive stepping, every step).");
        prm.declare_entry("Adaptive time step",
                          "false",
                          Patterns::Bool(),
                          "Use dt = min(Maximum time step, CFL number * h_min "
                          "/ max |U|).");
        prm.declare_entry("CFL number",
                          "0.5",
                          Patterns::Double(0.),
                          "C of the adaptive time step, > 0.");
        prm.declare_entry("Maximum time step",
                          "0.05",
                          Patterns::Double(0.),
                          "Upper bound of the adaptive time step [time], > 0.");
        prm.declare_entry(
          "Gap step fraction",
          "0",
          Patterns::Double(0., 1.),
          "0 to 1. Above 0, the step (the fixed Time step, or the adaptive "
          "one) is cut wherever it would change a gap D_ij by more than this "
          "fraction f of itself, with the velocities at the start of the "
          "step: by closing or opening it (dt <= f D_ij / |v_ij|, v_ij the normal "
          "speed of the pair, or of particle and wall), or by the chord "
          "error of a straight step of a pair sliding past each other at "
          "w_ij (dt <= (2 r_ij f D_ij)^(1/2) / w_ij, r_ij the distance of the "
          "centres). The approach to contact and a tumbling pair are then "
          "followed in steps that shrink with the gap, so the flow, not the "
          "step, sets the gaps; afterwards the step grows back, at most "
          "doubling per step (AB2 extrapolates with the ratio of successive "
          "steps). 0 (default): gaps do not limit the step "
          "(doc/results.md, \"A step that follows the gaps\").");
        prm.declare_entry(
          "Gap step floor",
          "1e-3",
          Patterns::Double(0.),
          "Gaps below this fraction of the smaller radius (the particle's own "
          "for a wall) do not limit the step, >= 0: they belong to the contact "
          "model, which holds a glued pair at a zero gap while the fluid still "
          "closes it. Set it near Contact/Roughness with the lubrication "
          "correction, and near Fluid/Cut minimum gap with the cut finite "
          "element.");
        prm.declare_entry(
          "Scheme",
          "AB2",
          Patterns::Selection("AB2|trapezoidal"),
          "How the positions advance. AB2: the seed's Adams-Bashforth 2 "
          "extrapolation of the solved rigid velocities, one fluid solve per "
          "step. trapezoidal: the mean of the velocities at the start of the "
          "step and at the positions it reaches, found from the AB2 "
          "prediction in Trapezoidal iterations passes of one fluid solve "
          "each; the last pass's velocities serve as the next step's start, "
          "so one pass costs what AB2 does. The trapezoidal rule is symmetric "
          "in time, so a reversed shear retraces the path up to the solver "
          "tolerances; AB2 leaves an O(dt^2) return error (doc/results.md, "
          "\"A time-symmetric scheme\").");
        prm.declare_entry("Trapezoidal iterations",
                          "1",
                          Patterns::Integer(1, 20),
                          "Fixed-point passes of the trapezoidal scheme, 1 to "
                          "20, one fluid solve each: 1 is a predictor-"
                          "corrector; each further pass divides the distance "
                          "to the trapezoidal rule, and that of the last solve "
                          "from the step's end positions, by about dt |grad "
                          "U| / 2.");
      }
      prm.leave_subsection();
    }



    /// Mesh refinement: the levels and the refined band.
    void
    declare_mesh_refinement(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh refinement");
      {
        prm.declare_entry("Initial global refinement",
                          "3",
                          Patterns::Integer(0, 12),
                          "Uniform refinements of the coarse box mesh (whose "
                          "cells are near-cubes of the smallest box side).");
        prm.declare_entry("Minimum level",
                          "3",
                          Patterns::Integer(0, 15),
                          "Coarsest level far from particles, <= Initial "
                          "global refinement.");
        prm.declare_entry("Maximum level",
                          "8",
                          Patterns::Integer(0, 15),
                          "Finest level at particle surfaces and in gaps, >= "
                          "Initial global refinement.");
        prm.declare_entry(
          "Interface band",
          "1",
          Patterns::Double(0.),
          "Cells closer to a particle surface than this many cell sizes (of "
          "their own size) are refined, > 0. 1 gives the error of 2 or 3 "
          "with 40 % fewer cells (doc/performance.md).");
        prm.declare_entry(
          "Gap refinement distance",
          "0.5",
          Patterns::Double(0.),
          "Cells closer than this distance (relative to the "
          "smaller radius) to both surfaces of a pair whose gap "
          "is below it are refined to the maximum level.");
        prm.declare_entry(
          "Remesh fraction",
          "0.5",
          Patterns::Double(0.),
          "Remesh only once a particle has moved more than this "
          "fraction of the band (band * finest cell size) since "
          "the last remesh; 0 remeshes every step.");
      }
      prm.leave_subsection();
    }



    /// Output: files, intervals, checkpoints, the screen.
    void
    declare_output(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        prm.declare_entry("Field output interval",
                          "0",
                          Patterns::Integer(0),
                          "Steps between VTU field outputs; 0 = never.");
        prm.declare_entry("Particle output interval",
                          "0",
                          Patterns::Integer(0),
                          "Steps between VTP particle outputs; 0 = never.");
        prm.declare_entry("Particle CSV interval",
                          "1",
                          Patterns::Integer(1),
                          "Steps between the rows of particles.csv (step 0 "
                          "and every multiple of this value), >= 1; long "
                          "runs such as many shear cycles would otherwise "
                          "write every particle every step.");
        prm.declare_entry(
          "Progress interval",
          "0",
          Patterns::Integer(0),
          "Steps between progress lines on screen; 0 (the default) writes one "
          "line every 'Progress wall interval' seconds instead, plus the "
          "first and the last step.");
        prm.declare_entry("Progress wall interval",
                          "5",
                          Patterns::Double(0.),
                          "Seconds of wall clock between progress lines when "
                          "'Progress interval' is 0; 0 writes every step.");
        prm.declare_entry(
          "Checkpoint interval",
          "0",
          Patterns::Integer(0),
          "Steps between checkpoints (Output directory/checkpoint-NNNNNN); "
          "0 = never. Whenever checkpoints are on, the last step of the run "
          "is checkpointed too. Resume with 'fidus --resume input.prm'.");
        prm.declare_entry(
          "Checkpoint wall interval",
          "0",
          Patterns::Double(0.),
          "Seconds of wall clock between checkpoints, so that a stopped run "
          "loses at most that much; 0 = never. Combines with 'Checkpoint "
          "interval' (whichever comes first).");
        prm.declare_entry("Verbosity",
                          "normal",
                          Patterns::Selection("quiet|normal|verbose"),
                          "Screen output: 'quiet' (errors and warnings only), "
                          "'normal' (progress lines and timing table), "
                          "'verbose' (solver details).");
      }
      prm.leave_subsection();
    }
  } // namespace



  void
  Parameters::declare(ParameterHandler &prm)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Space dimension of the scene, chosen at run time. "
                      "Allowed: 2 or 3.");
    prm.declare_entry("Output directory",
                      "output",
                      Patterns::FileName(Patterns::FileName::output),
                      "Folder for all output files (created if missing). "
                      "Relative paths are relative to the working directory.");
    declare_domain(prm);
    declare_fluid_model(prm);
    declare_fluid_gaps(prm);
    declare_linear_solver(prm);
    declare_particles(prm);
    declare_contact(prm);
    declare_time_stepping(prm);
    declare_mesh_refinement(prm);
    declare_output(prm);
  }
} // namespace Fidus
