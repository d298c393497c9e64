#include "srp/execution/CellRenderer.h"

#include <mrpt/img/CImage.h>
#include <mrpt/opengl/CBox.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSphere.h>
#include <mrpt/poses/CPose3D.h>

#include "srp/core/Error.h"
#include "srp/core/PoseConversions.h"
#include "srp/execution/SafetyChecker.h"

namespace srp::execution {

struct CellRenderer::Impl {
  RobotModel model;
  CellDescription cell;
  CellRendererOptions options;
  SafetyChecker spheres;
  std::unique_ptr<mrpt::opengl::CFBORender> fbo;
  Impl(RobotModel m, CellDescription c, CellRendererOptions o)
      : model(m), cell(c), options(o), spheres(m, c.X_world_base, SafetyLimits{}, {}) {}
};

namespace {
mrpt::opengl::CBox::Ptr box(const WorldBox& b, const Eigen::Vector3d& rgb) {
  const Eigen::Vector3d h = b.halfExtents_m;
  auto o = mrpt::opengl::CBox::Create(mrpt::math::TPoint3D(-h.x(), -h.y(), -h.z()),
                                      mrpt::math::TPoint3D(h.x(), h.y(), h.z()));
  o->setPose(srp::core::toMrpt(b.X_world_box));
  o->setColor(static_cast<float>(rgb.x()), static_cast<float>(rgb.y()), static_cast<float>(rgb.z()));
  return o;
}
}  // namespace

CellRenderer::CellRenderer(RobotModel model, CellDescription cell, CellRendererOptions options)
    : impl_(std::make_unique<Impl>(std::move(model), std::move(cell), options)) {
  try {
    impl_->fbo = std::make_unique<mrpt::opengl::CFBORender>(options.width_px, options.height_px);
  } catch (const std::exception& e) {
    throw srp::core::Error(std::string("CellRenderer: cannot create an off-screen OpenGL (EGL) context: ") + e.what());
  }
}

CellRenderer::~CellRenderer() = default;

void CellRenderer::renderPng(const CellSnapshot& snapshot, const std::string& path) {
  Impl& m = *impl_;
  mrpt::opengl::COpenGLScene scene;
  WorldBox table;
  table.X_world_box.translation() = Eigen::Vector3d(m.cell.tableCentre_m.x(), m.cell.tableCentre_m.y(), -0.01);
  table.halfExtents_m = Eigen::Vector3d(m.cell.tableHalfExtents_m.x(), m.cell.tableHalfExtents_m.y(), 0.01);
  scene.insert(box(table, Eigen::Vector3d(0.76, 0.7, 0.6)));
  for (const auto& o : m.cell.objects) {
    if (o.kind == CellObjectKind::Container) {
      for (WorldBox b : CellDescription::containerBoxes(o)) {
        b.X_world_box = o.X_world_object * b.X_world_box;
        scene.insert(box(b, o.rgb));
      }
    } else {
      const auto it = snapshot.X_world_parts.find(o.name);
      WorldBox b;
      b.X_world_box = (it != snapshot.X_world_parts.end() ? it->second : o.X_world_object) *
                      Eigen::Translation3d(0, 0, o.size_m.z() / 2);
      b.halfExtents_m = o.size_m / 2;
      scene.insert(box(b, o.rgb));
    }
  }
  for (const auto& s : m.spheres.armSpheres(snapshot.q_rad)) {
    auto sp = mrpt::opengl::CSphere::Create(static_cast<float>(std::max(s.radius_m, 0.008)));
    sp->setLocation(s.centre_world_m.x(), s.centre_world_m.y(), s.centre_world_m.z());
    const bool tool = s.link == "tool" || s.link == "tcp";
    sp->setColor(tool ? 0.2f : 0.35f, tool ? 0.2f : 0.55f, tool ? 0.2f : 0.75f);
    scene.insert(sp);
  }
  auto& cam = m.fbo->getCamera(scene);
  cam.setPointingAt(m.options.lookAt_world_m.x(), m.options.lookAt_world_m.y(), m.options.lookAt_world_m.z());
  cam.setZoomDistance(static_cast<float>(m.options.distance_m));
  cam.setAzimuthDegrees(static_cast<float>(m.options.azimuth_deg));
  cam.setElevationDegrees(static_cast<float>(m.options.elevation_deg));
  mrpt::img::CImage image;
  m.fbo->render_RGB(scene, image);
  if (!image.saveToFile(path)) throw srp::core::FileError(path, "cannot write the rendered PNG frame");
}

}  // namespace srp::execution
