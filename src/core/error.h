// Errors that reach the user. Each carries enough context to act on:
// bad input names the file, line and key; numerical failure names the quantity,
// the step, the time, the likely cause and the parameter to change.
#pragma once

#include <stdexcept>
#include <string>

namespace periflex {

// Exit codes of the command line program.
enum ExitCode : int {
  kExitOk = 0,
  kExitOther = 1,
  kExitBadInput = 2,
  kExitNumerical = 3,
};

// Where in a scene file a problem is. line/column are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
  std::string key;  // dotted key path, e.g. "bodies.crank.mass"
};

// Invalid or unreadable input (scene file, --set override, command-line option). Exit code 2.
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& what_is_wrong);
  const SourceLocation& where() const { return where_; }
  const std::string& detail() const { return detail_; }

 private:
  SourceLocation where_;
  std::string detail_;
};

// What went wrong numerically and what to do about it. Exit code 3.
struct NumericalDiagnostic {
  std::string quantity;  // e.g. "constraint violation", "kinetic energy", "Newton residual"
  long step = -1;
  double time = 0.0;
  std::string cause;     // likely cause, e.g. "time step above the critical step"
  std::string remedy;    // parameter to change, e.g. "lower solver.dt below 2.1e-8"
};

class NumericalError : public std::runtime_error {
 public:
  explicit NumericalError(NumericalDiagnostic diagnostic);
  const NumericalDiagnostic& diagnostic() const { return diagnostic_; }

 private:
  NumericalDiagnostic diagnostic_;
};

// "file:line:column: key: message" in the form compilers use, so editors can jump to it.
std::string format_location(const SourceLocation& where);

}  // namespace periflex
