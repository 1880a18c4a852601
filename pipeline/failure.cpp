#include "pipeline/failure.h"

#include <fmt/format.h>

#include "geometry/core/error_checks.h"
#include "io/file.h"

namespace fabmesh {

Failure describe_failure(const std::exception_ptr& error, const std::string& subject) {
  // A message without a place of its own is about the file at hand.
  auto about_subject = [&](const std::string& text) {
    return subject.empty() ? text : subject + ": " + text;
  };
  try {
    std::rethrow_exception(error);
  } catch (const FileError& e) {
    return {kExitBadInput, "error", e.what()};
  } catch (const InputError& e) {
    // A value only building can judge (a shape the design's numbers make
    // impossible, a budget, an output): at the key that gave it, as io placed it.
    const ErrorLocation& at = e.location();
    if (!at.key.empty() && !at.place.empty())
      return {kExitBadInput, "error", location_text(at) + ": " + e.what()};
    return {kExitBadInput, "error", about_subject(e.what())};
  } catch (const MachineError& e) {
    return {
        kExitEnvironment, "environment error",
        fmt::format("{} (a failure of the machine, not of the input: run again once it is fixed)", e.what())};
  } catch (const ValidationFailed& e) {
    return {kExitInvalid, "invalid", about_subject(e.what())};
  } catch (const std::exception& e) {
    return {kExitInternal, "internal error", about_subject(e.what())};
  } catch (...) {
    return {kExitInternal, "internal error", about_subject("unknown exception")};
  }
}

const char* to_string(ItemStatus status) {
  switch (status) {
    case ItemStatus::Ok:
      return "ok";
    case ItemStatus::Invalid:
      return "invalid";
    case ItemStatus::BadInput:
      return "bad input";
    case ItemStatus::Error:
      return "error";
    case ItemStatus::Missing:
      return "missing";
    case ItemStatus::Environment:
      return "environment";
  }
  return "error";
}

ItemStatus status_of(int exit_code) {
  switch (exit_code) {
    case kExitOk:
      return ItemStatus::Ok;
    case kExitInvalid:
      return ItemStatus::Invalid;
    case kExitBadInput:
      return ItemStatus::BadInput;
    case kExitEnvironment:
      return ItemStatus::Environment;
    default:
      return ItemStatus::Error;
  }
}

int exit_code_of(ItemStatus status) {
  switch (status) {
    case ItemStatus::Ok:
    case ItemStatus::Missing:
      return kExitOk;
    case ItemStatus::Invalid:
      return kExitInvalid;
    case ItemStatus::BadInput:
      return kExitBadInput;
    case ItemStatus::Environment:
      return kExitEnvironment;
    case ItemStatus::Error:
      break;
  }
  return kExitInternal;
}

std::string printable_message(const std::string& message) {
  std::string text;
  for (std::size_t i = 0; i < message.size(); ++i) {
    const auto u = static_cast<unsigned char>(message[i]);
    if (u == '\r' && i + 1 < message.size() && message[i + 1] == '\n') continue;  // CRLF: one break
    if (u == '\n') {
      text += "\n  ";
    } else if (u < 0x20 || u == 0x7f) {
      text += fmt::format("\\x{:02x}", u);
    } else {
      text += message[i];
    }
  }
  return text;
}

std::string failure_line(const Failure& failure) {
  return fmt::format("fabmesh: {}: {}", failure.label, printable_message(failure.message));
}

}  // namespace fabmesh
