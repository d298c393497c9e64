#include "srp/perception/ModelBasedTracker.h"

#include <visp3/core/vpImageConvert.h>
#include <visp3/mbt/vpMbGenericTracker.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "srp/core/Error.h"
#include "srp/interop/PoseConversions.h"

namespace srp::perception {

namespace {

using Key = std::array<long long, 3>;

Key vertexKey(const Eigen::Vector3d& p) {
  // Vertices of a triangle soup that coincide to 0.1 um are one vertex.
  return {std::llround(p.x() * 1e7), std::llround(p.y() * 1e7), std::llround(p.z() * 1e7)};
}

/// The mesh's triangles over its unique vertices (welded at 0.1 um), without
/// triangles that weld to fewer than three vertices.
struct WeldedMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

WeldedMesh weldVertices(const kb::TriangleMesh& mesh) {
  WeldedMesh out;
  std::map<Key, int> index;
  for (const auto& t : mesh.triangles()) {
    std::array<int, 3> ids{};
    for (int k = 0; k < 3; ++k) {
      const auto [it, added] = index.emplace(vertexKey(t[k]), static_cast<int>(out.vertices.size()));
      if (added) out.vertices.push_back(t[k]);
      ids[k] = it->second;
    }
    if (ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2]) continue;  // degenerate
    out.triangles.push_back(ids);
  }
  return out;
}

}  // namespace

std::string ModelBasedTracker::caoModel(const kb::TriangleMesh& mesh) {
  const WeldedMesh welded = weldVertices(mesh);
  const auto& vertices = welded.vertices;
  const auto& tris = welded.triangles;
  // Coplanar edge-connected triangles become one polygon when their boundary
  // is a single loop (no hole), so that the edge tracker does not see the
  // diagonals of a tessellated face and KLT gets whole faces.
  auto normalOf = [&](const std::array<int, 3>& t) {
    return (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).normalized();
  };
  std::map<std::pair<int, int>, std::vector<int>> edgeTris;
  for (int i = 0; i < static_cast<int>(tris.size()); ++i)
    for (int k = 0; k < 3; ++k)
      edgeTris[{std::min(tris[i][k], tris[i][(k + 1) % 3]), std::max(tris[i][k], tris[i][(k + 1) % 3])}].push_back(i);
  std::vector<int> group(tris.size(), -1);
  std::vector<std::vector<int>> groups;
  for (int seed = 0; seed < static_cast<int>(tris.size()); ++seed) {
    if (group[seed] >= 0) continue;
    const Eigen::Vector3d n = normalOf(tris[seed]);
    const double d = n.dot(vertices[tris[seed][0]]);
    groups.emplace_back();
    std::vector<int> stack{seed};
    group[seed] = static_cast<int>(groups.size()) - 1;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      groups.back().push_back(i);
      for (int k = 0; k < 3; ++k) {
        const auto e = std::make_pair(std::min(tris[i][k], tris[i][(k + 1) % 3]), std::max(tris[i][k], tris[i][(k + 1) % 3]));
        for (int j : edgeTris[e]) {
          if (group[j] >= 0) continue;
          const Eigen::Vector3d nj = normalOf(tris[j]);
          if (nj.dot(n) < 1.0 - 1e-6 || std::abs(n.dot(vertices[tris[j][0]]) - d) > 1e-6) continue;
          group[j] = group[seed];
          stack.push_back(j);
        }
      }
    }
  }
  std::vector<std::vector<int>> faces;
  for (const auto& g : groups) {
    // Directed boundary edges: those whose reverse is not in the group.
    std::map<std::pair<int, int>, int> directed;
    for (int i : g)
      for (int k = 0; k < 3; ++k) ++directed[{tris[i][k], tris[i][(k + 1) % 3]}];
    std::map<int, int> next;
    bool simple = true;
    for (const auto& [e, count] : directed) {
      if (directed.count({e.second, e.first})) continue;
      if (next.count(e.first)) simple = false;
      next[e.first] = e.second;
    }
    std::vector<int> loop;
    if (simple && !next.empty()) {
      int v = next.begin()->first;
      do {
        loop.push_back(v);
        const auto it = next.find(v);
        if (it == next.end()) break;
        v = it->second;
      } while (v != loop.front() && loop.size() <= next.size());
      simple = v == loop.front() && loop.size() == next.size();
    }
    if (simple && loop.size() >= 3) {
      faces.push_back(loop);
    } else {
      for (int i : g) faces.push_back({tris[i][0], tris[i][1], tris[i][2]});
    }
  }
  std::ostringstream cao;
  cao.precision(9);
  cao << "V1\n# 3D Points\n" << vertices.size() << "\n";
  for (const auto& v : vertices) cao << v.x() << " " << v.y() << " " << v.z() << "\n";
  cao << "# 3D Lines\n0\n# Faces from 3D lines\n0\n# Faces from 3D points\n" << faces.size() << "\n";
  for (const auto& f : faces) {
    cao << f.size();
    for (int v : f) cao << " " << v;
    cao << "\n";
  }
  cao << "# 3D cylinders\n0\n# 3D circles\n0\n";
  return cao.str();
}

