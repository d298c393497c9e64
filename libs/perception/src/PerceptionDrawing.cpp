#include "srp/perception/PerceptionDrawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/rawlog/RawlogReader.h"

namespace srp::perception {

namespace {

// At most this many mesh vertices per class are projected for its outline.
constexpr std::size_t kMaxOutlineVertices = 4000;

cv::Scalar bgrOf(const Eigen::Vector3d& rgb) {
  const auto c = [](double v) { return std::clamp(v, 0.0, 1.0) * 255.0; };
  return cv::Scalar(c(rgb.z()), c(rgb.y()), c(rgb.x()));
}

// Text with a dark halo, readable on any background.
void label(cv::Mat& img, const std::string& text, cv::Point at, double scale, const cv::Scalar& colour, int thickness) {
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), thickness + 2, cv::LINE_AA);
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

std::string fixed2(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

}  // namespace

PerceptionDrawing::PerceptionDrawing(const PerceptionResult& result, const core::ObjectCatalogue& catalogue)
    : PerceptionDrawing(result, catalogue, Options{}) {}

PerceptionDrawing::PerceptionDrawing(const PerceptionResult& result, const core::ObjectCatalogue& catalogue,
                                     Options options)
    : result_(result), options_(std::move(options)) {
  if (!options_.X_camera_table) options_.X_camera_table = result.X_camera_table;
  for (const auto& t : result.objects) {
    if (hull_object_.count(t.className)) continue;
    const core::ObjectClass* cls = catalogue.find(t.className);
    if (!cls) continue;
    std::vector<Eigen::Vector3d> vertices;
    const kb::TriangleMesh mesh = kb::loadClassMesh(*cls);
    const std::size_t stride = std::max<std::size_t>(1, mesh.size() * 3 / kMaxOutlineVertices);
    std::size_t k = 0;
    for (const auto& tri : mesh.triangles())
      for (const auto& v : tri)
        if (k++ % stride == 0) vertices.push_back(v);
    hull_object_[t.className] = std::move(vertices);
    colour_[t.className] = bgrOf(cls->rgb);
  }
}

void PerceptionDrawing::draw(cv::Mat& img, int frame) const {
  const core::CameraIntrinsics& K = result_.intrinsics;
  const double sx = K.width_px > 0 ? static_cast<double>(img.cols) / K.width_px : 1.0;
  const double sy = K.height_px > 0 ? static_cast<double>(img.rows) / K.height_px : 1.0;
  const double zoom = std::max(1.0, static_cast<double>(img.cols) / std::max(1, options_.readableWidth_px));
  const double font = 0.45 * zoom;
  const int thick = std::max(1, static_cast<int>(std::lround(zoom)));
  const auto pixel = [&](const Eigen::Vector3d& p_camera) -> std::optional<cv::Point> {
    const auto uv = K.project(p_camera);
    if (!uv) return std::nullopt;
    return cv::Point(cvRound(uv->x() * sx), cvRound(uv->y() * sy));
  };

  // The table frame (and rectangle) under everything else.
  if (options_.X_camera_table) {
    const core::Pose3& X = *options_.X_camera_table;
    if (options_.tableSize_m) {
      const Eigen::Vector2d h = *options_.tableSize_m / 2;
      std::vector<cv::Point> corners;
      for (const auto& c : {Eigen::Vector2d(-h.x(), -h.y()), Eigen::Vector2d(h.x(), -h.y()), Eigen::Vector2d(h.x(), h.y()),
                            Eigen::Vector2d(-h.x(), h.y())})
        if (const auto p = pixel(X * Eigen::Vector3d(c.x(), c.y(), 0.0))) corners.push_back(*p);
      if (corners.size() == 4) cv::polylines(img, corners, true, cv::Scalar(255, 255, 255), thick, cv::LINE_AA);
    }
    const auto origin = pixel(X.translation());
    const cv::Scalar axisColour[3] = {cv::Scalar(0, 0, 255), cv::Scalar(0, 200, 0), cv::Scalar(255, 80, 0)};
    const char* axisName[3] = {"x", "y", "z"};
    for (int a = 0; a < 3 && origin; ++a) {
      const auto tip = pixel(X * (Eigen::Vector3d::Unit(a) * options_.axisLength_m));
      if (!tip) continue;
      cv::arrowedLine(img, *origin, *tip, axisColour[a], 2 * thick, cv::LINE_AA, 0, 0.15);
      label(img, axisName[a], *tip + cv::Point(3, 3), font, axisColour[a], thick);
    }
    if (origin) label(img, "table", *origin + cv::Point(-10 * thick, 18 * thick), font, cv::Scalar(255, 255, 255), thick);
  }

  // Every object: outline, name, confidence.
  for (const auto& t : result_.objects) {
    const auto sample = std::find_if(t.samples.begin(), t.samples.end(), [&](const auto& s) { return s.frame == frame; });
    const auto hull = hull_object_.find(t.className);
    if (sample == t.samples.end() || hull == hull_object_.end()) continue;
    std::vector<cv::Point> projected;
    for (const auto& v : hull->second)
      if (const auto p = pixel(sample->X_camera_object * v)) projected.push_back(*p);
    if (projected.size() < 3) continue;
    std::vector<cv::Point> outline;
    cv::convexHull(projected, outline);
    const cv::Scalar colour = sample->detected ? colour_.at(t.className) : cv::Scalar(160, 160, 160);
    const int width = sample->detected ? 2 * thick : thick;
    // A dark underlay keeps the outline visible on an object of its own colour.
    cv::polylines(img, outline, true, cv::Scalar(0, 0, 0), width + 2 * thick, cv::LINE_AA);
    cv::polylines(img, outline, true, colour, width, cv::LINE_AA);
    const auto top = *std::min_element(outline.begin(), outline.end(), [](const auto& a, const auto& b) { return a.y < b.y; });
    const std::string text = t.key() + " " + (sample->detected ? fixed2(sample->confidence) : std::string("(kept)"));
    label(img, text, top + cv::Point(-20 * thick, -6 * thick), font, colour, thick);
  }

  // The palm.
  const auto& hand = result_.hand.samples();
  const auto h = std::find_if(hand.begin(), hand.end(), [&](const auto& s) { return s.frame == frame; });
  if (h != hand.end() && h->valid) {
    if (const auto p = pixel(h->p_m)) {
      cv::circle(img, *p, 7 * thick, cv::Scalar(0, 0, 0), 2 * thick + 2, cv::LINE_AA);
      cv::circle(img, *p, 7 * thick, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);
      label(img, "palm", *p + cv::Point(10 * thick, 5 * thick), font, cv::Scalar(255, 255, 255), thick);
    }
  } else {
    label(img, "no hand", cv::Point(8 * thick, img.rows - 10 * thick), font, cv::Scalar(0, 200, 255), thick);
  }
}

cv::Mat composeContactSheet(const std::vector<ContactSheetTile>& tiles, const std::string& title, int columns,
                            int tileWidth_px) {
  columns = std::max(1, std::min<int>(columns, static_cast<int>(std::max<std::size_t>(1, tiles.size()))));
  const double aspect =
      !tiles.empty() && !tiles[0].image.empty() ? static_cast<double>(tiles[0].image.rows) / tiles[0].image.cols : 0.75;
  const int tileHeight = static_cast<int>(std::lround(tileWidth_px * aspect));
  constexpr int kBorder = 4, kCaption = 26, kTitle = 34, kGap = 6;
  const int rows = static_cast<int>((tiles.size() + static_cast<std::size_t>(columns) - 1) / static_cast<std::size_t>(columns));
  const int cellW = tileWidth_px + 2 * kBorder + kGap, cellH = tileHeight + 2 * kBorder + kCaption + kGap;
  cv::Mat sheet(kTitle + std::max(1, rows) * cellH, columns * cellW + kGap, CV_8UC3, cv::Scalar(32, 32, 32));
  label(sheet, title, cv::Point(kGap, 24), 0.6, cv::Scalar(255, 255, 255), 1);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
    const cv::Point origin(kGap + c * cellW, kTitle + r * cellH);
    cv::rectangle(sheet, cv::Rect(origin, cv::Size(tileWidth_px + 2 * kBorder, tileHeight + 2 * kBorder)),
                  tiles[i].border, cv::FILLED);
    cv::Mat tile;
    if (!tiles[i].image.empty()) {
      cv::resize(tiles[i].image, tile, cv::Size(tileWidth_px, tileHeight), 0, 0, cv::INTER_AREA);
      tile.copyTo(sheet(cv::Rect(origin + cv::Point(kBorder, kBorder), tile.size())));
    }
    if (!tiles[i].flag.empty())
      label(sheet, tiles[i].flag, origin + cv::Point(kBorder + 6, kBorder + 22), 0.6, cv::Scalar(40, 40, 255), 2);
    label(sheet, tiles[i].caption, origin + cv::Point(kBorder, tileHeight + 2 * kBorder + 18), 0.5,
          cv::Scalar(235, 235, 235), 1);
  }
  return sheet;
}

