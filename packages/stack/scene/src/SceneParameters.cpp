#include "tribos/stack/SceneParameters.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <limits>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/core/ParameterTable.hpp"
#include "tribos/core/Validators.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/qp/SolverParameters.hpp"
#include "tribos/stack/Scene.hpp"

namespace tribos::stack {

namespace {
using Teuchos::ParameterList;
constexpr int kMaxCount = 1000000000;  // iteration caps: any int a run could reach

// A template entry ("Materials/*/...") that has no default: the user gives it or leaves it
// out. The placeholder NaN never passes the validator, so it can never reach the solver, and
// --list-parameters prints it as "none (required)". (ParameterList::set would validate it.)
void setWithoutDefault(ParameterList& pl, const std::string& name, const std::string& doc,
                       const Teuchos::RCP<const Teuchos::ParameterEntryValidator>& validator) {
  pl.setEntry(name, Teuchos::ParameterEntry(std::numeric_limits<double>::quiet_NaN(), false, false, doc, validator));
}

// The friction law of an interface, bound to contact::FrictionLaw (its member initialisers are
// the defaults): declared in the Contact list and its interface sublists, read back by
// readContactInterfaces.
const core::ParameterTable<contact::FrictionLaw>& frictionLawTable() {
  using L = contact::FrictionLaw;
  static const auto table =
      core::ParameterTable<L>()
          .add("Friction Model", &L::model,
               "\"None\" (frictionless), \"Tresca\" (given slip bound), \"Coulomb\" (successive "
               "approximations on the slip bound), \"Bonded\" (contact rows as equalities: the surfaces are tied "
               "where they are, an initial gap kept)",
               contact::kFrictionModelNames)
          .add("F1", &L::F1, "friction coefficient along t1 (isotropic when F1 = F2)",
               core::closedInterval(0.0, core::kMaxMagnitude))
          .add("F2", &L::F2,
               "friction coefficient along t2; not given: F1 of the same list (isotropic; an interface sublist "
               "that gives neither takes the flat list's)",
               core::closedInterval(0.0, core::kMaxMagnitude))
          .add("Slip Bound", &L::slipBound, "Tresca: the given slip bound g as a nodal force [force]",
               core::closedInterval(0.0, core::kMaxMagnitude));
  return table;
}

// How Coulomb's slip bound is found, bound to contact::FrictionSettings: one choice for the
// whole solve (the flat Contact list only).
const core::ParameterTable<contact::FrictionSettings>& fixedPointTable() {
  using F = contact::FrictionSettings;
  static const auto table =
      core::ParameterTable<F>()
          .add("Fixed Point", &F::fixedPoint,
               "Coulomb: \"Inexact\" updates the slip bound g := lambda_nu after every SMALSE-M outer iteration "
               "(the paper's choice); \"Exact\" solves every Tresca problem to Solver/Tolerance first",
               contact::kFixedPointNames)
          .add("Slip Bound Test", &F::slipBoundTest,
               "Coulomb, Inexact: \"Epsilon\" stops only when the last update moved the slip bound by at most "
               "Solver/Tolerance (relative); \"Paper\" on SMALSE-M's criteria alone, as the paper's Section 5 "
               "(its Table 1 counts), which may stop with g a few epsilon from lambda_nu and Coulomb's law broken at "
               "that bound: the KKT gate then reports the run as not converged (doc/parameters.md)",
               contact::kSlipBoundTestNames)
          .add("Max Fixed Point Iterations", &F::maxFixedPointIterations,
               "Coulomb, Exact: cap on the Tresca solves; reaching it ends the solve as not converged (exit 3)",
               core::intRange(1, kMaxCount));
  return table;
}

void meshParameters(ParameterList& pl) {
  Teuchos::setStringToIntegralParameter<int>(
      "Generator", "Two Bricks",
      "\"Two Bricks\": the paper's model problem (Section 6), generated; \"Exodus\": read "
      "Mesh/File (element blocks = bodies, node sets / side sets name the boundary parts)",
      Teuchos::Array<std::string>(core::namesOf(kMeshGeneratorNames)), &pl);
  pl.set("Subdomains Per Brick", std::string("2x1x1"),
         "Two Bricks: subdomain grid NXxNYxNZ of each brick, cubic subdomains (NX = 2 NY = 2 NZ); "
         "the paper's s = NX*NY*NZ (Table 1: 2x1x1, 4x2x2, 6x3x3, 8x4x4, 10x5x5)");
  pl.set("H Over h", 2,
         "Two Bricks: elements per subdomain edge H/h (a scene that cannot fit in memory is refused before the "
         "mesh is built)",
         core::intRange(1, 1000));
  pl.set("Initial Gap", 0.0,
         "Two Bricks: initial gap d [length] between the bricks (the steel brick is lifted by it); "
         "set Contact/Search Distance above it so that the contact nodes pair",
         core::closedInterval(0.0, core::kMaxMagnitude));
  pl.set("File", std::string(""),
         "Exodus: path of the Exodus II mesh (TETRA, TETRA10, HEX8 and WEDGE6 blocks); relative paths are relative to the scene file "
         "(gmsh meshes: convert with tribos-msh2exo)");
  pl.set("Subdomains", 0,
         "Exodus, or Decomposition = METIS: number of subdomains (METIS parts, split among bodies "
         "in proportion to their element counts; at least one per body); 0: chosen from the mesh, one per "
         "Nodes Per Subdomain corner nodes (at least one per body and one per rank)",
         core::intRange(0, 1000000));
  pl.set("Nodes Per Subdomain", 2000,
         "Subdomains = 0: the mesh's corner nodes (element vertices: a quadratic element's mid-edge nodes do "
         "not count) per subdomain the count is chosen for (the measured optimum of the curved scenes, "
         "doc/measurements/curved_iterations.md); a subdomain's size in elements, and H/h, then stays the "
         "same as the mesh is refined",
         core::intRange(1, 100000000));
  Teuchos::setStringToIntegralParameter<int>(
      "Decomposition", "Structured",
      "\"Structured\": the brick grid of Subdomains Per Brick (Two Bricks only); \"METIS\": "
      "METIS_PartMeshDual per body into Mesh/Subdomains parts (always used for Exodus meshes)",
      Teuchos::Array<std::string>(core::namesOf(kMeshDecompositionNames)), &pl);
}

void materialParameters(ParameterList& pl) {
  // One sublist per element block, named after the block; "*" is the template.
  ParameterList& body = pl.sublist("*", false,
                                   "one sublist per element block (body), named after the block; "
                                   "give either the Lame constants or (E, nu)");
  setWithoutDefault(body, "Lame Lambda", "Lame's first parameter lambda [stress], with Lame Mu (3 lambda + 2 mu > 0)",
                    core::closedInterval(-core::kMaxMagnitude, core::kMaxMagnitude));
  setWithoutDefault(body, "Lame Mu", "shear modulus mu [stress], with Lame Lambda",
                    core::openClosed(0.0, core::kMaxMagnitude));
  setWithoutDefault(body, "Young Modulus", "E [stress], with Poisson Ratio (instead of Lame constants)",
                    core::openClosed(0.0, core::kMaxMagnitude));
  setWithoutDefault(body, "Poisson Ratio", "nu, with Young Modulus", core::openInterval(-1.0, 0.5));
}

void loadParameters(ParameterList& pl) {
  ParameterList& load = pl.sublist("*", false,
                                   "one sublist per load, any name: a constant traction and/or a normal pressure on a "
                                   "side set (or on the boundary faces of a node set) or a volume force on an element "
                                   "block");
  load.set("Side Set", std::string(""), "side set that carries the traction (Traction, Pressure)");
  load.set("Node Set", std::string(""),
           "instead of Side Set: the traction acts on the boundary faces whose nodes all lie in this node set "
           "(meshes with node sets only, e.g. written by meshio)");
  load.set("Traction", Teuchos::Array<double>(3, 0.0), "{px, py, pz}: traction density [stress]",
           core::finiteArray(3, core::kMaxMagnitude));
  load.set("Pressure", 0.0,
           "pressure normal to each face of the side set (or node set) [stress], positive in compression (it "
           "pushes the face inwards); added to Traction",
           core::closedInterval(-core::kMaxMagnitude, core::kMaxMagnitude));
  load.set("Element Block", std::string(""), "element block that carries the volume force");
  load.set("Volume Force", Teuchos::Array<double>(3, 0.0), "{bx, by, bz}: force per volume",
           core::finiteArray(3, core::kMaxMagnitude));
}

void boundaryParameters(ParameterList& pl) {
  pl.set("Dirichlet Node Sets", Teuchos::Array<std::string>(),
         "node sets with zero displacement in all components (enforced by multipliers: T-FETI); Two Bricks "
         "clamps the paper's dirichlet_aluminium and dirichlet_steel when Boundary is empty");
  ParameterList& condition = pl.sublist("*", false,
                                        "one sublist per displacement condition, any name: u_c = value on the "
                                        "chosen components c of a node set (symmetry planes, plane strain, "
                                        "prescribed displacements)");
  condition.set("Node Set", std::string(""), "the node set (required)");
  condition.set("Components", std::string("xyz"),
                "the prescribed components, any of x, y, z once each (e.g. \"x\" for a symmetry plane x = const)");
  condition.set("Displacement", Teuchos::Array<double>(3, 0.0),
                "{ux, uy, uz} [length]: the values of the prescribed components (the others are ignored)",
                core::finiteArray(3, core::kMaxMagnitude));
}

// The surfaces and rows of one interface: in the flat Contact list and in each Contact/<name>.
void interfaceParameters(ParameterList& pl) {
  pl.set("Slave Side Set", std::string(""),
         "contact surface of the slave body (its nodes are projected on the master surface); empty with an "
         "empty Master Side Set: no contact (the paper's pair: contact_aluminium). Without a side set of this name, "
         "a node set of this name stands for its boundary faces (all their nodes in the set)");
  pl.set("Master Side Set", std::string(""),
         "contact surface of the master body (the paper's: contact_steel); a node set of this name also serves, "
         "as for the Slave Side Set");
  pl.set("T1 Direction", Teuchos::Array<double>(Teuchos::tuple<double>(1.0, 0.0, 0.0)),
         "{x, y, z}: the first tangential direction t1 (F1 acts along it), projected on each node's "
         "tangent plane",
         core::finiteArray(3));
  Teuchos::setStringToIntegralParameter<int>(
      "Discretization", "Mortar",
      "contact rows of a slave node: \"Mortar\" (dual mortar weights of the master nodes, integrated over the "
      "slave surface: no pressure oscillation on non-matching meshes; node-to-node on matching ones) or "
      "\"Node To Surface\" (the master displacement interpolated at the node's projection)",
      Teuchos::Array<std::string>(core::namesOf(feti::kContactDiscretizationNames)), &pl);
  Teuchos::setStringToIntegralParameter<int>(
      "Surface Geometry", "Automatic",
      "the surfaces between which the mortar gaps are measured: \"Faceted\" (the faces as meshed), "
      "\"Smoothed\" (linear faces curved by their nodal normals, Nagata's patches: for 4-node tetrahedra or "
      "8-node hexahedra meshed on a curved surface, whose facets' sag h^2 / (8 R) would otherwise count as gap; "
      "not for a surface meant to be faceted) or \"Automatic\" (Smoothed on an interface whose master's "
      "facets sag by a tenth or more of the fit it closes, its largest initial overlap plus its Interference, "
      "and whose overlaps are more even between the smoothed surfaces than between the faces: a fit meshed on "
      "a curved surface; Faceted elsewhere, and on bonded interfaces). 6-node faces keep their own quadratic "
      "geometry either way",
      Teuchos::Array<std::string>(core::namesOf(feti::kSurfaceGeometryNames)), &pl);
  pl.set("Search Distance", 0.0,
         "contact search: a slave node is projected on the nearest master face within this distance [length] "
         "(set it above the largest initial gap that may close; 0, the default: the size of the slave surface's "
         "largest face); a slave node with no master face that near "
         "gets no contact rows (it cannot touch), except one inside the master body (an interference, up to a "
         "master face's size deep), which is always paired. The initial gap d is the signed distance along the "
         "master normal (negative: initial overlap). After the solve a slave node without rows found inside the "
         "master body makes the run not converged (exit 3)",
         core::atLeast(0.0));
  pl.set("Interference", 0.0,
         "[length] an overlap the interface is to close (> 0: a shrink or press fit modelled on nominal, touching "
         "geometry) or a clearance (< 0), subtracted from every pair's gap d (as Abaqus's contact interference). "
         "In Load Steps it follows the ramp k / N like a load without a table. Not on a Bonded interface",
         core::closedInterval(-core::kMaxMagnitude, core::kMaxMagnitude));
}

void contactParameters(ParameterList& pl) {
  frictionLawTable().declare(pl);
  fixedPointTable().declare(pl);
  interfaceParameters(pl);
  ParameterList& named = pl.sublist(
      "*", false,
      "one sublist per contact interface, any name (several bodies and interfaces): its Slave Side Set and Master "
      "Side Set (required), and any of Friction Model, F1, F2, Slip Bound, T1 Direction, Discretization, Surface "
      "Geometry, Search Distance, Interference, which default to the flat Contact list's values. A node may be the slave of one interface only; "
      "a body may be the slave of one interface and the master of another; both surfaces of an interface must be "
      "on different bodies (no self-contact). With such sublists the flat Slave/Master Side Set stay empty");
  frictionLawTable().declare(named);
  interfaceParameters(named);
}

// Thresholds measured once (doc/measurements/coarse_problem.md, doc/factorization.md) and kept as
// parameters for such measurements; each depends on a matrix alone, never on the layout, so
// every rank and thread count takes the same path and results keep their bits.
void fetiTuningParameters(ParameterList& pl) {
  Teuchos::setStringToIntegralParameter<int>(
      "CHOLMOD Mode", "Auto",
      "how CHOLMOD factorises each matrix: \"Auto\" (supernodal from 4000 rows: the supernodal factorisation is "
      "faster from about 2000 rows on one thread, but it holds the BLAS lock, so in a team of two threads it "
      "catches up with two concurrent simplicial ones only at 4000-6500 rows), \"Simplicial\" or \"Supernodal\" "
      "(doc/factorization.md); the solves cost the same in both modes",
      Teuchos::Array<std::string>(core::namesOf(feti::kCholmodModeNames)), &pl);
  pl.set("Subtree Solve From", 500000,
         "the factor of G G^T (solved on one rank's threads) splits its elimination tree for concurrent solves "
         "when it stores at least this many values (doc/measurements/coarse_problem.md)",
         core::intRange(0, std::numeric_limits<int>::max()));
  pl.set("Distributed Coarse From", 200000,
         "with several ranks, coarse factors of at least this many stored values are solved over the ranks "
         "(smaller ones on rank 0 alone, where the three collectives of a spread solve cost more than they save; "
         "doc/measurements/coarse_problem.md, \"The coarse solve over the ranks\"); the bits are the serial solve's either way",
         core::intRange(0, std::numeric_limits<int>::max()));
  pl.set("Single Coarse Gate", 1e-3,
         "the single-precision coarse factor (Coarse Factor Precision) is kept when one solve with it differs from "
         "the double one by at most this (relative): the rounding then perturbs P by about as much on Im G^T, which "
         "leaves A_rho's spectrum and the refinement of the exact solves (about this contraction per step) "
         "untouched; else G G^T is factorised again in double (doc/measurements/coarse_problem.md)",
         core::openClosed(0.0, 1.0));
}

void fetiParameters(ParameterList& pl) {
  Teuchos::setStringToIntegralParameter<int>(
      "Factorization", "CHOLMOD",
      "sparse Cholesky of the regularised subdomain stiffness K_reg and of G G^T (doc/factorization.md)",
      Teuchos::Array<std::string>(core::namesOf(feti::kFactorizationNames)), &pl);
  Teuchos::setStringToIntegralParameter<int>(
      "Dual Operator", "Implicit",
      "F = B K^dagger B^T: \"Implicit\" (two triangular solves per subdomain and application) or "
      "\"Explicit\" (dense local F_s assembled once, then dense matrix-vector products)",
      Teuchos::Array<std::string>(core::namesOf(feti::kDualOperatorNames)), &pl);
  Teuchos::setStringToIntegralParameter<int>(
      "Preconditioner", "Dirichlet",
      "dual preconditioner P D P: \"None\", \"Lumped\" (D = B K B^T) or \"Dirichlet\" (D = B S B^T, S the "
      "Schur complement on the constrained dofs); linear solves: projected CG; contact: MPGP's CG steps "
      "preconditioned in face (restricted to the free set)",
      Teuchos::Array<std::string>(core::namesOf(feti::kDualPreconditionerNames)), &pl);
  Teuchos::setStringToIntegralParameter<int>(
      "Displacement Conditions", "Automatic",
      "how a displacement component prescribed to 0 is held (Dirichlet Node Sets; a Boundary/<name> of value 0 "
      "that holds from the reference): \"Multipliers\" (a row of B per subdomain copy, T-FETI as the paper), "
      "\"Eliminated\" (removed from K_s; a subdomain's rigid modes are then those the eliminated components "
      "leave free) or \"Automatic\" (eliminated but at clamped nodes, those held in all three components, which "
      "keep their rows). In both eliminating modes a subdomain where such components are few and hold a rigid "
      "mode only weakly keeps their rows. Elimination keeps F well conditioned where the rows cover most nodes "
      "of a thin body (a plane-strain slice); at clamps the rows do better on the paper's bricks, elimination "
      "on some curved scenes (doc/measurements/curved_iterations.md); other components keep their rows",
      Teuchos::Array<std::string>(core::namesOf(feti::kZeroComponentNames)), &pl);
  Teuchos::setStringToIntegralParameter<int>(
      "Coarse Factor Precision", "Auto",
      "contact solves: the factor of G G^T that SMALSE-M's projections use: \"Single\" (rounded to 4 bytes per "
      "value: half the bytes per coarse solve; SMALSE-M's penalty on G mu keeps the solution that of the exact "
      "projector; lambda_Im and the rigid body coefficients are refined to double; used only where one solve "
      "differs from the double one by at most 1e-3), \"Double\", or \"Auto\" (Single where two coarse solves "
      "read at least as many bytes as the subdomain solves of one F application: many small subdomains). Linear "
      "solves: always double "
      "(projected CG needs the exact projector). doc/measurements/coarse_problem.md",
      Teuchos::Array<std::string>(core::namesOf(feti::kCoarsePrecisionNames)), &pl);
  pl.set("Max Iterations", 1000,
         "linear solves: cap on projected CG iterations; reaching it ends the solve as not converged (exit 3)",
         core::intRange(1, kMaxCount));
  fetiTuningParameters(pl);
}

void solverParameters(ParameterList& pl) {
  // SMALSE-M and MPGP declare their own parameters (qp/SolverParameters.hpp): Tolerance,
  // Max Outer Iterations and the sublists SMALSE-M and MPGP. The rest is the stack's.
  qp::declareSolverParameters(pl);
  pl.set("Max Seconds", 0.0,
         "wall-clock budget of the run [s], from its start: checked between the set-up's phases, between subdomain "
         "factorisations and at every iteration. When it runs out during the solve the iterations stop and the run "
         "ends as not converged (exit 3, results written, the message names the budget); before the solve, exit 3 "
         "with the summary saying so and no results; 0: no budget",
         core::atLeast(0.0));
  pl.set("Pairing Updates", 3,
         "contact scenes: after a solve the slave nodes are paired again on the deformed bodies (search, "
         "projections and mortar weights at x + u, gaps still from the reference); where a slave node without rows "
         "now lies inside the master, or a paired one has slid past its master nodes, the contact rows are built on "
         "the deformed bodies and the problem is solved again (factorised again), at most this many times (a load "
         "history: at each step, from the first step whose state changed the pairing on). Nothing changed: the "
         "first result stands, as it was. A scene solved once whose pairing still changes after the last of them "
         "is not converged (exit 3). 0: the reference mesh decides the pairing (issue 41; "
         "doc/contact_surfaces.md)",
         core::intRange(0, 20));
  pl.set("Verbose", true, "print the solver chain and one progress line per outer iteration (rank 0)");
  pl.set("Progress Interval", 2.0,
         "Verbose: inside a long inner solve, a progress line (MPGP iterations, ||g^P||, F applications, time) "
         "whenever this many seconds passed without one [s]; 0: every 10 MPGP iterations",
         core::atLeast(0.0));
}

void parallelParameters(ParameterList& pl) {
  pl.set("Threads", 0,
         "threads per MPI rank over its subdomains; 0 = OMP_NUM_THREADS (or all cores)",
         core::intRange(0, 4096));
}

// One sublist per section (any name), like Abaqus's *PRE-TENSION SECTION or CalculiX's.
void pretensionParameters(ParameterList& pl) {
  ParameterList& section = pl.sublist(
      "*", false,
      "one pretension section, any name: the two sides of a cut through a bolt (the surfaces of a Contact/<name> "
      "interface with Friction Model Bonded, e.g. a bolt meshed in two bodies) pulled into each other by a "
      "shortening, along the interface's normal; the section then carries the bolt's tension");
  section.set("Interface", std::string(""), "the Contact/<name> (Bonded) whose two surfaces are the cut (required)");
  section.set("Force", 0.0,
              "the tension the section carries at the end of its Steps [force; > 0]: its shortening is found by "
              "secant iterations, each a solve of the step (the solver's accuracy: Pretension/<name>/Force "
              "Tolerance). Give Force or Shortening",
              core::closedInterval(0.0, core::kMaxMagnitude));
  section.set("Shortening", 0.0,
              "the shortening of the section at the end of its Steps [length; > 0]: the cut's two sides pulled "
              "into each other by this much. Give Force or Shortening",
              core::closedInterval(0.0, core::kMaxMagnitude));
  section.set("Steps", 1,
              "the pretension is applied over steps 1 .. Steps (its force or shortening ramped k / Steps), then "
              "locked: the shortening reached stays, and the section's force follows the other loads",
              core::intRange(1, 100000));
  section.set("Force Tolerance", 1e-6,
              "with Force: the secant iterations end when |section force - target| <= this x Force",
              core::openClosed(0.0, 1.0));
}
}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> sceneValidParameters() {
  static const Teuchos::RCP<const ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new ParameterList("Tribos"));
    meshParameters(pl->sublist("Mesh", false, "the mesh and its decomposition"));
    materialParameters(pl->sublist("Materials", false,
                                   "materials per element block; Two Bricks defaults to the paper's "
                                   "aluminium and steel when this list is empty"));
    loadParameters(pl->sublist("Loads", false,
                               "loads; Two Bricks defaults to the paper's tractions on load_end and "
                               "load_top when this list is empty"));
    boundaryParameters(pl->sublist("Boundary", false, "displacement conditions"));
    contactParameters(pl->sublist("Contact", false,
                                  "contact pair and friction law; without side sets the scene has no contact and "
                                  "is solved by linear T-FETI"));
    solverParameters(pl->sublist("Solver", false, "stopping, budgets and progress of the solve; SMALSE-M and MPGP"));
    fetiParameters(pl->sublist("FETI", false, "T-FETI operators and the linear (projected CG) solver"));
    parallelParameters(pl->sublist("Parallel", false, "hybrid MPI + threads"));
    ParameterList& steps = pl->sublist(
        "Load Steps", false,
        "a quasi-static load history (contact scenes): loads and prescribed displacements ramped over the steps, "
        "friction acting on the slip increment of each step (ALGORITHMS.md 11)");
    steps.set("Number Of Steps", 1,
              "steps of the history; a load or prescribed displacement without a table follows the linear "
              "ramp k / N in step k; 1: the static problem, all loads at once. Each step is a time step of the "
              "Exodus result and an entry of the summary's steps",
              core::intRange(1, 100000));
    steps.set("Warm Start", true,
              "start each step from the last step's multipliers (scaled to the load factor when every load and "
              "prescribed displacement follows the ramp), the slip bound they imply and the last ||PFP||; false: "
              "each step from zero, as a one-step solve (for comparison: ALGORITHMS.md 11)");
    steps.set("Max Cutbacks", 4,
              "a step that does not converge is retried from the last converged state with half the increment, "
              "again and again down to 2^-(this) of a step (4: 1/16), before the history gives up; converged "
              "sub-steps are states of the history (their slip is remembered) but not results; each try is a "
              "line of the log and counted in its step's entry (attempts, cutbacks, reached). 0: no retry",
              core::intRange(0, 30));
    steps.set("Restart From", std::string(),
              "an Exodus result of a load history of this scene (a path relative to the working directory, like "
              "--output): the history continues after its last converged step, from the relative tangential "
              "displacement, accumulated slip and dissipated energy reached there (the first step starts from "
              "its contact forces); the new result holds the new steps. Empty: start at step 1");
    steps.set("Checkpoint Seconds", 60.0,
              "with --output: each converged step is appended to a draft of the result file as it converges; after "
              "a converged step, once this many seconds passed since the run started or the last checkpoint, a "
              "copy of the draft replaces the result file (whole, under a temporary name, then renamed: never "
              "partial), so that a job killed later leaves the steps so far to continue from (Restart From). 0: "
              "after every step (each copy is the whole file so far: for long histories of small steps, give "
              "seconds). At the end the draft, with every step, replaces the file",
              core::atLeast(0.0));
    steps.set("Times", Teuchos::Array<double>(),
              "the time of each step in the results (Number Of Steps increasing values); not given: the ramp k / N",
              core::finiteArray(core::FiniteArrayValidator::kAnyLength, core::kMaxMagnitude));
    steps.sublist("*", false,
                  "one sublist per Loads/<name> or Boundary/<name> (a prescribed displacement) that does not follow "
                  "the ramp or does not hold in every step, named after it")
        .set("Factors", Teuchos::Array<double>(1, 1.0),
             "its factor in each step (Number Of Steps values): e.g. {1, 1} for a normal load held while a shear "
             "{1, 0} is applied and removed; a Boundary/<name>'s Displacement is scaled the same way",
             core::finiteArray(-1, core::kMaxMagnitude))
        .set("Active", Teuchos::Array<int>(1, 1),
             "a Boundary/<name> only: whether it holds in each step (Number Of Steps values, 1 or 0), e.g. {0, 1, 1} "
             "for a grip added after a preload. Where it takes hold after step 1 it holds its nodes where the step "
             "before left them, then moves them by its Displacement times its factor; where it does not hold, its "
             "nodes are free. Each change rebuilds the constraints and factorises again. Not given: every step");
    pretensionParameters(pl->sublist("Pretension", false,
                                     "bolt pretension sections (contact scenes and load histories): a cut through "
                                     "a bolt given as a Bonded interface, shortened to a force or by a length"));
    return Teuchos::rcp_const_cast<const ParameterList>(pl);
  }();
  return valid;
}

