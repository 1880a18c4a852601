// libFuzzer entry for the DXF loop reader (io/design/dxf_loops.h, over the
// group-code reader io/dxf/dxf_reader.h): a shop's template read into closed
// loops of exact segments. It may only return closed loops with segments, or
// throw FileError; anything else (a crash, another exception, a sanitizer
// report, a hang caught by -timeout, memory for a count the input cannot
// hold) is a finding. The seeds (tests/data/fuzz-seeds/dxf) hold lines longer
// than 1024 characters, polylines without their counts, and (refused-*.dxf)
// files cut short, counts that disagree, values that are no number. Every loop it
// returns is then built as the countertop reader would, where a RangeError or
// GeometryError (a degenerate span, a joint that does not close) is a
// clean refusal.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "geometry/core/errors.h"
#include "geometry/curves/composite.h"
#include "io/design/dxf_loops.h"

namespace {

// What a reader's success promises: closed loops with segments, which build
// or are refused as the countertop reader refuses them.
void check_loops(const fabmesh::DxfLoops& loops) {
  for (const fabmesh::DxfLoop& loop : loops.loops) {
    if (!loop.curve.closed || loop.curve.segments.empty()) std::abort();
    try {
      const fabmesh::CompositeCurve curve = fabmesh::construct_curve(loop.curve);
      fabmesh::verify_declared_continuity(loop.curve, curve);
    } catch (const fabmesh::InputError&) {  // RangeError, GeometryError
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  // Every layer, and the layers the seeds use for outlines and holes.
  for (const char* layer : {"", "OUTLINE", "HOLES"}) {
    fabmesh::DxfLoopQuery query;
    query.layer = layer;
    query.max_gap = 1e-3;
    query.units = "mm";
    fabmesh::DxfLoops loops;
    try {
      loops = fabmesh::parse_dxf_loops(bytes, "fuzz-input.dxf", query);
    } catch (const fabmesh::FileError&) {
      continue;  // rejected cleanly
    }
    check_loops(loops);
  }
  return 0;
}
