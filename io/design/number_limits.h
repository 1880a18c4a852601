#pragma once
// Bounds on the numbers a design may hold. Private to io/design.

namespace fabmesh {

/// Largest magnitude of any number in a design or a points CSV (model
/// units, counts, budgets). Polynomial intermediates of degree up to 20 in
/// such values stay finite in double precision (1e12^20 = 1e240), so no
/// builder meets an infinity or a NaN made from finite input; larger values
/// are bad input naming the field.
inline constexpr double kMaxDesignNumber = 1e12;

/// Smallest `tolerance` a design may ask for (model units). Far below any
/// fabrication tolerance, and far enough above the smallest double that
/// unit conversions cannot underflow it to 0.
inline constexpr double kMinDesignTolerance = 1e-12;

}  // namespace fabmesh