namespace {
// The parameters of `list` that it gives override `rows` (the flat list's values otherwise).
void readInterfaceRows(const ParameterList& list, feti::ContactInterfaceSpec& rows) {
  if (list.isParameter("Slave Side Set")) rows.slaveSideSet = list.get<std::string>("Slave Side Set");
  if (list.isParameter("Master Side Set")) rows.masterSideSet = list.get<std::string>("Master Side Set");
  if (list.isParameter("T1 Direction")) {
    const auto& t = list.get<Teuchos::Array<double>>("T1 Direction");
    rows.t1Direction = {t[0], t[1], t[2]};
  }
  if (list.isParameter("Search Distance")) rows.searchDistance = list.get<double>("Search Distance");
  if (list.isParameter("Interference")) rows.interference = list.get<double>("Interference");
  if (list.isParameter("Discretization"))
    rows.discretization = core::valueOf(feti::kContactDiscretizationNames, list.get<std::string>("Discretization"));
  if (list.isParameter("Surface Geometry"))
    rows.surfaceGeometry = core::valueOf(feti::kSurfaceGeometryNames, list.get<std::string>("Surface Geometry"));
}

// The friction law of `list` over `law` (the flat list's, or the defaults): F2 not given in
// `list` but F1 given (or filled in) there follows F1, so that a coefficient given alone is
// isotropic friction, never F1 against the default F2.
void readFrictionLaw(const ParameterList& list, contact::FrictionLaw& law) {
  frictionLawTable().read(list, law);
  if (list.isParameter("F1") && !core::givenByUser(list, "F2")) law.F2 = law.F1;
}
}  // namespace

