#include "pipeline/studio/http_reception.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace fabmesh {
namespace {

using Clock = std::chrono::steady_clock;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// How long a refused connection's further bytes are read and dropped before
// it is closed, so that the client reads the answer instead of a reset.
constexpr double kLingerSeconds = 2.0;

// The longest line that gives a chunk's size (and its extensions).
constexpr std::size_t kMaxChunkLine = 1024;

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", s);
  return text;
}

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n'))
    s.remove_suffix(1);
  return s;
}

// After the blank line that ends the header (CRLF CRLF, or bare LFs), or npos.
std::size_t head_end(std::string_view bytes) {
  for (std::size_t i = bytes.find('\n'); i != std::string_view::npos; i = bytes.find('\n', i + 1)) {
    if (i + 1 < bytes.size() && bytes[i + 1] == '\n') return i + 2;
    if (i + 2 < bytes.size() && bytes[i + 1] == '\r' && bytes[i + 2] == '\n') return i + 3;
  }
  return std::string_view::npos;
}

RequestExtent refused(int status, std::string reason) {
  RequestExtent e;
  e.state = RequestExtent::State::Refused;
  e.status = status;
  e.reason = std::move(reason);
  return e;
}

const char* status_text(int status) {
  switch (status) {
    case 400:
      return "Bad Request";
    case 408:
      return "Request Timeout";
    case 413:
      return "Payload Too Large";
    case 431:
      return "Request Header Fields Too Large";
    case 501:
      return "Not Implemented";
    default:
      return "Error";
  }
}

// A connection between requests, or while its request arrives.
struct Connection {
  int fd = -1;
  std::string bytes;           ///< received and not answered yet
  Clock::time_point deadline;  ///< of the request begun, or of the wait for one
  Clock::time_point since;     ///< waiting since (the longest waiting goes first when full)
  std::size_t served = 0;      ///< requests answered on it
  bool started = false;        ///< a byte of the next request has come
  bool ended = false;          ///< the client sends no more (end of file)
  bool refused = false;        ///< answered with an error: its bytes are dropped until it is closed
};

struct Job {
  Connection connection;
  std::string request;
};

