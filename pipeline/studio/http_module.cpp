// The studio's HTTP module: the only file that includes cpp-httplib (a heavy
// header, and a library that initialises OpenSSL when it is loaded). Built as
// fabmesh-http.so and loaded only by `fabmesh studio`, so that no other run
// loads httplib, libssl and libcrypto. It binds the studio's socket itself
// (no SO_REUSEPORT), lets the reception (http_reception.h) read each request
// whole, turns it into an HttpRequest for the studio's handler with httplib's
// parser, and sends back its HttpResponse.

#include <arpa/inet.h>
#include <httplib.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <memory>

#include "pipeline/studio/http_reception.h"
#include "pipeline/studio/http_transport.h"

namespace fabmesh {
namespace {

using Clock = std::chrono::steady_clock;

// One whole request already read by the reception, and the connection its
// answer goes to (within a deadline: a client that does not read cannot
// hold the worker).
class RequestStream : public httplib::Stream {
 public:
  RequestStream(int fd, const std::string& request, Clock::time_point deadline)
      : fd_(fd), request_(request), deadline_(deadline) {}

  bool is_readable() const override { return read_ < request_.size(); }
  bool is_writable() const override { return wait_writable(); }

  ssize_t read(char* ptr, size_t size) override {
    if (read_ >= request_.size()) return -1;  // the reception gave the whole request
    const std::size_t n = std::min(size, request_.size() - read_);
    std::memcpy(ptr, request_.data() + read_, n);
    read_ += n;
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, size_t size) override {
    for (;;) {
      const ssize_t n = ::send(fd_, ptr, size, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n >= 0) return n;
      if (errno == EINTR) continue;
      if ((errno != EAGAIN && errno != EWOULDBLOCK) || !wait_writable()) return -1;
    }
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override { address(true, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address(false, ip, port); }
  socket_t socket() const override { return fd_; }

 private:
  bool wait_writable() const {
    for (;;) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - Clock::now()).count();
      if (left <= 0) return false;
      pollfd p{fd_, POLLOUT, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
      if (ready > 0) return (p.revents & POLLOUT) != 0;
      if (ready < 0 && errno != EINTR) return false;
    }
  }

  void address(bool peer, std::string& ip, int& port) const {
    sockaddr_storage a{};
    socklen_t length = sizeof a;
    const int got = peer ? ::getpeername(fd_, reinterpret_cast<sockaddr*>(&a), &length)
                         : ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &length);
    char host[NI_MAXHOST], service[NI_MAXSERV];
    if (got != 0 || ::getnameinfo(reinterpret_cast<sockaddr*>(&a), length, host, sizeof host, service,
                                  sizeof service, NI_NUMERICHOST | NI_NUMERICSERV) != 0)
      return;
    ip = host;
    port = std::atoi(service);
  }

  int fd_;
  const std::string& request_;
  std::size_t read_ = 0;
  Clock::time_point deadline_;
};

// A task queue that runs each task at once, on the accepting thread: the
// task is process_and_close_socket, which only hands the connection to the
// reception. Stopping it stops the reception.
class AdmitAtOnce : public httplib::TaskQueue {
 public:
  explicit AdmitAtOnce(HttpReception& reception) : reception_(reception) {}
  void enqueue(std::function<void()> fn) override { fn(); }
  void shutdown() override { reception_.stop(); }

 private:
  HttpReception& reception_;
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

// httplib's server with the studio's socket and reception.
class Server : public httplib::Server {
 public:
  Server(const HttpLimits& limits, HttpHandler handler)
      : limits_(limits),
        handler_(std::move(handler)),
        reception_(limits, [this](int fd, const std::string& request, bool last) {
          return serve(fd, request, last);
        }) {
    new_task_queue = [this] { return new AdmitAtOnce(reception_); };
    set_payload_max_length(limits.max_body_bytes);
    // Every path and method to the handler, once its body is read.
    const auto route = [this](const httplib::Request& req, httplib::Response& res) { answer(req, res); };
    Get(".*", route);
    Post(".*", route);
    Put(".*", route);
    Patch(".*", route);
    Delete(".*", route);
    Options(".*", route);
  }
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;
  ~Server() override {
    const socket_t sock = svr_sock_.exchange(INVALID_SOCKET);
    if (sock != INVALID_SOCKET) ::close(sock);  // bound, never served
  }

