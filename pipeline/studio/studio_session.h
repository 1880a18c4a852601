#pragma once
// What `fabmesh studio` does with a design, apart from HTTP: the answers of
// its JSON API (docs/studio.md) to request bodies, as status codes and JSON
// texts. The server (studio_server.h) only checks who asks and routes.

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace fabmesh {

struct Result;
struct OutputFormat;

/// The report of POST /api/build: `run --json`'s item of `result` (read
/// from `design_path`), less the facts only encoding gives (outputs, files,
/// skipped outputs), with "pending" naming them and the `formats` export
/// encodes. JSON text.
std::string studio_build_report(const std::string& design_path, const Result& result,
                                const std::vector<const OutputFormat*>& formats);

/// An answer of the studio's API.
struct StudioResponse {
  int status = 200;  ///< HTTP status: 200, 400 (a malformed request), 404, 422 (the design fails), 500
  std::string content_type = "application/json";
  std::string body;
};

struct StudioSessionOptions {
  std::string design_path;       ///< the design file: read on every request, written by save
  std::string out_dir = "out";   ///< where export writes the outputs (as `run -o`)
  std::size_t kept_meshes = 16;  ///< built meshes kept for GET /api/mesh/ID.glb, the newest
};

/// The parameters a design's text declares, read again only when the text
/// changes (a slider's builds all read the same text). Thread-safe.
class DeclaredNames {
 public:
  /// \throw as load_design_text, when the text does not read
  std::vector<std::string> of(const std::string& text, const std::string& path) const;

 private:
  mutable std::mutex mutex_;
  mutable bool read_ = false;  ///< text_ and names_ are set
  mutable std::string text_;
  mutable std::vector<std::string> names_;
};

/// One design open in the studio. Every method may be called from several
/// threads at once.
class StudioSession {
 public:
  /// Opens the design: reads it once so that a bad one fails here.
  /// \throw InputError (FileError naming file, line, column and field)
  explicit StudioSession(StudioSessionOptions options);
  StudioSession(const StudioSession&) = delete;
  StudioSession& operator=(const StudioSession&) = delete;
  ~StudioSession();

  /// GET /api/design: the text, name, kind, units, parameters with their
  /// ranges, the curves' shape parameters with the ranges the schema gives
  /// them, and the file's version. 422 when the file no longer reads.
  StudioResponse design() const;

  /// POST /api/build with {"overrides": {NAME or -D path: number or text}}:
  /// the run --json item, the plot's SVG, the mesh's URL and the build time.
  StudioResponse build(const std::string& request_body);

  /// GET /api/mesh/ID.glb: a mesh a build made (404 once dropped).
  StudioResponse mesh(const std::string& id) const;

  /// POST /api/export: writes the outputs with the overrides, as `run -o OUT_DIR`.
  StudioResponse export_outputs(const std::string& request_body);

  /// POST /api/save: writes the overrides' values into the design file in
  /// place of the old ones (edit_values), everything else kept.
  StudioResponse save(const std::string& request_body);

  /// POST /api/save_set with {"name": NAME, "overrides": {...}}: adds the
  /// parameter set NAME to the design file's `parameter_sets`, holding every
  /// parameter's value with the overrides applied (add_parameter_set),
  /// everything else kept. 400 for a name that is not a set's name, 422 when
  /// the design has that set already or the values do not make a design.
  StudioResponse save_set(const std::string& request_body);

  /// POST /api/fairest with {"overrides": {...}, "energy": "strain" or
  /// "curvature_variation"}: the fairest shape parameters of the design's
  /// curves for their control points as the overrides place them (the
  /// papers' fairing, as `fabmesh optimize`), as overrides by key path
  /// ({"overrides": {"profile.lambdas[0]": -0.4, ...}, "skipped": [...]}).
  /// Strain applies to quasi-B-splines, curvature variation to them and to
  /// T-Bézier curves; other curves are listed as skipped.
  StudioResponse fairest(const std::string& request_body);

  /// GET /api/version: changes when the design file changes (its
  /// modification time and size), for the page to reload.
  StudioResponse version() const;

 private:
  StudioSessionOptions options_;
  mutable std::mutex mutex_;                                ///< guards meshes_ and next_mesh_
  std::deque<std::pair<std::string, std::string>> meshes_;  ///< id, GLB bytes
  std::uint64_t next_mesh_ = 1;
  DeclaredNames names_;  ///< of the design file's text, checked against every request's plain names
};

}  // namespace fabmesh
