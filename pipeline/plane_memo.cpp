#include "pipeline/plane_memo.h"

#include <utility>

namespace fabmesh {
namespace {

template <class T>
std::size_t vector_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

std::size_t curve_bytes(const CompositeCurve& curve) { return curve.size() * sizeof(Segment); }

}  // namespace

std::size_t plane_bytes(const CountertopPlane& plane) {
  std::size_t bytes = sizeof(CountertopPlane);
  for (const NamedBuiltCurve& c : plane.curves) {
    bytes += curve_bytes(c.curve.curve) + vector_bytes(c.curve.joints) + vector_bytes(c.curve.declared) +
             vector_bytes(c.curve.segments) + vector_bytes(c.curve.through);
  }
  for (const RegionHole& h : plane.holes) bytes += curve_bytes(h.curve);
  const Region2& r = plane.region;
  bytes += vector_bytes(r.outer) + vector_bytes(r.outer_along) + r.proof.size();
  for (const auto& hole : r.holes) bytes += vector_bytes(hole);
  bytes += vector_bytes(plane.top.vertices) + vector_bytes(plane.top.triangles);
  for (const auto& cycle : plane.top.boundary) bytes += vector_bytes(cycle);
  return bytes;
}

PlaneMemo::PlaneMemo(std::size_t max_bytes) : max_bytes_(max_bytes) {}

std::shared_ptr<const CountertopPlane> PlaneMemo::find(const std::string& key) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    if (it->key != key) continue;
    entries_.splice(entries_.begin(), entries_, it);
    ++reused_;
    return entries_.front().plane;
  }
  return nullptr;
}

void PlaneMemo::keep(const std::string& key, std::shared_ptr<const CountertopPlane> plane) {
  if (plane == nullptr) return;
  const std::size_t bytes = plane_bytes(*plane) + key.size();
  if (bytes > max_bytes_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const Entry& e : entries_) {
    if (e.key == key) return;  // another build kept the same plane first
  }
  entries_.push_front({key, std::move(plane), bytes});
  bytes_ += bytes;
  while (bytes_ > max_bytes_) {
    bytes_ -= entries_.back().bytes;
    entries_.pop_back();
  }
}

std::size_t PlaneMemo::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

std::size_t PlaneMemo::reused() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return reused_;
}

}  // namespace fabmesh
