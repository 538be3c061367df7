// The gmsh reader trusts nothing in its input: each class of bad file is an InputError
// naming the file, the line or entity, and what is wrong; random damage to a good file
// never gives anything else (no crash, no std::bad_alloc, no other exception).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "TestPaths.hpp"
#include "TinyGmsh.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/mesh/GmshReader.hpp"

using namespace tribos;
using tribos::test::TinyGmsh;

namespace {
const std::string kSource = "tiny.msh";

/// parseGmsh(text) throws core::InputError starting with the source and containing each of `parts`.
void expectInputError(const std::string& text, std::initializer_list<std::string> parts) {
  try {
    mesh::parseGmsh(text, kSource, false);
    ADD_FAILURE() << "no error for:\n" << text.substr(0, 2000);
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(kSource + ": ", 0), 0u) << what;
    for (const auto& part : parts) EXPECT_NE(what.find(part), std::string::npos) << "expected \"" << part << "\" in: " << what;
  }
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}
}  // namespace

TEST(GmshReader, readsTinyMeshAndTheSampleMesh) {
  const auto mesh = mesh::parseGmsh(TinyGmsh().addCube().text(), kSource, false);
  EXPECT_EQ(mesh.numNodes(), 8);
  EXPECT_EQ(mesh.numElements(), 6);
  ASSERT_EQ(mesh.numBlocks(), 1);
  EXPECT_EQ(mesh.blocks[0].name, "cube");
  ASSERT_EQ(mesh.sideSets.size(), 1u);
  EXPECT_EQ(mesh.sideSets[0].name, "bottom");
  EXPECT_EQ(mesh.sideSets[0].elements.size(), 2u);
  const auto sample = mesh::readGmsh(tribos::test::sourceDir() + "/input/meshes/block_on_plate.msh", true);
  EXPECT_EQ(sample.numBlocks(), 2);
  EXPECT_EQ(sample.numElements(), 1386);
}

TEST(GmshReader, corruptCountsAreErrorsBeforeAnyAllocation) {
  const std::string good = TinyGmsh().addCube().text();
  // Once "cannot create std::vector larger than max_size()".
  expectInputError(replaced(good, "$Nodes\n1 8 1 8", "$Nodes\n1 99999999999 1 8"),
                   {"line 15 ($Nodes)", "the number of nodes is 99999999999, more than the rest of the file can hold"});
  expectInputError(replaced(good, "3 1 0 8", "3 1 0 4611686018427387904"), {"the number of nodes in a block"});
  expectInputError(replaced(good, "$Nodes\n1 8 1 8", "$Nodes\n1 -8 1 8"), {"the number of nodes is -8, outside 0.."});
  expectInputError(replaced(good, "$Nodes\n1 8 1 8", "$Nodes\n1 99999999999999999999 1 8"),
                   {"the number of nodes", "out of range"});
  expectInputError(replaced(good, "$Nodes\n1 8 1 8", "$Nodes\n1 9 1 8"),
                   {"the node blocks hold 8 nodes but the section header says 9"});
  expectInputError(replaced(good, "3 1 4 6", "3 1 4 5"), {"the element blocks hold 7 elements but the section header says 8"});
  expectInputError(replaced(good, "$PhysicalNames\n2", "$PhysicalNames\n2000000000"), {"the number of physical names"});
}

