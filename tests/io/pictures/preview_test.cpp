#include "io/pictures/preview.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "geometry/core/errors.h"
#include "io/pictures/png.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/io/pictures/png_decode.h"

using namespace fabmesh;
using test::DecodedPng;

namespace {

bool is_background(const DecodedPng& image, int x, int y, const Rgb& background) {
  return image.at(x, y) == background;
}

// The foreground (non-background) pixels within columns [x0, x1): count, centroid and the
// largest distance of a foreground pixel centre from `centre`.
struct Blob {
  double count = 0, cx = 0, cy = 0;
};

Blob foreground(const DecodedPng& image, int x0, int x1, const Rgb& background) {
  Blob b;
  for (int y = 0; y < image.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      if (is_background(image, x, y, background)) continue;
      b.count += 1;
      b.cx += x + 0.5;
      b.cy += y + 0.5;
    }
  }
  if (b.count > 0) {
    b.cx /= b.count;
    b.cy /= b.count;
  }
  return b;
}

// Every pixel centre nearer than r - slack to (cx, cy) is foreground, every one
// farther than r + slack is background (within columns [x0, x1)).
void require_disc(const DecodedPng& image, int x0, int x1, double cx, double cy, double r, double slack,
                  const Rgb& background) {
  int wrong_inside = 0, wrong_outside = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
      const bool bg = is_background(image, x, y, background);
      if (d < r - slack && bg) ++wrong_inside;
      if (d > r + slack && !bg) ++wrong_outside;
    }
  }
  CHECK(wrong_inside == 0);
  CHECK(wrong_outside == 0);
}

TriangleSoup moved(TriangleSoup soup, const Vec3& by) {
  for (Vec3& v : soup.vertices) v += by;
  return soup;
}

}  // namespace

TEST_CASE("preview: the PNG decodes to the requested size and shows a shaded mesh",
          "[io][pictures][preview]") {
  PreviewOptions o;
  o.width = 320;
  o.height = 200;
  o.views = 2;
  const std::string png = encode_png(render_preview(test::box(Vec3(0, 0, 0), Vec3(3, 2, 1)), o));
  REQUIRE(png.substr(1, 3) == "PNG");
  const DecodedPng image = test::decode_png(png);
  CHECK(image.width == 320);
  CHECK(image.height == 200);
  std::set<std::array<std::uint8_t, 3>> colours;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) colours.insert(image.at(x, y));
  }
  // Background plus three visible faces of the box, each shaded differently.
  CHECK(colours.size() >= 4);
  CHECK(colours.count(o.background) == 1);
  CHECK(is_background(image, 0, 0, o.background));
  CHECK(is_background(image, image.width - 1, image.height - 1, o.background));
}

TEST_CASE("preview: a sphere's silhouette is a disc of the fitted radius at the frame's centre",
          "[io][pictures][preview]") {
  const double radius = 2.0;
  const TriangleSoup sphere = moved(test::sphere(radius, 192, 96), Vec3(10, -4, 7));
  for (const int supersample : {1, 2}) {
    PreviewOptions o;
    o.width = 400;
    o.height = 300;
    o.supersample = supersample;
    const DecodedPng image = test::decode_png(encode_png(render_preview(sphere, o)));
    // The projected bounding box is the sphere's diameter: it fills the height less the margins.
    const double r = 0.5 * o.height * (1.0 - 2.0 * o.margin);
    const Blob blob = foreground(image, 0, image.width, o.background);
    CHECK(blob.cx == Approx(200.0).margin(0.25));
    CHECK(blob.cy == Approx(150.0).margin(0.25));
    CHECK(blob.count == Approx(M_PI * r * r).epsilon(0.01));
    require_disc(image, 0, image.width, 200.0, 150.0, r, 1.5, o.background);
  }
}

