/// \file ConstraintMatrix.cpp
/// B = [N; T1; T2; B_e; B_d] and c (paper Sections 3-4, ALGORITHMS.md 2). Every row is
/// built once as a list of (subdomain, local dof, value) entries, given its owner rank and
/// a sort key, then all rows are numbered by (owner, key) and scattered into the
/// per-subdomain blocks. Cost: O(#copies + #rows log #rows) plus the contact search
/// (geometry/ContactSearch.hpp: O(#slave log #master faces)).
#include "tribos/feti/ConstraintMatrix.hpp"

#include "ConstraintRows.hpp"
#include "EliminatedComponents.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"

namespace tribos::feti {

std::vector<std::pair<LO, double>> ContactNode::sides() const {
  std::vector<std::pair<LO, double>> out{{slaveNode, slaveWeight}};
  for (size_t k = 0; k < otherSlaveNodes.size(); ++k) out.push_back({otherSlaveNodes[k], otherSlaveWeights[k]});
  for (size_t v = 0; v < masterNodes.size(); ++v) out.push_back({masterNodes[v], -masterWeights[v]});
  return out;
}

GO ConstraintMatrix::count(RowKind k) const { return std::count(kind.begin(), kind.end(), k); }

GO ConstraintMatrix::unpairedSlaveNodes() const {
  GO n = 0;
  for (const auto& i : interfaces) n += i.unpairedSlaveNodes;
  return n;
}

namespace rows {

NodeCopies nodeCopies(const mesh::Decomposition& decomposition, LO numNodes) {
  NodeCopies c;
  c.ptr.assign(numNodes + 1, 0);
  for (const auto& s : decomposition.subdomains)
    for (LO n : s.nodes) c.ptr[n + 1]++;
  for (LO n = 0; n < numNodes; ++n) c.ptr[n + 1] += c.ptr[n];
  c.copies.resize(c.ptr[numNodes]);
  std::vector<LO> fill(c.ptr.begin(), c.ptr.end() - 1);
  for (int s = 0; s < decomposition.numSubdomains(); ++s) {
    const auto& nodes = decomposition.subdomains[s].nodes;
    for (LO k = 0; k < static_cast<LO>(nodes.size()); ++k) c.copies[fill[nodes[k]]++] = {s, k};
  }
  return c;
}

Prescribed prescribedComponents(const mesh::Mesh& mesh, const ConstraintSpec& spec) {
  std::vector<DisplacementCondition> conditions;
  for (const auto& name : spec.dirichletNodeSets)
    conditions.push_back({"Dirichlet Node Sets (" + name + ")", name, {true, true, true}, {0.0, 0.0, 0.0}});
  conditions.insert(conditions.end(), spec.displacementConditions.begin(), spec.displacementConditions.end());
  const size_t n3 = 3 * static_cast<size_t>(mesh.numNodes());
  Prescribed p{std::vector<char>(n3, 0), std::vector<double>(n3, 0.0), std::vector<double>(n3, 0.0),
               std::vector<int>(n3, -1)};
  const int firstCondition = static_cast<int>(spec.dirichletNodeSets.size());
  std::vector<int> by(n3, -1);
  for (size_t k = 0; k < conditions.size(); ++k) {
    const auto& condition = conditions[k];
    const int j = static_cast<int>(k) - firstCondition;  // its index in spec.displacementConditions
    if (j >= 0 && static_cast<size_t>(j) < spec.presentConditions.size() && !spec.presentConditions[j]) continue;
    const auto* base = j >= 0 && static_cast<size_t>(j) < spec.conditionBase.size() ? spec.conditionBase[j] : nullptr;
    for (double v : condition.value)
      core::requireInput(std::isfinite(v), "Boundary/" + condition.name + ": Displacement is not finite");
    for (LO n : mesh.nodeSet(condition.nodeSet).nodes)
      for (int c = 0; c < 3; ++c) {
        if (!condition.components[c]) continue;
        const size_t i = 3 * static_cast<size_t>(n) + c;
        if (by[i] >= 0 && p.value[i] != condition.value[c])
          throw core::InputError("Boundary: node " + std::to_string(n + 1) + " at " + str(mesh.coords[n]) + " gets u_" +
                                 "xyz"[c] + " = " + str(p.value[i]) + " from " + conditions[by[i]].name + " and " +
                                 str(condition.value[c]) + " from " + condition.name);
        const int shared = p.condition[i];
        if (shared >= 0 && condition.value[c] != 0.0 && shared != static_cast<int>(k) - firstCondition)
          p.overlapping.insert({shared, static_cast<int>(k) - firstCondition});
        p.fixed[i] = 1;
        p.value[i] = condition.value[c];
        p.base[i] = base ? (*base)[static_cast<size_t>(n)][c] : 0.0;
        by[i] = static_cast<int>(k);
        p.condition[i] = static_cast<int>(k) - firstCondition;
      }
  }
  return p;
}
}  // namespace rows

using namespace rows;

namespace {
/// A component prescribed to 0 from the reference (no base): what elimination may take out of K_s.
bool zeroFromTheReference(const Prescribed& p, size_t dof) {
  return p.fixed[dof] && p.value[dof] == 0.0 && p.base[dof] == 0.0;
}
/// Whether `dof` leaves K_s under `rule` (ZeroComponents): Automatic keeps the rows of a node
/// held in all three components. Measured (doc/measurements/curved_iterations.md): Table 1's
/// bricks, clamped on whole faces, take the rows' counts this way (eliminated, up to 4x more);
/// the plane-strain slices and symmetry planes keep what elimination gains.
bool eliminable(const Prescribed& p, size_t dof, ZeroComponents rule) {
  if (rule == ZeroComponents::Multipliers || !zeroFromTheReference(p, dof)) return false;
  if (rule == ZeroComponents::Eliminated) return true;
  const size_t first = dof - dof % 3;
  return !(zeroFromTheReference(p, first) && zeroFromTheReference(p, first + 1) &&
           zeroFromTheReference(p, first + 2));
}

/// Per subdomain, whether it eliminates its zero components (ConstraintSpec::zeroComponents):
/// not where they are few (under kFewComponents of its dofs) and hold a rigid mode only weakly
/// (weakestRestraint under kWeakRestraint): eliminated there, K_s keeps a nearly rigid motion
/// held at a small patch, whose compliance enters F. Measured (doc/measurements/curved_iterations.md):
/// a subdomain of the Cattaneo sphere touching its symmetry plane at 35 of its 1 233 dofs holds
/// a mode at 5.3e-3 and made ||PFP|| 17 times larger eliminated; the plane-strain slices' subdomains
/// hold theirs at 3.7e-3 and more but with 70 % of their dofs, and eliminated are what makes F
/// well conditioned. Neither number alone separates them.
constexpr double kWeakRestraint = 1e-2;
constexpr double kFewComponents = 0.05;

std::vector<char> subdomainsThatEliminate(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                          const Prescribed& prescribed, ZeroComponents rule) {
  std::vector<char> out(decomposition.subdomains.size(), 0);
  for (size_t s = 0; s < out.size(); ++s) {
    const auto& nodes = decomposition.subdomains[s].nodes;
    std::vector<std::array<double, 3>> coords;
    std::vector<LO> dofs;
    for (size_t k = 0; k < nodes.size(); ++k) {
      coords.push_back(mesh.coords[nodes[k]]);
      for (int c = 0; c < 3; ++c)
        if (eliminable(prescribed, 3 * static_cast<size_t>(nodes[k]) + c, rule)) dofs.push_back(static_cast<LO>(3 * k + c));
    }
    if (dofs.empty()) continue;
    const bool few = static_cast<double>(dofs.size()) < kFewComponents * 3.0 * static_cast<double>(nodes.size());
    out[s] = !(few && weakestRestraint(coords, dofs) < kWeakRestraint);
  }
  return out;
}

/// (3) Gluing rows (Helmert basis of the differences of the copies) per free component, and
/// displacement rows per prescribed component.
void addGluingAndDirichletRows(LO numNodes, const RowContext& ctx, RowList& list) {
  for (LO n = 0; n < numNodes; ++n) {
    const LO k = ctx.copies.count(n);
    // Copies ascend by subdomain, so copy 1 is the lowest one: every gluing row at this
    // node touches it and has the same owner.
    const int owner = k > 1 ? mesh::ownerRank(ctx.copies.of(n, 0).subdomain, ctx.numSubdomains, ctx.numRanks) : 0;
    for (int c = 0; c < 3; ++c) {
      const size_t dof = 3 * static_cast<size_t>(n) + c;
      if (ctx.prescribed.fixed[dof]) {
        // Every copy prescribed, no gluing rows: the paper's count (k-1 gluing + 1
        // Dirichlet per component) and B stays orthonormal (ALGORITHMS.md 2). A copy in a
        // subdomain that eliminates its zero components has none (TotalFeti takes it out of K_s).
        for (LO j = 0; j < k; ++j) {
          const Copy& cp = ctx.copies.of(n, j);
          if (!ctx.eliminateIn.empty() && ctx.eliminateIn[cp.subdomain] && eliminable(ctx.prescribed, dof, ctx.zeroComponents)) {
            list.eliminated.push_back({cp.subdomain, 3 * cp.localNode + c});
            continue;
          }
          Row row = list.begin();
          row.kind = RowKind::Dirichlet;
          list.append({cp.subdomain, 3 * cp.localNode + c, 1.0});
          row.c = ctx.prescribed.base[3 * n + c] + ctx.prescribed.value[3 * n + c];
          list.addPart(row, ctx.prescribed.condition[3 * n + c], ctx.prescribed.value[3 * n + c]);
          row.key = {2, n, j, c};
          row.owner = mesh::ownerRank(cp.subdomain, ctx.numSubdomains, ctx.numRanks);
          list.add(row);
        }
        continue;
      }
      for (LO j = 1; j < k; ++j) {
        // Row j: copy j+1 against the mean of copies 1..j, i.e. coefficients -1/j and +1,
        // normalised by 1/sqrt(1 + 1/j); orthonormal and orthogonal to the mean.
        Row row = list.begin();
        row.kind = RowKind::Gluing;
        const double scale = 1.0 / std::sqrt(1.0 + 1.0 / j);
        for (LO i = 0; i < j; ++i) {
          const Copy& cp = ctx.copies.of(n, i);
          list.append({cp.subdomain, 3 * cp.localNode + c, -scale / j});
        }
        const Copy& cp = ctx.copies.of(n, j);
        list.append({cp.subdomain, 3 * cp.localNode + c, scale});
        row.key = {1, n, c, j};
        row.owner = owner;
        list.add(row);
      }
    }
  }
}

/// (4) Numbers the rows by (owner rank, key) (rank p owns a contiguous range), scatters them
/// into the per-subdomain blocks (of `keepForRank`'s subdomains and own rows only when >= 0),
/// and gives every row its id in the numbering by key alone.
void numberRows(RowList& list, int numSubdomains, int numRanks, int keepForRank, ConstraintMatrix& B) {
  std::vector<Row>& rows = list.rows;
  std::vector<size_t> order(rows.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::tie(rows[a].owner, rows[a].key) < std::tie(rows[b].owner, rows[b].key);
  });
  B.numRows = static_cast<GO>(rows.size());
  B.kind.resize(rows.size());
  B.c.resize(rows.size());
  B.firstRowOfRank.assign(numRanks + 1, 0);
  B.blocks.assign(numSubdomains, SubdomainBlock{});
  for (auto& blk : B.blocks) blk.rowPtr.push_back(0);
  // keepForRank: a row's entries in a subdomain of another rank are kept only when the row is
  // the rank's own (keepRankRows' rule).
  const bool keepAll = keepForRank < 0;
  const int firstKept = keepAll ? 0 : mesh::firstSubdomain(keepForRank, numSubdomains, numRanks);
  const int endKept = keepAll ? numSubdomains : mesh::firstSubdomain(keepForRank + 1, numSubdomains, numRanks);
  for (size_t r = 0; r < order.size(); ++r) {
    Row& row = rows[order[r]];
    B.kind[r] = row.kind;
    B.c[r] = row.c;
    B.firstRowOfRank[row.owner + 1]++;
    if (row.contact >= 0) B.contact[row.contact].normalRow = static_cast<GO>(r);
    for (int k = 0; k < row.numParts; ++k) {
      const auto& [condition, value] = list.parts[row.firstPart + static_cast<size_t>(k)];
      B.prescribedParts.push_back({static_cast<GO>(r), condition, value});
    }
    // Scatter into the blocks: rows arrive in ascending order, entries of one row sorted
    // by (subdomain, dof).
    Entry* entries = list.entriesOf(row);
    const size_t count = static_cast<size_t>(row.numEntries);
    std::sort(entries, entries + count,
              [](const Entry& a, const Entry& b) { return std::tie(a.subdomain, a.dof) < std::tie(b.subdomain, b.dof); });
    const bool ownRow = keepAll || row.owner == keepForRank;
    for (size_t e = 0; e < count;) {
      const int s = entries[e].subdomain;
      if (!ownRow && (s < firstKept || s >= endKept)) {
        while (e < count && entries[e].subdomain == s) ++e;
        continue;
      }
      SubdomainBlock& blk = B.blocks[s];
      blk.rows.push_back(static_cast<GO>(r));
      for (; e < count && entries[e].subdomain == s; ++e) {
        blk.dof.push_back(entries[e].dof);
        blk.value.push_back(entries[e].value);
      }
      blk.rowPtr.push_back(static_cast<LO>(blk.dof.size()));
    }
  }
  for (int p = 0; p < numRanks; ++p) B.firstRowOfRank[p + 1] += B.firstRowOfRank[p];
  for (const auto& [s, dof] : list.eliminated)
    if (keepAll || (s >= firstKept && s < endKept)) B.blocks[s].eliminated.push_back(dof);
  for (auto& blk : B.blocks) std::sort(blk.eliminated.begin(), blk.eliminated.end());
  // Row ids: the position in the order by key alone (keys are unique), i.e. the numbering
  // that one rank uses.
  std::vector<size_t> byKey(order);
  std::sort(byKey.begin(), byKey.end(), [&](size_t a, size_t b) { return rows[a].key < rows[b].key; });
  std::vector<GO> numberOf(rows.size());
  for (size_t r = 0; r < order.size(); ++r) numberOf[order[r]] = static_cast<GO>(r);
  B.rowId.resize(rows.size());
  for (size_t k = 0; k < byKey.size(); ++k) B.rowId[numberOf[byKey[k]]] = static_cast<GO>(k);
  // Contact nodes in row order (the header's contract).
  std::sort(B.contact.begin(), B.contact.end(),
            [](const ContactNode& a, const ContactNode& b) { return a.normalRow < b.normalRow; });
}
}  // namespace

