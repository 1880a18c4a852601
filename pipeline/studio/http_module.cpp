// The studio's HTTP module: the only file that includes cpp-httplib (a heavy
// header, and a library that initialises OpenSSL when it is loaded). Built as
// fabmesh-http.so and loaded only by `fabmesh studio`, so that no other run
// loads httplib, libssl and libcrypto. It turns every request into an
// HttpRequest for the studio's handler and sends back its HttpResponse.

#include <httplib.h>

#include <memory>

#include "pipeline/studio/http_transport.h"

namespace fabmesh {
namespace {

struct Server {
  httplib::Server http;
  HttpHandler handler;
};

HttpRequest plain(const httplib::Request& req) {
  HttpRequest r;
  r.method = req.method;
  r.path = req.path;
  r.body = req.body;
  for (const auto& [name, value] : req.params) r.params.emplace_back(name, value);
  for (const auto& [name, value] : req.headers) r.headers.emplace_back(name, value);
  return r;
}

void* listen_at(const std::string& host, int port, std::size_t max_payload, HttpHandler handler,
                int* bound_port) {
  auto server = std::make_unique<Server>();
  server->handler = std::move(handler);
  server->http.set_payload_max_length(max_payload);
  // An answer's header and body go out as they are written: with Nagle's
  // algorithm the body waited for the browser's delayed ACK of the header
  // (40 ms on Linux), a third of a slider change's time.
  server->http.set_tcp_nodelay(true);
  Server* s = server.get();
  // Every path and method to the handler, once its body is read (a
  // pre-routing handler would run before the body arrives).
  const auto serve = [s](const httplib::Request& req, httplib::Response& res) {
    // httplib compresses a text or JSON answer when the browser accepts it,
    // with brotli at its highest quality: 200 ms of CPU for a plot's JSON,
    // seconds for three.js, to save nothing on this machine's loopback. The
    // studio's answers go as they are: httplib decides from the request's
    // Accept-Encoding after this handler, so the studio drops it (the request
    // is httplib's own object, not a const one).
    const_cast<httplib::Request&>(req).headers.erase("Accept-Encoding");
    const HttpResponse answer = s->handler(plain(req));
    res.status = answer.status;
    for (const auto& [name, value] : answer.headers) res.set_header(name, value);
    res.set_content(answer.body, answer.content_type);
  };
  server->http.Get(".*", serve);
  server->http.Post(".*", serve);
  server->http.Put(".*", serve);
  server->http.Patch(".*", serve);
  server->http.Delete(".*", serve);
  server->http.Options(".*", serve);
  const int bound =
      port == 0 ? server->http.bind_to_any_port(host) : (server->http.bind_to_port(host, port) ? port : -1);
  if (bound <= 0) return nullptr;
  *bound_port = bound;
  return server.release();
}

void run(void* server) { static_cast<Server*>(server)->http.listen_after_bind(); }
void stop(void* server) { static_cast<Server*>(server)->http.stop(); }
void destroy(void* server) { delete static_cast<Server*>(server); }

}  // namespace
}  // namespace fabmesh

extern "C" __attribute__((visibility("default"))) const fabmesh::HttpModuleApi* fabmesh_http_module() {
  static const fabmesh::HttpModuleApi api{fabmesh::kHttpModuleAbi, &fabmesh::listen_at, &fabmesh::run,
                                          &fabmesh::stop, &fabmesh::destroy};
  return &api;
}
