#pragma once
// Exceptions to exit codes and messages, the same for every command.

#include <exception>
#include <string>

namespace fabmesh {

/// How a failure is reported.
struct Failure {
  int exit_code = 3;    ///< 2 bad input, 1 an invalid mesh, 3 an internal error
  std::string label;    ///< "error", "invalid" or "internal error"
  std::string message;  ///< names the file (line, column and field where known)
};

/// Classifies `error`: InputError (and its kinds) -> 2, ValidationFailed -> 1,
/// anything else -> 3. An InputError whose location io has placed is reported
/// there ("path:line:column: key: message", "-D path=value: key: message",
/// "path: key (default): message"); FileError messages name their file;
/// `subject` (the design or mesh file at hand) prefixes any other message.
Failure describe_failure(const std::exception_ptr& error, const std::string& subject = "");

/// "fabmesh: error: message" (one line: control characters are escaped).
std::string failure_line(const Failure& failure);

}  // namespace fabmesh
