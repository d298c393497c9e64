#include "srp/rawlog/DepthRegistration.h"

#include <algorithm>
#include <cmath>

#include "srp/core/Error.h"

namespace srp::rawlog {
namespace {

// Neighbouring depth pixels belong to one surface when their depths differ by
// less than a plane seen at atan(kMaxSlope) = 76 degrees from its normal
// would make them (over 1.5 pixel, the diagonal with margin) plus sensor
// noise; larger jumps are silhouettes and are not bridged.
constexpr double kMaxSlope = 4.0;
constexpr double kRelativeNoise = 0.005;
// Triangles wider than this in the colour image are not one surface patch
// seen from two nearby cameras (e.g. grazing views): skipped.
constexpr int kMaxTriangleSpan_px = 64;

struct Projected {
  float u, v, z;  // colour pixel and depth along the colour axis; z = 0: none
};

/// The largest depth step between neighbouring pixels of one surface at depth `d` (focal length fMin).
double jumpTolerance(double d, double fMin) { return d * (kMaxSlope * 1.5 / fMin + kRelativeNoise); }

void keepNearest(float& cell, float z) {
  if (cell <= 0.f || z < cell) cell = z;
}

/// A triangle between continuous neighbours into `mesh`, 1/Z interpolated (exact for planes).
void rasteriseTriangle(cv::Mat& mesh, const Projected& a, const Projected& b, const Projected& c) {
  const int Wc = mesh.cols, Hc = mesh.rows;
  const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.u, b.u, c.u}))));
  const int x1 = std::min(Wc - 1, static_cast<int>(std::floor(std::max({a.u, b.u, c.u}))));
  const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.v, b.v, c.v}))));
  const int y1 = std::min(Hc - 1, static_cast<int>(std::floor(std::max({a.v, b.v, c.v}))));
  if (x1 < x0 || y1 < y0 || x1 - x0 > kMaxTriangleSpan_px || y1 - y0 > kMaxTriangleSpan_px) return;
  const double area = (double(b.u) - a.u) * (double(c.v) - a.v) - (double(c.u) - a.u) * (double(b.v) - a.v);
  if (std::abs(area) < 1e-9) return;
  const double ia = 1.0 / a.z, ib = 1.0 / b.z, ic = 1.0 / c.z;
  constexpr double kEdgeEps = -1e-7;  // shared edges belong to both triangles
  for (int y = y0; y <= y1; ++y) {
    float* row = mesh.ptr<float>(y);
    for (int x = x0; x <= x1; ++x) {
      const double wa = ((double(b.u) - x) * (double(c.v) - y) - (double(c.u) - x) * (double(b.v) - y)) / area;
      const double wb = ((double(c.u) - x) * (double(a.v) - y) - (double(a.u) - x) * (double(c.v) - y)) / area;
      const double wc = 1.0 - wa - wb;
      if (wa < kEdgeEps || wb < kEdgeEps || wc < kEdgeEps) continue;
      keepNearest(row[x], static_cast<float>(1.0 / (wa * ia + wb * ib + wc * ic)));
    }
  }
}

/// Inside a continuous surface the triangles of the four quads around a pixel tile its footprint
/// already: true when pixel (r, c) of the W x H depth image is such an interior pixel.
bool interiorPixel(const std::vector<Projected>& centres, int r, int c, int W, int H, double fMin) {
  if (!(r > 0 && c > 0 && r + 1 < H && c + 1 < W)) return false;
  const Projected& centre = centres[static_cast<std::size_t>(r) * W + c];
  const float tol = static_cast<float>(0.45 * jumpTolerance(centre.z, fMin));
  bool interior = true;
  for (int dr = -1; dr <= 1 && interior; ++dr)
    for (int dc = -1; dc <= 1 && interior; ++dc) {
      const float z = centres[static_cast<std::size_t>(r + dr) * W + c + dc].z;
      interior = z > 0.f && std::abs(z - centre.z) <= tol;
    }
  return interior;
}

/// The footprint of depth pixel (r, c) is tilted like its surface: the depth gradient (gu, gv) in colour
/// pixels from one continuous neighbour across and one down (or up), and the range [zLo, zHi] of the
/// depths it was estimated from (no extrapolation beyond them: edges of boxes).
struct Tilt {
  double gu = 0.0, gv = 0.0;
  float zLo, zHi;
};

