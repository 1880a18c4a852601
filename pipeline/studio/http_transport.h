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
  std::vector<std::pair<std::string, std::string>> headers;  ///< as sent, every one (a name may repeat)
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

/// How long and how much a connection may take. A request is read whole
/// (its header and its body) before a worker sees it, by one thread that
/// waits for every connection at once: a client that sends slowly holds no
/// worker, and one that has not sent its whole request within
/// `request_seconds` of its first byte gets 408 and is closed.
struct HttpLimits {
  std::size_t max_body_bytes = std::size_t{1} << 20;   ///< a larger body: 413
  std::size_t max_head_bytes = std::size_t{64} << 10;  ///< request line and headers; larger: 431
  double request_seconds = 10.0;                       ///< from a request's first byte to its last
  double idle_seconds = 5.0;          ///< a kept-alive connection's wait for its next request
  double answer_seconds = 60.0;       ///< sending one answer
  std::size_t workers = 8;            ///< threads that answer whole requests
  std::size_t max_connections = 256;  ///< waiting connections; beyond, the longest waiting is closed
};

/// Why listen failed: the errno of bind or listen (EADDRINUSE, EACCES,
/// EADDRNOTAVAIL, ...), or 0 when the address is not one (then `message` says why).
struct HttpListenError {
  int error_number = 0;
  std::string message;
};

/// The module's entry points (fabmesh_http_module returns them).
struct HttpModuleApi {
  int abi = 0;
  /// Binds host:port without SO_REUSEPORT, so that a port another program
  /// listens on is refused (port 0: a free one, written to *bound_port);
  /// null when it cannot, with *error saying why.
  void* (*listen)(const std::string& host, int port, const HttpLimits& limits, HttpHandler handler,
                  int* bound_port, HttpListenError* error) = nullptr;
  void (*run)(void* server) = nullptr;   ///< serves until stop
  void (*stop)(void* server) = nullptr;  ///< from any thread
  void (*destroy)(void* server) = nullptr;
};

/// Changes whenever HttpRequest, HttpResponse, HttpLimits or HttpModuleApi change.
inline constexpr int kHttpModuleAbi = 2;

}  // namespace fabmesh
