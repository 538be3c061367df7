#include "tribos/core/Validators.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterEntry.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <stdexcept>

namespace tribos::core {

namespace {
std::string endText(double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return formatShortest(x);
}

[[noreturn]] void refuse(const std::string& what) { throw std::invalid_argument(what); }
}  // namespace

std::string formatShortest(double x) {
  char text[32];
  // Whole numbers as such ("10", "100000"; %g would write 1e+01).
  if (std::nearbyint(x) == x && std::abs(x) < 1e15) {
    std::snprintf(text, sizeof text, "%.0f", x);
    return text;
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, x);
    if (std::strtod(text, nullptr) == x) break;
  }
  return text;
}

void RangeValidator::printDoc(const std::string& docString, std::ostream& out) const {
  out << "# " << docString << "\n# range: " << rangeText() << "\n";
}

RealRangeValidator::RealRangeValidator(double low, bool lowIncluded, double high, bool highIncluded)
    : low_(low), high_(high), lowIncluded_(lowIncluded && std::isfinite(low)),
      highIncluded_(highIncluded && std::isfinite(high)) {}

std::string RealRangeValidator::rangeText() const {
  if (std::isinf(low_) && std::isinf(high_)) return "finite";
  return std::string(lowIncluded_ ? "[" : "(") + endText(low_) + ", " + endText(high_) + (highIncluded_ ? "]" : ")");
}

void RealRangeValidator::validate(const Teuchos::ParameterEntry& entry, const std::string&,
                                  const std::string&) const {
  const auto& any = entry.getAny(false);
  if (any.type() != typeid(double) && any.type() != typeid(int))
    refuse("has type " + any.typeName() + " but must be double");
  const double x = any.type() == typeid(int) ? Teuchos::any_cast<int>(any) : Teuchos::any_cast<double>(any);
  if (!std::isfinite(x)) refuse(formatShortest(x) + " is not a finite number (range " + rangeText() + ")");
  const bool aboveLow = lowIncluded_ ? x >= low_ : x > low_;
  const bool belowHigh = highIncluded_ ? x <= high_ : x < high_;
  if (!aboveLow || !belowHigh) refuse(formatShortest(x) + " is outside the range " + rangeText());
}

void RealRangeValidator::validateAndModify(const std::string& paramName, const std::string& sublistName,
                                           Teuchos::ParameterEntry* entry) const {
  validate(*entry, paramName, sublistName);
  if (entry->getAny(false).type() == typeid(int))
    entry->setValue(static_cast<double>(Teuchos::any_cast<int>(entry->getAny(false))), false, entry->docString(),
                    entry->validator());
}

std::string IntRangeValidator::rangeText() const {
  return "[" + std::to_string(low_) + ", " + std::to_string(high_) + "]";
}

void IntRangeValidator::validate(const Teuchos::ParameterEntry& entry, const std::string&, const std::string&) const {
  const auto& any = entry.getAny(false);
  if (any.type() != typeid(int)) refuse("has type " + any.typeName() + " but must be int");
  const int n = Teuchos::any_cast<int>(any);
  if (n < low_ || n > high_) refuse(std::to_string(n) + " is outside the range " + rangeText());
}

std::string FiniteArrayValidator::rangeText() const {
  const std::string text = (size_ == kAnyLength ? std::string("none or more")
                            : size_ < 0           ? std::string("one or more")
                                                  : std::to_string(size_)) +
                           " finite numbers";
  return std::isinf(maxAbs_) ? text : text + " of magnitude <= " + formatShortest(maxAbs_);
}

void FiniteArrayValidator::validate(const Teuchos::ParameterEntry& entry, const std::string&,
                                    const std::string&) const {
  const auto& any = entry.getAny(false);
  if (any.type() != typeid(Teuchos::Array<double>)) refuse("has type " + any.typeName() + " but must be Array(double)");
  const auto& a = Teuchos::any_cast<Teuchos::Array<double>>(any);
  if (size_ == kOneOrMore && a.empty()) refuse("needs at least one component");
  if (size_ >= 0 && static_cast<int>(a.size()) != size_)
    refuse("needs exactly " + std::to_string(size_) + " components, got " + std::to_string(a.size()));
  for (double x : a)
    if (!std::isfinite(x)) refuse("component " + formatShortest(x) + " is not a finite number");
  for (double x : a)
    if (std::abs(x) > maxAbs_) refuse("component " + formatShortest(x) + " is outside the range " + rangeText());
}

Teuchos::RCP<const RealRangeValidator> greaterThan(double low) {
  return Teuchos::rcp(new RealRangeValidator(low, false, kInfinity, false));
}
Teuchos::RCP<const RealRangeValidator> atLeast(double low) {
  return Teuchos::rcp(new RealRangeValidator(low, true, kInfinity, false));
}
Teuchos::RCP<const RealRangeValidator> openInterval(double low, double high) {
  return Teuchos::rcp(new RealRangeValidator(low, false, high, false));
}
Teuchos::RCP<const RealRangeValidator> closedInterval(double low, double high) {
  return Teuchos::rcp(new RealRangeValidator(low, true, high, true));
}
Teuchos::RCP<const RealRangeValidator> openClosed(double low, double high) {
  return Teuchos::rcp(new RealRangeValidator(low, false, high, true));
}
Teuchos::RCP<const RealRangeValidator> finite() {
  return Teuchos::rcp(new RealRangeValidator(-kInfinity, false, kInfinity, false));
}
Teuchos::RCP<const IntRangeValidator> intRange(int low, int high) {
  return Teuchos::rcp(new IntRangeValidator(low, high));
}
Teuchos::RCP<const FiniteArrayValidator> finiteArray(int size, double maxAbs) {
  return Teuchos::rcp(new FiniteArrayValidator(size, maxAbs));
}

std::string describeRange(const Teuchos::ParameterEntry& entry) {
  const auto validator = entry.validator();
  if (validator.is_null()) return "";
  if (const auto* range = dynamic_cast<const RangeValidator*>(validator.get())) return range->rangeText();
  const auto strings = validator->validStringValues();
  if (strings.is_null()) return "";
  std::string text;
  for (const auto& s : *strings) text += (text.empty() ? "" : " | ") + s;
  return text;
}

}  // namespace tribos::core
