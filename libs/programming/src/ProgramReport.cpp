#include "srp/programming/ProgramReport.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <iomanip>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"
#include "srp/core/SafeText.h"
#include "srp/motion/SkillPlots.h"
#include "srp/perception/PerceptionDrawing.h"
#include "srp/plot/Figure.h"
#include "srp/programming/ProgrammingStages.h"
#include "srp/rawlog/RawlogReader.h"

#include <opencv2/imgcodecs.hpp>

namespace srp::programming {

void writeHandFigure(const std::string& pngPath, const perception::PerceptionResult& seen,
                     const motion::Segmentation& segmentation) {
  plot::Figure fig(1100, 800, 2, 2);
  fig.title = "Hand trajectory (camera frame), " + std::to_string(seen.handDetected) + " of " +
              std::to_string(seen.frames) + " frames detected";
  const char* axisName[3] = {"x", "y", "z"};
  const auto& smoothed = segmentation.hand;
  const double fps = frameRateOf(seen.hand);
  for (int k = 0; k < 3; ++k) {
    auto& ax = fig.axes(k / 2, k % 2);
    ax.title = std::string("hand ") + axisName[k];
    ax.xLabel = "t [s]";
    ax.yLabel = std::string(axisName[k]) + " [m]";
    // Time from frame numbers: the rawlog's clock and the smoother's differ in origin.
    std::vector<double> td, pd, ts, ps;
    for (const auto& s : seen.hand.samples())
      if (s.valid) { td.push_back(s.frame / fps); pd.push_back(s.p_m[k]); }
    for (const auto& s : smoothed.samples()) { ts.push_back(s.frame / fps); ps.push_back(s.p_m[k]); }
    ax.scatter(td, pd, "detected", plot::Colour::tab(0), plot::Marker::Circle, 2);
    ax.line(ts, ps, "smoothed", plot::Colour::tab(1), 2);
    for (std::size_t i = 0; i < segmentation.objects.size(); ++i) {
      const auto& o = segmentation.objects[i];
      if (!o.moved) continue;
      ax.verticalLine(o.graspFrame / fps, k == 0 ? "grasp " + o.name : "", plot::Colour::tab(2 + static_cast<int>(i)));
      ax.verticalLine(o.releaseFrame / fps, k == 0 ? "release" : "", plot::Colour::tab(2 + static_cast<int>(i)));
    }
  }
  auto& top = fig.axes(1, 1);
  top.title = "top view (image x right, y down)";
  top.xLabel = "x [m]";
  top.yLabel = "-y [m]";
  top.equalAspect = true;
  std::vector<double> x, y;
  for (const auto& s : smoothed.samples()) { x.push_back(s.p_m.x()); y.push_back(-s.p_m.y()); }
  top.line(x, y, "hand", plot::Colour::tab(1), 1.5);
  for (std::size_t i = 0; i < segmentation.objects.size(); ++i) {
    const auto& o = segmentation.objects[i];
    if (!o.moved) continue;
    const auto colour = plot::Colour::tab(2 + static_cast<int>(i));
    top.scatter({o.p_initial_m.x()}, {-o.p_initial_m.y()}, o.name + " grasp", colour, plot::Marker::Circle, 6);
    top.scatter({o.p_final_m.x()}, {-o.p_final_m.y()}, "", colour, plot::Marker::Cross, 6);
  }
  fig.save(pngPath);
}

std::vector<std::string> writeContactSheet(const std::string& dir, const ProgrammingOptions& o,
                                           const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                           const motion::Segmentation& segmentation,
                                           const std::optional<taskdb::PerceivedScene>& scene) {
  perception::PerceptionDrawing::Options view;
  if (scene) {
    view.X_camera_table = scene->X_table_camera.inverse();
    view.tableSize_m = scene->tableSize_m;
  }
  const perception::PerceptionDrawing drawing(seen, kb, view);
  struct Event {
    std::string caption;
    cv::Scalar border;
    bool lowConfidence;
  };
  std::map<int, std::vector<Event>> events;
  std::vector<int> marked;
  for (const auto& ob : segmentation.objects) {
    if (!ob.moved) continue;
    if (ob.graspFrame >= 0) events[ob.graspFrame].push_back({"GRASP " + ob.name, cv::Scalar(60, 200, 60), ob.graspLowConfidence});
    if (ob.releaseFrame >= 0)
      events[ob.releaseFrame].push_back({"RELEASE " + ob.name, cv::Scalar(230, 150, 40), ob.releaseLowConfidence});
  }
  for (const auto& [frame, e] : events) marked.push_back(frame);
  const std::vector<int> frames = perception::contactSheetFrames(seen.frames, kContactSheetSpreadFrames, marked);
  std::vector<perception::ContactSheetTile> tiles;
  rawlog::RawlogReader reader(o.demoPath);
  std::size_t next = 0;
  while (next < frames.size()) {
    const auto f = reader.next();
    if (!f) break;
    if (f->index != frames[next]) continue;
    ++next;
    perception::ContactSheetTile tile;
    tile.image = f->colour_bgr8.clone();
    drawing.draw(tile.image, f->index);
    tile.caption = "frame " + std::to_string(f->index);
    const auto e = events.find(f->index);
    if (e != events.end())
      for (const auto& ev : e->second) {
        tile.caption += "  " + ev.caption;
        tile.border = ev.border;
        if (ev.lowConfidence) {
          tile.flag = "LOW CONFIDENCE";
          tile.border = cv::Scalar(40, 40, 255);
        }
      }
    tiles.push_back(std::move(tile));
  }
  const cv::Mat sheet = perception::composeContactSheet(
      tiles, "What perception saw: " + std::to_string(seen.frames) + " frames, hand in " +
                 std::to_string(seen.handDetected) + "; outlines with confidence, table frame, grasp/release framed");
  const std::string path = dir + "/contact_sheet.png";
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", sheet, png)) throw core::FileError(path, "cannot encode the contact sheet");
  core::writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
  return {path};
}

std::vector<std::string> writeProgramReport(const std::string& dir, const ProgramResult& r,
                                            const perception::PerceptionResult& seen,
                                            const motion::Segmentation& segmentation,
                                            const std::vector<motion::SkillSet>& skills) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw core::FileError(dir, "cannot create the report folder (" + ec.message() + ")");
  std::vector<std::string> files;
  const std::string hand = dir + "/hand_trajectory.png";
  writeHandFigure(hand, seen, segmentation);
  files.push_back(hand);
  for (const auto& s : skills)
    for (const auto& o : segmentation.objects)
      if (o.name == s.objectName && o.moved) {
        const std::string path = dir + "/" + core::safeFileName(o.name) + "_skills.png";
        motion::writeSkillFigure(path, segmentation, o, s);
        files.push_back(path);
      }

