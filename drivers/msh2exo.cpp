// tribos-msh2exo: gmsh 4.1 ASCII mesh -> Exodus II for tribos (Physical Volumes become element
// blocks, Physical Surfaces side sets and node sets).
//   tribos-msh2exo [--split-bodies] mesh.msh mesh.exo
// --split-bodies duplicates the nodes that two bodies share, so a conforming interface meshed
// once becomes a node-to-node contact pair ("<surface>_<body>" side sets on each side).
// Exit status: 0 written, 2 bad input (the message names the file), 4 the mesh could not be
// written (an I/O failure), 1 internal error.
#include <iostream>
#include <string>

#include "tribos/core/Errors.hpp"
#include "tribos/core/InputFiles.hpp"
#include "tribos/core/OutputFile.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/mesh/GmshReader.hpp"

int main(int argc, char** argv) {
  bool split = false;
  std::string in, out;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--split-bodies") split = true;
    else if (in.empty()) in = arg;
    else if (out.empty()) out = arg;
    else {
      std::cerr << "usage: tribos-msh2exo [--split-bodies] mesh.msh mesh.exo\n";
      return 2;
    }
  }
  if (out.empty()) {
    std::cerr << "usage: tribos-msh2exo [--split-bodies] mesh.msh mesh.exo\n";
    return 2;
  }
  // Written under a temporary name unique to this run and renamed when complete
  // (core/OutputFile.hpp): a failed conversion leaves no file that looks like a mesh, nor
  // clobbers an older one; the input itself is never the output.
  try {
    tribos::core::requireRegularInputFile(in, "the gmsh file");
    if (tribos::core::sameFile(in, out))
      throw tribos::core::InputError(out + ": is the input mesh; writing it would destroy it: give another name");
    tribos::core::OutputFile file(out, "the Exodus mesh", false);
    const auto mesh = tribos::mesh::readGmsh(in, split);
    file.writeWith([&](const std::string& path) { tribos::mesh::writeExodus(path, mesh); });
    std::cout << "tribos-msh2exo: " << in << " -> " << out << ": " << mesh.numNodes() << " nodes, "
              << mesh.numElements() << " elements, " << mesh.numBlocks() << " bodies, " << mesh.sideSets.size()
              << " side sets\n";
    for (const auto& s : mesh.sideSets) std::cout << "  side set \"" << s.name << "\": " << s.elements.size() << " faces\n";
    return 0;
  } catch (const tribos::core::InputError& e) {
    std::cerr << "tribos-msh2exo: error: " << e.what() << "\n";
    return 2;
  } catch (const tribos::core::IoError& e) {
    std::cerr << "tribos-msh2exo: error: " << e.what() << "\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "tribos-msh2exo: internal error: " << e.what() << "\n";
    return 1;
  }
}
