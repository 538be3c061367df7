#pragma once
/// \file ParameterTable.hpp
/// One declaration per parameter: a table binds each parameter's name, documentation and
/// validator to a field of a component's settings struct. The same table declares the valid
/// list (the defaults are the struct's own member initialisers) and reads a validated list
/// back into the struct, so a new parameter is one field with its default plus one add()
/// line, and the declared default can never drift from the one the code uses.
///
///   const core::ParameterTable<MpgpSettings> table = core::ParameterTable<MpgpSettings>()
///       .add("step scale", &MpgpSettings::stepScale, "alpha_bar = ...", core::openInterval(0.0, 2.0))
///       .add("optimal expansion", &MpgpSettings::optimalExpansion, "...");
///   table.declare(valid.sublist("MPGP"));           // getValidParameters()
///   table.read(validated.sublist("MPGP"), settings);  // after core::validateAndSetDefaults
///
/// Includes Teuchos: include it only in the .cpp files that declare valid lists.
#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <functional>
#include <string>
#include <vector>

#include "tribos/core/EnumNames.hpp"
#include "tribos/core/Validators.hpp"

namespace tribos::core {

template <class Settings>
class ParameterTable {
 public:
  /// A finite real in the validator's range.
  ParameterTable& add(const std::string& name, double Settings::*field, const std::string& doc,
                      Teuchos::RCP<const RealRangeValidator> range) {
    return bind(name, field, doc, range);
  }
  /// An integer in the validator's range.
  ParameterTable& add(const std::string& name, int Settings::*field, const std::string& doc,
                      Teuchos::RCP<const IntRangeValidator> range) {
    return bind(name, field, doc, range);
  }
  /// A flag.
  ParameterTable& add(const std::string& name, bool Settings::*field, const std::string& doc) {
    return bind(name, field, doc, Teuchos::null);
  }
  /// One of `choices` (the default must be one of them).
  ParameterTable& add(const std::string& name, std::string Settings::*field, const std::string& doc,
                      const std::vector<std::string>& choices) {
    entries_.push_back({[=](Teuchos::ParameterList& pl, const Settings& defaults) {
                          Teuchos::setStringToIntegralParameter<int>(name, defaults.*field, doc,
                                                                     Teuchos::Array<std::string>(choices), &pl);
                        },
                        reader(name, field)});
    return *this;
  }

  /// One of the names of an option (core/EnumNames.hpp): declared as its names, read back as
  /// the value.
  template <class E, std::size_t N>
  ParameterTable& add(const std::string& name, E Settings::*field, const std::string& doc,
                      const EnumNames<E, N>& names) {
    entries_.push_back({[=](Teuchos::ParameterList& pl, const Settings& defaults) {
                          Teuchos::setStringToIntegralParameter<int>(name, nameOf(names, defaults.*field), doc,
                                                                     Teuchos::Array<std::string>(namesOf(names)), &pl);
                        },
                        [=](const Teuchos::ParameterList& pl, Settings& s) {
                          if (pl.isParameter(name)) s.*field = valueOf(names, pl.get<std::string>(name));
                        }});
    return *this;
  }

  /// Declares every parameter in `valid` with the defaults of `defaults`.
  void declare(Teuchos::ParameterList& valid, const Settings& defaults = Settings()) const {
    for (const auto& e : entries_) e.declare(valid, defaults);
  }

  /// Copies every parameter present in `validated` (a list that passed
  /// core::validateAndSetDefaults) into `settings`; absent ones keep their value.
  void read(const Teuchos::ParameterList& validated, Settings& settings) const {
    for (const auto& e : entries_) e.read(validated, settings);
  }

 private:
  struct Entry {
    std::function<void(Teuchos::ParameterList&, const Settings&)> declare;
    std::function<void(const Teuchos::ParameterList&, Settings&)> read;
  };

  template <class T>
  static std::function<void(const Teuchos::ParameterList&, Settings&)> reader(const std::string& name,
                                                                              T Settings::*field) {
    return [=](const Teuchos::ParameterList& pl, Settings& s) {
      if (pl.isParameter(name)) s.*field = pl.get<T>(name);
    };
  }

  template <class T>
  ParameterTable& bind(const std::string& name, T Settings::*field, const std::string& doc,
                       Teuchos::RCP<const Teuchos::ParameterEntryValidator> validator) {
    entries_.push_back({[=](Teuchos::ParameterList& pl, const Settings& defaults) {
                          pl.set(name, defaults.*field, doc, validator);
                        },
                        reader(name, field)});
    return *this;
  }

  std::vector<Entry> entries_;
};

}  // namespace tribos::core