TEST(GmshReader, truncatedFilesAndSectionsAreErrorsNamingTheSection) {
  const std::string good = TinyGmsh().addCube().text();
  expectInputError(good.substr(0, good.find("$EndNodes") - 2),
                   {"($Nodes)", "the file ends where the z coordinate of node 8 should be (truncated?)"});
  expectInputError(good.substr(0, good.find("$EndElements") - 8), {"($Elements)", "a corrupt count or a truncated file"});
  expectInputError(good.substr(0, good.find("$EndElements")), {"the file ends where $EndElements should be"});
  expectInputError(good.substr(0, good.find("$Elements")), {"the file has no $Elements section"});
  expectInputError(replaced(good, "$EndNodes\n", ""), {"($Nodes)", "expected $EndNodes"});
  expectInputError(replaced(good, "$EndMeshFormat", "$EndMeshFormatX"), {"expected $EndMeshFormat"});
  expectInputError("", {"not a gmsh mesh"});
  expectInputError("hello\n", {"not a gmsh mesh"});
  expectInputError(replaced(good, "4.1 0 8", "2.2 0 8"), {"only gmsh 4.x ASCII", "version 2.2"});
  expectInputError(replaced(good, "4.1 0 8", "4.1 1 8"), {"binary"});
  expectInputError(replaced(good, "2 1 \"bottom\"", "2 1 \"bottom"), {"no closing double quote"});
  expectInputError(replaced(good, "$Entities\n0 0 1 1", "$Entities\n0 0 x 1"), {"must be an integer, not \"x\""});
  expectInputError(good + "$Comments\nnever closed\n", {"$EndComments to close the section"});
}

TEST(GmshReader, undefinedAndRepeatedNodesAreErrorsNamingTheElement) {
  TinyGmsh bad;
  bad.addCube().tets[0][2] = 99;
  expectInputError(bad.text(), {"element 3 of Physical Volume \"cube\" references node 99, which $Nodes does not define"});
  TinyGmsh badTriangle;
  badTriangle.addCube().bottom[1][0] = 42;
  expectInputError(badTriangle.text(), {"triangle 2 of Physical Surface \"bottom\" references node 42"});
  expectInputError(replaced(TinyGmsh().addCube().text(), "\n8\n", "\n7\n"), {"node 7 is defined twice"});
  expectInputError(replaced(TinyGmsh().addCube().text(), "\n8\n", "\n0\n"), {"a node tag is 0, outside 1.."});
}

TEST(GmshReader, nonFiniteCoordinatesAreErrorsNamingTheNode) {
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    TinyGmsh mesh;
    mesh.addCube().nodes[6][2] = bad;
    expectInputError(mesh.text(), {"($Nodes)", "the z coordinate of node 7 is not finite"});
  }
  expectInputError(replaced(TinyGmsh().addCube().text(), "\n1 1 1\n", "\n1 1 1e999\n"), {"coordinate", "out of range"});
}

TEST(GmshReader, degenerateAndOverlappingTetrahedraAreErrorsNamingThem) {
  TinyGmsh flat;
  flat.addCube().tets[2] = {1, 2, 3, 4};  // the four nodes of the face z = 0
  expectInputError(flat.text(), {"element 5 of Physical Volume \"cube\" is degenerate (volume 0"});
  TinyGmsh repeated;
  repeated.addCube().tets[5] = {1, 1, 7, 8};
  expectInputError(repeated.text(), {"element 8 of Physical Volume \"cube\" is degenerate"});
  // Two tets on the same side of their common face z = 0: one folded onto the other.
  TinyGmsh folded;
  folded.addCube();
  folded.tets = {{1, 2, 4, 5}, {1, 2, 4, 8}};
  folded.bottom.clear();
  expectInputError(folded.text(), {"lie on the same side of their common face", "folded over (inverted) or they overlap"});
  // A duplicated tet: its faces bound three elements.
  TinyGmsh twice;
  twice.addCube().tets.push_back(twice.tets[0]);
  expectInputError(twice.text(), {"elements", "a face bounds at most two"});
}

TEST(GmshReader, aBodyInSeveralPiecesIsAnErrorNamingItAndItsIslands) {
  TinyGmsh two;
  two.addCube(0.0).addCube(3.0);
  expectInputError(two.text(), {"element block \"cube\" is 2 separate pieces",
                                "6 elements from element 3, 6 elements from element 9", "its own Physical Volume"});
}

