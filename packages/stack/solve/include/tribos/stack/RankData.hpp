#pragma once
/// \file RankData.hpp
/// What a rank keeps once the set-up is done (issue 11: memory per rank that shrinks with the
/// ranks). Every rank builds the global mesh, decomposition and B (the set-up needs them: the
/// contact search, the row numbering, feti::requireRestrainedBodies); the solve and the
/// result gathering need far less, and the rest is freed before the factorisation.
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/stack/Scene.hpp"

namespace tribos::stack {

/// Frees on rank `rank` of `numRanks`, after assembly, B and its checks:
///  - of B, the blocks of other ranks' subdomains except the rows this rank owns
///    (feti::keepRankRows);
///  - of the decomposition, the elements and connectivity of every subdomain (assembled)
///    and the node lists of other ranks' subdomains;
///  - on ranks other than 0 (which writes the results on the global mesh), the global
///    connectivity, the element -> subdomain map and the side sets. Coordinates and node
///    sets stay (the owned subdomains' coordinates, the reactions' prescribed components).
/// A scene that may pair again after its solve (Scene::pairingUpdates) keeps its mesh and
/// decomposition whole on every rank: the contact rows are built again from them.
void keepRankData(Scene& scene, feti::ConstraintMatrix& B, int rank, int numRanks);

/// Entries (rows, nonzeros) of B's blocks that a rank holds, for tests and doc/measurements/scalability.md.
struct HeldRows {
  long long rows = 0, nonzeros = 0;
};
HeldRows heldRows(const feti::ConstraintMatrix& B);

}  // namespace tribos::stack