TEST_CASE("preview: the lamp lights a sphere from the upper left", "[io][pictures][preview]") {
  PreviewOptions o;
  o.width = 200;
  o.height = 200;
  const DecodedPng image = test::decode_png(encode_png(render_preview(test::sphere(1.0, 96, 48), o)));
  int best = -1, bx = 0, by = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto c = image.at(x, y);
      if (c == o.background) continue;
      if (c[0] + c[1] + c[2] > best) {
        best = c[0] + c[1] + c[2];
        bx = x;
        by = y;
      }
    }
  }
  CHECK(bx < 100);
  CHECK(by < 100);
}

TEST_CASE("preview: two views stand side by side at one scale", "[io][pictures][preview]") {
  PreviewOptions o;
  o.width = 600;
  o.height = 250;
  o.views = 2;
  const DecodedPng image = test::decode_png(encode_png(render_preview(test::sphere(1.0, 192, 96), o)));
  const double r = 0.5 * 250 * (1.0 - 2.0 * o.margin);
  for (const int v : {0, 1}) {
    const Blob blob = foreground(image, 300 * v, 300 * (v + 1), o.background);
    CHECK(blob.cx == Approx(150.0 + 300 * v).margin(0.25));
    CHECK(blob.cy == Approx(125.0).margin(0.25));
    require_disc(image, 300 * v, 300 * (v + 1), 150.0 + 300 * v, 125.0, r, 1.5, o.background);
  }
}

TEST_CASE("preview: a mesh seen from inside shows its back faces in the back colour",
          "[io][pictures][preview]") {
  TriangleSoup inside_out = test::sphere(1.0, 48, 24);
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  PreviewOptions o;
  o.width = 100;
  o.height = 100;
  const DecodedPng image = test::decode_png(encode_png(render_preview(inside_out, o)));
  int front = 0, back = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto c = image.at(x, y);
      if (c == o.background) continue;
      (c[2] > c[0] ? back : front) += 1;
    }
  }
  CHECK(back > 1000);
  CHECK(front == 0);
}

TEST_CASE("preview: the same mesh gives the same PNG bytes every time", "[io][pictures][preview]") {
  const TriangleSoup sphere = test::sphere(1.0, 300, 150);
  PreviewOptions o;
  o.views = 2;
  o.supersample = 2;
  const std::string a = encode_png(render_preview(sphere, o));
  const std::string b = encode_png(render_preview(sphere, o));
  CHECK(a == b);
}

TEST_CASE("preview: an empty soup gives the background", "[io][pictures][preview]") {
  PreviewOptions o;
  o.width = 32;
  o.height = 16;
  const Image image = render_preview(TriangleSoup{}, o);
  REQUIRE(image.rgb.size() == 32u * 16u * 3u);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) CHECK(image.rgb[i] == o.background[i % 3]);
}

TEST_CASE("preview: bad options and bad soups are refused with typed errors", "[io][pictures][preview]") {
  const TriangleSoup box = test::box();
  PreviewOptions o;
  o.views = 3;
  CHECK_THROWS_AS(render_preview(box, o), RangeError);
  o = PreviewOptions{};
  o.width = 0;
  CHECK_THROWS_AS(render_preview(box, o), RangeError);
  o = PreviewOptions{};
  o.supersample = 4;
  CHECK_THROWS_AS(render_preview(box, o), RangeError);
  o = PreviewOptions{};
  o.first.elevation_deg = 90.0;
  CHECK_THROWS_AS(render_preview(box, o), RangeError);
  TriangleSoup bad = box;
  bad.triangles.push_back({0, 1, 99});
  CHECK_THROWS_AS(render_preview(bad, PreviewOptions{}), InputError);
  bad = box;
  bad.vertices[3].x() = std::nan("");
  CHECK_THROWS_WITH(render_preview(bad, PreviewOptions{}), Catch::Contains("vertex 3"));
}

TEST_CASE("png: an image whose bytes do not match its size is refused", "[io][pictures][png]") {
  Image image;
  image.width = 4;
  image.height = 3;
  image.rgb.resize(35);
  CHECK_THROWS_WITH(encode_png(image), Catch::Contains("36 bytes"));
  image.rgb.resize(36);
  CHECK_NOTHROW(encode_png(image));
  image.width = 0;
  CHECK_THROWS_AS(encode_png(image), RangeError);
}

