#pragma once
/// \file ConstraintMatrix.hpp
/// The T-FETI constraint matrix B = [N; T1; T2; B_e; B_d] and the gap vector c (paper
/// Sections 3-4, ALGORITHMS.md 2), with every row of unit norm and B B^T = I:
///  - gluing: a node shared by k subdomain copies gets k-1 rows per component, an
///    orthonormal (Helmert) basis of the differences: row j couples copy j+1 against the
///    mean of copies 1..j;
///  - displacement conditions: at a node whose component c is prescribed (u_c = value,
///    c = x, y or z; "Dirichlet Node Sets" prescribe all three to 0) every copy gets a unit
///    row for that component with the value in c, and that component gets no gluing rows —
///    the paper's count, and B stays orthonormal;
///  - contact (geometry/ContactSearch.hpp, geometry/MortarCoupling.hpp): rows N_r, T1_r, T2_r acting
///    on (mean of the slave copies - sum_i w_i mean of the copies of master node i)
///    projected on nu, t1, t2, with w the dual mortar weights of the slave node or the
///    barycentric weights of its projection on the master surface (the paper's transfer
///    mapping chi; node-to-node on matching meshes),
///    scaled to unit norm; orthogonal to the gluing rows by construction. Prescribed
///    components are dropped from a contact row and their known contribution moved into c
///    (so the row stays orthogonal to the displacement rows); a row with nothing left (both
///    sides clamped, or a direction fully prescribed, e.g. t2 = the axis of a plane-strain
///    slice) is removed and counted. Contact rows of different slave nodes that share
///    master vertices are not orthogonal (B B^T != I on those rows; doc/theory.md).
/// B is built on every rank, cut to what the rank needs for the solve (keepRankRows, or
/// buildConstraintMatrix's keepForRank while it is built); each row is owned
/// by one rank — the owner of the lowest subdomain it touches — and rows are numbered so
/// that the rows of rank p are the contiguous range [firstRowOfRank[p], firstRowOfRank[p+1]).
/// Within a rank: contact triples (N, T1, T2 consecutive per contact node), then gluing,
/// then Dirichlet rows.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tribos/core/EnumNames.hpp"
#include "tribos/mesh/Decomposition.hpp"

