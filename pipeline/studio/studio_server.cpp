// Who may ask and what each path answers. The HTTP itself is the module of
// pipeline/studio/http_module.cpp (cpp-httplib), loaded when a studio starts.
#include "pipeline/studio/studio_server.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <thread>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "io/module.h"
#include "pipeline/studio/http_transport.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

// The page's files below web_root, the only ones served, and their types.
constexpr std::pair<const char*, const char*> kPageFiles[] = {
    {"studio.js", "text/javascript; charset=utf-8"},
    {"studio.css", "text/css; charset=utf-8"},
    {"three/build/three.module.js", "text/javascript; charset=utf-8"},
    {"three/examples/jsm/controls/OrbitControls.js", "text/javascript; charset=utf-8"},
    {"three/examples/jsm/loaders/GLTFLoader.js", "text/javascript; charset=utf-8"},
    {"three/examples/jsm/utils/BufferGeometryUtils.js", "text/javascript; charset=utf-8"},
};

constexpr const char* kTokenPlaceholder = "{{TOKEN}}";

struct PageFile {
  std::string bytes;
  std::string type;
};

// The files of web_root that exist, by their path below it.
std::map<std::string, PageFile> read_page_files(const std::string& web_root) {
  std::map<std::string, PageFile> files;
  for (const auto& [name, type] : kPageFiles) {
    const fs::path path = fs::path(web_root) / name;
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) files[name] = {read_file(path.string()), type};
  }
  return files;
}

// Compares without stopping at the first difference, so that the time taken
// tells nothing about how much of a guess was right.
bool same_secret(const std::string& given, const std::string& secret) {
  if (given.size() != secret.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < given.size(); ++i)
    diff = static_cast<unsigned char>(diff | (given[i] ^ secret[i]));
  return diff == 0;
}

std::string error_body(const std::string& message) {
  return nlohmann::json{{"error", {{"message", message}}}}.dump();
}

// The address as a Host header writes it (an IPv6 address in brackets).
std::string host_name(const std::string& host) {
  return host.find(':') != std::string::npos ? "[" + host + "]" : host;
}

HttpResponse json_answer(int status, std::string body) {
  HttpResponse r;
  r.status = status;
  r.body = std::move(body);
  return r;
}

HttpResponse answer(const StudioResponse& r) {
  HttpResponse out;
  out.status = r.status;
  out.body = r.body;
  out.content_type = r.content_type;
  return out;
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

// The NAME of /api/mesh/NAME.glb when it is letters and digits only, else empty.
std::string mesh_name(const std::string& path) {
  const std::string prefix = "/api/mesh/", suffix = ".glb";
  if (!starts_with(path, prefix) || path.size() <= prefix.size() + suffix.size() ||
      path.compare(path.size() - suffix.size(), suffix.size(), suffix) != 0)
    return {};
  std::string name = path.substr(prefix.size(), path.size() - prefix.size() - suffix.size());
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) return {};
  }
  return name;
}

const HttpModuleApi& http_module() {
  return required_module<HttpModuleApi>("fabmesh-http.so", "fabmesh_http_module", kHttpModuleAbi, "studio",
                                        "install fabmesh with its studio module (cpp-httplib)");
}

// Why the studio cannot listen at host:port: a host that is not an address
// of this machine is bad input (exit code 2); a port another program listens
// on, or one this user may not take, is the machine's state (exit code 5:
// the same command works once the port is free, or with another port).
[[noreturn]] void throw_listen_failure(const std::string& host, int port, const HttpListenError& error) {
  const std::string at = fmt::format("{}:{}", host_name(host), port);
  if (error.error_number == 0) {
    throw InputError(fmt::format("--host {}: not an address: {}", host, error.message));
  }
  if (error.error_number == EADDRNOTAVAIL) {
    throw InputError(fmt::format("--host {}: not an address of this machine ({})", host, error.message));
  }
  if (error.error_number == EADDRINUSE) {
    throw MachineError(
        at, error.error_number,
        fmt::format("--port {}: the port is taken: another program (another studio?) listens on {}; "
                    "end it, or choose another port (--port 0: a free one)",
                    port, at));
  }
  if (error.error_number == EACCES) {
    throw MachineError(at, error.error_number,
                       fmt::format("--port {}: permission denied to listen on {} (ports below 1024 "
                                   "need privileges; --port 0 chooses a free one)",
                                   port, at));
  }
  throw MachineError(at, error.error_number, fmt::format("cannot listen on {}: {}", at, error.message));
}

bool same_name(const std::string& a, const std::string& b, bool any_case) {
  if (!any_case) return a == b;
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// How many headers named `name` (without case) the request has.
std::size_t header_count(const HttpRequest& req, const std::string& name) {
  return static_cast<std::size_t>(std::count_if(
      req.headers.begin(), req.headers.end(), [&](const auto& h) { return same_name(h.first, name, true); }));
}

}  // namespace

const std::string* find_value(const std::vector<std::pair<std::string, std::string>>& pairs,
                              const std::string& name, bool any_case) {
  for (const auto& [key, value] : pairs) {
    if (same_name(key, name, any_case)) return &value;
  }
  return nullptr;
}

std::string random_token() {
  std::random_device device;
  std::string token;
  for (int i = 0; i < 4; ++i) token += fmt::format("{:08x}", static_cast<std::uint32_t>(device()));
  return token;
}

struct StudioServer::Impl {
  StudioSession& session;
  StudioServerOptions options;
  const HttpModuleApi& http;
  void* server = nullptr;
  int port = 0;
  std::string index_html;  ///< with the token in place
  std::map<std::string, PageFile> files;
  std::set<std::string> hosts;  ///< the Host headers accepted
  std::atomic<bool> started{false}, stopping{false}, done{false};

