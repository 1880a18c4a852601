#include "io/pictures/preview.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/core/error_checks.h"
#include "geometry/mesh/bounding_box.h"

namespace fabmesh {
namespace {

constexpr double kDegree = M_PI / 180.0;
constexpr std::uint32_t kNoFace = std::numeric_limits<std::uint32_t>::max();
constexpr int kBandRows = 16;  // rows of the supersampled buffer rasterised by one task

// An orthographic camera: screen right, screen up, towards the viewer, and the lamp.
struct Camera {
  Vec3 right, up, toward, light;
};

Camera camera_for(const PreviewView& view) {
  const double a = view.azimuth_deg * kDegree, e = view.elevation_deg * kDegree;
  Camera c;
  c.toward = Vec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
  c.right = Vec3(-std::sin(a), std::cos(a), 0.0);
  c.up = c.toward.cross(c.right);
  c.light = (-0.4 * c.right + 0.6 * c.up + 0.7 * c.toward).normalized();
  return c;
}

// A 5 x 7 pixel font for captions: the rows of each glyph, top first, bit 4 the left column.
struct Glyph {
  char ch;
  std::array<std::uint8_t, 7> rows;
};

constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'x', {0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11}}, {' ', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}},
    {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}}, {'c', {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}},
    {'i', {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}}, {'n', {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}},
};

const Glyph* glyph(char ch) {
  for (const Glyph& g : kFont) {
    if (g.ch == ch) return &g;
  }
  return nullptr;
}

constexpr Rgb kInk{55, 55, 55};

void put(Image& image, int x, int y, const Rgb& c, double alpha) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  std::uint8_t* px = image.rgb.data() + (static_cast<std::size_t>(y) * image.width + x) * 3;
  for (int k = 0; k < 3; ++k) px[k] = static_cast<std::uint8_t>(std::lround(px[k] + alpha * (c[k] - px[k])));
}

// The caption at the bottom left, each font pixel a square of `scale` pixels.
void draw_caption(Image& image, const std::string& caption) {
  if (caption.empty()) return;
  const int scale = std::max(1, image.height / 200);
  const int x0 = 3 * scale, y0 = image.height - 10 * scale;
  for (std::size_t i = 0; i < caption.size(); ++i) {
    const Glyph& g = *glyph(caption[i]);
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 5; ++col) {
        if (((g.rows[static_cast<std::size_t>(row)] >> (4 - col)) & 1) == 0) continue;
        for (int dy = 0; dy < scale; ++dy) {
          for (int dx = 0; dx < scale; ++dx) {
            put(image, x0 + (static_cast<int>(i) * 6 + col) * scale + dx, y0 + row * scale + dy, kInk, 1.0);
          }
        }
      }
    }
  }
}

// The columns of the (supersampled) buffer that one view owns.
struct Frame {
  int x0 = 0, width = 0;
};

void validate(const TriangleSoup& soup, const PreviewOptions& o) {
  require_in_range("preview width", o.width, 16, 8192);
  require_in_range("preview height", o.height, 16, 8192);
  require_in_range("preview views", o.views, 1, 2);
  require_in_range("preview supersample", o.supersample, 1, 2);
  require_in_range("preview margin", o.margin, 0.0, 0.45);
  require_in_range("preview ambient", o.ambient, 0.0, 1.0);
  for (const PreviewView& v : {o.first, o.second}) {
    require_in_range("preview azimuth_deg", v.azimuth_deg, -360.0, 360.0);
    require_in_range("preview elevation_deg", v.elevation_deg, -89.0, 89.0);
  }
  if (o.caption.size() > 64)
    throw InputError(fmt::format("preview: the caption has {} characters; at most 64", o.caption.size()));
  for (const char ch : o.caption) {
    if (glyph(ch) == nullptr)
      throw InputError(
          fmt::format("preview: the caption's font has no '{}' (caption \"{}\")", ch, o.caption));
  }
  for (const auto& g : o.guides) {
    if (!g[0].allFinite() || !g[1].allFinite())
      throw InputError("preview: a guide line has a non-finite end");
  }
  require_indices_in_range(soup);
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    if (!soup.vertices[i].allFinite()) {
      throw InputError(fmt::format("preview: vertex {} has a non-finite coordinate", i));
    }
  }
}

// Projected extent of the vertices along the camera's right and up axes: {min, max}.
std::pair<Eigen::Vector2d, Eigen::Vector2d> projected_bounds(const TriangleSoup& soup,
                                                             const std::vector<std::array<Vec3, 2>>& guides,
                                                             const Camera& c) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  auto add = [&](const Vec3& p) {
    const Eigen::Vector2d q(p.dot(c.right), p.dot(c.up));
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  };
  for (const Vec3& p : soup.vertices) add(p);
  for (const auto& g : guides) {
    add(g[0]);
    add(g[1]);
  }
  return {lo, hi};
}

