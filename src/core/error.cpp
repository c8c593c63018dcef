#include "core/error.h"

#include <sstream>

namespace periflex {

std::string format_location(const SourceLocation& where) {
  std::ostringstream out;
  out << (where.file.empty() ? "<input>" : where.file);
  if (where.line > 0) {
    out << ':' << where.line;
    if (where.column > 0) out << ':' << where.column;
  }
  if (!where.key.empty()) out << ": key '" << where.key << "'";
  return out.str();
}

InputError::InputError(SourceLocation where, const std::string& what_is_wrong)
    : std::runtime_error(format_location(where) + ": " + what_is_wrong),
      where_(std::move(where)),
      detail_(what_is_wrong) {}

static std::string describe(const NumericalDiagnostic& d) {
  std::ostringstream out;
  out << d.quantity;
  if (d.step >= 0) out << " at step " << d.step << ", t = " << d.time;
  if (!d.cause.empty()) out << ": " << d.cause;
  if (!d.remedy.empty()) out << ". Try: " << d.remedy;
  return out.str();
}

NumericalError::NumericalError(NumericalDiagnostic diagnostic)
    : std::runtime_error(describe(diagnostic)), diagnostic_(std::move(diagnostic)) {}

}  // namespace periflex
