// fabmesh studio against hostile requests (issue 43's audit): overrides that
// name files outside the design, numbers beyond a double, a port already
// taken, slow clients, repeated Host headers, designs and bodies over the
// limits, NULs in values, values that need quoting when saved, and two
// signals at once. Through real HTTP, and raw sockets for what httplib's
// client will not send.

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "pipeline/failure.h"
#include "pipeline/load_design.h"
#include "tests/pipeline/studio/studio_fixture.h"  // last: it includes httplib.h

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

// A TCP connection to 127.0.0.1:port, for requests httplib's client will not
// send (two Host headers, a header sent a byte at a time). Reads wait at most
// a minute, so that a server that never answers fails the test, not hangs it.
class RawConnection {
 public:
  explicit RawConnection(int port) : fd_(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)) {
    REQUIRE(fd_ >= 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    REQUIRE(::connect(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0);
    const timeval minute{60, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &minute, sizeof minute);
  }
  RawConnection(RawConnection&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  RawConnection& operator=(RawConnection&&) = delete;
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;
  ~RawConnection() {
    if (fd_ >= 0) ::close(fd_);
  }

  bool send(const std::string& bytes) const {
    return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
  }
  /// What the server sends until it closes the connection.
  std::string receive_all() const {
    std::string got;
    char buffer[4096];
    for (ssize_t n; (n = ::recv(fd_, buffer, sizeof buffer, 0)) > 0;)
      got.append(buffer, static_cast<std::size_t>(n));
    return got;
  }

 private:
  int fd_;
};

std::string status_line(const std::string& answer) { return answer.substr(0, answer.find("\r\n")); }

// A copy of a bundled example and the files it reads, in a folder of its own.
fs::path example_copy(const std::string& test, const std::string& name,
                      const std::vector<std::string>& files) {
  const fs::path dir = fresh_dir(test);
  for (const std::string& f : files) fs::copy_file(fs::path(example(f)), dir / f);
  fs::copy_file(fs::path(example(name)), dir / name);
  return dir / name;
}

// The body of a request overriding `key` with the JSON value `value`.
std::string overriding(const std::string& key, const Json& value) {
  return Json{{"overrides", {{key, value}}}}.dump();
}

}  // namespace

TEST_CASE("studio: an override names only files the design names, and no other file is read or quoted",
          "[studio][security]") {
  const fs::path design =
      example_copy("studio_files", "countertop_dxf_template.yaml", {"kitchen_template.dxf"});
  const std::string text = file_text(design);
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  // What the files say, none of which an answer may hold.
  const std::string passwd = file_text("/etc/passwd");
  const std::string passwd_line = passwd.substr(0, passwd.find('\n'));
  REQUIRE(passwd_line.size() > 5);
  const struct {
    std::string key;
    Json value;
    std::string field;
  } cases[] = {
      {"outline.dxf", "/etc/passwd", "overrides.outline.dxf"},
      {"outline.dxf", "../../../../../../../etc/shadow", "overrides.outline.dxf"},
      {"outline.dxf", "/proc/self/environ", "overrides.outline.dxf"},
      {"holes[0].dxf", "/etc/passwd", "overrides.holes[0].dxf"},
      {"outline.dxf", "kitchen_template.dxf/../../../../../../etc/passwd", "overrides.outline.dxf"},
      {"holes[0]", "{dxf: /etc/passwd}", "overrides.holes[0]"},
      {"holes[0]", "{dxf: ../kitchen_template.dxf, layer: HOLES}", "overrides.holes[0]"},
  };
  for (const auto& bad : cases) {
    for (const char* route : {"/api/build", "/api/export", "/api/save", "/api/fairest"}) {
      Json body = {{"overrides", {{bad.key, bad.value}}}};
      if (std::string(route) == "/api/fairest") body["energy"] = "curvature_variation";
      const auto r = c.Post(route, studio.token(), body.dump(), "application/json");
      REQUIRE(r);
      INFO(route << " " << bad.key << " = " << bad.value << ": " << r->body);
      CHECK(r->status == 400);
      CHECK(Json::parse(r->body)["error"]["field"] == bad.field);
      CHECK(r->body.find(passwd_line.substr(0, passwd_line.find(':') + 1) + "x:") == std::string::npos);
      CHECK(r->body.find("PATH=") == std::string::npos);
    }
  }
  CHECK(file_text(design) == text);
  CHECK_FALSE(fs::exists(design.parent_path() / "out"));
  // The design's own file, however it is spelled, may be named; or none at all.
  for (const auto& [key, value] : std::vector<std::pair<std::string, Json>>{
           {"holes[0].dxf", "./kitchen_template.dxf"},
           {"outline.dxf", (design.parent_path() / "kitchen_template.dxf").string()},
           {"holes[0]", "{rounded_rect: {center: [1700, 300], size: [500, 300], radius: 20}}"}}) {
    const auto r = c.Post("/api/build", studio.token(), overriding(key, value), "application/json");
    REQUIRE(r);
    INFO(key << " = " << value << ": " << r->body.substr(0, 300));
    CHECK(r->status == 200);
  }
}

TEST_CASE("studio: a points file an override names must be the design's own", "[studio][security]") {
  const fs::path design =
      example_copy("studio_points_file", "countertop_digitised.yaml", {"countertop_digitised.csv"});
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  const auto r = c.Post("/api/build", studio.token(),
                        overriding("outline.segments[0].polyline.file", "/etc/passwd"), "application/json");
  REQUIRE(r);
  CHECK(r->status == 400);
  CHECK(Json::parse(r->body)["error"]["field"] == "overrides.outline.segments[0].polyline.file");
  CHECK(r->body.find("root:") == std::string::npos);
  const auto whole =
      c.Post("/api/build", studio.token(),
             overriding("outline.segments[0]", "{polyline: {file: /etc/passwd}}"), "application/json");
  REQUIRE(whole);
  CHECK(whole->status == 400);
  CHECK(Json::parse(whole->body)["error"]["field"] == "overrides.outline.segments[0]");
  const auto same = c.Post("/api/build", studio.token(),
                           overriding("outline.segments[0].polyline", "{file: countertop_digitised.csv}"),
                           "application/json");
  REQUIRE(same);
  CHECK(same->status == 200);
}

TEST_CASE("studio: a number beyond a double's range is 400 naming its field", "[studio]") {
  const fs::path design = cup_file("studio_overflow");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  for (const auto& [body, field] : std::vector<std::pair<std::string, std::string>>{
           {R"({"overrides": {"height": 1e999}})", "overrides.height"},
           {R"({"overrides": {"width": 3, "height": -1e400}})", "overrides.height"},
           {R"({"overrides": {"profile.lambdas[1]": 2e308}})", "overrides.profile.lambdas[1]"},
           {R"({"draft": 1e999})", "draft"}}) {
    const auto r = c.Post("/api/build", studio.token(), body, "application/json");
    REQUIRE(r);
    INFO(body << ": " << r->body);
    CHECK(r->status == 400);
    const Json e = Json::parse(r->body)["error"];
    CHECK(e["field"] == field);
    CHECK(e["message"].get<std::string>().find(field) != std::string::npos);
  }
}

TEST_CASE("studio: a port another studio listens on is refused, with exit code 5", "[studio]") {
  const fs::path design = cup_file("studio_port_taken");
  RunningStudio first(design.string(), (design.parent_path() / "out").string());
  StudioServerOptions options = RunningStudio::options({});
  options.port = first.server.port();
  REQUIRE_THROWS_AS(StudioServer(first.session, options), MachineError);
  try {
    StudioServer second(first.session, options);
  } catch (...) {
    const Failure f = describe_failure(std::current_exception());
    CHECK(f.exit_code == kExitEnvironment);
    CHECK(f.message.find("the port is taken") != std::string::npos);
  }
  std::string output;
  CHECK(run_cli({"studio", "--no-open", "--port", std::to_string(first.server.port()), design.string()},
                &output) == kExitEnvironment);
  CHECK(output.find("--port " + std::to_string(first.server.port()) + ": the port is taken") !=
        std::string::npos);
  // An address that is not this machine's (TEST-NET-1, RFC 5737) is bad input.
  options.port = 0;
  options.host = "192.0.2.1";
  CHECK_THROWS_AS(StudioServer(first.session, options), InputError);
  // Every request still goes to the first studio, and it answers each.
  httplib::Client c = first.client();
  for (int i = 0; i < 32; ++i) CHECK(c.Get("/api/version", first.token())->status == 200);
}

TEST_CASE("studio: clients that send slowly hold no worker, and a request begun and not finished gets 408",
          "[studio][security]") {
  const fs::path design = cup_file("studio_slow");
  HttpLimits patient;
  patient.request_seconds = 3600;  // the slow ones stay for the whole test
  RunningStudio studio(design.string(), (design.parent_path() / "out").string(), patient);
  const std::string port = std::to_string(studio.server.port());
  // Far more slow connections than workers, each sending its header a byte at a time.
  std::vector<RawConnection> slow;
  for (int i = 0; i < 48; ++i) {
    slow.emplace_back(studio.server.port());
    REQUIRE(slow.back().send("GET /api/version HTTP/1.1\r\nHost: 127.0.0.1:" + port + "\r\nX-Slow: "));
  }
  std::atomic<bool> done{false};
  std::thread trickle([&] {
    while (!done) {
      for (const RawConnection& s : slow) (void)s.send("a");
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  httplib::Client c = studio.client();
  c.set_read_timeout(60, 0);
  const auto answered = c.Get("/api/version", studio.token());
  done = true;
  trickle.join();
  REQUIRE(answered);
  CHECK(answered->status == 200);

  HttpLimits brief;
  brief.request_seconds = 1;
  RunningStudio strict(design.string(), (design.parent_path() / "out").string(), brief);
  const RawConnection half(strict.server.port());
  REQUIRE(half.send("GET /api/version HTTP/1.1\r\nHost: 127.0.0.1:"));
  const std::string answer = half.receive_all();
  CHECK(status_line(answer) == "HTTP/1.1 408 Request Timeout");
  CHECK(answer.find("did not arrive whole within 1 s") != std::string::npos);
}

TEST_CASE("studio: a request with two Host headers is 400, whichever comes first", "[studio][security]") {
  const fs::path design = cup_file("studio_two_hosts");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  const std::string own = "Host: 127.0.0.1:" + std::to_string(studio.server.port()) + "\r\n";
  const std::string other = "Host: evil.example\r\n";
  const std::string token = "X-Fabmesh-Token: " + studio.server.token() + "\r\n";
  for (const std::string& hosts : {own + other, other + own, own + own}) {
    const RawConnection r(studio.server.port());
    REQUIRE(r.send("GET /api/design HTTP/1.1\r\n" + hosts + token + "Connection: close\r\n\r\n"));
    const std::string answer = r.receive_all();
    INFO(hosts);
    CHECK(status_line(answer) == "HTTP/1.1 400 Bad Request");
    CHECK(answer.find("more than one Host header") != std::string::npos);
  }
  const RawConnection one(studio.server.port());
  REQUIRE(one.send("GET /api/version HTTP/1.1\r\n" + own + token + "Connection: close\r\n\r\n"));
  CHECK(status_line(one.receive_all()) == "HTTP/1.1 200 OK");
}

TEST_CASE("studio: a design over the size every command reads is refused, and request bodies are bounded",
          "[studio]") {
  const fs::path design = cup_file("studio_big");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  // The file grows past 16 MiB while the studio runs (a comment: still a valid design).
  write_text(design, kCommentedCup + "# " + std::string(kMaxDesignFileBytes, 'x') + "\n");
  std::string output;
  CHECK(run_cli({"run", "-q", design.string(), "-o", (design.parent_path() / "run").string()}, &output) ==
        kExitBadInput);
  const auto shown = c.Get("/api/design", studio.token());
  REQUIRE(shown);
  CHECK(shown->status == 422);
  CHECK(shown->body.find("is larger than 16777216 bytes") != std::string::npos);
  const auto built = c.Post("/api/build", studio.token(), "{}", "application/json");
  REQUIRE(built);
  CHECK(built->status == 422);
  // A request body over the documented 1 MiB is 413, before the studio reads it.
  write_text(design, kCommentedCup);
  const std::string huge =
      R"({"overrides": {"height": ")" + std::string(HttpLimits{}.max_body_bytes, '1') + "\"}}";
  const auto big = c.Post("/api/build", studio.token(), huge, "application/json");
  REQUIRE(big);
  CHECK(big->status == 413);
  CHECK(c.Post("/api/build", studio.token(), "{}", "application/json")->status == 200);
  // A body sent in chunks (as Node's http client sends one) is read whole too.
  const RawConnection chunked(studio.server.port());
  REQUIRE(chunked.send("POST /api/build HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(studio.server.port()) +
                       "\r\nX-Fabmesh-Token: " + studio.server.token() +
                       "\r\nTransfer-Encoding: chunked\r\nConnection: close\r\n\r\n"
                       "e\r\n{\"overrides\": \r\n10\r\n{\"height\": 5.5}}\r\n0\r\n\r\n"));
  const std::string answer = chunked.receive_all();
  CHECK(status_line(answer) == "HTTP/1.1 200 OK");
  CHECK(answer.find("\"height\":5.5") != std::string::npos);
}

TEST_CASE("studio: a NUL in an override is shown escaped, and the message whole", "[studio]") {
  const fs::path design = cup_file("studio_nul");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  for (const std::string key : {"height", "body.wall", "profile.points[0]"}) {
    const auto r = c.Post("/api/build", studio.token(), overriding(key, std::string("5\0 and the rest", 15)),
                          "application/json");
    REQUIRE(r);
    INFO(r->body);
    CHECK(r->status == 422);
    const std::string message = Json::parse(r->body)["error"]["message"];
    CHECK(message.find('\0') == std::string::npos);
    CHECK(message == "-D " + key +
                         "=5\\x00 and the rest: the value holds a control character (\\x00, byte 2), "
                         "which YAML does not allow");
  }
}

TEST_CASE("studio: save writes values that need quoting as valid YAML, which reads back to every value",
          "[studio]") {
  const fs::path design = cup_file("studio_save_quoted");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  const Json overrides = {
      {"height", "=max(width, 5)"},              // into a flow map: its comma would end the value
      {"width", "=min(8, 3 + 4)"},               // the same, and parentheses
      {"wall", "=min(width, 5) / 20"},           // a block value with a comment after it
      {"profile.lambdas[1]", "=max(-1, -0.5)"},  // into a flow list
      {"profile.points[4][0]", "=width / 4"},    // a list in a block list
      {"body.wall", "\"=wall\""},                // already quoted: written as given
  };
  const auto saved =
      c.Post("/api/save", studio.token(), Json{{"overrides", overrides}}.dump(), "application/json");
  REQUIRE(saved);
  INFO(saved->body);
  REQUIRE(saved->status == 200);
  const std::string text = file_text(design);
  INFO(text);
  // Everything else as it was.
  for (const char* kept : {"# keep this comment", "# a bare parameter", "# shape parameters, in [-8, 1]",
                           "step: 0.1, description: \"foot to rim\"}", "body:\n  mode: shell\n"})
    CHECK(text.find(kept) != std::string::npos);
  // The design reader reads the saved file to the values the overrides give.
  std::vector<Override> given;
  for (const auto& [key, value] : overrides.items())
    given.push_back(make_override(key, value.get<std::string>()));
  write_text(design.parent_path() / "original.yaml", kCommentedCup);
  const Design expected = load_design((design.parent_path() / "original.yaml").string(), given);
  const Design read = load_design(design.string());
  REQUIRE(read.common.parameters.size() == expected.common.parameters.size());
  for (std::size_t i = 0; i < read.common.parameters.size(); ++i) {
    CHECK(read.common.parameters[i].name == expected.common.parameters[i].name);
    CHECK(read.common.parameters[i].value == expected.common.parameters[i].value);
  }
  const auto& vessel = std::get<VesselDesign>(read.body);
  const auto& wanted = std::get<VesselDesign>(expected.body);
  CHECK(vessel.profile.bspline_lambdas == wanted.profile.bspline_lambdas);
  CHECK(vessel.profile.bspline_points == wanted.profile.bspline_points);
  CHECK(vessel.wall == wanted.wall);
  CHECK(vessel.profile.bspline_lambdas[1] == -0.5);
  CHECK(read.common.parameters[0].value == 7.0);  // height = max(width, 5), width = min(8, 7)
}

TEST_CASE("studio: a second SIGTERM while the studio stops still ends it with exit code 0", "[studio]") {
  // A cup at a tolerance fine enough that its build takes seconds (3.8 million triangles).
  const fs::path design = cup_file("studio_two_signals");
  std::string slow = kCommentedCup;
  slow.replace(slow.find("tolerance: 0.005"), 16, "tolerance: 0.00002");
  write_text(design, slow);
  for (int round = 0; round < 3; ++round) {
    // The studio as a program of its own, its first line (the address) read from a pipe.
    int out[2];
    REQUIRE(::pipe2(out, O_CLOEXEC) == 0);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    std::string program = FABMESH_BINARY, command = "studio", no_open = "--no-open", file = design.string(),
                o = "-o", out_dir = (design.parent_path() / "out").string();
    char* argv[] = {program.data(), command.data(), no_open.data(), file.data(),
                    o.data(),       out_dir.data(), nullptr};
    pid_t pid = -1;
    REQUIRE(posix_spawn(&pid, program.c_str(), &actions, nullptr, argv, environ) == 0);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    std::string line;
    for (char ch; line.find('\n') == std::string::npos && ::read(out[0], &ch, 1) == 1;) line += ch;
    ::close(out[0]);
    const std::size_t colon = line.find(':', 7), slash = line.find('/', colon);
    REQUIRE(slash != std::string::npos);
    const int port = std::stoi(line.substr(colon + 1, slash - colon - 1));
    const std::string token = line.substr(line.find("token=") + 6, 32);
    // A build in progress makes the stop wait for it: the second signal comes while it stops.
    std::thread build([&] {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(300, 0);
      (void)c.Post("/api/build", {{"X-Fabmesh-Token", token}}, "{}", "application/json");
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    REQUIRE(::kill(pid, SIGTERM) == 0);
    // Stopping: the studio no longer accepts connections.
    for (bool listening = true; listening;) {
      const int probe = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_port = htons(static_cast<std::uint16_t>(port));
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      listening = ::connect(probe, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0;
      ::close(probe);
    }
    (void)::kill(pid, SIGTERM);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    build.join();
    INFO("round " << round);
    CHECK(WIFEXITED(status));
    CHECK((WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status)) == 0);
  }
}