// Sends a short error answer (best effort: it fits any socket buffer) and
// stops writing; the caller drops the connection's further bytes for a while.
void refuse(Connection& c, int status, const std::string& reason) {
  const std::string body = "{\"error\": {\"message\": \"" + reason + "\"}}";
  const std::string answer =
      "HTTP/1.1 " + std::to_string(status) + " " + status_text(status) +
      "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
      "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n" + body;
  (void)::send(c.fd, answer.data(), answer.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  ::shutdown(c.fd, SHUT_WR);
  c.refused = true;
  c.bytes.clear();
  c.deadline = Clock::now() + seconds(kLingerSeconds);
}

// What a request's header says of its body.
struct BodyHeaders {
  std::size_t length = 0;  ///< Content-Length
  bool has_length = false;
  bool chunked = false;  ///< Transfer-Encoding: chunked
  RequestExtent extent;  ///< the Expect: 100-continue line, if any
  int status = 0;        ///< a header the reception refuses: its answer's status,
  std::string problem;   ///< and why
};

BodyHeaders body_headers(std::string_view head) {
  BodyHeaders h;
  std::size_t line = head.find('\n') + 1;  // after the request line
  while (line < head.size()) {
    const std::size_t next = head.find('\n', line) + 1;
    const std::string_view header = head.substr(line, next - line);
    const std::size_t colon = header.find(':');
    const std::string_view name = trimmed(header.substr(0, colon));
    const std::string_view value = colon == std::string_view::npos ? "" : trimmed(header.substr(colon + 1));
    if (same_name(name, "Transfer-Encoding")) {
      h.chunked = same_name(value, "chunked");
      if (!h.chunked) return {0, false, false, {}, 501, "a Transfer-Encoding other than chunked"};
    } else if (same_name(name, "Content-Length")) {
      if (value.empty() || value.size() > 18 || value.find_first_not_of("0123456789") != std::string::npos)
        return {0, false, false, {}, 400, "the Content-Length is not a number"};
      const std::size_t n = std::stoull(std::string(value));
      if (h.has_length && n != h.length)
        return {0, false, false, {}, 400, "two Content-Length headers that differ"};
      h.length = n;
      h.has_length = true;
    } else if (same_name(name, "Expect") && same_name(value, "100-continue")) {
      h.extent.continue_begin = line;
      h.extent.continue_end = next;
    }
    line = next;
  }
  if (h.chunked && h.has_length)  // which one ends the body would be the reader's guess
    return {0, false, false, {}, 400, "both a Content-Length and a Transfer-Encoding"};
  return h;
}

RequestExtent too_large(const HttpLimits& limits) {
  return refused(413, "the request body is larger than " + std::to_string(limits.max_body_bytes) + " bytes");
}

// Where a chunked body that starts at `at` ends (its last chunk, size 0, and
// the trailer's blank line), as the request's extent.
RequestExtent chunked_extent(std::string_view bytes, std::size_t at, const BodyHeaders& h,
                             const HttpLimits& limits) {
  RequestExtent e = h.extent;
  std::size_t total = 0;
  for (;;) {
    const std::size_t line_end = bytes.find('\n', at);
    if (line_end == std::string_view::npos) {
      if (bytes.size() - at > kMaxChunkLine) return refused(400, "a chunk's size line is too long");
      return e;
    }
    std::string_view size_text = trimmed(bytes.substr(at, line_end - at));
    size_text = trimmed(size_text.substr(0, size_text.find(';')));
    if (size_text.empty() || size_text.size() > 15 ||
        size_text.find_first_not_of("0123456789abcdefABCDEF") != std::string_view::npos)
      return refused(400, "a chunk's size is not a hexadecimal number");
    const std::size_t size = std::stoull(std::string(size_text), nullptr, 16);
    at = line_end + 1;
    if (size == 0) break;
    total += size;
    if (total > limits.max_body_bytes) return too_large(limits);
    if (bytes.size() < at + size + 1) return e;
    at += size;
    if (bytes[at] == '\r') ++at;
    if (at >= bytes.size()) return e;
    if (bytes[at] != '\n') return refused(400, "a chunk does not end with a line end");
    ++at;
  }
  // Trailer lines, then a blank one.
  const std::size_t trailer_end = head_end(bytes.substr(at - 1));  // from the size line's end
  if (trailer_end == std::string_view::npos) {
    if (bytes.size() - at > limits.max_head_bytes)
      return refused(431, "the chunked body's trailer is too large");
    return e;
  }
  e.state = RequestExtent::State::Complete;
  e.size = at - 1 + trailer_end;
  return e;
}

}  // namespace

RequestExtent request_extent(std::string_view bytes, const HttpLimits& limits) {
  const std::size_t end = head_end(bytes);
  if ((end == std::string_view::npos && bytes.size() > limits.max_head_bytes) ||
      (end != std::string_view::npos && end > limits.max_head_bytes)) {
    return refused(431,
                   "the request's header is larger than " + std::to_string(limits.max_head_bytes) + " bytes");
  }
  if (end == std::string_view::npos) return {};
  const BodyHeaders h = body_headers(bytes.substr(0, end));
  if (!h.problem.empty()) return refused(h.status, h.problem);
  if (h.chunked) return chunked_extent(bytes, end, h, limits);
  if (h.length > limits.max_body_bytes) return too_large(limits);
  RequestExtent e = h.extent;
  if (bytes.size() - end < h.length) return e;
  e.state = RequestExtent::State::Complete;
  e.size = end + h.length;
  return e;
}

struct HttpReception::Impl {
  HttpLimits limits;
  RequestServer serve;
  int wake[2] = {-1, -1};  ///< a pipe: a byte on it wakes the poller

  std::mutex mutex;
  std::condition_variable work;
  std::vector<Connection> incoming;  ///< admitted, not yet polled (guarded by mutex)
  std::deque<Job> jobs;              ///< whole requests for the workers (guarded)
  bool stopping = false;             ///< (guarded)