  /// Binds and listens at host:port (0: a free one); the port, or -1 with *error set.
  int bind_at(const std::string& host, int port, HttpListenError* error) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
    addrinfo* found = nullptr;
    const std::string service = std::to_string(port);
    if (const int gai = ::getaddrinfo(host.c_str(), service.c_str(), &hints, &found); gai != 0) {
      *error = {0, ::gai_strerror(gai)};
      return -1;
    }
    int sock = -1;
    for (const addrinfo* a = found; a != nullptr && sock < 0; a = a->ai_next) sock = bound_socket(*a, error);
    ::freeaddrinfo(found);
    if (sock < 0) return -1;
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    ::getsockname(sock, reinterpret_cast<sockaddr*>(&address), &length);
    svr_sock_ = sock;
    const sockaddr* s = reinterpret_cast<const sockaddr*>(&address);
    return ntohs(s->sa_family == AF_INET6 ? reinterpret_cast<const sockaddr_in6*>(s)->sin6_port
                                          : reinterpret_cast<const sockaddr_in*>(s)->sin_port);
  }

 private:
  // A socket bound to `a` and listening, or -1 with *error set. SO_REUSEADDR
  // only lets it take a port whose last connections are closing (TIME_WAIT);
  // unlike SO_REUSEPORT, it never shares a port another socket listens on.
  static int bound_socket(const addrinfo& a, HttpListenError* error) {
    const int sock = ::socket(a.ai_family, a.ai_socktype | SOCK_CLOEXEC, a.ai_protocol);
    if (sock < 0) {
      *error = {errno, std::strerror(errno)};
      return -1;
    }
    const int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    ::setsockopt(sock, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
    if (::bind(sock, a.ai_addr, a.ai_addrlen) != 0 || ::listen(sock, SOMAXCONN) != 0) {
      *error = {errno, std::strerror(errno)};
      ::close(sock);
      return -1;
    }
    return sock;
  }

  // httplib's own overridable step for an accepted connection: the reception takes it.
  bool process_and_close_socket(socket_t sock) override {
    // An answer's header and body go out as they are written: with Nagle's
    // algorithm the body waited for the browser's delayed ACK of the header
    // (40 ms on Linux), a third of a slider change's time.
    const int yes = 1;
    ::setsockopt(sock, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
    reception_.admit(sock);
    return true;
  }

  bool serve(int fd, const std::string& request, bool last) {
    RequestStream stream(fd, request,
                         Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                            std::chrono::duration<double>(limits_.answer_seconds)));
    bool closed = false;
    const bool ok = process_request(stream, last, closed, nullptr);
    return ok && !closed;
  }

  void answer(const httplib::Request& req, httplib::Response& res) {
    // httplib compresses a text or JSON answer when the browser accepts it,
    // with brotli at its highest quality: 200 ms of CPU for a plot's JSON,
    // seconds for three.js, to save nothing on this machine's loopback. The
    // studio's answers go as they are: httplib decides from the request's
    // Accept-Encoding after this handler, so the studio drops it (the request
    // is httplib's own object, not a const one).
    const_cast<httplib::Request&>(req).headers.erase("Accept-Encoding");
    const HttpResponse answer = handler_(plain(req));
    res.status = answer.status;
    for (const auto& [name, value] : answer.headers) res.set_header(name, value);
    res.set_content(answer.body, answer.content_type);
  }

  HttpLimits limits_;
  HttpHandler handler_;
  HttpReception reception_;
};

void* listen_at(const std::string& host, int port, const HttpLimits& limits, HttpHandler handler,
                int* bound_port, HttpListenError* error) {
  auto server = std::make_unique<Server>(limits, std::move(handler));
  const int bound = server->bind_at(host, port, error);
  if (bound <= 0) return nullptr;
  *bound_port = bound;
  return server.release();
}

void run(void* server) { static_cast<Server*>(server)->listen_after_bind(); }
void stop(void* server) { static_cast<Server*>(server)->stop(); }
void destroy(void* server) { delete static_cast<Server*>(server); }

}  // namespace
}  // namespace fabmesh

// The loader calls this through `const void* (*)()` (io/module.h): the type it
// is defined with, so the call is well defined; the table is a HttpModuleApi.
extern "C" __attribute__((visibility("default"))) const void* fabmesh_http_module() {
  static const fabmesh::HttpModuleApi api{fabmesh::kHttpModuleAbi, &fabmesh::listen_at, &fabmesh::run,
                                          &fabmesh::stop, &fabmesh::destroy};
  return &api;
}
