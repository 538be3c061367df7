#include "tribos/stack/SceneParameters.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

namespace tribos::stack {

namespace {
using Teuchos::ParameterList;

template <class T>
Teuchos::RCP<Teuchos::EnhancedNumberValidator<T>> atLeast(T min) {
  auto v = Teuchos::rcp(new Teuchos::EnhancedNumberValidator<T>());
  v->setMin(min);
  return v;
}

void meshParameters(ParameterList& pl) {
  Teuchos::setStringToIntegralParameter<int>(
      "Generator", "Two Bricks",
      "\"Two Bricks\": the paper's model problem (Section 6), generated; \"Exodus\": read "
      "Mesh/File (element blocks = bodies, node sets / side sets name the boundary parts)",
      Teuchos::tuple<std::string>("Two Bricks", "Exodus"), &pl);
  pl.set("Subdomains Per Brick", std::string("2x1x1"),
         "Two Bricks: subdomain grid NXxNYxNZ of each brick, cubic subdomains (NX = 2 NY = 2 NZ); "
         "the paper's s = NX*NY*NZ (Table 1: 2x1x1, 4x2x2, 6x3x3, 8x4x4, 10x5x5)");
  pl.set("H Over h", 2, "Two Bricks: elements per subdomain edge, H/h >= 1", atLeast<int>(1));
  pl.set("Initial Gap", 0.0,
         "Two Bricks: initial gap d >= 0 [length] between the bricks (the steel brick is lifted by it); "
         "set Contact/Search Distance above it so that the contact nodes pair",
         atLeast<double>(0.0));
  pl.set("File", std::string(""),
         "Exodus: path of the Exodus II mesh (linear tetrahedra); relative paths are relative to the scene file "
         "(gmsh meshes: convert with tribos-msh2exo)");
  pl.set("Subdomains", 4,
         "Exodus, or Decomposition = METIS: number of subdomains (METIS parts, split among bodies "
         "in proportion to their element counts; at least one per body)",
         atLeast<int>(1));
  Teuchos::setStringToIntegralParameter<int>(
      "Decomposition", "Structured",
      "\"Structured\": the brick grid of Subdomains Per Brick (Two Bricks only); \"METIS\": "
      "METIS_PartMeshDual per body into Mesh/Subdomains parts (always used for Exodus meshes)",
      Teuchos::tuple<std::string>("Structured", "METIS"), &pl);
}

void materialParameters(ParameterList& pl) {
  // One sublist per element block, named after the block; "*" is the template.
  ParameterList& body = pl.sublist("*", false,
                                   "one sublist per element block (body), named after the block; "
                                   "give either the Lame constants or (E, nu)");
  body.set("Lame Lambda", 0.0, "Lame's first parameter lambda [stress], with Lame Mu");
  body.set("Lame Mu", 0.0, "shear modulus mu > 0 [stress], with Lame Lambda");
  body.set("Young Modulus", 0.0, "E > 0 [stress], with Poisson Ratio (instead of Lame constants)");
  body.set("Poisson Ratio", 0.0, "-1 < nu < 0.5, with Young Modulus");
}

void loadParameters(ParameterList& pl) {
  ParameterList& load = pl.sublist("*", false,
                                   "one sublist per load, any name: a constant traction on a side set "
                                   "(or on the boundary faces of a node set) or a volume force on an element block");
  load.set("Side Set", std::string(""), "side set that carries the traction (Traction)");
  load.set("Node Set", std::string(""),
           "instead of Side Set: the traction acts on the boundary faces whose three nodes all lie in this node set "
           "(meshes with node sets only, e.g. written by meshio)");
  load.set("Traction", Teuchos::Array<double>(3, 0.0), "{px, py, pz}: traction density [stress]");
  load.set("Element Block", std::string(""), "element block that carries the volume force");
  load.set("Volume Force", Teuchos::Array<double>(3, 0.0), "{bx, by, bz}: force per volume");
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
                "{ux, uy, uz} [length]: the values of the prescribed components (the others are ignored)");
}

void contactParameters(ParameterList& pl) {
  Teuchos::setStringToIntegralParameter<int>(
      "Friction Model", "Coulomb",
      "\"None\" (frictionless), \"Tresca\" (given slip bound), \"Coulomb\" (successive "
      "approximations on the slip bound), \"Bonded\" (contact rows as equalities)",
      Teuchos::tuple<std::string>("None", "Tresca", "Coulomb", "Bonded"), &pl);
  pl.set("F1", 0.3, "friction coefficient along t1 (isotropic when F1 = F2), >= 0", atLeast<double>(0.0));
  pl.set("F2", 0.3, "friction coefficient along t2, >= 0", atLeast<double>(0.0));
  pl.set("Slave Side Set", std::string(""),
         "contact surface of the slave body (its nodes are projected on the master surface); empty with an "
         "empty Master Side Set: no contact (the paper's pair: contact_aluminium). Without a side set of this name, "
         "a node set of this name stands for its boundary faces (all three nodes in the set)");
  pl.set("Master Side Set", std::string(""),
         "contact surface of the master body (the paper's: contact_steel); a node set of this name also serves, "
         "as for the Slave Side Set");
  pl.set("Slip Bound", 0.0, "Tresca: the given slip bound g as a nodal force [force], >= 0", atLeast<double>(0.0));
  Teuchos::setStringToIntegralParameter<int>(
      "Fixed Point", "Inexact",
      "Coulomb: \"Inexact\" updates the slip bound g := lambda_nu after every SMALSE-M outer iteration "
      "(the paper's choice); \"Exact\" solves every Tresca problem to Solver/Tolerance first",
      Teuchos::tuple<std::string>("Inexact", "Exact"), &pl);
  pl.set("Max Fixed Point Iterations", 50, "Coulomb, Exact: cap on the Tresca solves", atLeast<int>(1));
  pl.set("T1 Direction", Teuchos::Array<double>(Teuchos::tuple<double>(1.0, 0.0, 0.0)),
         "{x, y, z}: the first tangential direction t1 (F1 acts along it), projected on each node's "
         "tangent plane");
  Teuchos::setStringToIntegralParameter<int>(
      "Discretization", "Mortar",
      "contact rows of a slave node: \"Mortar\" (dual mortar weights of the master nodes, integrated over the "
      "slave surface: no pressure oscillation on non-matching meshes; node-to-node on matching ones) or "
      "\"Node To Surface\" (the master displacement interpolated at the node's projection)",
      Teuchos::tuple<std::string>("Mortar", "Node To Surface"), &pl);
  pl.set("Search Distance", 1e-6,
         "contact search: a slave node is projected on the nearest master face within this distance [length] "
         "(set it above the largest initial gap that may close); a slave node with no master face that near "
         "gets no contact rows (it cannot touch). The initial gap d is the signed distance along the master "
         "normal (negative: initial overlap)",
         atLeast<double>(0.0));
}

void fetiParameters(ParameterList& pl) {
  Teuchos::setStringToIntegralParameter<int>(
      "Factorization", "CHOLMOD",
      "sparse Cholesky of the regularised subdomain stiffness K_reg and of G G^T (doc/factorization.md)",
      Teuchos::tuple<std::string>("CHOLMOD", "Tacho"), &pl);
  Teuchos::setStringToIntegralParameter<int>(
      "Dual Operator", "Implicit",
      "F = B K^dagger B^T: \"Implicit\" (two triangular solves per subdomain and application) or "
      "\"Explicit\" (dense local F_s assembled once, then dense matrix-vector products)",
      Teuchos::tuple<std::string>("Implicit", "Explicit"), &pl);
  Teuchos::setStringToIntegralParameter<int>(
      "Preconditioner", "Dirichlet",
      "dual preconditioner P D P: \"None\", \"Lumped\" (D = B K B^T) or \"Dirichlet\" (D = B S B^T, S the "
      "Schur complement on the constrained dofs); linear solves: projected CG; contact: MPGP's CG steps "
      "preconditioned in face (restricted to the free set)",
      Teuchos::tuple<std::string>("None", "Lumped", "Dirichlet"), &pl);
  pl.set("Max Iterations", 1000, "linear solves: cap on projected CG iterations", atLeast<int>(1));
}

void solverParameters(ParameterList& pl) {
  pl.set("Tolerance", 1e-5,
         "the paper's epsilon > 0: SMALSE-M stops when ||g^P|| and ||G mu|| are <= epsilon ||P h|| (and "
         "Coulomb's slip bound moved by <= epsilon); linear solves: ||P r|| <= epsilon ||P h||",
         atLeast<double>(0.0));
  pl.set("Max Outer Iterations", 100, "cap on SMALSE-M outer iterations", atLeast<int>(1));
  pl.set("Verbose", true, "print the solver chain and one progress line per outer iteration (rank 0)");
  pl.set("Progress Interval", 2.0,
         "Verbose: inside a long inner solve, a progress line (MPGP iterations, ||g^P||, F applications, time) "
         "whenever this many seconds passed without one [s]; 0: every 10 MPGP iterations",
         atLeast<double>(0.0));
  ParameterList& smalse = pl.sublist("SMALSE-M", false, "augmented Lagrangian (paper Section 5)");
  smalse.set("eta", 1.0, "eta > 0, relative to ||P h||: cap of the inner stopping bound min(M ||G mu||, eta)",
             atLeast<double>(0.0));
  smalse.set("rho", 10.0,
             "rho > 0, relative to ||PFP||: penalty of A_rho = PFP + rho Q (the paper: 1; 10 needs far fewer "
             "outer iterations here, doc/smalse_parameters.md)", atLeast<double>(0.0));
  smalse.set("initial M", 1.0,
             "M_0 > 0, relative to ||PFP||: inner precision control (the paper: 1e-6; doc/smalse_parameters.md)", atLeast<double>(0.0));
  smalse.set("beta", 0.5,
             "0 < beta_M < 1: M is multiplied by it when the Lagrangian does not grow enough (the paper: 0.1; "
             "PERMON: 0.5)",
             atLeast<double>(0.0));
  Teuchos::setStringToIntegralParameter<int>(
      "equality test", "Conventional",
      "outer test on ||G mu||: \"Conventional\" (<= epsilon ||P h||) or \"Paper\" (<= epsilon M_0 ||mu||)",
      Teuchos::tuple<std::string>("Conventional", "Paper"), &smalse);
  smalse.set("rho growth", 1.0,
             ">= 1: rho is multiplied by it after an outer iteration that reduced ||G mu|| by less than half "
             "(1: fixed rho, the paper's algorithm)",
             atLeast<double>(1.0));
  smalse.set("power iterations", 50, "products with PFP in the power method for ||PFP||", atLeast<int>(1));
  ParameterList& mpgp = pl.sublist("MPGP", false, "inner solver for the bound and elliptic-cone constraints");
  mpgp.set("step scale", 1.9, "alpha_bar = step scale / ||A_rho||, in (0, 2)", atLeast<double>(0.0));
  mpgp.set("Gamma", 1.0, "Gamma > 0: proportioning parameter", atLeast<double>(0.0));
  mpgp.set("max iterations", 100000, "cap on MPGP iterations per inner solve", atLeast<int>(1));
  mpgp.set("optimal expansion", false,
           "expansion steps try the exact minimiser along the free gradient (projected, monotone safeguard) "
           "before the fixed alpha_bar step");
  mpgp.set("chopped proportioning", true,
           "a proportioning step that follows another goes along the chopped gradient with the exact step length "
           "on the constraint boundary (MPRGP's step, the ellipses' curvature included, projected), instead of "
           "the gradient projection step with alpha_bar (doc/smalse_parameters.md)");
}

void parallelParameters(ParameterList& pl) {
  pl.set("Threads", 0,
         "threads per MPI rank over its subdomains; 0 = OMP_NUM_THREADS (or all cores)",
         atLeast<int>(0));
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
    solverParameters(pl->sublist("Solver", false, "SMALSE-M outer loop"));
    fetiParameters(pl->sublist("FETI", false, "T-FETI operators and the linear (projected CG) solver"));
    parallelParameters(pl->sublist("Parallel", false, "hybrid MPI + threads"));
    return Teuchos::rcp_const_cast<const ParameterList>(pl);
  }();
  return valid;
}

}  // namespace tribos::stack