namespace tribos::feti {

enum class RowKind : int { ContactNormal = 0, ContactT1 = 1, ContactT2 = 2, Gluing = 3, Dirichlet = 4 };

/// u_c = value[c] for the chosen components c of every node of a node set.
struct DisplacementCondition {
  std::string name;                             ///< for messages (the XML sublist)
  std::string nodeSet;
  std::array<bool, 3> components{true, true, true};
  std::array<double, 3> value{0.0, 0.0, 0.0};
};

/// Contact/Discretization: dual mortar weights (geometry/MortarCoupling.hpp; node-to-node on
/// matching meshes), or the barycentric weights of the slave node's projection.
enum class ContactDiscretization { Mortar, NodeToSurface };
inline constexpr core::EnumNames<ContactDiscretization, 2> kContactDiscretizationNames{
    {{"Mortar", ContactDiscretization::Mortar}, {"Node To Surface", ContactDiscretization::NodeToSurface}}};

/// Contact/Surface Geometry: the gaps measured between the faces as meshed, or between their
/// smoothed surfaces (Nagata's curved faces from the nodal normals: geometry/SmoothedFaces.hpp),
/// for linear faces meshed on a curved surface; Automatic: smoothed where the master's facets
/// sag by a fair part of the fit the interface is to close (rows::facetsDominate), faceted
/// elsewhere.
enum class SurfaceGeometry { Automatic, Faceted, Smoothed };
inline constexpr core::EnumNames<SurfaceGeometry, 3> kSurfaceGeometryNames{
    {{"Automatic", SurfaceGeometry::Automatic},
     {"Faceted", SurfaceGeometry::Faceted},
     {"Smoothed", SurfaceGeometry::Smoothed}}};

/// One contact interface (Contact or Contact/<name>): a slave surface paired with a master
/// surface. A slave node that several interfaces pair (a corner of a body resting on a floor and
/// against a wall) gets the rows of the one where its gap is smallest (ties: the earlier), and
/// is counted in ContactInterfaceRows::sharedSlaveNodes of the others. A node may be the master of other
/// interfaces. Both surfaces of one interface must lie in different bodies (self-contact is not
/// modelled), and one contact may not be modelled twice (slave and master swapped: a double pass).
struct ContactInterfaceSpec {
  std::string name;                        ///< for messages and results ("" for the flat Contact list)
  std::string slaveSideSet, masterSideSet;
  bool tangentialRows = true;              ///< T1, T2 rows (friction or bonded); false: N only
  /// Bonded: the rows tie the surfaces where they are (u_slave = chi u_master, an initial gap
  /// kept); otherwise the normal row reads N u <= d and a gap may close.
  bool tied = false;
  std::array<double, 3> t1Direction{1.0, 0.0, 0.0};  ///< t1 = this projected on the tangent plane
  /// A slave node is projected on the master surface within this distance (the mesh's
  /// units); a slave node farther from every master face gets no contact rows. 0: derived from
  /// the mesh, the size of the slave surface's largest face (rows::searchReach).
  double searchDistance = 0.0;
  /// An overlap to close (> 0) or a clearance (< 0), subtracted from every pair's gap
  /// (Contact/<name>/Interference); a load history ramps it (ContactNode::interference).
  double interference = 0.0;
  ContactDiscretization discretization = ContactDiscretization::Mortar;
  SurfaceGeometry surfaceGeometry = SurfaceGeometry::Automatic;
  /// "Contact/<name>", or "Contact" without a name: the parameter list of the interface.
  std::string list() const { return name.empty() ? "Contact" : "Contact/" + name; }
  /// "Contact/<name> (slave -> master)", or "Contact (slave -> master)" without a name.
  std::string label() const { return list() + " (" + slaveSideSet + " -> " + masterSideSet + ")"; }
};

struct ConstraintMatrix;

/// FETI/Displacement Conditions. Multipliers: rows of B (the paper's T-FETI). Eliminated: every
/// component prescribed to 0 leaves K_s. Automatic: those of nodes not held in all three
/// components (symmetry planes, plane-strain faces) leave K_s; a clamped node keeps its rows, so
/// that a subdomain at a clamp keeps its rigid modes in the coarse space (T-FETI's reason for
/// Dirichlet rows). In either eliminating mode a subdomain whose zero components are few and hold
/// a rigid mode only weakly keeps their rows (ConstraintMatrix.cpp).
enum class ZeroComponents { Multipliers, Automatic, Eliminated };
inline constexpr core::EnumNames<ZeroComponents, 3> kZeroComponentNames{
    {{"Multipliers", ZeroComponents::Multipliers}, {"Automatic", ZeroComponents::Automatic},
     {"Eliminated", ZeroComponents::Eliminated}}};

struct ConstraintSpec {
  std::vector<std::string> dirichletNodeSets;  ///< node sets with u = 0 (all components)
  std::vector<DisplacementCondition> displacementConditions;
  /// Per displacement condition, whether it has rows in this B (Load Steps/<name>/Active of the
  /// steps B serves; stack/solve/src/ConditionSteps.hpp); empty: every one. Absent conditions keep
  /// their index, so that PrescribedPart::condition and the factor tables still name them.
  std::vector<char> presentConditions;
  /// Per displacement condition (empty, or a null entry: the reference), the displacement of
  /// every global node its rows start from: a condition that takes hold after step 1 holds its
  /// nodes where the solved state before left them, u_c = base_c + factor x value_c. The base
  /// goes into c alone (PrescribedPart::value stays the condition's value, which factors scale).
  std::vector<const std::vector<std::array<double, 3>>*> conditionBase;
  std::vector<ContactInterfaceSpec> interfaces;  ///< none: no contact
  /// A pairing on the deformed bodies (stack/solve/src/PairingUpdate.cpp; issue 41): the displacement
  /// u of every global node of a solved state, and that state's pairing (its B). Each slave node
  /// keeps the pairing it had unless the bodies at x + u show it wrong (DeformedPairing.cpp):
  /// a node without rows there lies inside the master by more than 1e-3 of the master face's
  /// size (newly inside), or a paired node's nearest master node at x + u is none of its rows'
  /// master nodes, or it has slid along its master by more than half the master face's size since
  /// its rows were built (moved on). Those nodes, and the ones paired so before, take the pairing at
  /// x + u: search, projections and mortar weights on the deformed coordinates, the gap still
  /// measured from the reference, d = -sum over the row's nodes of w nu . x (the deformed gap
  /// plus sum w nu . u), so that N u <= d holds for the total displacement as before. Null:
  /// the reference mesh decides.
  const std::vector<std::array<double, 3>>* pairingDisplacement = nullptr;
  const ConstraintMatrix* solvedPairing = nullptr;
  /// FETI/Displacement Conditions: how a component prescribed to 0 (every Dirichlet Node Set; a
  /// Boundary/<name> with value 0 that starts from the reference) is held. Eliminated ones get no
  /// rows; their dofs are listed in SubdomainBlock::eliminated and TotalFeti removes them from K_s
  /// (doc/measurements/curved_iterations.md: the u_y = 0 rows of a thin plane-strain slice).
  ZeroComponents zeroComponents = ZeroComponents::Multipliers;
};

/// One slave contact node r with its projection and frame (DESIGN.md conventions).
struct ContactNode {
  LO slaveNode = -1;                       ///< global mesh node id
  int interface = 0;                       ///< index into ConstraintSpec::interfaces
  LO masterNode = -1;                      ///< the master vertex with the largest weight
  std::vector<LO> masterNodes;             ///< the master nodes of the rows (ascending)
  std::vector<double> masterWeights;       ///< their weights (sum 1; barycentric or dual mortar)
  /// The slave node's weight in its rows (geometry::MortarRow::slaveWeight: 1 but at a 6-node
  /// slave triangle's mid-edge node), and the other slave nodes of the rows with their weights:
  /// the ends of that node's edge (geometry::MortarRow::slaveNodes); empty otherwise.
  double slaveWeight = 1.0;
  std::vector<LO> otherSlaveNodes;
  std::vector<double> otherSlaveWeights;
  /// (node, weight) of every node the rows couple: the slave node, the other slave nodes,
  /// the master nodes (-w); a row is this times its direction and scale.
  std::vector<std::pair<LO, double>> sides() const;
  bool mortar = false;                     ///< weights from the dual mortar integrals
  bool pairedDeformed = false;             ///< paired on the deformed bodies (ConstraintSpec::pairingDisplacement)
  /// The row's weighted displacement sum over sides() of w u at the state it was paired at
  /// (zero for the reference mesh): how far the node has slid since is measured from it.
  std::array<double, 3> pairedAt{0.0, 0.0, 0.0};
  std::array<double, 3> normal{}, t1{}, t2{};  ///< orthonormal frame, normal from slave to master
  double gap = 0.0;                        ///< d_r: signed distance along normal (< 0: initial overlap)
  /// The interface's Interference, already subtracted from `gap` (a load history ramps this part).
  double interference = 0.0;
  GO normalRow = -1;                       ///< row of N_r; the present tangential rows follow it
  std::array<bool, 2> hasTangential{false, false};  ///< T1_r, T2_r present
  double rowScale = 1.0;                   ///< the factor that made N_r unit norm (force = rowScale lambda)
  std::array<double, 2> tangentialScale{1.0, 1.0};  ///< the same for T1_r, T2_r
  /// T1_r (j = 0) or T2_r (j = 1) absent because the slave node and its nearest master node
  /// are held along t_j at different values: the relative tangential displacement there is
  /// prescribed, its friction (F_j times the normal force against the slip, between the slave
  /// and that master node) acts on held components and is added to the reactions and contact
  /// fields after the solve (stack::addPrescribedSlipFriction).
  std::array<bool, 2> slipPrescribed{false, false};
  /// Row of T1_r (j = 0) or T2_r (j = 1), or -1 when that row is absent.
  GO tangentialRow(int j) const {
    if (!hasTangential[j]) return -1;
    return normalRow + 1 + (j == 1 && hasTangential[0] ? 1 : 0);
  }
  int numRows() const { return 1 + hasTangential[0] + hasTangential[1]; }
  /// Row d of the node (0: N_r, 1: T1_r, 2: T2_r; -1 when absent), its direction and its scale
  /// (the force along the direction is scale x lambda).
  GO row(int d) const { return d == 0 ? normalRow : tangentialRow(d - 1); }
  const std::array<double, 3>& direction(int d) const { return d == 0 ? normal : d == 1 ? t1 : t2; }
  double scale(int d) const { return d == 0 ? rowScale : tangentialScale[d - 1]; }
};

/// B_s: the rows of B that touch subdomain s, as a sparse (rows x local dofs) matrix.
/// The force a support takes at a component eliminated from K_s (TotalFeti::eliminatedReactions).
struct EliminatedReaction {
  int subdomain;
  LO dof;        ///< local dof of the subdomain
  double force;
};

struct SubdomainBlock {
  std::vector<GO> rows;      ///< global row ids, ascending
  std::vector<LO> rowPtr;    ///< rows.size() + 1
  std::vector<LO> dof;       ///< local dof (3 * local node + component)
  std::vector<double> value;
  /// Local dofs prescribed to 0 and eliminated from K_s instead of given rows
  /// (ConstraintSpec::zeroComponents), ascending; owned subdomains only.
  std::vector<LO> eliminated;
};

/// What the contact search and the mortar integration found on one interface (every pair,
/// on every rank).
struct ContactInterfaceRows {
  std::string label;                 ///< ContactInterfaceSpec::label()
  std::string list;                  ///< ContactInterfaceSpec::list()
  bool tied = false;                 ///< ContactInterfaceSpec::tied (no gap in the normal rows' c)
  GO pairedSlaveNodes = 0;           ///< slave nodes with a master face within the search distance
  GO unpairedSlaveNodes = 0;         ///< slave nodes with no master face within the search distance
  /// Of the paired ones, those beyond the search distance: inside the master body (an
  /// interference), paired whatever the distance (geometry::MasterSurface::pairingProjection).
  GO pairedInside = 0;
  std::vector<LO> unpairedSample;    ///< the first few of them (global node ids), for messages
  GO sharedSlaveNodes = 0;           ///< paired here too but given to another interface (no rows here)
  double searchDistance = 0.0;       ///< its search distance, for messages
  double interference = 0.0;         ///< ContactInterfaceSpec::interference, for messages
  GO overlappingPairs = 0;           ///< contact nodes whose row has a negative initial gap (beyond round-off)
  double largestOverlap = 0.0;       ///< max(-gap) over them
  /// Mortar rows whose weighted gap was kept within the pointwise gap over the node's support
  /// (geometry::MortarRow::gapLimited): slave elements coarse for the master's curvature.
  GO limitedMortarGaps = 0;
  double largestGapLimit = 0.0;  ///< max |weighted gap - gap kept| over them
  /// The largest geometry::MortarRow::facetSag of its rows, and whether its gaps were measured on
  /// the smoothed surfaces (Contact/Surface Geometry = Smoothed, or Automatic where it chose
  /// them): a faceted interface whose master sags by a fair part of its initial overlaps is
  /// reported (stack/RunReport).
  double largestFacetSag = 0.0;
  bool smoothedSurfaces = false;
  /// Whether Surface Geometry = Automatic chose the smoothed surfaces (rows::facetsDominate).
  bool smoothedByChoice = false;
  /// Projections on curved master faces that did not settle (geometry/FaceProjection.hpp):
  /// of slave nodes in the search and of mortar quadrature points; the first slave node's
  /// described (empty if only quadrature points failed).
  long long unsettledProjections = 0;
  std::string firstUnsettled;
  /// A pairing on the deformed bodies (ConstraintSpec::pairingDisplacement): the slave nodes it
  /// paired anew there, newly inside the master or moved on past their master nodes.
  GO newlyInside = 0, movedOn = 0;
};

/// The part of a row's c that one displacement condition's values make (a Dirichlet row's
/// value, a contact row's known part from prescribed components): a load history scales it by
/// the condition's factor in each step (stack/LoadHistory). Zero parts are not listed.
struct PrescribedPart {
  GO row = 0;
  int condition = 0;  ///< index into ConstraintSpec::displacementConditions
  double value = 0.0;
};

struct ConstraintMatrix {
  GO numRows = 0;                    ///< n_d after removing redundant rows
  GO removedRedundantRows = 0;       ///< rows removed as redundant (n_d + this = paper's n_d)
  std::vector<RowKind> kind;         ///< per row
  std::vector<double> c;             ///< per row: scaled gap for N rows, 0 otherwise
  std::vector<GO> firstRowOfRank;    ///< numRanks + 1 entries
  /// Per row: its index in the numbering by the documented order alone, ranks ignored — the
  /// numbering on one rank (rowId[r] == r there), the same row for every number of ranks.
  /// The dual map's global ids: whatever depends on them (the power method's start vector)
  /// is the same on every rank count (issue 9).
  std::vector<GO> rowId;
  std::vector<PrescribedPart> prescribedParts;  ///< ascending rows (every row, on every rank)
  /// Pairs (i < j) of displacement conditions prescribing one component of a node to the same
  /// non-zero value: a load history must give them the same factors.
  std::vector<std::pair<int, int>> overlappingConditions;
  std::vector<ContactNode> contact;  ///< contact nodes, in row order
  /// Per mesh node, the axes a displacement condition holds it along while it stays free along
  /// another (bit c: axis c; geometry::HeldAxes): the contact normals at such nodes lie in those
  /// planes (geometry::inSymmetryPlanes). Empty without contact interfaces.
  std::vector<std::uint8_t> heldAxes;
  std::vector<ContactInterfaceRows> interfaces;  ///< per ConstraintSpec::interfaces, same order
  GO unpairedSlaveNodes() const;  ///< over every interface
  std::vector<SubdomainBlock> blocks;  ///< index = global subdomain
  GO count(RowKind k) const;
};

/// Builds B and c. Throws core::InputError naming the set / node on bad input (unknown
/// set, a component prescribed twice with different values, folded contact surfaces, an
/// interface within one body, a contact modelled twice).
/// With `keepForRank` >= 0 the blocks hold only what that rank needs, as after keepRankRows
/// (its own subdomains whole, of every other subdomain the rows it owns), without the whole
/// B ever being held (issue 11: at 4 000 subdomains the whole blocks were the largest item of
/// a rank's set-up); every other member is the same. Enough for requireRestrainedBodies with
/// a communicator, TotalFeti, the contact solver and the result gathering on that rank.
ConstraintMatrix buildConstraintMatrix(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                       const ConstraintSpec& spec, int numRanks, int keepForRank = -1);

/// What buildConstraintMatrix with `spec` (its pairingDisplacement and solvedPairing given) would
/// pair anew, over every interface: the slave nodes newly inside and moved on
/// (ContactInterfaceRows::newlyInside, movedOn), from the searches at x + u alone, no row built:
/// a check after each solve that costs a contact search where the pairing stands.
std::array<GO, 2> pairingChanges(const mesh::Mesh& mesh, const ConstraintSpec& spec);

/// Keeps of B what rank `rank` needs during the solve (issue 11): the blocks of its own
/// subdomains [firstOwned, endOwned) whole, and of every other subdomain only the rows this
/// rank owns (the entries g_{s,r} of G on its owned rows need them, TotalFeti). The row data
/// (kind, c, rowId, contact) stays. B is then fit for TotalFeti, the contact solver, the
/// result gathering and feti::requireRestrainedBodies with a communicator (each rank checks the
/// rows it owns) on `rank` only; not for requireRestrainedBodies without one (every row).
void keepRankRows(ConstraintMatrix& B, int rank, int firstOwned, int endOwned);

}  // namespace tribos::feti