  std::vector<Connection> waiting;  ///< the poller's own
  std::thread poller;
  std::vector<std::thread> workers;

  void wake_poller() const {
    const char byte = 0;
    (void)!::write(wake[1], &byte, 1);
  }

  void enter(Connection c) {
    std::unique_lock<std::mutex> lock(mutex);
    if (stopping) {
      lock.unlock();
      ::close(c.fd);
      return;
    }
    incoming.push_back(std::move(c));
    lock.unlock();
    wake_poller();
  }

  // Reads what the connection has (up to a whole request and a header more);
  // false when it is closed or fails.
  static bool receive(Connection& c, const HttpLimits& limits) {
    const std::size_t cap = limits.max_head_bytes + limits.max_body_bytes + limits.max_head_bytes;
    char buffer[16384];
    while (c.bytes.size() < cap) {
      const ssize_t n = ::recv(c.fd, buffer, sizeof buffer, MSG_DONTWAIT);
      if (n > 0) {
        if (!c.refused) c.bytes.append(buffer, static_cast<std::size_t>(n));
        continue;
      }
      if (n == 0) {
        c.ended = true;
        return true;
      }
      return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    }
    return true;
  }

  // What becomes of a connection after its bytes were read: true when it
  // leaves the waiting list (to a worker, or closed).
  bool settle(Connection& c, Clock::time_point now) {
    if (c.refused) return c.ended || now >= c.deadline;
    if (!c.started && !c.bytes.empty()) {
      c.started = true;
      c.deadline = now + seconds(limits.request_seconds);
    }
    RequestExtent e = request_extent(c.bytes, limits);
    if (e.state == RequestExtent::State::Incomplete && e.continue_end > 0) {
      // The studio answers once the whole body is here: let the client send it now.
      static constexpr char kContinue[] = "HTTP/1.1 100 Continue\r\n\r\n";
      (void)::send(c.fd, kContinue, sizeof kContinue - 1, MSG_NOSIGNAL | MSG_DONTWAIT);
      c.bytes.erase(e.continue_begin, e.continue_end - e.continue_begin);
      e = request_extent(c.bytes, limits);
    }
    if (e.state == RequestExtent::State::Complete) {
      Job job;
      job.request = c.bytes.substr(0, e.size);
      c.bytes.erase(0, e.size);
      job.connection = std::exchange(c, Connection{});  // the worker's now: c's fd is -1
      {
        const std::lock_guard<std::mutex> lock(mutex);
        jobs.push_back(std::move(job));
      }
      work.notify_one();
      return true;
    }
    if (e.state == RequestExtent::State::Refused) {
      refuse(c, e.status, e.reason);
      return c.ended;
    }
    if (c.ended) return true;
    if (now >= c.deadline) {
      if (c.started) {
        refuse(c, 408, "the request did not arrive whole within " + seconds_text(limits.request_seconds));
        return false;
      }
      return true;  // idle too long between requests
    }
    return false;
  }

  // Moves admitted connections to the waiting list; false when stopping.
  bool take_incoming() {
    const std::lock_guard<std::mutex> lock(mutex);
    if (stopping) return false;
    for (Connection& c : incoming) {
      if (waiting.size() >= limits.max_connections) {
        const auto oldest = std::min_element(waiting.begin(), waiting.end(),
                                             [](const auto& a, const auto& b) { return a.since < b.since; });
        ::close(oldest->fd);
        waiting.erase(oldest);
      }
      waiting.push_back(std::move(c));
    }
    incoming.clear();
    return true;
  }

  int poll_timeout_ms(Clock::time_point now) const {
    if (waiting.empty()) return -1;
    Clock::time_point first = waiting.front().deadline;
    for (const Connection& c : waiting) first = std::min(first, c.deadline);
    if (first <= now) return 0;
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(first - now).count() + 1;
    return static_cast<int>(std::min<long long>(ms, 60000));
  }

