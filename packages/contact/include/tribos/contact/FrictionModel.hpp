#pragma once
/// \file FrictionModel.hpp
/// The options of the friction law (Contact sublist), with their names: light enough for
/// the scene (stack/Scene.hpp) to hold them without the solver's headers.
#include <algorithm>

#include "tribos/core/EnumNames.hpp"

namespace tribos::contact {

/// Contact/Friction Model. Bonded scenes are solved as linear ones (contact rows as
/// equalities), never by solveContact.
enum class FrictionModel { None, Tresca, Coulomb, Bonded };
inline constexpr core::EnumNames<FrictionModel, 4> kFrictionModelNames{{{"None", FrictionModel::None},
                                                                        {"Tresca", FrictionModel::Tresca},
                                                                        {"Coulomb", FrictionModel::Coulomb},
                                                                        {"Bonded", FrictionModel::Bonded}}};
/// The friction law of one contact interface (Contact, or Contact/<name>), and what each law
/// implies for the rows, the bound on the tangential force and the messages: the one place
/// that asks which model it is, so the scene, the report and the solve ask the law instead.
/// What each model implies, the one place that names the models (FrictionLaw's queries and the
/// contact solver's per-node arrays ask these; a new law answers them here).
/// Bonded: the contact rows are equalities that tie the surfaces where they are (a linear
/// scene when every interface is bonded), never inequalities of a contact solve.
inline bool tiesSurfaces(FrictionModel m) { return m == FrictionModel::Bonded; }
/// Rows along t1 and t2: every law but None (frictionless contact has normal rows only).
inline bool hasTangentialRows(FrictionModel m) { return m != FrictionModel::None; }
/// Coulomb: the bound on the tangential force is F lambda_nu, followed by successive
/// approximations of the slip bound (paper Section 4, ALGORITHMS.md 10).
inline bool boundFollowsNormalForce(FrictionModel m) { return m == FrictionModel::Coulomb; }
/// Tresca: the bound is the given slip bound g per node, not F lambda_nu.
inline bool boundIsGiven(FrictionModel m) { return m == FrictionModel::Tresca; }

struct FrictionLaw {
  FrictionModel model = FrictionModel::Coulomb;
  double F1 = 0.3, F2 = 0.3;       ///< friction coefficients along t1, t2
  double slipBound = 0.0;          ///< Tresca: g as a nodal force [force]

  bool tiesSurfaces() const { return contact::tiesSurfaces(model); }
  bool hasTangentialRows() const { return contact::hasTangentialRows(model); }
  bool boundFollowsNormalForce() const { return contact::boundFollowsNormalForce(model); }
  bool boundIsGiven() const { return contact::boundIsGiven(model); }
  /// The coefficient of the friction capacity F N quoted in messages: the larger of F1 and F2;
  /// 0 without friction.
  double capacityCoefficient() const { return model == FrictionModel::None ? 0.0 : std::max(F1, F2); }
  /// The friction force of a node sliding along t_j (j = 0: t1, 1: t2) under the normal force
  /// `normalForce`: F_j lambda_nu (Coulomb), the given bound (Tresca), 0 (frictionless, tied).
  double slidingForce(int j, double normalForce) const {
    if (model == FrictionModel::Coulomb) return (j == 0 ? F1 : F2) * std::max(normalForce, 0.0);
    return model == FrictionModel::Tresca ? slipBound : 0.0;
  }
};

/// Contact/Fixed Point: Coulomb's slip bound updated after every outer iteration, or after
/// every Tresca problem solved to epsilon.
enum class FixedPoint { Inexact, Exact };
inline constexpr core::EnumNames<FixedPoint, 2> kFixedPointNames{
    {{"Inexact", FixedPoint::Inexact}, {"Exact", FixedPoint::Exact}}};
/// Contact/Slip Bound Test (Coulomb, Inexact).
enum class SlipBoundTest { Epsilon, Paper };
inline constexpr core::EnumNames<SlipBoundTest, 2> kSlipBoundTestNames{
    {{"Epsilon", SlipBoundTest::Epsilon}, {"Paper", SlipBoundTest::Paper}}};

}  // namespace tribos::contact
