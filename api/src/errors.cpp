#include "geometry/core/errors.h"

#include <exception>
#include <new>

#include "api/src/detail.h"
#include "fabmesh/version.h"
#include "pipeline/failure.h"

namespace fabmesh::api {

const char* version() noexcept { return FABMESH_VERSION_STRING; }

namespace detail {

void rethrow_public() {
  const std::exception_ptr error = std::current_exception();
  try {
    throw;
  } catch (const Published&) {
    throw;  // already public
  } catch (const std::bad_alloc&) {
    throw;  // out of memory stays what it is
  } catch (const fabmesh::MissingFileError& e) {
    throw Public<fabmesh::MissingFileError>(e.path(), e.line(), e.column(), describe_failure(error).message,
                                            e.location());
  } catch (const fabmesh::InputError& e) {
    throw Public<fabmesh::InputError>(describe_failure(error).message, e.location());
  } catch (const fabmesh::MachineError& e) {
    throw Public<fabmesh::MachineError>(e.path(), e.error_number(), describe_failure(error).message);
  } catch (...) {
    // The same classes with the command line's whole message.
    const Failure failure = describe_failure(error);
    if (failure.exit_code == kExitInvalid) throw Public<fabmesh::ValidationFailed>(failure.message);
    throw Public<fabmesh::Error>(failure.message, failure.exit_code);
  }
}

void bad_argument(const std::string& argument, const std::string& message) {
  ErrorLocation at;
  at.key = argument;
  throw Public<fabmesh::InputError>(argument + ": " + message, std::move(at));
}

}  // namespace detail
}  // namespace fabmesh::api