  Impl(StudioSession& s, StudioServerOptions o) : session(s), options(std::move(o)), http(http_module()) {}
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (server != nullptr) http.destroy(server);
  }

  bool has_token(const HttpRequest& req, bool header_allowed) const {
    const std::string* param = find_value(req.params, "token");
    if (param != nullptr && same_secret(*param, options.token)) return true;
    const std::string* header = find_value(req.headers, "X-Fabmesh-Token", true);
    return header_allowed && header != nullptr && same_secret(*header, options.token);
  }

  // Who may ask: the Host header names this server, and the request carries the token.
  bool allowed(const HttpRequest& req) const {
    const std::string* host = find_value(req.headers, "Host", true);
    if (host == nullptr || hosts.count(*host) == 0) return false;
    const std::string prefix = "/t/";
    if (starts_with(req.path, prefix)) {
      const std::size_t end = req.path.find('/', prefix.size());
      return end != std::string::npos &&
             same_secret(req.path.substr(prefix.size(), end - prefix.size()), options.token);
    }
    return has_token(req, starts_with(req.path, "/api/"));
  }

  // What a request that may ask gets.
  HttpResponse route(const HttpRequest& req) {
    const std::string& path = req.path;
    if (req.method == "GET") {
      if (path == "/") {
        HttpResponse r;
        r.headers.emplace_back(
            "Content-Security-Policy",
            "default-src 'self'; script-src 'self' 'unsafe-inline'; style-src 'self' 'unsafe-inline'; "
            "img-src 'self' data: blob:; connect-src 'self' blob: data:; frame-ancestors 'none'");
        r.body = index_html;
        r.content_type = "text/html; charset=utf-8";
        return r;
      }
      if (starts_with(path, "/t/")) {  // allowed() checked the token between the slashes
        const std::string name = path.substr(path.find('/', 3) + 1);
        const auto it = files.find(name);
        if (it == files.end()) return json_answer(404, error_body("no such file: " + name));
        HttpResponse r;
        r.body = it->second.bytes;
        r.content_type = it->second.type;
        return r;
      }
      if (path == "/api/design") return answer(session.design());
      if (path == "/api/version") return answer(session.version());
      const std::string mesh = mesh_name(path);
      if (!mesh.empty()) return answer(session.mesh(mesh));
    } else if (req.method == "POST") {
      if (path == "/api/build") return answer(session.build(req.body));
      if (path == "/api/export") return answer(session.export_outputs(req.body));
      if (path == "/api/fairest") return answer(session.fairest(req.body));
      if (path == "/api/save") return answer(session.save(req.body));
      if (path == "/api/save_set") return answer(session.save_set(req.body));
    }
    return json_answer(404, error_body(fmt::format("no such request: {} {}", req.method, path)));
  }

  HttpResponse handle(const HttpRequest& req) {
    // Two Host headers could name this server in one and another in the
    // other: which one a proxy or browser believes is not ours to guess.
    HttpResponse r = header_count(req, "Host") > 1
                         ? json_answer(400, error_body("the request has more than one Host header"))
                     : allowed(req)
                         ? route(req)
                         : json_answer(403, error_body("forbidden: this studio answers only its own "
                                                       "page (the URL it printed, with its token, at "
                                                       "127.0.0.1 or localhost)"));
    r.headers.emplace_back("Cache-Control", "no-store");
    r.headers.emplace_back("X-Content-Type-Options", "nosniff");
    r.headers.emplace_back("Referrer-Policy", "no-referrer");
    return r;
  }
};

StudioServer::StudioServer(StudioSession& session, StudioServerOptions options)
    : impl_(std::make_unique<Impl>(session, std::move(options))) {
  Impl& s = *impl_;
  if (s.options.token.empty()) s.options.token = random_token();
  s.files = read_page_files(s.options.web_root);
  const fs::path index = fs::path(s.options.web_root) / "index.html";
  std::error_code ec;
  if (fs::is_regular_file(index, ec)) {
    s.index_html = read_file(index.string());
    for (std::size_t at = s.index_html.find(kTokenPlaceholder); at != std::string::npos;
         at = s.index_html.find(kTokenPlaceholder, at))
      s.index_html.replace(at, std::string(kTokenPlaceholder).size(), s.options.token);
  } else {
    s.index_html = fmt::format(
        "<!doctype html><title>fabmesh studio</title><p>The studio's page is not installed: fabmesh looked "
        "for it in {}. The API works (docs/studio.md).</p>",
        s.options.web_root);
  }
  HttpListenError error;
  s.server = s.http.listen(
      s.options.host, s.options.port, s.options.limits,
      [&s](const HttpRequest& req) { return s.handle(req); }, &s.port, &error);
  if (s.server == nullptr) throw_listen_failure(s.options.host, s.options.port, error);
  const std::string p = std::to_string(s.port);
  s.hosts = {"127.0.0.1:" + p, "localhost:" + p, host_name(s.options.host) + ":" + p};
}

StudioServer::~StudioServer() { stop(); }

int StudioServer::port() const { return impl_->port; }

const std::string& StudioServer::token() const { return impl_->options.token; }

std::string StudioServer::url() const {
  const std::string& host = impl_->options.host;
  const bool any = host == "0.0.0.0" || host == "::";
  return fmt::format("http://{}:{}/?token={}", any ? "127.0.0.1" : host_name(host), impl_->port,
                     impl_->options.token);
}

void StudioServer::run() {
  impl_->started = true;
  if (!impl_->stopping) impl_->http.run(impl_->server);
  impl_->done = true;
}

void StudioServer::stop() {
  impl_->stopping = true;
  if (!impl_->started) return;
  // listen_after_bind may not have started listening yet: stop until run() returns.
  while (!impl_->done) {
    impl_->http.stop(impl_->server);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace fabmesh