/// A crease edge of the mesh with the outward normals of its two faces (one when on a border).
struct CreaseEdge {
  Eigen::Vector3d a, b, nA, nB;
};

std::vector<CreaseEdge> creaseEdges(const kb::TriangleMesh& mesh, double creaseAngle_rad) {
  const WeldedMesh welded = weldVertices(mesh);
  const auto& vertices = welded.vertices;
  const auto& tris = welded.triangles;
  std::map<std::pair<int, int>, std::vector<Eigen::Vector3d>> normals;
  for (const auto& ids : tris) {
    const Eigen::Vector3d n = (vertices[ids[1]] - vertices[ids[0]]).cross(vertices[ids[2]] - vertices[ids[0]]);
    if (n.norm() < 1e-12) continue;
    for (int k = 0; k < 3; ++k)
      normals[{std::min(ids[k], ids[(k + 1) % 3]), std::max(ids[k], ids[(k + 1) % 3])}].push_back(n.normalized());
  }
  std::vector<CreaseEdge> out;
  const double cosCrease = std::cos(creaseAngle_rad);
  for (const auto& [e, ns] : normals) {
    if (ns.size() == 2 && ns[0].dot(ns[1]) > cosCrease) continue;  // smooth or flat: no edge in the image
    out.push_back({vertices[e.first], vertices[e.second], ns[0], ns.size() >= 2 ? ns[1] : ns[0]});
  }
  return out;
}

struct ModelBasedTracker::Impl {
  Options options;
  std::vector<CreaseEdge> creases;
  core::CameraIntrinsics intrinsics;
  std::unique_ptr<vpMbGenericTracker> tracker;
  bool initialised = false;
  vpImage<unsigned char> grey;
  std::vector<vpColVector> cloud;
  int colourType = 0;

  void setImages(const rawlog::RgbdFrame& frame) {
    if (frame.colour_bgr8.empty() || frame.depth_m.empty())
      throw core::InvalidInputError("frame " + std::to_string(frame.index) +
                                    ": model-based tracking needs colour and registered depth");
    cv::Mat g;
    cv::cvtColor(frame.colour_bgr8, g, cv::COLOR_BGR2GRAY);
    vpImageConvert::convert(g, grey);
    const int w = frame.depth_m.cols, h = frame.depth_m.rows;
    cloud.resize(static_cast<std::size_t>(w) * h);
    const auto& k = frame.intrinsics;
    for (int v = 0; v < h; ++v) {
      const float* z = frame.depth_m.ptr<float>(v);
      for (int u = 0; u < w; ++u) {
        vpColVector& p = cloud[static_cast<std::size_t>(v) * w + u];
        if (p.size() != 3) p.resize(3, false);
        const double Z = (std::isfinite(z[u]) && z[u] > 0 && z[u] < options.maxDepth_m) ? z[u] : 0.0;
        p[0] = (u - k.cx_px) * Z / k.fx_px;
        p[1] = (v - k.cy_px) * Z / k.fy_px;
        p[2] = Z;
      }
    }
  }
};