TEST_CASE("preview: a caption is drawn at the bottom left and nowhere else", "[io][pictures][preview]") {
  PreviewOptions o;
  o.width = 400;
  o.height = 300;
  const TriangleSoup box = test::box(Vec3(0, 0, 0), Vec3(3, 2, 1));
  const DecodedPng plain = test::decode_png(encode_png(render_preview(box, o)));
  o.caption = "120.5 x 80 x 9 mm";
  const DecodedPng captioned = test::decode_png(encode_png(render_preview(box, o)));
  const int scale = o.height / 200;
  const int right = 3 * scale + static_cast<int>(o.caption.size()) * 6 * scale, top = o.height - 10 * scale;
  int ink = 0, elsewhere = 0;
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) {
      if (captioned.at(x, y) == plain.at(x, y)) continue;
      if (x < right && y >= top) {
        ink += captioned.at(x, y) == Rgb{55, 55, 55} ? 1 : 0;
      } else {
        ++elsewhere;
      }
    }
  }
  CHECK(ink > 100);
  CHECK(elsewhere == 0);
  o.caption = "1e-3 mm";  // the font has no 'e'
  CHECK_THROWS_AS(render_preview(box, o), InputError);
  o.caption = std::string(65, '1');
  CHECK_THROWS_AS(render_preview(box, o), InputError);
}

TEST_CASE("preview: a guide line is dashed, dark where seen, faint where the mesh hides it",
          "[io][pictures][preview]") {
  PreviewOptions o;
  o.width = 400;
  o.height = 400;
  o.margin = 0.05;
  const TriangleSoup sphere = test::sphere(1.0, 96, 48);
  const DecodedPng alone = test::decode_png(encode_png(render_preview(sphere, o)));
  o.guides.push_back({Vec3(0, 0, -2), Vec3(0, 0, 2)});
  const DecodedPng guided = test::decode_png(encode_png(render_preview(sphere, o)));
  // The guide is fitted too: the sphere is drawn smaller.
  const Blob a = foreground(alone, 0, o.width, o.background);
  const Blob g = foreground(guided, 0, o.width, o.background);
  CHECK(g.count < 0.6 * a.count);
  // The z axis projects to the frame's middle column; the sphere's disc is around the centre.
  const double radius = std::sqrt(g.count / M_PI);
  int seen = 0, dark_inside = 0, faint_inside = 0;
  for (int y = 0; y < o.height; ++y) {
    for (int x = o.width / 2 - 3; x <= o.width / 2 + 3; ++x) {
      // Within 0.85 of the disc's radius the axis is inside the sphere (it leaves it at the poles,
      // which project to 0.906 of the radius): the front of the sphere hides it there.
      const bool inside = std::hypot(x + 0.5 - 200.0, y + 0.5 - 200.0) < 0.85 * radius;
      const bool ink = guided.at(x, y) == Rgb{55, 55, 55};
      if (!inside && ink) ++seen;
      if (inside && ink) ++dark_inside;
      if (inside && !ink && !(guided.at(x, y) == alone.at(x, y))) ++faint_inside;
    }
  }
  CHECK(seen > 40);
  CHECK(dark_inside == 0);
  CHECK(faint_inside > 20);
  // Dashed: along the visible part above the sphere, ink and gaps alternate.
  int changes = 0;
  bool last = false;
  for (int y = 0; y < static_cast<int>(200.0 - radius) - 2; ++y) {
    const bool ink = guided.at(200, y) == Rgb{55, 55, 55} || guided.at(201, y) == Rgb{55, 55, 55};
    changes += y > 0 && ink != last ? 1 : 0;
    last = ink;
  }
  CHECK(changes >= 4);
  o.guides[0][1] = Vec3(0, 0, std::nan(""));
  CHECK_THROWS_AS(render_preview(sphere, o), InputError);
}
