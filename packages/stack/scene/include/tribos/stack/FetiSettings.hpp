#pragma once
/// \file FetiSettings.hpp
/// The T-FETI operators' settings from the validated "FETI" list: one reading of it for the
/// linear and the contact solves alike, its option strings turned into the settings' values
/// once, here.
namespace Teuchos {
class ParameterList;
}

namespace tribos::feti {
struct TotalFetiSettings;
enum class DualPreconditioner;
}

namespace tribos::stack {

/// Everything of TotalFetiSettings the FETI list gives (Factorization, Dual Operator,
/// Preconditioner, Coarse Factor Precision and the tuning thresholds); the deadline is the
/// caller's. `exactProjector`: the linear solve's projected CG needs the exact projector, so
/// the coarse factor stays double whatever Coarse Factor Precision says.
feti::TotalFetiSettings totalFetiSettings(const Teuchos::ParameterList& feti, bool exactProjector);

/// FETI/Preconditioner as its value.
feti::DualPreconditioner dualPreconditioner(const Teuchos::ParameterList& feti);

}  // namespace tribos::stack
