#pragma once
// What a builder reports about what it made, beyond the mesh itself
// ("angular_segments": 128, "mould": {"slip_volume": ...}): typed values
// under names. A fact is added once, where it is known (a builder), and
// every report shows it through the one serializer of a job's Result
// (pipeline/result_json.h): `run --json`, batch rows, the studio, the
// library and Python.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace fabmesh {

/// Named facts, each a number, a flag, a text, a list of numbers or texts, a
/// group of facts or a list of groups. Names are unique within a group (a
/// name added again replaces the value, in place).
class Facts {
 public:
  struct Entry;
  /// A fact's value. Whole numbers stay whole (counts print as 128, not 128.0).
  using Value = std::variant<std::nullptr_t, bool, std::int64_t, double, std::string, std::vector<double>,
                             std::vector<std::string>, Facts, std::vector<Facts>>;

  /// Sets `name` to `value` (a new name at the end); returns *this. Any
  /// whole number is kept as std::int64_t, any other number as a double, a
  /// C string as a std::string.
  template <class T>
  Facts& set(std::string_view name, T&& value);

  /// The value of `name`, or nullptr when there is none.
  const Value* find(std::string_view name) const;
  bool contains(std::string_view name) const { return find(name) != nullptr; }
  /// The number under `name` (a whole number as a double). \throw std::logic_error when it is not one
  double number(std::string_view name) const;
  /// The text under `name`. \throw std::logic_error when it is not one
  const std::string& text(std::string_view name) const;
  /// The group under `name`. \throw std::logic_error when it is not one
  const Facts& group(std::string_view name) const;

  /// Every fact, in the order first set.
  const std::vector<Entry>& entries() const { return entries_; }
  bool empty() const;

 private:
  Facts& put(std::string_view name, Value value);
  std::vector<Entry> entries_;
};

/// One named fact.
struct Facts::Entry {
  std::string name;
  Value value;
};

template <class T>
Facts& Facts::set(std::string_view name, T&& value) {
  using Plain = std::decay_t<T>;
  if constexpr (std::is_same_v<Plain, bool>) {
    return put(name, Value(value));
  } else if constexpr (std::is_integral_v<Plain>) {
    return put(name, Value(static_cast<std::int64_t>(value)));
  } else if constexpr (std::is_floating_point_v<Plain>) {
    return put(name, Value(static_cast<double>(value)));
  } else if constexpr (std::is_convertible_v<T, std::string> && !std::is_same_v<Plain, std::string>) {
    return put(name, Value(std::string(value)));
  } else {
    return put(name, Value(std::forward<T>(value)));
  }
}

}  // namespace fabmesh
