#include "srp/perception/ObjectDetector.h"
#include "srp/core/Log.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"
#include "srp/perception/DepthCloud.h"

namespace srp::perception {
namespace {

/// Agreement [0, 1] of two RGB colours by chromaticity (brightness, i.e.
/// shading, does not count).
double colourAgreement(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double chromaSigma) {
  const Eigen::Vector3d ca = a / std::max(1e-6, a.sum()), cb = b / std::max(1e-6, b.sum());
  const double dChroma = (ca - cb).norm();
  return std::exp(-0.5 * std::pow(dChroma / chromaSigma, 2));
}

/// Depth fits every symmetric turn of a nearly symmetric part equally
/// well; the colour outline tells which one puts the origin right. Also
/// for a tracked part: one first found half hidden (a part just placed,
/// the hand still over it) keeps a wrong turn otherwise. Returns the pose of
/// the turn chosen (`bestPose` refitted from it, or `bestPose` itself).
core::Pose3 silhouetteBranch(const ObjectPoseFitter& fitter, const core::Pose3& bestPose, const ObjectSegment& seg,
                             const Plane& support, const cv::Mat& cloud, const CameraModel& camera,
                             const SilhouetteBranchPicker& picker,
                             const std::map<std::string, core::Pose3>& previous, double trackRadius_m) {
  const auto branches = fitter.symmetricBranches(bestPose);
  std::vector<double> iou;
  const auto k = picker.pick(fitter.model().mesh, branches, seg.pixels, seg.colour_bgr8, camera, &iou);
  if (core::Log::enabled("perception", core::Log::Level::Debug)) {
    std::string line = fitter.model().name + " branches (IoU):";
    char value[32];
    for (double v : iou) line += (std::snprintf(value, sizeof value, " %.3f", v), value);
    core::Log::write("perception", core::Log::Level::Debug,
                     line + " -> " + std::to_string(k ? static_cast<int>(*k) : -1));
  }
  std::size_t chosen = k ? *k : 0;
  const auto prev = previous.find(fitter.model().name);
  if (!k && prev != previous.end() && core::translationDistance(prev->second, bestPose) < trackRadius_m) {
    // Colour inconclusive (a partial view): the turn nearest the part's last pose (it has not moved).
    double nearest = 1e9;
    for (std::size_t b = 0; b < branches.size(); ++b) {
      const double a = core::rotationAngleBetween(prev->second.linear(), branches[b].linear());
      if (a < nearest) {
        nearest = a;
        chosen = b;
      }
    }
  }
  if (chosen == 0) return bestPose;
  return fitter.fit(seg.points_camera_m, support, cloud, camera, &branches[chosen]).X_camera_object;
}

}  // namespace

ObjectDetector::ObjectDetector(std::vector<ObjectModel> models) : ObjectDetector(std::move(models), Options{}) {}

ObjectDetector::ObjectDetector(std::vector<ObjectModel> models, const Options& options)
    : branchPicker_(options.branches), options_(options) {
  core::require(!models.empty(), "ObjectDetector: no object models (is the knowledge base empty?)");
  for (const auto& m : models) {
    fitters_.emplace_back(m, options.fit);
    refiners_.emplace_back(m, options.edges);
  }
}

std::vector<ObjectModel> ObjectDetector::modelsFromCatalogue(const core::ObjectCatalogue& catalogue,
                                                             const std::vector<std::string>& classNames) {
  std::vector<ObjectModel> models;
  if (classNames.empty())
    for (const auto& c : catalogue.classes()) models.push_back(ObjectModel::fromCatalogue(c));
  else
    for (const auto& n : classNames) models.push_back(ObjectModel::fromCatalogue(catalogue.at(n)));
  return models;
}

int ObjectDetector::segment(const cv::Mat& cloud, const Plane& plane, cv::Mat& labels) const {
  // Pixels above the plane, joined to their 4-neighbours when the depth step
  // between them is small (union-find): flying pixels at depth edges break the chain.
  const int W = cloud.cols, H = cloud.rows;
  // Per-thread buffers: a frame loop reuses their memory (no 2 x 1.2 MB of
  // fresh pages per frame).
  thread_local std::vector<int> parent, rootLabel;
  parent.assign(static_cast<std::size_t>(W) * H, -1);
  auto find = [](int i) {  // parent is thread_local: no capture
    while (parent[i] != i) {
      parent[i] = parent[parent[i]];
      i = parent[i];
    }
    return i;
  };
  auto unite = [&](int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  for (int v = 0; v < H; ++v) {
    const cv::Vec3f* row = cloud.ptr<cv::Vec3f>(v);
    for (int u = 0; u < W; ++u) {
      if (row[u][2] <= 0.f) continue;
      const double h = plane.height({row[u][0], row[u][1], row[u][2]});
      if (h >= options_.minHeight_m && h <= options_.maxHeight_m) parent[v * W + u] = v * W + u;
    }
  }
  const double depthEdge = options_.depthEdge_m;
  auto joinable = [depthEdge](float za, float zb) { return std::abs(za - zb) < depthEdge * std::max(1.0f, za); };
  for (int v = 0; v < H; ++v) {
    const cv::Vec3f* row = cloud.ptr<cv::Vec3f>(v);
    const cv::Vec3f* below = v + 1 < H ? cloud.ptr<cv::Vec3f>(v + 1) : nullptr;
    for (int u = 0; u < W; ++u) {
      const int i = v * W + u;
      if (parent[i] < 0) continue;
      if (u + 1 < W && parent[i + 1] >= 0 && joinable(row[u][2], row[u + 1][2])) unite(i, i + 1);
      if (below && parent[i + W] >= 0 && joinable(row[u][2], below[u][2])) unite(i, i + W);
    }
  }
  labels.create(H, W, CV_32S);
  labels.setTo(cv::Scalar(0));
  rootLabel.assign(parent.size(), 0);
  int n = 0;
  for (int v = 0; v < H; ++v) {
    int* out = labels.ptr<int>(v);
    for (int u = 0; u < W; ++u) {
      const int i = v * W + u;
      if (parent[i] < 0) continue;
      const int r = find(i);
      if (rootLabel[r] == 0) rootLabel[r] = ++n;
      out[u] = rootLabel[r];
    }
  }
  return n;
}

std::vector<ObjectDetection> ObjectDetector::detect(const rawlog::RgbdFrame& frame, const Plane* support) const {
  return detect(frame, support, {});
}

std::vector<ObjectDetection> ObjectDetector::detect(const rawlog::RgbdFrame& frame, const Plane* support,
                                                    const std::map<std::string, core::Pose3>& previous) const {
  if (frame.depth_m.empty())
    throw core::InvalidInputError("frame " + std::to_string(frame.index) + " has no depth image: objects need depth");
  const CameraModel camera(frame.intrinsics);
  const cv::Mat cloud = depthToCloud(frame.depth_m, camera);
  lastPlane_ = support ? std::optional<Plane>(*support) : fitDominantPlane(cloud, options_.plane);
  if (!lastPlane_) return {};
  std::vector<ObjectDetection> out;
  for (const ObjectSegment& seg : segments(frame, cloud, *lastPlane_))
    if (auto d = explain(seg, *lastPlane_, cloud, camera, previous)) out.push_back(std::move(*d));
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.confidence > b.confidence; });
  return out;
}

