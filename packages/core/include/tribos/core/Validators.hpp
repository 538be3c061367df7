#pragma once
/// \file Validators.hpp
/// Validators that encode the real ranges of Tribos's parameters (STYLE.md 3): real numbers
/// in an interval with open or closed ends, always finite (NaN and Inf are refused
/// everywhere: a NaN passes every comparison-based check and would reach the solver);
/// integers in a closed range; arrays of a fixed number of finite reals. Each one can say
/// its range in words for `tribos --list-parameters` and doc/parameters.md.
///
/// Includes Teuchos: include it only in the .cpp files that declare valid lists.
#include <Teuchos_ParameterEntryValidator.hpp>
#include <Teuchos_RCP.hpp>

#include <limits>
#include <string>

namespace tribos::core {

/// A validator that states its range in words: "(0, 2)", "[1, 1000]", "3 finite numbers".
class RangeValidator : public Teuchos::ParameterEntryValidator {
 public:
  virtual std::string rangeText() const = 0;
  ValidStringsList validStringValues() const override { return Teuchos::null; }
  void printDoc(const std::string& docString, std::ostream& out) const override;
};

/// Finite reals between `low` and `high`; each end is included or not ("[" or "("). An
/// infinite end means "unbounded" (and is never included). An int value is accepted and
/// converted to double (a scene may write type="int" value="10" for a real).
class RealRangeValidator : public RangeValidator {
 public:
  RealRangeValidator(double low, bool lowIncluded, double high, bool highIncluded);
  std::string rangeText() const override;
  const std::string getXMLTypeName() const override { return "TribosRealRange"; }
  void validate(const Teuchos::ParameterEntry& entry, const std::string& paramName,
                const std::string& sublistName) const override;
  void validateAndModify(const std::string& paramName, const std::string& sublistName,
                         Teuchos::ParameterEntry* entry) const override;

 private:
  double low_, high_;
  bool lowIncluded_, highIncluded_;
};

/// Integers in [low, high].
class IntRangeValidator : public RangeValidator {
 public:
  IntRangeValidator(int low, int high) : low_(low), high_(high) {}
  std::string rangeText() const override;
  const std::string getXMLTypeName() const override { return "TribosIntRange"; }
  void validate(const Teuchos::ParameterEntry& entry, const std::string& paramName,
                const std::string& sublistName) const override;

 private:
  int low_, high_;
};

/// Arrays of exactly `size` finite reals (Array(double): tractions, directions), each of
/// magnitude at most `maxAbs`; size kOneOrMore: any length but empty, kAnyLength: empty too
/// (an optional table, empty when not given).
class FiniteArrayValidator : public RangeValidator {
 public:
  static constexpr int kOneOrMore = -1, kAnyLength = -2;
  explicit FiniteArrayValidator(int size, double maxAbs = std::numeric_limits<double>::infinity())
      : size_(size), maxAbs_(maxAbs) {}
  std::string rangeText() const override;
  const std::string getXMLTypeName() const override { return "TribosFiniteArray"; }
  void validate(const Teuchos::ParameterEntry& entry, const std::string& paramName,
                const std::string& sublistName) const override;

 private:
  int size_;
  double maxAbs_;
};

// Short names for the declarations of valid lists.
constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// The largest magnitude of a physical input (moduli, loads, displacements, friction
/// coefficients). Norms square their entries, and the square of anything above ~1.3e154
/// overflows to Inf: E = 1e300 or a traction of 1e300 ended as non-finite or stalled runs,
/// F = 1e300 ran without end (doc/stability.md). 1e100 leaves 54 decades for the products
/// with lengths, areas and strains; no physical scene comes near it.
constexpr double kMaxMagnitude = 1e100;
/// x > low (and finite).
Teuchos::RCP<const RealRangeValidator> greaterThan(double low);
/// x >= low (and finite).
Teuchos::RCP<const RealRangeValidator> atLeast(double low);
/// low < x < high.
Teuchos::RCP<const RealRangeValidator> openInterval(double low, double high);
/// low <= x <= high.
Teuchos::RCP<const RealRangeValidator> closedInterval(double low, double high);
/// low < x <= high.
Teuchos::RCP<const RealRangeValidator> openClosed(double low, double high);
/// Any finite real.
Teuchos::RCP<const RealRangeValidator> finite();
/// low <= n <= high.
Teuchos::RCP<const IntRangeValidator> intRange(int low, int high);
/// `size` finite reals (any number >= 1 when size < 0), each of magnitude at most `maxAbs`.
Teuchos::RCP<const FiniteArrayValidator> finiteArray(int size, double maxAbs = kInfinity);

/// The range of an entry in words: the range validators' text, "A | B | C" for a string
/// choice, "" when there is no validator.
std::string describeRange(const Teuchos::ParameterEntry& entry);

/// Shortest text that reads back as the same double ("0.3", "1e-05", "100000").
std::string formatShortest(double x);

}  // namespace tribos::core
