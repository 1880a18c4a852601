#pragma once
// What the studio's HTTP module (pipeline/studio/http_module.cpp, the only
// file that includes cpp-httplib, loaded only by `fabmesh studio`) gets and
// gives: plain requests and answers. The studio decides everything (who may
// ask, what each path answers); the module only speaks HTTP.

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace fabmesh {

struct HttpRequest {
  std::string method;  ///< "GET", "POST", ...
  std::string path;    ///< without the query
  std::string body;
  std::vector<std::pair<std::string, std::string>> params;   ///< the query's, decoded
  std::vector<std::pair<std::string, std::string>> headers;  ///< as sent
};

/// The first value of `name` in `pairs` (header names compared without case
/// when `any_case`), or nullptr.
const std::string* find_value(const std::vector<std::pair<std::string, std::string>>& pairs,
                              const std::string& name, bool any_case = false);

struct HttpResponse {
  int status = 200;
  std::string body;
  std::string content_type = "application/json";
  std::vector<std::pair<std::string, std::string>> headers;
};

using HttpHandler = std::function<HttpResponse(const HttpRequest&)>;

/// The module's entry points (fabmesh_http_module returns them).
struct HttpModuleApi {
  int abi = 0;
  /// Binds host:port (port 0: a free one, written to *bound_port); null when it cannot.
  void* (*listen)(const std::string& host, int port, std::size_t max_payload, HttpHandler handler,
                  int* bound_port) = nullptr;
  void (*run)(void* server) = nullptr;   ///< serves until stop
  void (*stop)(void* server) = nullptr;  ///< from any thread
  void (*destroy)(void* server) = nullptr;
};

/// Changes whenever HttpRequest, HttpResponse or HttpModuleApi change.
inline constexpr int kHttpModuleAbi = 1;

}  // namespace fabmesh