ModelBasedTracker::ModelBasedTracker(const kb::TriangleMesh& mesh, const core::CameraIntrinsics& intrinsics,
                                     const Options& options)
    : impl_(std::make_unique<Impl>()) {
  if (mesh.empty()) throw core::InvalidInputError("ModelBasedTracker: the part's mesh has no triangles; give a CAD mesh");
  if (intrinsics.fx_px <= 0 || intrinsics.fy_px <= 0 || intrinsics.width_px <= 0 || intrinsics.height_px <= 0)
    throw core::InvalidInputError("ModelBasedTracker: invalid camera intrinsics (fx, fy, width, height must be > 0)");
  if (!options.useKlt && !options.useEdges && !options.useDepthDense)
    throw core::InvalidInputError("ModelBasedTracker: Options turn every feature off; enable KLT, edges or dense depth");
  Impl& m = *impl_;
  m.options = options;
  m.intrinsics = intrinsics;
  m.creases = creaseEdges(mesh, options.supportCreaseAngle_rad);
  int colourType = 0;
  if (options.useKlt) colourType |= vpMbGenericTracker::KLT_TRACKER;
  if (options.useEdges) colourType |= vpMbGenericTracker::EDGE_TRACKER;
  std::vector<int> types;
  std::vector<std::string> names;
  if (colourType) {
    types.push_back(colourType);
    names.push_back("Colour");
  }
  if (options.useDepthDense) {
    types.push_back(vpMbGenericTracker::DEPTH_DENSE_TRACKER);
    names.push_back("Depth");
  }
  m.colourType = colourType;
  m.tracker = std::make_unique<vpMbGenericTracker>(names, types);

  // ViSP reads its model from a file: the CAO text goes through a temporary one.
  // A name of its own per tracker and process (tests run in parallel processes).
  const auto path = std::filesystem::temp_directory_path() /
                    ("srp_mbt_" + std::to_string(std::random_device{}()) + "_" +
                     std::to_string(reinterpret_cast<std::uintptr_t>(this)) + ".cao");
  {
    std::ofstream f(path);
    if (!f) throw core::FileError(path.string(), "cannot write the tracker's temporary CAO model");
    f << caoModel(mesh);
  }
  std::map<std::string, std::string> models;
  for (const auto& n : names) models[n] = path.string();
  // ViSP prints the model's counts on std::cout, which carries srp's JSON output.
  std::ostringstream quiet;
  std::streambuf* const coutBuf = std::cout.rdbuf(quiet.rdbuf());
  try {
    m.tracker->loadModel(models);
    std::cout.rdbuf(coutBuf);
  } catch (const std::exception& e) {
    std::cout.rdbuf(coutBuf);
    std::filesystem::remove(path);
    throw core::InvalidInputError(std::string("ModelBasedTracker: ViSP could not load the mesh as a CAO model: ") + e.what());
  }
  std::filesystem::remove(path);

  const vpCameraParameters cam(intrinsics.fx_px, intrinsics.fy_px, intrinsics.cx_px, intrinsics.cy_px);
  std::map<std::string, vpCameraParameters> cams;
  std::map<std::string, vpHomogeneousMatrix> transforms;
  for (const auto& n : names) {
    cams[n] = cam;
    transforms[n] = vpHomogeneousMatrix();  // depth registered to colour: one camera
  }
  m.tracker->setCameraParameters(cams);
  m.tracker->setCameraTransformationMatrix(transforms);
  m.tracker->setReferenceCameraName(names.front());
  m.tracker->setDisplayFeatures(false);
  // ViSP's projection error is measured along the model's edges: with edge tracking only.
  m.tracker->setProjectionErrorComputation(options.useEdges);
  m.tracker->setAngleAppear(vpMath::rad(85.0));
  m.tracker->setAngleDisappear(vpMath::rad(89.0));
  m.tracker->setNearClippingDistance(0.05);
  m.tracker->setFarClippingDistance(options.maxDepth_m);
  if (options.useKlt) {
    vpKltOpencv klt;
    klt.setMaxFeatures(options.kltMaxPoints);
    klt.setWindowSize(options.kltWindow_px);
    klt.setQuality(options.kltQuality);
    klt.setMinDistance(options.kltMinDistance_px);
    klt.setHarrisFreeParameter(0.01);
    klt.setBlockSize(3);
    klt.setPyramidLevels(options.kltPyramidLevels);
    std::map<std::string, vpKltOpencv> klts{{names.front(), klt}};
    m.tracker->setKltOpencv(klts);
    std::map<std::string, unsigned int> borders{{names.front(), static_cast<unsigned int>(options.kltMaskBorder_px)}};
    m.tracker->setKltMaskBorder(borders);
  }
  if (options.useEdges) {
    vpMe me;
    me.setMaskSize(5);
    me.setMaskNumber(180);
    me.setRange(static_cast<unsigned int>(options.edgeRange_px));
    me.setThreshold(10000);
    me.setMu1(0.5);
    me.setMu2(0.5);
    me.setSampleStep(options.edgeSampleStep_px);
    std::map<std::string, vpMe> mes{{names.front(), me}};
    m.tracker->setMovingEdge(mes);
  }
  if (options.useDepthDense)
    m.tracker->setDepthDenseSamplingStep(static_cast<unsigned int>(options.depthSampling_px),
                                         static_cast<unsigned int>(options.depthSampling_px));
}