Tilt footprintTilt(const std::vector<Projected>& centres, int r, int c, int W, int H, double fMin) {
  const Projected& centre = centres[static_cast<std::size_t>(r) * W + c];
  Tilt tilt;
  const auto neighbour = [&](int dc, int dr) -> const Projected* {
    const int cc = c + dc, rr = r + dr;
    if (cc < 0 || rr < 0 || cc >= W || rr >= H) return nullptr;
    const Projected& p = centres[static_cast<std::size_t>(rr) * W + cc];
    return p.z > 0.f && std::abs(p.z - centre.z) <= jumpTolerance(std::min(p.z, centre.z), fMin) ? &p : nullptr;
  };
  const Projected* a = neighbour(1, 0);
  if (!a) a = neighbour(-1, 0);
  const Projected* b = neighbour(0, 1);
  if (!b) b = neighbour(0, -1);
  if (a && b) {
    const double du1 = a->u - centre.u, dv1 = a->v - centre.v, dz1 = a->z - centre.z;
    const double du2 = b->u - centre.u, dv2 = b->v - centre.v, dz2 = b->z - centre.z;
    const double det = du1 * dv2 - du2 * dv1;
    if (std::abs(det) > 1e-6) {
      tilt.gu = (dz1 * dv2 - dz2 * dv1) / det;
      tilt.gv = (du1 * dz2 - du2 * dz1) / det;
    }
  }
  tilt.zLo = std::min({centre.z, a ? a->z : centre.z, b ? b->z : centre.z});
  tilt.zHi = std::max({centre.z, a ? a->z : centre.z, b ? b->z : centre.z});
  return tilt;
}

/// Footprint splats into `splat`: every colour pixel centre inside the projected depth pixel (its
/// corners through `project`), at borders, holes and jumps only (see interiorPixel).
template <typename Project>
void splatFootprints(cv::Mat& splat, const cv::Mat& depth_m, const std::vector<Projected>& centres,
                     const std::vector<Eigen::Vector2f>& cornerRays, const Project& project, double fMin) {
  const int W = depth_m.cols, H = depth_m.rows, Wc = splat.cols, Hc = splat.rows;
  for (int r = 0; r < H; ++r) {
    const float* d = depth_m.ptr<float>(r);
    for (int c = 0; c < W; ++c) {
      const Projected& centre = centres[static_cast<std::size_t>(r) * W + c];
      if (centre.z <= 0.f) continue;
      if (interiorPixel(centres, r, c, W, H, fMin)) continue;
      float uMin = 1e9f, uMax = -1e9f, vMin = 1e9f, vMax = -1e9f;
      bool ok = true;
      for (const auto& [dc, dr] : {std::pair{0, 0}, {1, 0}, {0, 1}, {1, 1}}) {
        Projected p;
        if (!project(cornerRays[static_cast<std::size_t>(r + dr) * (W + 1) + c + dc], d[c], p)) {
          ok = false;
          break;
        }
        uMin = std::min(uMin, p.u), uMax = std::max(uMax, p.u), vMin = std::min(vMin, p.v), vMax = std::max(vMax, p.v);
      }
      if (!ok) continue;
      int x0 = static_cast<int>(std::ceil(uMin)), x1 = static_cast<int>(std::ceil(uMax)) - 1;
      int y0 = static_cast<int>(std::ceil(vMin)), y1 = static_cast<int>(std::ceil(vMax)) - 1;
      if (x1 < x0) x0 = x1 = static_cast<int>(std::lround(centre.u));  // footprint below a colour pixel
      if (y1 < y0) y0 = y1 = static_cast<int>(std::lround(centre.v));
      x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, Wc - 1), y1 = std::min(y1, Hc - 1);
      if (x1 - x0 > kMaxTriangleSpan_px || y1 - y0 > kMaxTriangleSpan_px) continue;
      const Tilt tilt = footprintTilt(centres, r, c, W, H, fMin);
      for (int y = y0; y <= y1; ++y) {
        float* row = splat.ptr<float>(y);
        for (int x = x0; x <= x1; ++x)
          keepNearest(row[x], std::clamp(static_cast<float>(centre.z + tilt.gu * (x - centre.u) + tilt.gv * (y - centre.v)),
                                         tilt.zLo, tilt.zHi));
      }
    }
  }
}

}  // namespace

DepthRegistration::DepthRegistration(const Camera& depthCamera, const Camera& colourCamera,
                                     const srp::core::Pose3& X_colour_depth)
    : depth_(depthCamera), colour_(colourCamera), X_colour_depth_(X_colour_depth) {
  depth_.K.validate("depth registration: depth camera");
  colour_.K.validate("depth registration: colour camera");
  const auto& K = depth_.K;
  const int W = K.width_px, H = K.height_px;
  rays_.resize(static_cast<std::size_t>(W) * H);
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c)
      rays_[static_cast<std::size_t>(r) * W + c] =
          depth_.distortion.undistort({(c - K.cx_px) / K.fx_px, (r - K.cy_px) / K.fy_px}).cast<float>();
  cornerRays_.resize(static_cast<std::size_t>(W + 1) * (H + 1));
  for (int r = 0; r <= H; ++r)
    for (int c = 0; c <= W; ++c)
      cornerRays_[static_cast<std::size_t>(r) * (W + 1) + c] =
          depth_.distortion.undistort({(c - 0.5 - K.cx_px) / K.fx_px, (r - 0.5 - K.cy_px) / K.fy_px}).cast<float>();
}

