// Who may ask and what each path answers. The HTTP itself is the module of
// pipeline/studio/http_module.cpp (cpp-httplib), loaded when a studio starts.
#include "pipeline/studio/studio_server.h"

#include <fmt/format.h>

#include <atomic>
#include <cctype>
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

}  // namespace

const std::string* find_value(const std::vector<std::pair<std::string, std::string>>& pairs,
                              const std::string& name, bool any_case) {
  for (const auto& [key, value] : pairs) {
    if (key.size() != name.size()) continue;
    bool same = true;
    for (std::size_t i = 0; i < key.size() && same; ++i) {
      same = any_case ? std::tolower(static_cast<unsigned char>(key[i])) ==
                            std::tolower(static_cast<unsigned char>(name[i]))
                      : key[i] == name[i];
    }
    if (same) return &value;
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
    }
    return json_answer(404, error_body(fmt::format("no such request: {} {}", req.method, path)));
  }

  HttpResponse handle(const HttpRequest& req) {
    HttpResponse r = allowed(req)
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
  s.server = s.http.listen(
      s.options.host, s.options.port, std::size_t{1} << 20,
      [&s](const HttpRequest& req) { return s.handle(req); }, &s.port);
  if (s.server == nullptr) {
    throw InputError(
        fmt::format("--host {} --port {}: cannot listen there (the port is taken, or the address "
                    "is not one of this machine's)",
                    s.options.host, s.options.port));
  }
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
