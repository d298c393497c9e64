#include "srp/execution/CellRenderer.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <mrpt/img/CImage.h>
#include <mrpt/opengl/CBox.h>
#include <mrpt/opengl/CCylinder.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/opengl/CSphere.h>
#include <mrpt/poses/CPose3D.h>

#include "srp/core/Error.h"
#include "srp/execution/SafetyChecker.h"
#include "srp/interop/PoseConversions.h"
#include "srp/kb/ShapeMeshes.h"
#include "srp/kb/TriangleMesh.h"

namespace srp::execution {
namespace {

using srp::core::Pose3;

// UR5 colours: the links' "LightGrey" (Universal_Robots_ROS2_Description,
// config/ur5/visual_parameters.yaml); the gripper dark grey with a black cup.
const Eigen::Vector3d kLinkRgb(0.7, 0.7, 0.7);
const Eigen::Vector3d kToolRgb(0.25, 0.25, 0.27);
const Eigen::Vector3d kCupRgb(0.05, 0.05, 0.05);
// The gripper model (see CellRenderer.h): along tool0's z axis.
constexpr double kToolRadius_m = 0.02, kCupStart_m = 0.085, kCupTipRadius_m = 0.018, kCupBaseRadius_m = 0.012;

mrpt::img::TColor toColour(const Eigen::Vector3d& rgb, double alpha = 1.0) {
  auto c = [](double v) { return static_cast<uint8_t>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5); };
  return mrpt::img::TColor(c(rgb.x()), c(rgb.y()), c(rgb.z()), c(alpha));
}

mrpt::opengl::CBox::Ptr box(const WorldBox& b, const Eigen::Vector3d& rgb) {
  const Eigen::Vector3d h = b.halfExtents_m;
  auto o = mrpt::opengl::CBox::Create(mrpt::math::TPoint3D(-h.x(), -h.y(), -h.z()),
                                      mrpt::math::TPoint3D(h.x(), h.y(), h.z()));
  o->setPose(srp::interop::toMrpt(b.X_world_box));
  o->setColor(static_cast<float>(rgb.x()), static_cast<float>(rgb.y()), static_cast<float>(rgb.z()));
  return o;
}

/// The mesh (moved by X_frame_mesh) as MRPT triangles with face normals, one colour.
mrpt::opengl::CSetOfTriangles::Ptr triangles(const srp::kb::TriangleMesh& mesh, const Pose3& X_frame_mesh,
                                             const Eigen::Vector3d& rgb) {
  auto o = mrpt::opengl::CSetOfTriangles::Create();
  o->reserve(mesh.size());
  const mrpt::img::TColor colour = toColour(rgb);
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3f a = (X_frame_mesh * t[0]).cast<float>(), b = (X_frame_mesh * t[1]).cast<float>(),
                          c = (X_frame_mesh * t[2]).cast<float>();
    mrpt::opengl::TTriangle tri(mrpt::math::TPoint3Df(a.x(), a.y(), a.z()), mrpt::math::TPoint3Df(b.x(), b.y(), b.z()),
                                mrpt::math::TPoint3Df(c.x(), c.y(), c.z()));
    for (auto& v : tri.vertices) v.setColor(colour);
    o->insertTriangle(tri);
  }
  o->setColor_u8(colour);
  return o;
}

}  // namespace

struct CellRenderer::Impl {
  RobotModel model;
  CellDescription cell;
  CellRenderer::Options options;
  SafetyChecker spheres;
  std::unique_ptr<mrpt::opengl::CFBORender> fbo;
  /// Link meshes in their link frames ([0] base .. [6] wrist 3), null when a link has none.
  std::array<mrpt::opengl::CSetOfTriangles::Ptr, 7> links;
  std::vector<mrpt::opengl::CRenderizable::Ptr> gripper;  ///< in the tool0 frame
  std::map<std::string, mrpt::opengl::CSetOfTriangles::Ptr> partMeshes;  ///< in the object frame
  std::optional<mrpt::opengl::TRenderMatrices> lastCamera;
  Impl(RobotModel m, CellDescription c, CellRenderer::Options o)
      : model(m), cell(c), options(o), spheres(m, c.X_world_base, SafetyLimits{}, {}) {}
};

CellRenderer::CellRenderer(RobotModel model, CellDescription cell, CellRenderer::Options options)
    : impl_(std::make_unique<Impl>(std::move(model), std::move(cell), options)) {
  Impl& m = *impl_;
  for (int i = 0; i < 7; ++i) {
    const LinkInertia& link = m.model.links()[i];
    if (link.collisionMesh.empty()) continue;
    m.links[i] = triangles(srp::kb::TriangleMesh::load(link.collisionMesh), link.X_link_mesh, kLinkRgb);
  }
  auto body = mrpt::opengl::CCylinder::Create(kToolRadius_m, kToolRadius_m, kCupStart_m, 24);
  body->setColor_u8(toColour(kToolRgb));
  const double toolLength_m = m.model.X_tool0_tcp().translation().z();
  auto cup = mrpt::opengl::CCylinder::Create(kCupBaseRadius_m, kCupTipRadius_m, toolLength_m - kCupStart_m, 24);
  cup->setLocation(0, 0, kCupStart_m);
  cup->setColor_u8(toColour(kCupRgb));
  m.gripper = {body, cup};
  for (const auto& o : m.cell.objects) {
    if (o.kind != CellObjectKind::Part) continue;
    if (o.observedClass)  // seen without a CAD file: its hull prism
      m.partMeshes[o.name] = triangles(srp::kb::makeClassMesh(*o.observedClass), Pose3::Identity(), o.rgb);
    else if (!o.meshPath.empty() && std::filesystem::exists(o.meshPath))
      m.partMeshes[o.name] = triangles(srp::kb::TriangleMesh::load(o.meshPath).scaled(o.meshScale), Pose3::Identity(), o.rgb);
  }
  try {
    m.fbo = std::make_unique<mrpt::opengl::CFBORender>(options.width_px, options.height_px);
  } catch (const std::exception& e) {
    throw srp::core::Error(std::string("CellRenderer: cannot create an off-screen OpenGL (EGL) context: ") + e.what());
  }
}

