// Writes one bad mesh per class of bad input into a directory, for the CTests
// integration.badMesh.* (tribos on Exodus files, 1 and 2 ranks) and integration.msh2exo.*
// (gmsh files): each must end with exit status 2, a message naming the culprit, and no
// output file. Also a good mesh of the same scene, which must run.
//   write_bad_inputs DIR
// The Exodus meshes are two stacked unit boxes of 2 x 2 x 1 cells (24 tets each): blocks
// "lower" and "upper" with the face sets of BoxMesh.hpp ("lower_z0", "upper_z1", ...).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>

#include "BoxMesh.hpp"
#include "TinyGmsh.hpp"
#include "tribos/mesh/ExodusIO.hpp"

namespace {
using namespace tribos;
using tribos::test::boxMesh;
using tribos::test::mergeMeshes;
using tribos::test::TinyGmsh;

mesh::Mesh stackedBoxes() {
  return mergeMeshes(boxMesh({0, 0, 0}, {1, 1, 1}, {2, 2, 1}, "lower"), boxMesh({0, 0, 1}, {1, 1, 1}, {2, 2, 1}, "upper"));
}

void writeExodusFiles(const std::filesystem::path& dir) {
  auto write = [&](const std::string& name, const mesh::Mesh& m) { mesh::writeExodus((dir / (name + ".exo")).string(), m); };
  write("good", stackedBoxes());

  mesh::Mesh inverted = stackedBoxes();
  std::swap(inverted.elements.mutableNodes(4)[1], inverted.elements.mutableNodes(4)[2]);
  write("invertedElement", inverted);  // element 5 of block "lower"

  mesh::Mesh degenerate = stackedBoxes();
  degenerate.elements.mutableNodes(30)[3] = degenerate.elements.mutableNodes(30)[2];
  write("degenerateElement", degenerate);  // element 31 of block "upper"

  mesh::Mesh nan = stackedBoxes();
  nan.coords[3][1] = std::numeric_limits<double>::quiet_NaN();
  write("nonFiniteCoordinate", nan);  // node 4

  mesh::Mesh outOfRange = stackedBoxes();
  outOfRange.elements.mutableNodes(2)[1] = 998;
  write("nodeOutOfRange", outOfRange);  // element 3 references node 999

  // "lower" = the lower box and a third box far away: one block in two pieces.
  mesh::Mesh islands = mergeMeshes(mergeMeshes(boxMesh({0, 0, 0}, {1, 1, 1}, {2, 2, 1}, "lower"),
                                               boxMesh({5, 0, 0}, {1, 1, 1}, {2, 2, 1}, "far")),
                                   boxMesh({0, 0, 1}, {1, 1, 1}, {2, 2, 1}, "upper"));
  islands.blocks = {{"lower", 1, 0, 48}, {"upper", 2, 48, 24}};
  write("bodyInTwoPieces", islands);

  mesh::Mesh emptyBlock = stackedBoxes();
  emptyBlock.blocks.insert(emptyBlock.blocks.begin() + 1, {"hollow", 7, 24, 0});
  write("emptyElementBlock", emptyBlock);

  mesh::Mesh emptySets = stackedBoxes();
  emptySets.nodeSets.push_back({"nothing", 99, {}});
  emptySets.sideSets.push_back({"nowhere", 99, {}, {}});
  write("emptyNodeSetInUse", emptySets);
  write("emptySideSetInUse", emptySets);

  // The first half of a good file.
  std::ifstream in(dir / "good.exo", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "truncatedFile.exo", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
}

void writeGmshFiles(const std::filesystem::path& dir) {
  auto write = [&](const std::string& name, const std::string& text) { std::ofstream(dir / (name + ".msh")) << text; };
  const std::string good = TinyGmsh().addCube().text();
  write("good", good);
  std::string corrupt = good;
  corrupt.replace(corrupt.find("$Nodes\n1 8 1 8"), 14, "$Nodes\n1 99999999999 1 8");
  write("corruptCount", corrupt);
  write("truncatedFile", good.substr(0, good.find("$EndNodes") - 2));  // the last coordinate cut off
  TinyGmsh undefinedNode;
  undefinedNode.addCube().tets[0][2] = 99;
  write("undefinedNode", undefinedNode.text());
  TinyGmsh nan;
  nan.addCube().nodes[6][2] = std::numeric_limits<double>::quiet_NaN();
  write("nonFiniteCoordinate", nan.text());
  TinyGmsh flat;
  flat.addCube().tets[2] = {1, 2, 3, 4};
  write("degenerateElement", flat.text());
  write("bodyInTwoPieces", TinyGmsh().addCube(0.0).addCube(3.0).text());
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: write_bad_inputs DIR\n";
    return 2;
  }
  const std::filesystem::path dir(argv[1]);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  writeExodusFiles(dir);
  writeGmshFiles(dir);
  return 0;
}