// Where a view puts model points: buffer pixels (x right, y down) and depth.
struct ViewTransform {
  Camera camera;
  Eigen::Vector2d mid;  ///< projected middle of the content
  double cx = 0.0, cy = 0.0, scale = 1.0;
  Vec3 middle;  ///< depth origin
  Vec3 project(const Vec3& q) const {
    return {cx + (q.dot(camera.right) - mid.x()) * scale, cy - (q.dot(camera.up) - mid.y()) * scale,
            (q - middle).dot(camera.toward)};
  }
};

// Vertices in buffer pixels (x right, y down) and depth (larger is nearer).
struct Projected {
  std::vector<float> x, y, z;
};

// The z-buffer of the whole (supersampled) image: nearest depth and its face.
struct DepthBuffer {
  int width = 0, height = 0;
  std::vector<float> depth;
  std::vector<std::uint32_t> face;
};

// Writes the pixels of triangle `f` whose centres it covers, within rows
// [row0, row1) and columns [col0, col1), where it is nearer than what is there.
void raster_triangle(const Projected& p, const std::array<std::uint32_t, 3>& t, std::uint32_t f, int row0,
                     int row1, int col0, int col1, DepthBuffer& buffer) {
  const float x0 = p.x[t[0]], y0 = p.y[t[0]], x1 = p.x[t[1]], y1 = p.y[t[1]], x2 = p.x[t[2]], y2 = p.y[t[2]];
  const float area = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
  if (!(area != 0.0f)) return;
  const int xa = std::max(col0, static_cast<int>(std::ceil(std::min({x0, x1, x2}) - 0.5f)));
  const int xb = std::min(col1 - 1, static_cast<int>(std::floor(std::max({x0, x1, x2}) - 0.5f)));
  const int ya = std::max(row0, static_cast<int>(std::ceil(std::min({y0, y1, y2}) - 0.5f)));
  const int yb = std::min(row1 - 1, static_cast<int>(std::floor(std::max({y0, y1, y2}) - 0.5f)));
  if (xa > xb || ya > yb) return;
  const float inv = 1.0f / area;
  const float z0 = p.z[t[0]], z1 = p.z[t[1]], z2 = p.z[t[2]];
  for (int y = ya; y <= yb; ++y) {
    const float py = static_cast<float>(y) + 0.5f;
    float* depth = buffer.depth.data() + static_cast<std::size_t>(y) * buffer.width;
    std::uint32_t* face = buffer.face.data() + static_cast<std::size_t>(y) * buffer.width;
    for (int x = xa; x <= xb; ++x) {
      const float px = static_cast<float>(x) + 0.5f;
      // Barycentric weights from the edge functions, normalised by the signed area.
      const float w0 = ((x2 - x1) * (py - y1) - (y2 - y1) * (px - x1)) * inv;
      const float w1 = ((x0 - x2) * (py - y2) - (y0 - y2) * (px - x2)) * inv;
      const float w2 = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)) * inv;
      if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) continue;
      const float z = w0 * z0 + w1 * z1 + w2 * z2;
      if (z > depth[x]) {
        depth[x] = z;
        face[x] = f;
      }
    }
  }
}