std::vector<ObjectSegment> ObjectDetector::segments(const rawlog::RgbdFrame& frame, const cv::Mat& cloud,
                                                    const Plane& plane) const {
  thread_local cv::Mat labels;  // reused frame to frame
  const int nSegments = segment(cloud, plane, labels);
  std::vector<ObjectSegment> segs(static_cast<std::size_t>(nSegments));
  {
    std::vector<int> size(static_cast<std::size_t>(nSegments), 0);
    for (int v = 0; v < labels.rows; ++v) {
      const int* l = labels.ptr<int>(v);
      for (int u = 0; u < labels.cols; ++u)
        if (l[u] > 0) ++size[static_cast<std::size_t>(l[u] - 1)];
    }
    for (std::size_t k = 0; k < segs.size(); ++k) {
      segs[k].points_camera_m.reserve(static_cast<std::size_t>(size[k]));
      segs[k].pixels.reserve(static_cast<std::size_t>(size[k]));
    }
  }
  const bool hasColour = !frame.colour_bgr8.empty();
  for (int v = 0; v < labels.rows; ++v) {
    const int* l = labels.ptr<int>(v);
    for (int u = 0; u < labels.cols; ++u) {
      if (l[u] <= 0) continue;
      ObjectSegment& seg = segs[static_cast<std::size_t>(l[u] - 1)];
      seg.points_camera_m.push_back(cloudAt(cloud, u, v));
      seg.pixels.emplace_back(u, v);
      if (hasColour) {
        const cv::Vec3b c = frame.colour_bgr8.at<cv::Vec3b>(v, u);
        seg.meanRgb += Eigen::Vector3d(c[2], c[1], c[0]) / 255.0;
      }
    }
  }
  const core::Pose3 X_plane_camera = plane.X_camera_plane().inverse();
  std::vector<ObjectSegment> out;
  for (ObjectSegment& seg : segs) {
    if (static_cast<int>(seg.points_camera_m.size()) < options_.minPixels) continue;
    seg.hasColour = hasColour;
    seg.colour_bgr8 = frame.colour_bgr8;
    seg.meanRgb /= static_cast<double>(seg.points_camera_m.size());
    std::vector<double> c[3];
    for (auto& v : c) v.reserve(seg.points_camera_m.size());
    for (const auto& p : seg.points_camera_m) {
      const Eigen::Vector3d q = X_plane_camera * p;
      for (int a = 0; a < 3; ++a) c[a].push_back(q[a]);
    }
    for (int a = 0; a < 3; ++a) {
      const std::size_t n = c[a].size();
      const std::size_t trim = static_cast<std::size_t>(options_.extentTrim * static_cast<double>(n));
      const std::size_t i0 = trim, i1 = n - 1 - trim;
      std::nth_element(c[a].begin(), c[a].begin() + static_cast<long>(i0), c[a].end());
      seg.lo_plane_m[a] = c[a][i0];
      // Everything after i0 is >= it now: the upper percentile is in that part.
      std::nth_element(c[a].begin() + static_cast<long>(std::min(i0 + 1, i1)), c[a].begin() + static_cast<long>(i1),
                       c[a].end());
      seg.hi_plane_m[a] = c[a][i1];
    }
    out.push_back(std::move(seg));
  }
  return out;
}