std::vector<int> contactSheetFrames(int frameCount, int count, const std::vector<int>& marked) {
  std::vector<int> frames;
  if (frameCount <= 0) return frames;
  count = std::max(2, count);
  for (int i = 0; i < count; ++i)
    frames.push_back(static_cast<int>(std::lround(i * (frameCount - 1.0) / (count - 1))));
  for (int f : marked)
    if (f >= 0 && f < frameCount) frames.push_back(f);
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

std::vector<std::string> writeDrawnFrames(const std::string& rawlogPath, const PerceptionResult& result,
                                          const core::ObjectCatalogue& catalogue, const std::string& folder, int every,
                                          int sheetFrames) {
  namespace fs = std::filesystem;
  core::require(every >= 1, "every n-th frame is drawn: n must be at least 1");
  const fs::path target = fs::absolute(folder).lexically_normal();
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  core::AtomicOutputFolder out(target);
  const PerceptionDrawing drawing(result, catalogue);
  const std::vector<int> sheet = contactSheetFrames(result.frames, sheetFrames);
  const std::set<int> onSheet(sheet.begin(), sheet.end());
  std::vector<ContactSheetTile> tiles;
  std::vector<std::string> written;
  rawlog::RawlogReader reader(rawlogPath);
  while (const auto f = reader.next()) {
    const bool drawn = f->index % every == 0, tiled = onSheet.count(f->index) > 0;
    if (!drawn && !tiled) continue;
    cv::Mat image = f->colour_bgr8.clone();
    drawing.draw(image, f->index);
    if (drawn) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05d.png", f->index);
      const fs::path path = out.temporaryPath() / name;
      if (!cv::imwrite(path.string(), image)) throw core::FileError((target / name).string(), "cannot write the drawn frame");
      written.push_back((target / name).string());
    }
    if (tiled) tiles.push_back({image, "frame " + std::to_string(f->index), cv::Scalar(60, 60, 60), ""});
  }
  if (reader.damage()) throw core::FileError(rawlogPath, "damaged " + *reader.damage() + "; nothing drawn");
  const cv::Mat contact = composeContactSheet(
      tiles, "What perception saw: " + std::to_string(result.frames) + " frames, hand in " +
                 std::to_string(result.handDetected) + "; outlines with confidence, table frame");
  if (!cv::imwrite((out.temporaryPath() / "contact_sheet.png").string(), contact))
    throw core::FileError((target / "contact_sheet.png").string(), "cannot write the contact sheet");
  written.push_back((target / "contact_sheet.png").string());
  out.commit();
  return written;
}

}  // namespace srp::perception