ConstraintMatrix buildConstraintMatrix(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                       const ConstraintSpec& spec, int numRanks, int keepForRank) {
  core::requireInput(numRanks >= 1, "buildConstraintMatrix: numRanks must be >= 1, got " + std::to_string(numRanks));
  core::requireInput(keepForRank < numRanks, "buildConstraintMatrix: keepForRank " + std::to_string(keepForRank) +
                                                 " is not a rank of " + std::to_string(numRanks));
  // (1) Copies of every global node, in ascending subdomain order (ALGORITHMS.md 2).
  const NodeCopies copies = nodeCopies(decomposition, mesh.numNodes());
  const Prescribed prescribed = prescribedComponents(mesh, spec);
  RowContext ctx{copies, prescribed, decomposition.numSubdomains(), numRanks, spec.zeroComponents};
  if (spec.zeroComponents != ZeroComponents::Multipliers)
    ctx.eliminateIn = subdomainsThatEliminate(mesh, decomposition, prescribed, spec.zeroComponents);
  RowList list;
  ConstraintMatrix B;
  B.overlappingConditions.assign(prescribed.overlapping.begin(), prescribed.overlapping.end());
  addAllContactRows(mesh, spec, ctx, list, B);                               // (2)
  addGluingAndDirichletRows(mesh.numNodes(), ctx, list);                    // (3)
  numberRows(list, decomposition.numSubdomains(), numRanks, keepForRank, B);  // (4)
  return B;
}