  const std::string md = dir + "/summary.md";
  std::ostringstream out;
  out << "# Task model " << r.taskModelId << ": " << r.name << " (version " << r.version << ")\n\n";
  out << "## Plan\n\n";
  for (std::size_t i = 0; i < r.planLines.size(); ++i) out << i + 1 << ". " << r.planLines[i] << "\n";
  out << "\n## Demonstration\n\n" << r.frames << " frames; hand detected in " << r.handDetectedFrames << " ("
      << std::fixed << std::setprecision(1) << (r.frames ? 100.0 * r.handDetectedFrames / r.frames : 0.0)
      << " %).\n\n![hand trajectory](hand_trajectory.png)\n\n";
  const auto has = [&](const std::string& name) {
    return std::any_of(r.reportFiles.begin(), r.reportFiles.end(),
                       [&](const std::string& f) { return std::filesystem::path(f).filename() == name; });
  };
  if (has("contact_sheet.png"))
    out << "What perception saw (palm, parts and containers with their confidence, the table frame; grasp and "
           "release frames marked):\n\n![contact sheet](contact_sheet.png)\n\n";
  if (has("scene.json"))
    out << "The scene the demonstration showed (`scene.json`, what `srp execute --db F --task " << r.taskModelId
        << "` runs in without `--scene`); robot base: " << r.robotBase << ".\n\n";
  if (!r.problems.empty()) {
    out << "## Incomplete (--allow-partial)\n\n";
    for (const auto& p : r.problems) out << "- " << p << "\n";
    out << "\n";
  }
  out << "## Segmentation and skills\n\n| object | detected frames | grasp frame | release frame | reach λ | move λ | note |\n"
         "|---|---|---|---|---|---|---|\n";
  out << std::setprecision(3) << std::defaultfloat;
  for (const auto& o : r.objects)
    out << "| " << (o.instanceId.empty() ? o.name : o.instanceId) << " | " << o.detectedFrames << " | " << o.graspFrame << " | " << o.releaseFrame << " | "
        << o.reachLambda << " | " << o.moveLambda << " | " << o.note << " |\n";
  out << "\n";
  for (const auto& f : files)
    if (f.find("_skills.png") != std::string::npos) {
      const std::string name = std::filesystem::path(f).filename().string();
      out << "![" << name << "](" << name << ")\n\n";
    }
  out << "## Timing\n\n";
  for (const auto& t : r.timings) out << "- " << t.stage << ": " << t.wall_s << " s\n";
  if (!r.warnings.empty()) {
    out << "\n## Warnings\n\n";
    for (const auto& w : r.warnings) out << "- " << w << "\n";
  }
  core::writeFileAtomically(md, out.str());
  files.push_back(md);
  return files;
}

}  // namespace srp::programming
