#pragma once
/// \file TwoBricks.hpp
/// The paper's model problem geometry (Section 6): Omega^1 = (0,20)x(0,10)x(0,10)
/// (block "aluminium", body 1, the slave side), Omega^2 = (0,20)x(0,10)x(10,20) (block
/// "steel", body 2). Each brick is an (nx*H/h) x (ny*H/h) x (nz*H/h) grid of cubes, each
/// cube cut into 5 tetrahedra with the cut alternating with the parity of (i + j + k)
/// counted over the whole brick, so that every decomposition gives the same global mesh
/// and interfaces conform for any H/h. The two bricks have separate nodes on z = 10.
///
/// Named sets (node set and side set of the same name and id):
///   1 "dirichlet_aluminium"  x = 0 face of brick 1
///   2 "dirichlet_steel"      x = 0 face of brick 2
///   3 "contact_aluminium"    z = 10 face of brick 1 (slave)
///   4 "contact_steel"        z = 10 face of brick 2 (master)
///   5 "load_end"             x = 20 face of brick 2, p = (1, 0, 20) MPa in the paper
///   6 "load_top"             z = 20 face of brick 2, p = (0, 0, -30) MPa in the paper
#include <string>
#include <vector>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh {

/// Subdomain grid of one brick, "NXxNYxNZ" (e.g. "2x1x1").
struct BrickGrid {
  int nx = 2, ny = 1, nz = 1;
  /// Parses "2x1x1"; throws core::InputError naming `parameter` on bad syntax or n < 1.
  static BrickGrid parse(const std::string& text, const std::string& parameter);
  int count() const { return nx * ny * nz; }
};

struct TwoBricksSpec {
  BrickGrid subdomainsPerBrick;  ///< the paper's s = nx*ny*nz subdomains per brick
  int hOverH = 2;                ///< elements per subdomain edge (H/h)
  double gap = 0.0;              ///< initial gap d >= 0: brick 2 occupies (10 + gap, 20 + gap) in z
};

/// Builds the global mesh. Requires the subdomains to be cubes: 20/nx == 10/ny == 10/nz
/// (true for the paper's 2x1x1, 4x2x2, 6x3x3, 8x4x4, 10x5x5); throws core::InputError
/// naming "Mesh/Subdomains Per Brick" otherwise.
Mesh generateTwoBricks(const TwoBricksSpec& spec);

/// Element -> subdomain of the structured split: subdomains of brick 1 first, numbered
/// x fastest, then those of brick 2.
std::vector<int> structuredPartition(const Mesh& mesh, const TwoBricksSpec& spec);

}  // namespace tribos::mesh