CellRenderer::~CellRenderer() = default;

const CellRenderer::Options& CellRenderer::options() const { return impl_->options; }

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
      continue;
    }
    const auto it = snapshot.X_world_parts.find(o.name);
    const Pose3 X_world_part = it != snapshot.X_world_parts.end() ? it->second : o.X_world_object;
    if (const auto mesh = m.partMeshes.find(o.name); mesh != m.partMeshes.end()) {
      mesh->second->setPose(srp::interop::toMrpt(X_world_part));
      scene.insert(mesh->second);
    } else {
      WorldBox b;
      b.X_world_box = X_world_part * Eigen::Translation3d(0, 0, o.size_m.z() / 2);
      b.halfExtents_m = o.size_m / 2;
      scene.insert(box(b, o.rgb));
    }
  }
  // The arm: each link mesh at its forward-kinematics pose, the gripper on tool0.
  const auto X_base_links = m.model.linkPoses(snapshot.q_rad);
  for (int i = 0; i < 7; ++i) {
    if (!m.links[i]) continue;
    m.links[i]->setPose(srp::interop::toMrpt(Pose3(m.cell.X_world_base * X_base_links[i])));
    scene.insert(m.links[i]);
  }
  const Pose3 X_world_tool0 = m.cell.X_world_base * X_base_links[6] * m.model.X_wrist3_tool0();
  for (const auto& g : m.gripper) {
    const Eigen::Vector3d offset(0, 0, g == m.gripper.front() ? 0.0 : kCupStart_m);
    g->setPose(srp::interop::toMrpt(Pose3(X_world_tool0 * Eigen::Translation3d(offset))));
    scene.insert(g);
  }
  if (m.options.drawSafetySpheres) {
    for (const auto& s : m.spheres.armSpheres(snapshot.q_rad)) {
      auto sp = mrpt::opengl::CSphere::Create(static_cast<float>(std::max(s.radius_m, 0.008)));
      sp->setLocation(s.centre_world_m.x(), s.centre_world_m.y(), s.centre_world_m.z());
      sp->setColor_u8(mrpt::img::TColor(60, 110, 200, 90));
      scene.insert(sp);
    }
  }
  // A light background and more ambient light: the grey arm's shaded side stays grey.
  auto viewport = scene.getViewport();
  viewport->setCustomBackgroundColor(mrpt::img::TColorf(0.93f, 0.95f, 0.98f));
  viewport->lightParameters().ambient = mrpt::img::TColorf(0.45f, 0.45f, 0.45f, 1.0f);
  viewport->lightParameters().diffuse = mrpt::img::TColorf(0.6f, 0.6f, 0.6f, 1.0f);
  auto& cam = m.fbo->getCamera(scene);
  cam.setPointingAt(m.options.lookAt_world_m.x(), m.options.lookAt_world_m.y(), m.options.lookAt_world_m.z());
  cam.setZoomDistance(static_cast<float>(m.options.distance_m));
  cam.setAzimuthDegrees(static_cast<float>(m.options.azimuth_deg));
  cam.setElevationDegrees(static_cast<float>(m.options.elevation_deg));
  mrpt::img::CImage image;
  m.fbo->render_RGB(scene, image);
  m.lastCamera = viewport->getRenderMatrices();
  if (!image.saveToFile(path)) throw srp::core::FileError(path, "cannot write the rendered PNG frame");
}

std::optional<Eigen::Vector3d> CellRenderer::project(const Eigen::Vector3d& p_world_m) const {
  const Impl& m = *impl_;
  if (!m.lastCamera) throw srp::core::InvalidInputError("CellRenderer::project: render a frame first");
  // clip = P V [x y z 1]' (the model matrix of the last drawn object is not wanted).
  const auto& c = *m.lastCamera;
  Eigen::Matrix4d P, V;
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < 4; ++k) P(r, k) = c.p_matrix(r, k), V(r, k) = c.v_matrix(r, k);
  const Eigen::Vector4d clip = P * V * p_world_m.homogeneous();
  if (!(clip.w() > 0.0)) return std::nullopt;
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  const double u = (ndc.x() + 1.0) / 2.0 * m.options.width_px;
  const double v = (1.0 - ndc.y()) / 2.0 * m.options.height_px;
  const Eigen::Vector3d eye(c.eye.x, c.eye.y, c.eye.z);
  return Eigen::Vector3d(u, v, (p_world_m - eye).norm());
}

}  // namespace srp::execution
