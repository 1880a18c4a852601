// The studio's reception: where a request ends in the bytes received, and
// which requests it answers itself (pipeline/studio/http_reception.h).

#include "pipeline/studio/http_reception.h"

#include <catch2/catch.hpp>
#include <string>

using namespace fabmesh;
using State = RequestExtent::State;

TEST_CASE("reception: a request is whole once its header and Content-Length bytes of body are here",
          "[studio][reception]") {
  const HttpLimits limits;
  const std::string head = "POST /api/build HTTP/1.1\r\nHost: 127.0.0.1:5\r\ncontent-length: 4\r\n\r\n";
  CHECK(request_extent("", limits).state == State::Incomplete);
  CHECK(request_extent("GET / HTTP/1.1\r\nHost: a", limits).state == State::Incomplete);
  CHECK(request_extent(head, limits).state == State::Incomplete);
  CHECK(request_extent(head + "{}", limits).state == State::Incomplete);
  const RequestExtent whole = request_extent(head + "{}{}GET", limits);  // a second request begun after it
  REQUIRE(whole.state == State::Complete);
  CHECK(whole.size == head.size() + 4);
  // Bare line feeds end a header too; no Content-Length: no body.
  const RequestExtent bare = request_extent("GET / HTTP/1.1\nHost: a\n\n", limits);
  REQUIRE(bare.state == State::Complete);
  CHECK(bare.size == 24);
}

TEST_CASE("reception: what it refuses itself, and a 100-continue it answers", "[studio][reception]") {
  HttpLimits limits;
  limits.max_body_bytes = 10;
  limits.max_head_bytes = 100;
  const auto refused = [&](const std::string& bytes) {
    const RequestExtent e = request_extent(bytes, limits);
    CHECK(e.state == State::Refused);
    return e.status;
  };
  CHECK(refused("POST / HTTP/1.1\r\nContent-Length: 11\r\n\r\n") == 413);
  CHECK(refused("GET / HTTP/1.1\r\nX: " + std::string(100, 'a')) == 431);
  CHECK(refused("POST / HTTP/1.1\r\nTransfer-Encoding: gzip\r\n\r\n") == 501);
  CHECK(refused("POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\nContent-Length: 2\r\n\r\n") == 400);
  CHECK(refused("POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n") == 400);
  CHECK(refused("POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n6\r\nabcdef\r\n6\r\nabcdef\r\n") ==
        413);
  CHECK(refused("POST / HTTP/1.1\r\nContent-Length: -1\r\n\r\n") == 400);
  CHECK(refused("POST / HTTP/1.1\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\n") == 400);
  const std::string expect = "POST / HTTP/1.1\r\nExpect: 100-continue\r\nContent-Length: 2\r\n\r\n";
  const RequestExtent e = request_extent(expect, limits);
  CHECK(e.state == State::Incomplete);
  CHECK(expect.substr(e.continue_begin, e.continue_end - e.continue_begin) == "Expect: 100-continue\r\n");
}

TEST_CASE("reception: a chunked body ends at its last chunk and the blank line after its trailer",
          "[studio][reception]") {
  const HttpLimits limits;
  const std::string head = "POST /api/build HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: chunked\r\n\r\n";
  const std::string body = "2\r\n{}\r\n3;ext=1\r\nabc\r\n0\r\n";
  for (std::size_t cut = 0; cut < body.size() + 2; ++cut)
    CHECK(request_extent(head + (body + "\r\n").substr(0, cut), limits).state == State::Incomplete);
  const RequestExtent whole = request_extent(head + body + "\r\nGET / HTTP/1.1\r\n", limits);
  REQUIRE(whole.state == State::Complete);
  CHECK(whole.size == head.size() + body.size() + 2);
  const std::string trailer = "X-Sum: 1\r\n\r\n";
  const RequestExtent with_trailer = request_extent(head + body + trailer, limits);
  REQUIRE(with_trailer.state == State::Complete);
  CHECK(with_trailer.size == head.size() + body.size() + trailer.size());
}
