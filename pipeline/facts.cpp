#include "pipeline/facts.h"

#include <algorithm>
#include <stdexcept>

namespace fabmesh {
namespace {

template <class T>
const T& typed(const Facts& facts, std::string_view name, const char* what) {
  const Facts::Value* value = facts.find(name);
  const T* typed_value = value != nullptr ? std::get_if<T>(value) : nullptr;
  if (typed_value == nullptr)
    throw std::logic_error("report fact '" + std::string(name) + "' is not " + what);
  return *typed_value;
}

}  // namespace

Facts& Facts::put(std::string_view name, Value value) {
  const auto it =
      std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
  if (it != entries_.end()) {
    it->value = std::move(value);
  } else {
    entries_.push_back({std::string(name), std::move(value)});
  }
  return *this;
}

bool Facts::empty() const { return entries_.empty(); }

const Facts::Value* Facts::find(std::string_view name) const {
  const auto it =
      std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
  return it == entries_.end() ? nullptr : &it->value;
}

double Facts::number(std::string_view name) const {
  const Value* value = find(name);
  if (value != nullptr) {
    if (const auto* whole = std::get_if<std::int64_t>(value)) return static_cast<double>(*whole);
  }
  return typed<double>(*this, name, "a number");
}

const std::string& Facts::text(std::string_view name) const {
  return typed<std::string>(*this, name, "a text");
}

const Facts& Facts::group(std::string_view name) const { return typed<Facts>(*this, name, "a group"); }

}  // namespace fabmesh
