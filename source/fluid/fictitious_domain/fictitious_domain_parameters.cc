// The fictitious domain's entries of the subsections Fluid and Fluid/Linear
// solver, and their 'auto' rules.

#include <deal.II/base/parameter_handler.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/fluid/fictitious_domain/fictitious_domain_parameters.h>
#include <limits>

namespace Fidus
{
  using namespace dealii;

  void
  FictitiousDomainParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    declare_solid_entries(prm);
    prm.enter_subsection("Linear solver");
    declare_fgmres_entries(prm);
    declare_preconditioner_entries(prm);
    prm.leave_subsection();
    prm.leave_subsection();
  }



  void
  FictitiousDomainParameters::declare_solid_entries(ParameterHandler &prm)
  {
    prm.declare_entry("Penalty factor",
                      "1000",
                      Patterns::Double(1.),
                      "r: the solid viscosity is r * eta_f; must be > 1. "
                      "It is also the augmentation of the Uzawa loop.");
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
      "Uzawa acceleration depth",
      "0",
      Patterns::Integer(0, 20),
      "Anderson acceleration of the Uzawa loop: each multiplier update "
      "combines the last iterates so that the strain left in the solid is "
      "least (GMRES on the loop's fixed point), instead of the plain "
      "update lambda += rho u. The number of earlier iterates kept; 0: the "
      "plain update (doc/theory/fictitious_domain.md, 'The Uzawa loop').");
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
      "0.3",
      Patterns::Double(0., 1.),
      "The region held rigid for each particle is a ball of radius "
      "a - c h, with c this value and h the finest cell size: the rigid "
      "motion of a cut cell reaches into its fluid part, so that with "
      "c = 0 (the seed's model) a particle acts about half a cell larger "
      "than it is. 0.3 (default) takes one sphere's stresslet from 14 % "
      "to 4 % above the exact one at 6.4 cells per radius and a disc's "
      "from 8 % to 1 % at 10 (doc/theory/fictitious_domain.md). The "
      "contact model always uses a. Between 0 and 1; the retracted "
      "radius must stay positive.");
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



  void
  FictitiousDomainParameters::declare_fgmres_entries(ParameterHandler &prm)
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
      "Tolerance. With Lubrication coupling = with the flow it also "
      "bounds the solves with new loads, which stop at 0.02 times the "
      "coupling's last change, between Tolerance and this bound, the last "
      "ones at Tolerance. 0: every solve to Tolerance (measured in "
      "doc/uzawa.md).");
    prm.declare_entry("Maximum cheap iterations",
                      "1000",
                      Patterns::Integer(0, 100000),
                      "FGMRES iterations with the cheap preconditioner "
                      "(one V-cycle on the velocity block, CG on the "
                      "pressure mass to 1e-2) before switching to inner "
                      "solves (CG with the V-cycle on the velocity block to "
                      "1e-2, CG on the pressure mass to 1e-6). 0: inner "
                      "solves only, "
                      "whose count grows much less with the penalty "
                      "factor; measured faster in 3D at a penalty factor "
                      "of 1e6 (doc/preconditioners.md).");
    prm.declare_entry("Maximum iterations",
                      "1000",
                      Patterns::Integer(1, 100000),
                      "FGMRES iterations with the expensive "
                      "preconditioner before failing, >= 1.");
    prm.declare_entry(
      "GMRES restart",
      "200",
      Patterns::Integer(1),
      "Iterations FGMRES keeps before it restarts, >= 1. It stores two "
      "vectors of the size of the system per iteration: with a million "
      "unknowns, 200 take 3.2 GB per copy of the system (spread over the "
      "ranks). Fewer save memory and may cost iterations; only solves "
      "that need more iterations than this restart.");
    prm.declare_entry(
      "Memory per rank",
      "auto",
      Patterns::Anything(),
      "Memory, in GB, that each rank may use for the whole run, > 0; auto: "
      "the ranks of a machine share nine tenths of what it has available "
      "(or of what a control group, as in a batch job, leaves). On each new "
      "mesh, before its system is built, the system, its preconditioner "
      "and the smallest FGMRES basis (a restart of 10) are estimated from "
      "the unknowns (about 2 KB per unknown with the matrix-free GMG, "
      "12.5 KB with an assembled velocity block, as measured in "
      "doc/cookbooks/cluster.md): a mesh that would not fit stops the run with "
      "a message, instead of the operating system killing it. Once the "
      "system is built, a 'GMRES restart' whose basis would not fit is "
      "lowered for that mesh to what does, with a warning. Not checked "
      "with the direct solver. With 'Fluid/Model = cut finite element' "
      "every solve is checked the same way, before its system is built "
      "(24 B per matrix entry with its iterative solver, checked once its "
      "sparsity pattern is known, and 8 KB per unknown before; 7 KB per "
      "unknown in 2D and 50 KB in 3D with its direct one; "
      "doc/theory/cut_element.md, 'Memory').");
  }



  void
  FictitiousDomainParameters::declare_preconditioner_entries(
    ParameterHandler &prm)
  {
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



  void
  FictitiousDomainParameters::parse(ParameterHandler  &prm,
                                    const unsigned int dim,
                                    const unsigned int velocity_degree)
  {
    prm.enter_subsection("Fluid");
    penalty_factor        = prm.get_double("Penalty factor");
    rigidity_per_particle = prm.get("Rigidity measure") == "particle";
    // auto: the single particle's work-precision optimum in each measure
    // (doc/theory/fictitious_domain.md).
    rigidity_tolerance =
      ParameterParsing::number_or_auto(prm.get("Rigidity tolerance"),
                                       "Fluid/Rigidity tolerance",
                                       rigidity_per_particle ? 5e-3 : 1e-3,
                                       "auto or a number in (0, 1)",
                                       [](const double v) {
                                         return v > 0. && v < 1.;
                                       });
    rigid_velocity_tolerance = prm.get_double("Rigid velocity tolerance");
    sliver_threshold         = prm.get_double("Sliver threshold");
    max_uzawa_iterations     = prm.get_integer("Maximum Uzawa iterations");
    uzawa_acceleration_depth = prm.get_integer("Uzawa acceleration depth");
    reuse_choice             = prm.get("Reuse multiplier");
    shared_cells_choice      = prm.get("Shared cells");
    solid_retraction         = prm.get_double("Solid retraction");
    solid_smoothing          = prm.get_double("Solid smoothing");

    prm.enter_subsection("Linear solver");
    linear_tolerance      = prm.get_double("Tolerance");
    inexact_uzawa_factor  = prm.get_double("Inexact Uzawa factor");
    max_cheap_iterations  = prm.get_integer("Maximum cheap iterations");
    max_linear_iterations = prm.get_integer("Maximum iterations");
    gmres_restart         = prm.get_integer("GMRES restart");
    memory_per_rank =
      1e9 *
      ParameterParsing::number_or_auto(prm.get("Memory per rank"),
                                       "Fluid/Linear solver/Memory "
                                       "per rank",
                                       0.,
                                       "auto or a number of GB > 0",
                                       [](const double v) { return v > 0.; });
    amg_aggregation_threshold = prm.get_double("AMG aggregation threshold");
    amg_smoother_sweeps       = prm.get_integer("AMG smoother sweeps");
    amg_smoother_type         = prm.get("AMG smoother type");
    // Method auto: direct in 2D (doc/theory/fictitious_domain.md, "Linear
    // solvers"), unless a preconditioner was chosen by name, which asks for
    // FGMRES; and FGMRES above a million unknowns, where the factorisation
    // takes more than twice FGMRES's memory and no less time.
    const std::string method         = prm.get("Method");
    const std::string preconditioner = prm.get("Preconditioner");
    direct_max_unknowns =
      method == "direct" ? std::numeric_limits<unsigned long long>::max() :
      method == "auto" && dim == 2 && preconditioner == "auto" ? 1000000ULL :
                                                                 0ULL;
    // Preconditioner auto: the faster one per dimension as measured: GMG in
    // 3D, AMG in 2D and for degrees the GMG does not have.
    geometric_multigrid =
      preconditioner == "GMG" ||
      (preconditioner == "auto" && dim == 3 && velocity_degree <= 3);
    mg_smoother_degree     = prm.get_integer("Multigrid smoother degree");
    mg_viscosity_averaging = prm.get("Multigrid viscosity averaging");
    mg_smoother_blocks     = prm.get("Multigrid smoother blocks");
    // auto: off where measured not to pay (GMG in 3D with its Galerkin
    // levels and cut-cell blocks).
    const std::string correction = prm.get("Rigid-body correction");
    rigid_body_correction =
      correction == "true" ||
      (correction == "auto" && !(geometric_multigrid && dim == 3));
    matrix_free_velocity_block = prm.get_bool("Matrix-free velocity block");
    if (geometric_multigrid && velocity_degree > 3)
      throw InputError(
        "entry 'Fluid/Linear solver/Preconditioner' has the value 'GMG' "
        "with 'Fluid/Velocity degree' = " +
        std::to_string(velocity_degree) +
        "; allowed: GMG with Velocity degree 2 or 3, or Preconditioner = "
        "AMG");
    prm.leave_subsection();
    prm.leave_subsection();
  }



  void
  FictitiousDomainParameters::resolve_shared_cells(const bool gaps_kept_apart)
  {
    release_shared_cells = shared_cells_choice == "auto" ?
                             gaps_kept_apart :
                             shared_cells_choice == "fluid";
    reuse_multiplier =
      reuse_choice == "auto" ? !release_shared_cells : reuse_choice == "true";
  }



  void
  FictitiousDomainParameters::check() const
  {
    ParameterParsing::require_positive(rigidity_tolerance,
                                       "Fluid/Rigidity tolerance");
    ParameterParsing::require_positive(linear_tolerance,
                                       "Fluid/Linear solver/Tolerance");
    if (!(penalty_factor > 1.))
      throw InputError("entry 'Fluid/Penalty factor' has the value " +
                       std::to_string(penalty_factor) +
                       "; allowed: a value > 1 (the solid must be more "
                       "viscous than the fluid)");
  }
} // namespace Fidus
