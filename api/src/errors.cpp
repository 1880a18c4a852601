#include "geometry/core/errors.h"

#include <exception>
#include <new>

#include "api/src/detail.h"
#include "fabmesh/version.h"
#include "io/file.h"
#include "pipeline/failure.h"

namespace fabmesh::api {
namespace {

// Where an InputError is, as the public place: the key and where the design
// gives it, or the file (and line) of a file that could not be read.
ErrorPlace place_of(const fabmesh::InputError& e) {
  const fabmesh::ErrorLocation& at = e.location();
  ErrorPlace place{at.key, at.file, at.line, at.column, at.override_text, at.is_default};
  if (const auto* file = dynamic_cast<const fabmesh::FileError*>(&e); file != nullptr && place.file.empty()) {
    place.file = file->path();
    place.line = file->line();
    place.column = file->column();
  }
  return place;
}

}  // namespace

const char* version() noexcept { return FABMESH_VERSION_STRING; }

namespace detail {

void rethrow_public() {
  const std::exception_ptr error = std::current_exception();
  try {
    throw;
  } catch (const api::Error&) {
    throw;  // already public
  } catch (const std::bad_alloc&) {
    throw;  // out of memory stays what it is
  } catch (const fabmesh::InputError& e) {
    throw api::InputError(describe_failure(error).message, place_of(e));
  } catch (...) {
    const Failure failure = describe_failure(error);
    if (failure.exit_code == kExitInvalid) throw api::ValidationFailed(failure.message);
    if (failure.exit_code == kExitEnvironment) throw api::EnvironmentError(failure.message);
    throw api::Error(failure.message, failure.exit_code);
  }
}

void bad_argument(const std::string& argument, const std::string& message) {
  ErrorPlace place;
  place.key = argument;
  throw api::InputError(argument + ": " + message, std::move(place));
}

}  // namespace detail
}  // namespace fabmesh::api