ModelBasedTracker::~ModelBasedTracker() = default;

bool ModelBasedTracker::initialised() const { return impl_->initialised; }

void ModelBasedTracker::initialise(const rawlog::RgbdFrame& frame, const core::Pose3& X_camera_mesh) {
  Impl& m = *impl_;
  m.setImages(frame);
  std::map<std::string, const vpImage<unsigned char>*> images;
  for (const auto& n : m.tracker->getCameraNames()) images[n] = &m.grey;
  m.tracker->initFromPose(images, std::map<std::string, vpHomogeneousMatrix>{
                                      {m.tracker->getCameraNames().front(), interop::toVisp(X_camera_mesh)}});
  m.initialised = true;
}

double ModelBasedTracker::edgeDistance_px(const rawlog::RgbdFrame& frame, const core::Pose3& X_camera_mesh) const {
  const Impl& m = *impl_;
  const Options& o = m.options;
  if (frame.colour_bgr8.empty())
    throw core::InvalidInputError("frame " + std::to_string(frame.index) + ": edgeDistance_px needs the colour image");
  const auto& k = frame.intrinsics;
  auto project = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(k.fx_px * p.x() / p.z() + k.cx_px, k.fy_px * p.y() / p.z() + k.cy_px);
  };
  // Visible edges, projected; the image is only looked at around them.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  double u0 = 1e9, v0 = 1e9, u1 = -1e9, v1 = -1e9;
  for (const auto& e : m.creases) {
    const Eigen::Vector3d a = X_camera_mesh * e.a, b = X_camera_mesh * e.b;
    if (a.z() <= 0.01 || b.z() <= 0.01) continue;
    const Eigen::Vector3d mid = 0.5 * (a + b);
    const bool facing = (X_camera_mesh.linear() * e.nA).dot(mid) < 0 || (X_camera_mesh.linear() * e.nB).dot(mid) < 0;
    if (!facing) continue;
    segments.emplace_back(a, b);
    for (const auto& p : {project(a), project(b)}) {
      u0 = std::min(u0, p.x());
      v0 = std::min(v0, p.y());
      u1 = std::max(u1, p.x());
      v1 = std::max(v1, p.y());
    }
  }
  if (segments.empty()) return o.supportTruncation_px;
  const int margin = static_cast<int>(std::ceil(o.supportTruncation_px)) + 4;
  const cv::Rect roi = cv::Rect(cv::Point(static_cast<int>(std::floor(u0)) - margin, static_cast<int>(std::floor(v0)) - margin),
                                cv::Point(static_cast<int>(std::ceil(u1)) + margin, static_cast<int>(std::ceil(v1)) + margin)) &
                       cv::Rect(0, 0, frame.colour_bgr8.cols, frame.colour_bgr8.rows);
  if (roi.width < 8 || roi.height < 8) return o.supportTruncation_px;
  cv::Mat grey, edges, distance;
  cv::cvtColor(frame.colour_bgr8(roi), grey, cv::COLOR_BGR2GRAY);
  cv::GaussianBlur(grey, grey, cv::Size(5, 5), o.supportBlurSigma_px);
  cv::Canny(grey, edges, o.supportCannyLow, o.supportCannyHigh);
  cv::distanceTransform(255 - edges, distance, cv::DIST_L2, 3);
  const bool haveDepth = !frame.depth_m.empty();
  double sum = 0.0;
  int count = 0;
  for (const auto& [a, b] : segments) {
    const int n = std::max(2, static_cast<int>((project(b) - project(a)).norm()));
    for (int i = 2; i < n - 2; ++i) {  // corners left out
      const Eigen::Vector3d P = a + (b - a) * (static_cast<double>(i) / n);
      const Eigen::Vector2d p = project(P);
      const int u = static_cast<int>(std::lround(p.x())), v = static_cast<int>(std::lround(p.y()));
      // Outside the image: no evidence either way.
      if (u < roi.x || v < roi.y || u >= roi.x + roi.width || v >= roi.y + roi.height) continue;
      // Something in front of the edge (a hand): no evidence either way.
      if (haveDepth) {
        const float z = frame.depth_m.at<float>(v, u);
        if (z > 0 && z < P.z() - o.supportOcclusion_m) continue;
      }
      sum += std::min(o.supportTruncation_px, static_cast<double>(distance.at<float>(v - roi.y, u - roi.x)));
      ++count;
    }
  }
  return count > 0 ? sum / count : o.supportTruncation_px;
}

