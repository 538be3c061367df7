// The constraint matrix B (ALGORITHMS.md 2): Table 1's dual dimensions, orthonormal rows,
// ownership, contact frames and gaps.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "tribos/core/Errors.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

namespace {
struct Cell {
  int subdomains, hOverH;
  long long nd;  // the paper's n_d
};
// This test's own copy of Table 1's n_d. The last cell prints 125047 in the paper; counted
// by the same rule (3m + m_e + m_d) it is 125178 (DESIGN.md), which is what we assert.
const Cell kTable1[] = {{4, 2, 153},      {4, 3, 276},      {4, 4, 435},      {4, 5, 630},      {32, 2, 1527},
                        {32, 3, 2889},    {32, 4, 4683},    {32, 5, 6909},    {108, 2, 5493},   {108, 3, 10506},
                        {108, 4, 17139},  {108, 5, 25392},  {256, 2, 13419},  {256, 3, 25791},  {256, 4, 42195},
                        {256, 5, 62631},  {500, 2, 26673},  {500, 3, 51408},  {500, 4, 84243},  {500, 5, 125178}};

mesh::TwoBricksSpec specFor(int subdomains, int hOverH) {
  int ny = 1;
  while (2 * ny * ny * ny != subdomains / 2) ++ny;
  return {{2 * ny, ny, ny}, hOverH};
}

feti::ConstraintSpec paperSpec(bool tangential = true) {
  feti::ConstraintSpec spec;
  spec.dirichletNodeSets = {"dirichlet_aluminium", "dirichlet_steel"};
  spec.slaveSideSet = "contact_aluminium";
  spec.masterSideSet = "contact_steel";
  spec.tangentialRows = tangential;
  return spec;
}

struct Built {
  mesh::Mesh mesh;
  mesh::Decomposition d;
  feti::ConstraintMatrix B;
};

Built build(const mesh::TwoBricksSpec& spec, const feti::ConstraintSpec& cs, int ranks = 1, int metisParts = 0) {
  Built b;
  b.mesh = mesh::generateTwoBricks(spec);
  b.d = mesh::buildDecomposition(b.mesh, metisParts ? mesh::metisPartition(b.mesh, metisParts)
                                                    : mesh::structuredPartition(b.mesh, spec));
  b.B = feti::buildConstraintMatrix(b.mesh, b.d, cs, ranks);
  return b;
}

// Row r as a map (subdomain, dof) -> value.
std::vector<std::map<std::pair<int, LO>, double>> rowsOf(const feti::ConstraintMatrix& B) {
  std::vector<std::map<std::pair<int, LO>, double>> rows(B.numRows);
  for (size_t s = 0; s < B.blocks.size(); ++s) {
    const auto& blk = B.blocks[s];
    for (size_t i = 0; i < blk.rows.size(); ++i)
      for (LO k = blk.rowPtr[i]; k < blk.rowPtr[i + 1]; ++k) rows[blk.rows[i]][{static_cast<int>(s), blk.dof[k]}] = blk.value[k];
  }
  return rows;
}
}  // namespace

TEST(ConstraintMatrix, dualDimensionsMatchTable1) {
  for (const Cell& cell : kTable1) {
    SCOPED_TRACE(std::to_string(cell.subdomains) + " / " + std::to_string(cell.hOverH));
    const auto b = build(specFor(cell.subdomains, cell.hOverH), paperSpec());
    EXPECT_EQ(b.B.numRows + b.B.removedRedundantRows, cell.nd);
    // Removed: the 3 contact rows of every contact node on the clamped edge x = 0.
    const auto spec = specFor(cell.subdomains, cell.hOverH);
    EXPECT_EQ(b.B.removedRedundantRows, 3LL * (spec.subdomainsPerBrick.ny * cell.hOverH + 1));
    EXPECT_EQ(b.B.count(feti::RowKind::ContactNormal), static_cast<GO>(b.B.contact.size()));
  }
}

TEST(ConstraintMatrix, rowsAreOrthonormal) {
  for (bool tangential : {true, false})
    for (const auto& [spec, parts] : std::vector<std::pair<mesh::TwoBricksSpec, int>>{
             {{{2, 1, 1}, 2}, 0}, {{{2, 1, 1}, 3}, 0}, {{{4, 2, 2}, 2}, 0}, {{{2, 1, 1}, 3}, 7}}) {
      const auto b = build(spec, paperSpec(tangential), 1, parts);
      const auto rows = rowsOf(b.B);
      // B B^T = I: rows touching a common (subdomain, dof) are orthogonal, every row unit norm.
      std::map<std::pair<int, LO>, std::vector<GO>> byColumn;
      for (GO r = 0; r < b.B.numRows; ++r)
        for (const auto& [col, v] : rows[r]) byColumn[col].push_back(r);
      std::map<std::pair<GO, GO>, double> product;
      for (const auto& [col, list] : byColumn)
        for (GO r : list)
          for (GO q : list) product[{r, q}] += rows[r].at(col) * rows[q].at(col);
      for (GO r = 0; r < b.B.numRows; ++r) EXPECT_NEAR(product[std::make_pair(r, r)], 1.0, 1e-14);
      for (const auto& [rq, v] : product)
        if (rq.first != rq.second) EXPECT_NEAR(v, 0.0, 1e-14);
    }
}