void keepRankRows(ConstraintMatrix& B, int rank, int firstOwned, int endOwned) {
  const GO first = B.firstRowOfRank.at(rank), end = B.firstRowOfRank.at(rank + 1);
  for (int s = 0; s < static_cast<int>(B.blocks.size()); ++s) {
    if (s >= firstOwned && s < endOwned) continue;
    const SubdomainBlock& full = B.blocks[s];
    SubdomainBlock kept;
    kept.rowPtr.push_back(0);
    // Rows ascend: the owned ones are one contiguous run.
    const auto lo = std::lower_bound(full.rows.begin(), full.rows.end(), first);
    const auto hi = std::lower_bound(lo, full.rows.end(), end);
    for (auto it = lo; it != hi; ++it) {
      const size_t i = static_cast<size_t>(it - full.rows.begin());
      kept.rows.push_back(*it);
      kept.dof.insert(kept.dof.end(), full.dof.begin() + full.rowPtr[i], full.dof.begin() + full.rowPtr[i + 1]);
      kept.value.insert(kept.value.end(), full.value.begin() + full.rowPtr[i], full.value.begin() + full.rowPtr[i + 1]);
      kept.rowPtr.push_back(static_cast<LO>(kept.dof.size()));
    }
    kept.rows.shrink_to_fit();
    kept.rowPtr.shrink_to_fit();
    kept.dof.shrink_to_fit();
    kept.value.shrink_to_fit();
    B.blocks[s] = std::move(kept);  // a foreign subdomain's eliminated dofs are not needed
  }
}

}  // namespace tribos::feti
