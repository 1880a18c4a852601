#include "pipeline/failure.h"

#include <fmt/format.h>

#include <string_view>

#include "geometry/core/errors.h"

namespace fabmesh {

Failure describe_failure(const std::exception_ptr& error, const std::string& subject) {
  // A message that starts at its place in the design already keeps it.
  auto located = [&](const char* what) {
    const std::string_view text(what);
    const bool placed = text.rfind("-D ", 0) == 0 || (!subject.empty() && text.rfind(subject + ":", 0) == 0);
    return subject.empty() || placed ? std::string(what) : subject + ": " + what;
  };
  try {
    std::rethrow_exception(error);
  } catch (const FileError& e) {
    return {2, "error", e.what()};
  } catch (const GeometryError& e) {
    // A shape the design's numbers make impossible: at the curve, hole or key that
    // caused it, whose `where` is its file:line:column (or -D override) when known.
    const std::string& where = e.where();
    const bool located_in_file =
        !subject.empty() && (where.rfind(subject + ":", 0) == 0 || where.rfind("-D ", 0) == 0);
    return {2, "error", located_in_file ? where + ": " + e.what() : located(e.what())};
  } catch (const InputError& e) {
    return {2, "error", located(e.what())};
  } catch (const ValidationFailed& e) {
    return {1, "invalid", located(e.what())};
  } catch (const std::exception& e) {
    return {3, "internal error", located(e.what())};
  } catch (...) {
    return {3, "internal error", located("unknown exception")};
  }
}

std::string failure_line(const Failure& failure) {
  std::string text;
  for (const char c : failure.message) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      text += fmt::format("\\x{:02x}", u);
    } else {
      text += c;
    }
  }
  return fmt::format("fabmesh: {}: {}", failure.label, text);
}

}  // namespace fabmesh
