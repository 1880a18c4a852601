#pragma once
// The HTTP server of `fabmesh studio`: the page and its files, and the JSON
// API of a StudioSession, to whoever holds the session's token and names the
// server by its own address (docs/studio.md, "Security").

#include <memory>
#include <string>

#include "pipeline/studio/http_transport.h"
#include "pipeline/studio/studio_session.h"

namespace fabmesh {

struct StudioServerOptions {
  std::string host = "127.0.0.1";  ///< the address to listen on
  int port = 0;                    ///< 0: a free port, chosen by the system
  std::string token;               ///< the session's token; empty: random_token()
  /// The page's folder: index.html, studio.js, studio.css and three/ (three.js's
  /// files); read once, when the server starts. A file missing there is a 404.
  std::string web_root;
  /// How long and how much a request may take (docs/studio.md, "Limits").
  HttpLimits limits;
};

/// 32 hexadecimal digits from std::random_device (128 bits).
std::string random_token();

/// Serves one session. Answers 400 to a request with more than one Host
/// header, and 403 to every request that does not carry the token (`?token=`
/// on the page, the path /t/TOKEN/ for its files, the header X-Fabmesh-Token
/// or `?token=` on /api/), and to every request whose Host header is not
/// 127.0.0.1:PORT, localhost:PORT or HOST:PORT. Sends no CORS headers.
class StudioServer {
 public:
  /// Listens (binds) at once, on a port no other socket listens on.
  /// \throw InputError when HOST is not an address of this machine;
  ///        MachineError (exit code 5) when the port is taken or may not be
  ///        used (a port below 1024 without privileges)
  StudioServer(StudioSession& session, StudioServerOptions options);
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;
  ~StudioServer();

  int port() const;                  ///< the bound port (the chosen one for port 0)
  const std::string& token() const;  ///< the session's token
  /// The page's address with its token: http://127.0.0.1:PORT/?token=...
  std::string url() const;

  /// Serves requests until stop(); returns at once when stop() came first.
  void run();
  /// Ends run() (from any thread, e.g. one that waits for SIGTERM) and waits for it.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fabmesh
