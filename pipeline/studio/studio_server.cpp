// The only file that includes httplib.h (a heavy header, and a library of
// its own): nothing of it reaches a header.
#include "pipeline/studio/studio_server.h"

#include <fmt/format.h>
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <thread>

#include "geometry/core/errors.h"
#include "io/file.h"

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

}  // namespace

std::string random_token() {
  std::random_device device;
  std::string token;
  for (int i = 0; i < 4; ++i) token += fmt::format("{:08x}", static_cast<std::uint32_t>(device()));
  return token;
}

struct StudioServer::Impl {
  StudioSession& session;
  StudioServerOptions options;
  httplib::Server server;
  int port = 0;
  std::string index_html;  ///< with the token in place
  std::map<std::string, PageFile> files;
  std::set<std::string> hosts;  ///< the Host headers accepted
  std::atomic<bool> started{false}, stopping{false}, done{false};

  Impl(StudioSession& s, StudioServerOptions o) : session(s), options(std::move(o)) {}

  bool has_token(const httplib::Request& req, bool header_allowed) const {
    if (req.has_param("token") && same_secret(req.get_param_value("token"), options.token)) return true;
    return header_allowed && req.has_header("X-Fabmesh-Token") &&
           same_secret(req.get_header_value("X-Fabmesh-Token"), options.token);
  }

  // Who may ask: the Host header names this server, and the request carries the token.
  bool allowed(const httplib::Request& req) const {
    if (hosts.count(req.get_header_value("Host")) == 0) return false;
    const std::string prefix = "/t/";
    if (req.path.compare(0, prefix.size(), prefix) == 0) {
      const std::size_t end = req.path.find('/', prefix.size());
      return end != std::string::npos &&
             same_secret(req.path.substr(prefix.size(), end - prefix.size()), options.token);
    }
    return has_token(req, req.path.compare(0, 5, "/api/") == 0);
  }

  void answer(httplib::Response& res, const StudioResponse& r) {
    res.status = r.status;
    res.set_content(r.body, r.content_type.c_str());
  }

  void add_routes() {
    server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      res.set_header("Cache-Control", "no-store");
      res.set_header("X-Content-Type-Options", "nosniff");
      res.set_header("Referrer-Policy", "no-referrer");
      if (allowed(req)) return httplib::Server::HandlerResponse::Unhandled;
      res.status = 403;
      res.set_content(error_body("forbidden: this studio answers only its own page (the URL it printed, with "
                                 "its token, at 127.0.0.1 or localhost)"),
                      "application/json");
      return httplib::Server::HandlerResponse::Handled;
    });
    server.Get("/", [this](const httplib::Request&, httplib::Response& res) {
      res.set_header(
          "Content-Security-Policy",
          "default-src 'self'; script-src 'self' 'unsafe-inline'; style-src 'self' 'unsafe-inline'; "
          "img-src 'self' data: blob:; connect-src 'self' blob: data:; frame-ancestors 'none'");
      res.set_content(index_html, "text/html; charset=utf-8");
    });
    server.Get(R"(/t/[0-9a-f]+/(.+))", [this](const httplib::Request& req, httplib::Response& res) {
      const auto it = files.find(req.matches[1].str());
      if (it == files.end()) {
        res.status = 404;
        res.set_content(error_body("no such file: " + req.matches[1].str()), "application/json");
        return;
      }
      res.set_content(it->second.bytes, it->second.type.c_str());
    });
    server.Get("/api/design",
               [this](const httplib::Request&, httplib::Response& res) { answer(res, session.design()); });
    server.Get("/api/version",
               [this](const httplib::Request&, httplib::Response& res) { answer(res, session.version()); });
    server.Get(R"(/api/mesh/([A-Za-z0-9]+)\.glb)",
               [this](const httplib::Request& req, httplib::Response& res) {
                 answer(res, session.mesh(req.matches[1].str()));
               });
    server.Post("/api/build", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, session.build(req.body));
    });
    server.Post("/api/export", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, session.export_outputs(req.body));
    });
    server.Post("/api/fairest", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, session.fairest(req.body));
    });
    server.Post("/api/save", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, session.save(req.body));
    });
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
  s.server.set_payload_max_length(std::size_t{1} << 20);
  s.add_routes();
  s.port = s.options.port == 0
               ? s.server.bind_to_any_port(s.options.host)
               : (s.server.bind_to_port(s.options.host, s.options.port) ? s.options.port : -1);
  if (s.port <= 0) {
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
  if (!impl_->stopping) impl_->server.listen_after_bind();
  impl_->done = true;
}

void StudioServer::stop() {
  impl_->stopping = true;
  if (!impl_->started) return;
  // listen_after_bind may not have started listening yet: stop until run() returns.
  while (!impl_->done) {
    impl_->server.stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace fabmesh
