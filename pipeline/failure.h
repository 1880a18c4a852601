#pragma once
// Exceptions to exit codes and messages, the same for every command.

#include <exception>
#include <string>

namespace fabmesh {

/// Exit codes, the same for every command.
constexpr int kExitOk = 0;        ///< done, every mesh valid
constexpr int kExitInvalid = 1;   ///< a mesh is not valid (ValidationFailed)
constexpr int kExitBadInput = 2;  ///< bad input (InputError)
constexpr int kExitInternal = 3;  ///< an internal error
/// Writing failed for a reason of the machine, not of the input (EnvironmentError:
/// disk full, I/O error, permission): the same command may succeed once that is fixed.
constexpr int kExitEnvironment = 5;

/// How a failure is reported.
struct Failure {
  int exit_code = kExitInternal;  ///< kExitBadInput, kExitInvalid, kExitInternal or kExitEnvironment
  std::string label;              ///< "error", "invalid", "internal error" or "environment error"
  std::string message;            ///< names the file (line, column and field where known)
};

/// Classifies `error`: InputError (and its kinds) -> 2, ValidationFailed -> 1,
/// EnvironmentError -> 5, anything else -> 3. An InputError whose location io has placed is reported
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

/// The status a report or batch row shows for a job that ended with
/// `exit_code` (describe_failure's, or 0): 0 Ok, 1 Invalid, 2 BadInput,
/// anything else Error (a batch tells 5 apart itself: its Environment status).
/// `Status`: an enum with those four values.
template <class Status>
Status status_of(int exit_code) {
  switch (exit_code) {
    case kExitOk:
      return Status::Ok;
    case kExitInvalid:
      return Status::Invalid;
    case kExitBadInput:
      return Status::BadInput;
    default:
      return Status::Error;
  }
}

}  // namespace fabmesh
