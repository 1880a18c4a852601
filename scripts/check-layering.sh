#!/usr/bin/env bash
# Fails when the code breaks the layering of docs/architecture.md (pipeline -> io
# -> geometry, never back), includes CGAL from a header (every includer would
# compile it), or includes the private YAML readers (yaml-cpp is a private
# dependency of fabmesh::io) from outside io/design, or muparser from anywhere but
# io/design/expression.cpp, or cpp-httplib from anywhere but the studio's server
# (pipeline/studio/http_module.cpp, a module loaded by `fabmesh studio` only; its tests use its client), or OpenCASCADE
# from anywhere but the STEP module (io/step/step_occt.cpp, loaded on demand), or includes the private
# parts of validation (geometry/validation/detail/: only validate.h is public;
# tests and benchmarks may check them) from outside geometry/validation.
set -euo pipefail
cd "$(dirname "$0")/.."
status=0
complain() { echo "check-layering: $*"; status=1; }

while IFS= read -r hit; do complain "geometry depends on io/pipeline: $hit"; done \
  < <(grep -rnE '#include "(io|pipeline)/' geometry || true)
while IFS= read -r hit; do complain "io depends on pipeline: $hit"; done \
  < <(grep -rnE '#include "pipeline/' io || true)
while IFS= read -r hit; do complain "curves depend on fairing (fairing builds on curves): $hit"; done \
  < <(grep -rnE '#include "geometry/fairing/' geometry/curves || true)
while IFS= read -r hit; do complain "an encoder reads the design: $hit"; done \
  < <(grep -rnE '#include "io/design/' io/mesh io/cutting io/pictures || true)
while IFS= read -r hit; do complain "an encoder builds geometry (builders return it): $hit"; done \
  < <(grep -rnE '\b(build_curve|construct_curve|build_patch_network|cut_loop|fair_[a-z_]+)\(' io/mesh io/cutting io/pictures || true)
while IFS= read -r hit; do complain "CGAL in a header: $hit"; done \
  < <(grep -rnE '#include <CGAL/' --include='*.h' geometry io pipeline || true)
while IFS= read -r hit; do complain "private YAML reader used outside io/design: $hit"; done \
  < <(grep -rnE '#include "io/design/yaml/' geometry io pipeline tests bench fuzz 2>/dev/null | grep -v '^io/design/' || true)
while IFS= read -r hit; do complain "yaml-cpp outside io/design: $hit"; done \
  < <(grep -rnE '#include <yaml-cpp/' geometry io pipeline 2>/dev/null | grep -v '^io/design/' || true)
while IFS= read -r hit; do complain "muparser outside io/design/expression.cpp: $hit"; done \
  < <(grep -rnE '#include <muParser' geometry io pipeline api python tests bench fuzz 2>/dev/null | grep -v '^io/design/expression\.cpp:' || true)
while IFS= read -r hit; do complain "cpp-httplib outside pipeline/studio/http_module.cpp: $hit"; done \
  < <(grep -rnE '#include <httplib' geometry io pipeline api python bench fuzz 2>/dev/null | grep -v '^pipeline/studio/http_module\.cpp:' || true)
while IFS= read -r hit; do complain "OpenCASCADE outside io/step/step_occt.cpp: $hit"; done \
  < <(grep -rnE '#include <[A-Za-z0-9]+_?[A-Za-z0-9_]*\.hxx>' geometry io pipeline api python tests bench fuzz 2>/dev/null | grep -v '^io/step/step_occt\.cpp:' || true)
while IFS= read -r hit; do complain "validation's private parts used outside geometry/validation: $hit"; done \
  < <(grep -rnE '#include "geometry/validation/detail/' geometry io pipeline 2>/dev/null | grep -v '^geometry/validation/' || true)

while IFS= read -r hit; do complain "a layer below api/ includes the public headers: $hit"; done \
  < <(grep -rnE '#include [<"]fabmesh/' geometry io pipeline 2>/dev/null || true)
while IFS= read -r hit; do complain "a public header includes more than the standard library: $hit"; done \
  < <(grep -rnE '#include ' api/include 2>/dev/null | grep -vE '#include ("fabmesh/[a-z_]+\.h"|<[a-z_]+>)' || true)
while IFS= read -r hit; do complain "the Python module reaches past the public headers: $hit"; done \
  < <(grep -rnE '#include "' python 2>/dev/null | grep -vE '#include "python/[a-z_]+\.h"' || true)

[[ $status -eq 0 ]] && echo "check-layering: python -> api -> pipeline -> io -> geometry holds; encoders see built data only; CGAL, yaml-cpp, muparser, httplib, OpenCASCADE and validation/detail stay private"
exit $status