const ObjectPoseFitter* ObjectDetector::fitterFor(const std::string& className) const {
  const auto it = std::find_if(fitters_.begin(), fitters_.end(),
                               [&](const ObjectPoseFitter& f) { return f.model().name == className; });
  return it == fitters_.end() ? nullptr : &*it;
}

std::set<std::string> ObjectDetector::overlappingParts(const std::vector<ObjectDetection>& detections,
                                                      const Plane& plane) const {
  const core::Pose3 X_plane_camera = plane.X_camera_plane().inverse();
  auto partOf = [this](const ObjectDetection& d) -> const ObjectModel* {
    const ObjectPoseFitter* f = fitterFor(d.key);
    return f && f->model().kind == core::ObjectKind::Part ? &f->model() : nullptr;
  };
  std::set<std::string> dropped;
  for (std::size_t a = 0; a < detections.size(); ++a)
    for (std::size_t b = a + 1; b < detections.size(); ++b) {
      const ObjectModel* ma = partOf(detections[a]);
      const ObjectModel* mb = partOf(detections[b]);
      if (!ma || !mb) continue;
      const Eigen::Vector3d pa = X_plane_camera * detections[a].X_camera_object.translation();
      const Eigen::Vector3d pb = X_plane_camera * detections[b].X_camera_object.translation();
      const double reach = 0.5 * std::min(ma->dimensions_m.head<2>().norm(), mb->dimensions_m.head<2>().norm());
      const double sharedHeight =
          std::min(pa.z() + ma->dimensions_m.z(), pb.z() + mb->dimensions_m.z()) - std::max(pa.z(), pb.z());
      if ((pa - pb).head<2>().norm() >= reach ||
          sharedHeight <= 0.5 * std::min(ma->dimensions_m.z(), mb->dimensions_m.z()))
        continue;  // apart, or stacked
      dropped.insert(detections[a].confidence < detections[b].confidence ? detections[a].key
                                                                         : detections[b].key);
    }
  return dropped;
}

