#pragma once
// The studio's tests share: a commented design to shape, and a studio serving
// on a free port of 127.0.0.1 in-process, asked with httplib's client.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "pipeline/studio/studio_server.h"
#include "pipeline/studio/studio_session.h"
#include "tests/pipeline/batch/batch_fixture.h"
#include "tests/pipeline/cli_harness.h"

// Last: glibc's <resolv.h>, which httplib.h includes, defines `_res`, a name Eigen's headers use.
#include <httplib.h>

namespace fabmesh::testing {

// The golden cup with its parameters, commented and laid out by hand: save
// must leave every byte but the values it changes.
inline const std::string kCommentedCup = R"(# A cup to shape in the studio.
name: studio_cup   # the file names
kind: vessel
units: cm
tolerance: 0.005
parameters:
  # the two numbers the sliders move
  height: {value: 4, min: 2, max: 10, step: 0.1, description: "foot to rim"}   # keep this comment
  width:  {value: 6,   min: 3, max: 12, step: 0.1}
  wall: 0.3          # a bare parameter
profile:
  family: quasi_bspline
  points:
    - ["=width / 4", "=2 + height"]
    - ["=width / 6", "=2 + height * 3 / 4"]
    - ["=width / 3", "=2 + height / 2"]
    - ["=width / 2", "=2 + height / 4"]
    - ["=width / 4", 2]
  lambdas: [0, 0, 0]   # shape parameters, in [-8, 1]
  fair: none
body:
  mode: shell
  wall: "=wall"
outputs: [stl, glb]
)";

// A studio on a free port of 127.0.0.1, serving on its own thread while it lives.
struct RunningStudio {
  StudioSession session;
  StudioServer server;
  std::thread thread;

  RunningStudio(const std::string& design, const std::string& out_dir, const HttpLimits& limits = {})
      : session(StudioSessionOptions{design, out_dir}), server(session, options(limits)) {
    thread = std::thread([this] { server.run(); });
  }
  RunningStudio(const RunningStudio&) = delete;
  RunningStudio& operator=(const RunningStudio&) = delete;
  ~RunningStudio() {
    server.stop();
    thread.join();
  }
  static StudioServerOptions options(const HttpLimits& limits) {
    StudioServerOptions o;
    o.web_root = FABMESH_STUDIO_PAGE_DIR;
    o.limits = limits;
    return o;
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", server.port());
    c.set_read_timeout(120, 0);
    return c;
  }
  httplib::Headers token() const { return {{"X-Fabmesh-Token", server.token()}}; }
};

inline nlohmann::json json_of(const httplib::Result& r) {
  REQUIRE(r);
  return nlohmann::json::parse(r->body);
}

inline std::filesystem::path cup_file(const std::string& test) {
  const std::filesystem::path dir = fresh_dir(test);
  write_text(dir / "cup.yaml", kCommentedCup);
  return dir / "cup.yaml";
}

}  // namespace fabmesh::testing
