#pragma once
// The studio's HTTP reception: one thread waits for every connection at once
// (poll) and reads each request whole, its header and its body, before a
// worker answers it; between two requests a kept-alive connection waits
// there too. A client that sends slowly, or not at all, costs a buffer and no
// worker, so slow clients cannot starve the studio (a slow-loris attack).
// Plain POSIX sockets; the HTTP itself (parsing, routing, answers) is
// httplib's, in http_module.cpp, which links this into the module.

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "pipeline/studio/http_transport.h"

namespace fabmesh {

/// What the bytes received on a connection hold so far.
struct RequestExtent {
  enum class State {
    Incomplete,  ///< more bytes are needed
    Complete,    ///< `size` bytes are one whole request
    Refused,     ///< answer `status` and close: `reason` says why
  };
  State state = State::Incomplete;
  std::size_t size = 0;  ///< Complete: the request's bytes, header and body
  int status = 0;        ///< Refused: 400, 413, 431 or 501
  std::string reason;    ///< Refused: for the answer's message
  /// The header asks for "100 Continue" before its body: the line
  /// [continue_begin, continue_end) is that header (0, 0: none).
  std::size_t continue_begin = 0, continue_end = 0;
};

/// Where the first request in `bytes` ends, by its header's Content-Length or
/// its chunked body's last chunk (a header over limits.max_head_bytes: 431;
/// a body over limits.max_body_bytes: 413; a Transfer-Encoding other than
/// chunked: 501; a Content-Length that is not one number, or beside a
/// Transfer-Encoding, or a malformed chunk: 400).
RequestExtent request_extent(std::string_view bytes, const HttpLimits& limits);

/// Answers one whole request read from connection `fd` (`request`: its
/// bytes); `last`: the connection closes after it. Returns whether the
/// connection stays open for another request.
using RequestServer = std::function<bool(int fd, const std::string& request, bool last)>;

/// The reception and its workers (limits.workers threads running `serve`).
class HttpReception {
 public:
  /// Starts the threads.
  HttpReception(const HttpLimits& limits, RequestServer serve);
  HttpReception(const HttpReception&) = delete;
  HttpReception& operator=(const HttpReception&) = delete;
  ~HttpReception();  ///< stop()

  /// Takes an accepted connection (and closes it when done).
  void admit(int fd);
  /// Closes every waiting connection and waits for the workers to finish the
  /// requests they are answering. Requests not begun are dropped.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fabmesh