TEST(ConstraintMatrix, ownershipIsContiguousAndTheRowsDoNotDependOnTheRankCount) {
  const mesh::TwoBricksSpec spec{{4, 2, 2}, 2};
  std::multiset<std::vector<std::tuple<int, LO, long long>>> reference;
  for (int ranks : {1, 2, 4}) {
    const auto b = build(spec, paperSpec(), ranks);
    ASSERT_EQ(b.B.firstRowOfRank.size(), static_cast<size_t>(ranks + 1));
    EXPECT_EQ(b.B.firstRowOfRank.front(), 0);
    EXPECT_EQ(b.B.firstRowOfRank.back(), b.B.numRows);
    const auto rows = rowsOf(b.B);
    std::multiset<std::vector<std::tuple<int, LO, long long>>> set;
    for (int p = 0; p < ranks; ++p)
      for (GO r = b.B.firstRowOfRank[p]; r < b.B.firstRowOfRank[p + 1]; ++r) {
        bool touchesOwner = false;
        std::vector<std::tuple<int, LO, long long>> entries;
        for (const auto& [col, v] : rows[r]) {
          touchesOwner = touchesOwner || mesh::ownerRank(col.first, b.d.numSubdomains(), ranks) == p;
          entries.push_back({col.first, col.second, std::llround(v * 1e12)});
        }
        EXPECT_TRUE(touchesOwner) << "row " << r;
        set.insert(entries);
      }
    if (reference.empty()) reference = set;
    EXPECT_EQ(set, reference);
  }
}

TEST(ConstraintMatrix, contactFramesAndGaps) {
  const auto b = build({{2, 1, 1}, 2}, paperSpec());
  for (const auto& c : b.B.contact) {
    EXPECT_NEAR(c.normal[2], 1.0, 1e-14);  // slave (aluminium, below) towards master
    EXPECT_NEAR(c.t1[0], 1.0, 1e-14);
    EXPECT_NEAR(c.t2[1], 1.0, 1e-14);      // right-handed: t2 = nu x t1
    EXPECT_EQ(c.gap, 0.0);
    EXPECT_EQ(b.B.c[c.normalRow], 0.0);
  }
  // A genuine gap: lift the steel brick by 0.5.
  Built lifted;
  lifted.mesh = mesh::generateTwoBricks({{2, 1, 1}, 2});
  for (LO n = lifted.mesh.numNodes() / 2; n < lifted.mesh.numNodes(); ++n) lifted.mesh.coords[n][2] += 0.5;
  lifted.d = mesh::buildDecomposition(lifted.mesh, mesh::structuredPartition(lifted.mesh, {{2, 1, 1}, 2}));
  auto spec = paperSpec();
  spec.searchDistance = 0.6;
  const auto B = feti::buildConstraintMatrix(lifted.mesh, lifted.d, spec, 1);
  ASSERT_FALSE(B.contact.empty());
  for (const auto& c : B.contact) {
    EXPECT_NEAR(c.normal[2], 1.0, 1e-14);
    EXPECT_NEAR(c.gap, 0.5, 1e-14);
    EXPECT_NEAR(B.c[c.normalRow], c.rowScale * 0.5, 1e-14);
  }
  spec.searchDistance = 0.4;  // no partner: an error naming the node
  try {
    feti::buildConstraintMatrix(lifted.mesh, lifted.d, spec, 1);
    ADD_FAILURE() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("slave node"), std::string::npos) << e.what();
  }
}

TEST(ConstraintMatrix, gluingAndContactRowsVanishOnARigidTranslation) {
  const auto b = build({{4, 2, 2}, 2}, paperSpec());
  const auto rows = rowsOf(b.B);
  for (GO r = 0; r < b.B.numRows; ++r) {
    if (b.B.kind[r] == feti::RowKind::Dirichlet) continue;
    double sum = 0.0;
    for (const auto& [col, v] : rows[r]) sum += v * (col.second % 3 == 0 ? 1.0 : (col.second % 3 == 1 ? 2.0 : -3.0));
    EXPECT_NEAR(sum, 0.0, 1e-13) << "row " << r;
  }
}