double ObjectDetector::colourScore(const ObjectSegment& segment, const ObjectModel& model) const {
  return model.useColour && segment.hasColour ? colourAgreement(segment.meanRgb, model.rgb, options_.colourChromaSigma) : 1.0;
}

ObjectDetection ObjectDetector::makeDetection(const ObjectPoseFitter& fitter, const core::Pose3& X_camera_object,
                                              double confidence, const ObjectSegment& segment,
                                              const Plane& plane) const {
  ObjectDetection d;
  d.key = fitter.model().name;
  d.classId = fitter.model().classId;
  d.X_camera_object = X_camera_object;
  d.size_m = fitter.model().dimensions_m;
  d.confidence = confidence;
  const core::Pose3 X_plane_object = plane.X_camera_plane().inverse() * X_camera_object;
  d.yaw_rad = std::atan2(X_plane_object.linear()(1, 0), X_plane_object.linear()(0, 0));
  d.segmentPixels = static_cast<int>(segment.points_camera_m.size());
  const cv::RotatedRect rr = cv::minAreaRect(segment.pixels);
  cv::Point2f corners[4];
  rr.points(corners);
  for (int c = 0; c < 4; ++c) d.obb_px[c] = {corners[c].x, corners[c].y};
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> vals;
    vals.reserve(segment.points_camera_m.size());
    for (const auto& p : segment.points_camera_m) vals.push_back(p[axis]);
    std::nth_element(vals.begin(), vals.begin() + static_cast<long>(vals.size() / 2), vals.end());
    d.p_camera_median_m[axis] = vals[vals.size() / 2];
  }
  return d;
}