TEST(GmshReader, elementTypesTribosCannotUseAreErrors) {
  const std::string good = TinyGmsh().addCube().text();
  expectInputError(replaced(good, "3 1 4 6", "3 1 17 6"),
                   {"volume entity 1", "gmsh type 17", "20-node hexahedron", "Mesh.ElementOrder = 1", "6-node prisms"});
  expectInputError(replaced(good, "3 1 4 6", "3 1 7 6"), {"gmsh type 7", "pyramid"});
  expectInputError(replaced(good, "2 1 2 2", "2 1 16 2"), {"gmsh type 16", "20-node hexahedron", "does not read"});
  expectInputError(replaced(good, "2 1 2 2", "2 1 4 2"), {"do not have its dimension"});
}

// The deterministic cousin of the libFuzzer target (test/fuzz): random byte changes of a
// good file give a mesh or an InputError, nothing else. Under the sanitizers this also
// checks every read.
TEST(GmshReader, randomDamageGivesMeshesOrInputErrorsOnly) {
  const std::string good = TinyGmsh().addCube().addCube(1.0).text();
  std::mt19937 random(20240607);
  const std::string alphabet = "0123456789 .-+e$\n\"abcEndNodes";
  int errors = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string text = good;
    const int changes = 1 + static_cast<int>(random() % 4);
    for (int c = 0; c < changes; ++c) {
      const size_t at = random() % text.size();
      switch (random() % 3) {
        case 0: text[at] = alphabet[random() % alphabet.size()]; break;
        case 1: text.erase(at, 1 + random() % 8); break;
        default: text.insert(at, 1, alphabet[random() % alphabet.size()]);
      }
    }
    try {
      mesh::parseGmsh(text, kSource, trial % 2 == 0);
    } catch (const core::InputError&) {
      ++errors;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an InputError: " << e.what() << "\nfor:\n" << text;
      break;
    }
  }
  EXPECT_GT(errors, 1000);  // the damage is found, not silently read
}

TEST(GmshReader, everyPhysicalGroupOfASurfaceAndTheWholeOfAGroupOverSeveralBodies) {
  // A surface in two physical groups gives a side set (and node set) for each (issue 30: the
  // second was dropped).
  std::string text = TinyGmsh().addCube().text();
  const std::string names = "$PhysicalNames\n2\n2 1 \"bottom\"\n3 2 \"cube\"\n";
  const std::string surface = "1 0 0 0 1 1 0 1 1 0\n";
  ASSERT_NE(text.find(names), std::string::npos);
  ASSERT_NE(text.find(surface), std::string::npos);
  text.replace(text.find(names), names.size(), "$PhysicalNames\n3\n2 1 \"bottom\"\n2 3 \"base\"\n3 2 \"cube\"\n");
  text.replace(text.find(surface), surface.size(), "1 0 0 0 1 1 0 2 1 3 0\n");
  const auto mesh = mesh::parseGmsh(text, kSource, false);
  EXPECT_EQ(mesh.sideSet("bottom").elements.size(), 2u);
  EXPECT_EQ(mesh.sideSet("base").elements.size(), 2u);
  EXPECT_EQ(mesh.nodeSet("base").nodes, mesh.nodeSet("bottom").nodes);
  // A group on the faces of two bodies (the sample's "interface", split into one body each):
  // a set per body and the whole group, which a contact interface may name as one surface.
  const auto sample = mesh::readGmsh(tribos::test::sourceDir() + "/input/meshes/block_on_plate.msh", true);
  const auto& plate = sample.sideSet("interface_plate");
  const auto& block = sample.sideSet("interface_block");
  const auto& whole = sample.sideSet("interface");
  EXPECT_EQ(whole.elements.size(), plate.elements.size() + block.elements.size());
  EXPECT_EQ(sample.nodeSet("interface").nodes.size(),
            sample.nodeSet("interface_plate").nodes.size() + sample.nodeSet("interface_block").nodes.size());
}
