// TotalFeti's traffic per product with P F P (the summary's bytes_per_f_application): what
// each component reads per application, summed over the ranks.
#include "CoarseSpace.hpp"
#include "Preconditioners.hpp"
#include "SubdomainSet.hpp"

namespace tribos::feti {

void TotalFeti::measureTraffic() {
  // The least each product with P F P must move between memory and the cores: every array
  // below is read (or written) once per use, the n_s-sized work vectors of a subdomain
  // staying in cache. doc/measurements/performance.md divides it by the triad bandwidth.
  constexpr double kDouble = sizeof(double), kIndex = sizeof(LO);
  double f = 0.0, factorEntries = 0.0;
  for (const auto& L : subdomains_->all()) {
    const double entries = static_cast<double>(L->block->value.size()), rows = L->m();
    if (settings_.explicitF) {
      f += kDouble * rows * (rows + 1) / 2;  // F_s's lower triangle (packLowerInRowOrder)
    } else {
      // the factor (forward whole, backward the part B_s's dofs reach; P F P applies K^+, not
      // K^dagger, so R is not read); B_s^T and B_s (its terms, twice)
      f += static_cast<double>(L->solver.generalizedInverseBytesOnDofs()) + 2 * entries * sizeof(BlockTerm);
    }
    f += rows * (2 * kIndex + 3 * kDouble);  // overlap indices in and out; x gathered, y added
    factorEntries += static_cast<double>(L->solver.factor().factorNonzeros());
  }
  const double subdomainF = f;
  // The preconditioner: K_bb's upper triangle (lumped), with the Dirichlet one K_ib twice (K_ib
  // and K_bi = K_ib^T) and the K_ii factor (both substitutions); B_s^T and B_s (its terms,
  // twice), the dual entries.
  const bool preconditioner = settings_.dirichletPreconditioner || settings_.lumpedPreconditioner;
  double dirichlet = 0.0;
  for (int i = 0; i < subdomains_->numOwned(); ++i) {
    if (!preconditioner) break;
    const OwnedSubdomain* L = &subdomains_->owned(i);
    const DirichletBlocks& D = preconditioners_->blocks(i);
    const double entries = static_cast<double>(L->block->value.size()), rows = L->m();
    dirichlet += D.Kbb.bytes() + 2 * entries * sizeof(BlockTerm) + rows * (2 * kIndex + 3 * kDouble);
    if (!settings_.dirichletPreconditioner) continue;
    dirichlet += 2 * D.Kib.bytes();
    if (D.interiorFactor) dirichlet += static_cast<double>(D.interiorFactor->solveBytes());
  }
  const CoarseRows& G = coarse_->rows();
  const double owned = static_cast<double>(G.numRows), gEntries = static_cast<double>(G.rowSubdomain.size());
  f += owned * kDouble;  // y cleared before the sum
  // One projection: G x and G^T a, each one pass over its terms (16 bytes each: G x's of
  // the owned subdomains, G^T a's of the owned rows) and the coordinate and full slots (the
  // run table and M_s are small); x read twice, y written. The memo's copies of x and P x
  // are not counted.
  const double gxTerms = static_cast<double>(G.ownedTerm.size());
  const double slots = static_cast<double>(G.coords.size() + G.full.size());
  const double projection = (gxTerms + gEntries) * sizeof(CoarseTerm) + 2 * slots * kDouble + owned * (kIndex + 3 * kDouble);
  if (preconditioner) dirichlet += owned * kDouble;
  // The subdomains' part alone (each counted once, by its owner: the same sum on every
  // layout, unlike the projection's slots, which ranks sharing a subdomain both hold).
  double local[5] = {f + 2 * projection, factorEntries, projection, dirichlet, subdomainF},
         global[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 5, local, global);
  bytesPerFApplication_ = global[0];
  subdomainBytesPerF_ = global[4];
  factorNonzeros_ = static_cast<long long>(global[1]);
  profile_.projectionBytes = global[2];
  profile_.preconditionerBytes = global[3];
}

}  // namespace tribos::feti