ModelBasedTracker::Result ModelBasedTracker::track(const rawlog::RgbdFrame& frame) {
  Impl& m = *impl_;
  Result r;
  if (!m.initialised) return r;
  m.setImages(frame);
  std::map<std::string, const vpImage<unsigned char>*> images;
  std::map<std::string, const std::vector<vpColVector>*> clouds;
  std::map<std::string, unsigned int> widths, heights;
  for (const auto& n : m.tracker->getCameraNames()) {
    images[n] = &m.grey;
    clouds[n] = &m.cloud;
    widths[n] = static_cast<unsigned int>(frame.depth_m.cols);
    heights[n] = static_cast<unsigned int>(frame.depth_m.rows);
  }
  try {
    m.tracker->track(images, clouds, widths, heights);
  } catch (const vpException&) {
    // ViSP throws when too few features remain: the part is lost.
    m.initialised = false;
    return r;
  }
  r.X_camera_mesh = interop::fromVisp(m.tracker->getPose());
  r.projectionError_deg = m.tracker->getProjectionError();
  r.kltPoints = m.options.useKlt ? m.tracker->getKltNbPoints() : 0;
  r.depthFeatures = static_cast<int>(m.tracker->getNbFeaturesDepthDense());
  r.edgeFeatures = static_cast<int>(m.tracker->getNbFeaturesEdge());
  r.tracked = (!m.options.useKlt || r.kltPoints >= m.options.minKltPoints) &&
              (!m.options.useDepthDense || r.depthFeatures >= m.options.minDepthFeatures) &&
              (!m.options.useEdges || r.projectionError_deg <= m.options.maxProjectionError_deg);
  if (!r.tracked) m.initialised = false;
  return r;
}

}  // namespace srp::perception
