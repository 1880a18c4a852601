#pragma once
// fabmesh as a library: everything a program needs, in namespace fabmesh
// (docs/library.md). No CGAL, OpenMesh or yaml-cpp type appears here; link
// the imported target fabmesh::fabmesh.

#include "fabmesh/build.h"
#include "fabmesh/curves.h"
#include "fabmesh/design.h"
#include "fabmesh/errors.h"
#include "fabmesh/mesh.h"
#include "fabmesh/repair.h"
#include "fabmesh/units.h"
#include "fabmesh/version.h"