  void poll_loop() {
    std::vector<pollfd> fds;
    while (take_incoming()) {
      Clock::time_point now = Clock::now();
      // A connection handed back with a request already in it is settled at once.
      for (std::size_t i = waiting.size(); i-- > 0;) {
        if (settle(waiting[i], now)) drop(i);
      }
      fds.assign(1, pollfd{wake[0], POLLIN, 0});
      for (const Connection& c : waiting) fds.push_back(pollfd{c.fd, POLLIN, 0});
      if (::poll(fds.data(), fds.size(), poll_timeout_ms(now)) < 0 && errno != EINTR) break;
      if ((fds[0].revents & POLLIN) != 0) {
        char drain[64];
        while (::read(wake[0], drain, sizeof drain) == static_cast<ssize_t>(sizeof drain)) {
        }
      }
      now = Clock::now();
      for (std::size_t i = waiting.size(); i-- > 0;) {
        Connection& c = waiting[i];
        const bool readable = (fds[i + 1].revents & (POLLIN | POLLHUP | POLLERR)) != 0;
        if ((readable && !receive(c, limits)) || settle(c, now)) drop(i);
      }
    }
    for (const Connection& c : waiting) ::close(c.fd);
    waiting.clear();
  }

  // Leaves waiting[i]: closed, unless a worker took it (its fd is then -1 here).
  void drop(std::size_t i) {
    if (waiting[i].fd >= 0) ::close(waiting[i].fd);
    waiting.erase(waiting.begin() + static_cast<std::ptrdiff_t>(i));
  }

  void work_loop() {
    for (;;) {
      Job job;
      {
        std::unique_lock<std::mutex> lock(mutex);
        work.wait(lock, [&] { return stopping || !jobs.empty(); });
        if (stopping) return;
        job = std::move(jobs.front());
        jobs.pop_front();
      }
      Connection& c = job.connection;
      const bool last = c.ended || c.served + 1 >= kMaxRequestsPerConnection;
      bool keep = false;
      try {
        keep = serve(c.fd, job.request, last) && !last;
      } catch (...) {
        keep = false;
      }
      if (!keep) {
        ::close(c.fd);
        continue;
      }
      ++c.served;
      const Clock::time_point now = Clock::now();
      c.since = now;
      c.started = false;
      c.deadline = now + seconds(limits.idle_seconds);
      enter(std::move(c));
    }
  }

  static constexpr std::size_t kMaxRequestsPerConnection = 1000;
};

HttpReception::HttpReception(const HttpLimits& limits, RequestServer serve)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.limits = limits;
  s.serve = std::move(serve);
  if (::pipe2(s.wake, O_CLOEXEC | O_NONBLOCK) != 0) throw std::system_error(errno, std::generic_category());
  s.poller = std::thread([&s] { s.poll_loop(); });
  for (std::size_t i = 0; i < std::max<std::size_t>(1, limits.workers); ++i)
    s.workers.emplace_back([&s] { s.work_loop(); });
}

HttpReception::~HttpReception() {
  stop();
  ::close(impl_->wake[0]);
  ::close(impl_->wake[1]);
}

void HttpReception::admit(int fd) {
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) {
    ::close(fd);
    return;
  }
  Connection c;
  c.fd = fd;
  c.since = Clock::now();
  c.deadline = c.since + seconds(impl_->limits.idle_seconds);
  impl_->enter(std::move(c));
}

void HttpReception::stop() {
  Impl& s = *impl_;
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.stopping = true;
  }
  s.work.notify_all();
  s.wake_poller();
  if (s.poller.joinable()) s.poller.join();
  for (std::thread& t : s.workers) {
    if (t.joinable()) t.join();
  }
  const std::lock_guard<std::mutex> lock(s.mutex);
  for (const Connection& c : s.incoming) ::close(c.fd);
  s.incoming.clear();
  for (const Job& job : s.jobs) ::close(job.connection.fd);
  s.jobs.clear();
}

}  // namespace fabmesh
