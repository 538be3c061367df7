/// \file PenetrationCheck.cpp
/// No slave node inside a master body after the solve (header).
#include "tribos/stack/PenetrationCheck.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "tribos/core/Format.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/geometry/MasterSurface.hpp"
#include "tribos/geometry/SurfaceNormals.hpp"

namespace tribos::stack {

namespace {
/// The master nodes of each slave node's rows on one interface.
std::map<LO, std::set<LO>> rowMasters(const feti::ConstraintMatrix& B, int interface) {
  std::map<LO, std::set<LO>> masters;
  for (const auto& node : B.contact)
    if (node.interface == interface) masters[node.slaveNode].insert(node.masterNodes.begin(), node.masterNodes.end());
  return masters;
}

/// True when face `face` of `master` has a node of `rowNodes`.
bool faceHasRowNode(const geometry::MasterSurface& master, LO face, const std::set<LO>& rowNodes) {
  for (LO n : master.faceNodes(face))
    if (rowNodes.count(n)) return true;
  return false;
}

/// The penetration of one interface in the displaced mesh `moved`.
Penetration interfacePenetration(const mesh::Mesh& moved, const feti::ContactInterfaceSpec& spec,
                                 const std::map<LO, std::set<LO>>& rows, const geometry::HeldAxes& held) {
  const geometry::MasterSurface master(moved, spec.masterSideSet, held);  // the rows' normals
  Penetration found;
  found.interface = spec.label();
  for (LO slave : geometry::sideSetNodes(moved, moved.sideSet(spec.slaveSideSet))) {
    const auto p = master.pairingProjection(moved.coords[slave], 0.0);
    if (p.face < 0 || p.distance == 0.0) continue;  // outside, or exactly on the surface
    const auto row = rows.find(slave);
    const bool held = row != rows.end() && faceHasRowNode(master, p.face, row->second);
    if (held) continue;
    const double tolerance = kPenetrationTolerance * master.faceSize(p.face);
    if (p.distance <= tolerance) continue;
    ++found.nodes;
    if (p.distance > found.depth) {
      found.depth = p.distance;
      found.node = slave;
      found.tolerance = tolerance;
      found.heldByRow = row != rows.end();
    }
  }
  return found;
}
}  // namespace

std::vector<Penetration> penetrationsAfterSolve(const Scene& scene, const feti::ConstraintMatrix& B,
                                                const std::vector<std::array<double, 3>>& u) {
  std::vector<Penetration> found;
  if (scene.contacts.empty()) return found;
  mesh::Mesh moved = scene.mesh;
  for (LO n = 0; n < moved.numNodes(); ++n)
    for (int c = 0; c < 3; ++c) moved.coords[n][c] += u[n][c];
  for (size_t i = 0; i < scene.contacts.size(); ++i) {
    const auto& spec = scene.contacts[i].rows;
    if (spec.tied) continue;
    Penetration p = interfacePenetration(moved, spec, rowMasters(B, static_cast<int>(i)), B.heldAxes);
    if (p.nodes > 0) found.push_back(std::move(p));
  }
  return found;
}

std::string describe(const Penetration& p) {
  return "contact check after the solve: slave node " + std::to_string(p.node + 1) + " of " + p.interface + " lies " +
         core::formatNumber(p.depth) + " inside the master body (" + std::to_string(p.nodes) +
         " node(s) deeper than " + core::formatNumber(kPenetrationTolerance) + " of the master face's size; here " +
         core::formatNumber(p.tolerance) + "), " +
         (p.heldByRow ? "having slid off the master faces its contact rows hold it to"
                      : "with no contact rows (out of reach of Search Distance when the rows were built)") +
         ": the bodies overlap, the result is not a contact solution (Solver/Pairing Updates pairs the nodes again "
         "on the deformed bodies)";
}

}  // namespace tribos::stack
