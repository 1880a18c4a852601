#pragma once
// Exceptions to exit codes and messages, the same for every command.

#include <exception>
#include <string>

#include "geometry/core/errors.h"

namespace fabmesh {

// The exit codes (kExitOk ... kExitEnvironment) are the error tree's: geometry/core/errors.h.

/// How a failure is reported.
struct Failure {
  int exit_code = kExitInternal;  ///< kExitBadInput, kExitInvalid, kExitInternal or kExitEnvironment
  std::string label;              ///< "error", "invalid", "internal error" or "environment error"
  std::string message;            ///< names the file (line, column and field where known)
};

/// Classifies `error`: InputError (and its kinds) -> 2, ValidationFailed -> 1,
/// MachineError -> 5, anything else -> 3. An InputError whose location io has placed is reported
/// there ("path:line:column: key: message", "-D path=value: key: message",
/// "path: key (default): message"); FileError messages name their file;
/// `subject` (the design or mesh file at hand) prefixes any other message.
Failure describe_failure(const std::exception_ptr& error, const std::string& subject = "");

/// `message` fit to print: a line break continues the message on an
/// indented line (so no line of it can pass for a message of its own), and
/// any other control character is escaped ("\x09").
std::string printable_message(const std::string& message);

/// "fabmesh: error: message" (printable_message: a multi-line message's
/// further lines indented, other control characters escaped).
std::string failure_line(const Failure& failure);

/// How one item of a report ended (a design run, a batch variant, a mesh
/// file checked): the status every report shows, in to_string's words (which
/// a batch's summary.jsonl keeps). One per exit code, and Missing.
enum class ItemStatus {
  Ok,        ///< done, valid (exit code 0)
  Invalid,   ///< a mesh is not valid (exit code 1)
  BadInput,  ///< bad input (exit code 2)
  Error,     ///< an internal error (exit code 3)
  Missing,   ///< not run yet: a batch variant no shard has built (no exit code)
  /// Writing failed for a reason of the machine (exit code 5).
  Environment,
};

/// "ok", "invalid", "bad input", "error", "missing", "environment".
const char* to_string(ItemStatus status);

/// The status of an item that ended with `exit_code` (describe_failure's, or
/// 0): 0 Ok, 1 Invalid, 2 BadInput, 5 Environment, anything else Error.
ItemStatus status_of(int exit_code);

/// The exit code of `status`, the inverse of status_of (Missing: 0, it ran nothing).
int exit_code_of(ItemStatus status);

}  // namespace fabmesh