std::vector<ContactInterface> readContactInterfaces(const ParameterList& contactList, const std::string& source) {
  // The flat list: the one-interface shorthand, and every named interface's defaults.
  ContactInterface flat;
  readFrictionLaw(contactList, flat.law);
  readInterfaceRows(contactList, flat.rows);
  std::vector<ContactInterface> named;
  std::string names;
  for (auto it = contactList.begin(); it != contactList.end(); ++it) {
    if (!contactList.entry(it).isList()) continue;
    ContactInterface one = flat;
    one.rows.name = contactList.name(it);
    // Its name prefixes its results (<name>_normal_force; the flat list's are contact_...).
    core::requireInput(!one.rows.name.empty(), source + ": Contact: an interface sublist has an empty name: name it "
                                                         "(its results are called <name>_normal_force, ...)");
    one.rows.slaveSideSet = one.rows.masterSideSet = "";
    const ParameterList& list = contactList.sublist(one.rows.name);
    readFrictionLaw(list, one.law);
    readInterfaceRows(list, one.rows);
    core::requireInput(!one.rows.slaveSideSet.empty() && !one.rows.masterSideSet.empty(),
                       source + ": " + one.rows.list() + ": give both \"Slave Side Set\" and \"Master Side Set\"");
    names += (names.empty() ? "" : ", ") + one.rows.list();
    named.push_back(one);
  }
  const bool flatSurfaces = !flat.rows.slaveSideSet.empty() || !flat.rows.masterSideSet.empty();
  if (!named.empty()) {
    core::requireInput(!flatSurfaces, source + ": Contact: \"Slave Side Set\" and \"Master Side Set\" describe the "
                                               "one-interface shorthand; with interface sublists (" + names +
                                               ") give the surfaces in each sublist and leave these empty");
  } else if (flatSurfaces) {
    core::requireInput(!flat.rows.slaveSideSet.empty() && !flat.rows.masterSideSet.empty(),
                       source + ": Contact: give both \"Slave Side Set\" and \"Master Side Set\", or neither (no "
                                "contact)");
    named.push_back(flat);
  }
  for (auto& one : named) {
    one.rows.tangentialRows = one.law.hasTangentialRows();
    one.rows.tied = one.law.tiesSurfaces();
    core::requireInput(!one.rows.tied || one.rows.interference == 0.0,
                       source + ": " + one.rows.list() + "/Interference: a Bonded interface keeps its gap as it is; "
                                "give no Interference there");
  }
  return named;
}

contact::FrictionSettings readFrictionParameters(const std::vector<ContactInterface>& interfaces,
                                                 const Teuchos::ParameterList& contactList) {
  contact::FrictionSettings friction;
  fixedPointTable().read(contactList, friction);
  friction.laws.clear();
  for (const auto& one : interfaces) friction.laws.push_back(one.law);
  if (friction.laws.empty()) readFrictionLaw(contactList, friction.laws.emplace_back());
  return friction;
}

}  // namespace tribos::stack
