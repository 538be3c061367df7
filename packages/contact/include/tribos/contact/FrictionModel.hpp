#pragma once
/// \file FrictionModel.hpp
/// The options of the friction law (Contact sublist), with their names: light enough for
/// the scene (stack/Scene.hpp) to hold them without the solver's headers.
#include "tribos/core/EnumNames.hpp"

namespace tribos::contact {

/// Contact/Friction Model. Bonded scenes are solved as linear ones (contact rows as
/// equalities), never by solveContact.
enum class FrictionModel { None, Tresca, Coulomb, Bonded };
inline constexpr core::EnumNames<FrictionModel, 4> kFrictionModelNames{{{"None", FrictionModel::None},
                                                                        {"Tresca", FrictionModel::Tresca},
                                                                        {"Coulomb", FrictionModel::Coulomb},
                                                                        {"Bonded", FrictionModel::Bonded}}};
/// The friction law of one contact interface (Contact, or Contact/<name>).
struct FrictionLaw {
  FrictionModel model = FrictionModel::Coulomb;
  double F1 = 0.3, F2 = 0.3;       ///< friction coefficients along t1, t2
  double slipBound = 0.0;          ///< Tresca: g as a nodal force [force]
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