std::optional<ObjectDetection> ObjectDetector::explain(const ObjectSegment& seg, const Plane& plane,
                                                       const cv::Mat& cloud, const CameraModel& camera,
                                                       const std::map<std::string, core::Pose3>& previous,
                                                       const std::set<std::string>& excluded) const {
  const core::Pose3 X_plane_camera = plane.X_camera_plane().inverse();
  // The fits stand the part on the table where it is (the gates below stay
  // in the global plane's frame, as the segment's extent).
  std::optional<Plane> local;
  if (options_.localSupport) local = fitLocalPlane(cloud, plane, cv::boundingRect(seg.pixels), options_.localPlane);
  const Plane& support = local ? *local : plane;
  const double segExtent = (seg.hi_plane_m - seg.lo_plane_m).head<2>().norm();
  const double segTop_m = seg.hi_plane_m.z();
  const Eigen::Vector3d segCentre = seg.centre_plane_m();

  const ObjectPoseFitter* bestFitter = nullptr;
  core::Pose3 bestPose = core::Pose3::Identity();
  double bestConfidence = 0.0;
  // Tracking: a class whose previous pose lies on this segment is refined from it first.
  for (const ObjectPoseFitter& fitter : fitters_) {
    if (excluded.count(fitter.model().name)) continue;
    const auto prev = previous.find(fitter.model().name);
    if (prev == previous.end()) continue;
    const Eigen::Vector3d p = X_plane_camera * prev->second.translation();
    if ((p - segCentre).head<2>().norm() > options_.trackRadius_m + 0.5 * fitter.model().dimensions_m.head<2>().norm())
      continue;
    // A fit's score is at most 1, so a colour below what it must reach cannot
    // win (a hand's fragment next to a part): no fit.
    const double colour = colourScore(seg, fitter.model());
    if (colour < options_.trackConfidence || colour <= bestConfidence) continue;
    const ObjectPoseFit fit = fitter.fit(seg.points_camera_m, support, cloud, camera, &prev->second);
    const double confidence = fit.score * colour;
    if (confidence >= options_.trackConfidence && confidence > bestConfidence) {
      bestFitter = &fitter;
      bestPose = fit.X_camera_object;
      bestConfidence = confidence;
    }
  }
  for (const ObjectPoseFitter& fitter : fitters_) {
    if (bestConfidence >= options_.trackConfidence) break;  // tracked
    const ObjectModel& model = fitter.model();
    if (excluded.count(model.name)) continue;
    const double modelDiag = model.dimensions_m.head<2>().norm();
    // Cheap gates before the fit: footprint size, height above the plane, colour.
    if (segExtent > options_.maxExtentPerDiagonal * modelDiag + options_.extentSlack_m ||
        segExtent < options_.minExtentPerSide * model.dimensions_m.head<2>().minCoeff())
      continue;
    if (segTop_m > model.dimensions_m.z() + options_.maxElevation_m + options_.extentSlack_m ||
        segTop_m < options_.minTopPerHeight * model.dimensions_m.z())
      continue;
    const double colour = colourScore(seg, model);
    if (colour < options_.minColour || colour < options_.minConfidence || colour <= bestConfidence)
      continue;  // cannot win (score <= 1)
    // A coarse score that even a perfect fine stage could not lift to half
    // the acceptance is not worth the fine stage.
    const ObjectPoseFit fit = fitter.fit(seg.points_camera_m, support, cloud, camera, nullptr,
                                         options_.giveUpShare * std::max(options_.minConfidence, bestConfidence) / colour);
    const double confidence = fit.score * colour;
    if (core::Log::enabled("perception", core::Log::Level::Debug))
      core::Log::writef("perception", core::Log::Level::Debug,
                        "segment (%zu px) %s: inliers %.2f coverage %.2f colour %.2f at %.3f %.3f %.3f\n",
                        seg.points_camera_m.size(), model.name.c_str(), fit.inlierRatio, fit.coverage, colour,
                        fit.X_camera_object.translation().x(), fit.X_camera_object.translation().y(),
                        fit.X_camera_object.translation().z());
    if (confidence > bestConfidence) {
      bestFitter = &fitter;
      bestPose = fit.X_camera_object;
      bestConfidence = confidence;
    }
  }
  if (!bestFitter || bestConfidence < options_.minConfidence) return std::nullopt;
  if (options_.pickBranchBySilhouette && bestFitter->hasOffCentreSymmetry() && seg.hasColour)
    bestPose = silhouetteBranch(*bestFitter, bestPose, seg, support, cloud, camera, branchPicker_, previous,
                                options_.trackRadius_m);
  if (options_.refineYawByEdges && bestFitter->model().kind == core::ObjectKind::Part) {
    const EdgeYawRefiner& refiner = refiners_[static_cast<std::size_t>(bestFitter - fitters_.data())];
    if (const auto X = refiner.refine(bestPose, seg.pixels, seg.colour_bgr8, camera, support)) bestPose = *X;
  }
  return makeDetection(*bestFitter, bestPose, bestConfidence, seg, plane);  // yaw in the frame of the global plane
}

}  // namespace srp::perception