cv::Mat DepthRegistration::registerDepth(const cv::Mat& depth_m) const {
  const auto& Kd = depth_.K;
  const auto& Kc = colour_.K;
  const int W = Kd.width_px, H = Kd.height_px, Wc = Kc.width_px, Hc = Kc.height_px;
  if (depth_m.type() != CV_32FC1 || depth_m.cols != W || depth_m.rows != H)
    throw srp::core::InvalidInputError("depth registration: the depth image must be float metres of the depth camera's size " +
                                       std::to_string(W) + "x" + std::to_string(H) + " (got " +
                                       std::to_string(depth_m.cols) + "x" + std::to_string(depth_m.rows) + ")");
  const Eigen::Matrix3d R = X_colour_depth_.linear();
  const Eigen::Vector3d t = X_colour_depth_.translation();
  const bool distorted = !colour_.distortion.isZero();
  // Beyond the colour image's own field of view (with margin) the distortion
  // polynomial may fold back into the image: such points are outside anyway.
  double maxR2 = 0.0;
  for (const double u : {-0.5, Wc - 0.5})
    for (const double v : {-0.5, Hc - 0.5})
      maxR2 = std::max(maxR2, colour_.distortion.undistort({(u - Kc.cx_px) / Kc.fx_px, (v - Kc.cy_px) / Kc.fy_px})
                                  .squaredNorm());
  maxR2 *= 2.0;
  const auto project = [&](const Eigen::Vector2f& ray, double d, Projected& out) {
    const Eigen::Vector3d p = R * Eigen::Vector3d(ray.x() * d, ray.y() * d, d) + t;
    if (!(p.z() > 1e-6)) return false;
    Eigen::Vector2d xy(p.x() / p.z(), p.y() / p.z());
    if (distorted) {
      if (xy.squaredNorm() > maxR2) return false;
      xy = colour_.distortion.distort(xy);
    }
    out = {static_cast<float>(Kc.fx_px * xy.x() + Kc.cx_px), static_cast<float>(Kc.fy_px * xy.y() + Kc.cy_px),
           static_cast<float>(p.z())};
    return true;
  };
  const double fMin = std::min(Kd.fx_px, Kd.fy_px);
  const auto jumpTol = [&](double d) { return jumpTolerance(d, fMin); };

  std::vector<Projected> centres(static_cast<std::size_t>(W) * H, Projected{0.f, 0.f, 0.f});
  for (int r = 0; r < H; ++r) {
    const float* d = depth_m.ptr<float>(r);
    for (int c = 0; c < W; ++c) {
      if (!(d[c] > 0.f) || !std::isfinite(d[c])) continue;
      const std::size_t i = static_cast<std::size_t>(r) * W + c;
      Projected p;
      if (project(rays_[i], d[c], p)) centres[i] = p;
    }
  }

  cv::Mat mesh(Hc, Wc, CV_32FC1, cv::Scalar(0)), splat(Hc, Wc, CV_32FC1, cv::Scalar(0));
  // Triangles between continuous neighbours, 1/Z interpolated (exact for planes).
  const auto continuous = [&](int i, int j, int k) {
    const Projected &a = centres[i], &b = centres[j], &c = centres[k];
    if (a.z <= 0.f || b.z <= 0.f || c.z <= 0.f) return false;
    const float lo = std::min({a.z, b.z, c.z}), hi = std::max({a.z, b.z, c.z});
    return hi - lo <= jumpTol(lo);
  };
  for (int r = 0; r + 1 < H; ++r)
    for (int c = 0; c + 1 < W; ++c) {
      const int i00 = r * W + c, i10 = i00 + 1, i01 = i00 + W, i11 = i01 + 1;
      if (continuous(i00, i10, i01)) rasteriseTriangle(mesh, centres[i00], centres[i10], centres[i01]);
      if (continuous(i10, i11, i01)) rasteriseTriangle(mesh, centres[i10], centres[i11], centres[i01]);
    }

  // Footprint splats: every colour pixel centre inside the projected depth pixel.
  splatFootprints(splat, depth_m, centres, cornerRays_, project, fMin);

  // Triangles win on their surface; a splat only where none reached or in front of it.
  for (int y = 0; y < Hc; ++y) {
    float* m = mesh.ptr<float>(y);
    const float* s = splat.ptr<float>(y);
    for (int x = 0; x < Wc; ++x)
      if (s[x] > 0.f && (m[x] <= 0.f || s[x] < m[x] - jumpTol(s[x]))) m[x] = s[x];
  }
  return mesh;
}

}  // namespace srp::rawlog