// Rasterises every triangle of `soup` seen through `camera` into the columns
// of `frame`. Triangles are binned into bands of rows; bands run in parallel
// and each band keeps the triangles' order, so the result is deterministic.
void raster_view(const TriangleSoup& soup, const Projected& p, const Frame& frame, DepthBuffer& buffer) {
  const int bands = (buffer.height + kBandRows - 1) / kBandRows;
  const std::size_t n = soup.triangles.size();
  // Band range of each triangle that covers at least one pixel centre; first = -1 for none.
  std::vector<std::int32_t> first(n), last(n);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const auto& t = soup.triangles[i];
          const float xlo = std::min({p.x[t[0]], p.x[t[1]], p.x[t[2]]});
          const float xhi = std::max({p.x[t[0]], p.x[t[1]], p.x[t[2]]});
          const float ylo = std::min({p.y[t[0]], p.y[t[1]], p.y[t[2]]});
          const float yhi = std::max({p.y[t[0]], p.y[t[1]], p.y[t[2]]});
          const int xa = std::max(frame.x0, static_cast<int>(std::ceil(xlo - 0.5f)));
          const int xb = std::min(frame.x0 + frame.width - 1, static_cast<int>(std::floor(xhi - 0.5f)));
          const int ya = std::max(0, static_cast<int>(std::ceil(ylo - 0.5f)));
          const int yb = std::min(buffer.height - 1, static_cast<int>(std::floor(yhi - 0.5f)));
          const bool covers = xa <= xb && ya <= yb;
          first[i] = covers ? ya / kBandRows : -1;
          last[i] = covers ? yb / kBandRows : -1;
        }
      });
  std::vector<std::size_t> start(static_cast<std::size_t>(bands) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::int32_t b = first[i]; b >= 0 && b <= last[i]; ++b) ++start[static_cast<std::size_t>(b) + 1];
  }
  for (int b = 0; b < bands; ++b) start[b + 1] += start[b];
  std::vector<std::uint32_t> binned(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::int32_t b = first[i]; b >= 0 && b <= last[i]; ++b)
      binned[fill[b]++] = static_cast<std::uint32_t>(i);
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& r) {
    for (int b = r.begin(); b != r.end(); ++b) {
      const int row0 = b * kBandRows, row1 = std::min(buffer.height, row0 + kBandRows);
      for (std::size_t k = start[b]; k < start[b + 1]; ++k) {
        const std::uint32_t f = binned[k];
        raster_triangle(p, soup.triangles[f], f, row0, row1, frame.x0, frame.x0 + frame.width, buffer);
      }
    }
  });
}

// The shaded colour of face `f` seen through `camera`.
Rgb shade(const TriangleSoup& soup, std::uint32_t f, const Camera& camera, const PreviewOptions& o) {
  const auto& t = soup.triangles[f];
  const Vec3& a = soup.vertices[t[0]];
  Vec3 normal = (soup.vertices[t[1]] - a).cross(soup.vertices[t[2]] - a);
  const double length = normal.norm();
  if (length > 0.0) normal /= length;
  const bool back = normal.dot(camera.toward) < 0.0;
  if (back) normal = -normal;
  // A key lamp above-left and a weaker lamp at the eye, so no face turned to the viewer is left flat.
  const double lambert = 0.75 * std::max(0.0, normal.dot(camera.light)) + 0.25 * normal.dot(camera.toward);
  const double intensity = o.ambient + (1.0 - o.ambient) * lambert;
  const Rgb& base = back ? o.back_color : o.front_color;
  Rgb c{};
  for (int k = 0; k < 3; ++k) c[k] = static_cast<std::uint8_t>(std::lround(base[k] * intensity));
  return c;
}

// Averages the supersamples of every output pixel into the image.
Image resolve(const TriangleSoup& soup, const DepthBuffer& buffer, const std::vector<Camera>& cameras,
              const std::vector<Frame>& frames, const PreviewOptions& o) {
  Image image;
  image.width = o.width;
  image.height = o.height;
  image.rgb.resize(static_cast<std::size_t>(o.width) * o.height * 3);
  const int s = o.supersample, n = s * s;
  tbb::parallel_for(tbb::blocked_range<int>(0, o.height, 8), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) {
      std::size_t view = 0;
      std::uint32_t cached = kNoFace;
      Rgb cached_color = o.background;
      for (int x = 0; x < o.width; ++x) {
        while (view + 1 < frames.size() && x * s >= frames[view + 1].x0) {
          ++view;
          cached = kNoFace;
        }
        std::array<int, 3> sum{0, 0, 0};
        for (int j = 0; j < s; ++j) {
          for (int i = 0; i < s; ++i) {
            const std::uint32_t f =
                buffer.face[static_cast<std::size_t>(y * s + j) * static_cast<std::size_t>(buffer.width) +
                            static_cast<std::size_t>(x * s + i)];
            if (f != cached) {
              cached = f;
              cached_color = f == kNoFace ? o.background : shade(soup, f, cameras[view], o);
            }
            for (int k = 0; k < 3; ++k) sum[k] += cached_color[k];
          }
        }
        std::uint8_t* out = image.rgb.data() + (static_cast<std::size_t>(y) * o.width + x) * 3;
        for (int k = 0; k < 3; ++k) out[k] = static_cast<std::uint8_t>((sum[k] + n / 2) / n);
      }
    }
  });
  return image;
}

// The guide lines, dashed, over the resolved image: a sample is hidden where
// the z-buffer holds a nearer face at its (supersampled) pixel.
void draw_guides(Image& image, const DepthBuffer& buffer, const std::vector<ViewTransform>& views,
                 const std::vector<Frame>& frames, const PreviewOptions& o) {
  const int s = o.supersample;
  const double dash = 6.0 * std::max(1, o.height / 300), period = 1.6 * dash;
  for (std::size_t v = 0; v < views.size(); ++v) {
    for (const auto& g : o.guides) {
      const Vec3 a = views[v].project(g[0]), b = views[v].project(g[1]);
      const double length = std::hypot(b.x() - a.x(), b.y() - a.y()) / s;  // output pixels
      const int steps = std::max(1, static_cast<int>(std::ceil(2.0 * length)));
      for (int i = 0; i <= steps; ++i) {
        const double t = static_cast<double>(i) / steps;
        if (std::fmod(t * length, period) > dash) continue;
        const Vec3 q = a + t * (b - a);
        const int bx = static_cast<int>(std::floor(q.x())), by = static_cast<int>(std::floor(q.y()));
        if (bx < frames[v].x0 || bx >= frames[v].x0 + frames[v].width || by < 0 || by >= buffer.height)
          continue;
        const std::size_t at = static_cast<std::size_t>(by) * static_cast<std::size_t>(buffer.width) +
                               static_cast<std::size_t>(bx);
        const bool hidden =
            buffer.face[at] != kNoFace && buffer.depth[at] > static_cast<float>(q.z()) + 1e-3f;
        const int x = bx / s, y = by / s;
        const double alpha = hidden ? 0.3 : 1.0;
        put(image, x, y, kInk, alpha);
        put(image, x + 1, y, kInk, alpha);  // two pixels wide
      }
    }
  }
}

}  // namespace

Image render_preview(const TriangleSoup& soup, const PreviewOptions& options) {
  validate(soup, options);
  const int s = options.supersample;
  DepthBuffer buffer;
  buffer.width = options.width * s;
  buffer.height = options.height * s;
  const std::size_t pixels = static_cast<std::size_t>(buffer.width) * buffer.height;
  buffer.depth.assign(pixels, -std::numeric_limits<float>::infinity());
  buffer.face.assign(pixels, kNoFace);

  std::vector<Camera> cameras{camera_for(options.first)};
  if (options.views == 2) cameras.push_back(camera_for(options.second));
  std::vector<Frame> frames;
  for (int v = 0; v < options.views; ++v) {
    const int x0 = options.width * v / options.views, x1 = options.width * (v + 1) / options.views;
    frames.push_back({x0 * s, (x1 - x0) * s});
  }
  if (soup.vertices.empty() || soup.triangles.empty()) {
    Image image = resolve(soup, buffer, cameras, frames, options);
    draw_caption(image, options.caption);
    return image;
  }

  // One scale for every view: the largest that fits each projection in its frame less the margins.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> bounds;
  double scale = std::numeric_limits<double>::infinity();
  for (std::size_t v = 0; v < cameras.size(); ++v) {
    bounds.push_back(projected_bounds(soup, options.guides, cameras[v]));
    const Eigen::Vector2d size = bounds[v].second - bounds[v].first;
    const double w = frames[v].width * (1.0 - 2.0 * options.margin);
    const double h = buffer.height * (1.0 - 2.0 * options.margin);
    if (size.x() > 0.0) scale = std::min(scale, w / size.x());
    if (size.y() > 0.0) scale = std::min(scale, h / size.y());
  }
  if (!std::isfinite(scale)) scale = 1.0;  // every vertex projects to one point

  // Depth relative to the mesh's middle keeps float precision for models far from the origin.
  const BoundingBox box = bounding_box(soup.vertices);
  const Vec3 middle = 0.5 * (box.lo + box.hi);
  Projected p;
  const std::size_t nv = soup.vertices.size();
  p.x.resize(nv);
  p.y.resize(nv);
  p.z.resize(nv);
  std::vector<ViewTransform> views;
  for (std::size_t v = 0; v < cameras.size(); ++v) {
    const ViewTransform view{cameras[v],
                             0.5 * (bounds[v].first + bounds[v].second),
                             frames[v].x0 + 0.5 * frames[v].width,
                             0.5 * buffer.height,
                             scale,
                             middle};
    views.push_back(view);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 8192),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          const Vec3 q = view.project(soup.vertices[i]);
                          p.x[i] = static_cast<float>(q.x());
                          p.y[i] = static_cast<float>(q.y());
                          p.z[i] = static_cast<float>(q.z());
                        }
                      });
    raster_view(soup, p, frames[v], buffer);
  }
  Image image = resolve(soup, buffer, cameras, frames, options);
  draw_guides(image, buffer, views, frames, options);
  draw_caption(image, options.caption);
  return image;
}

}  // namespace fabmesh
