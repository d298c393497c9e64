#include "srp/synth/SceneRenderer.h"

#include <EGL/egl.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdlib>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"
#include "srp/interop/PoseConversions.h"

namespace srp::synth {
namespace {

std::uint8_t toU8(double v) { return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); }

// Headless by default: EGL's surfaceless platform on Mesa needs no display.
// Variables the user already set win (setenv with overwrite = 0).
void prepareHeadlessEnvironment() {
  if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
    setenv("EGL_PLATFORM", "surfaceless", 0);
}

}  // namespace

struct SceneRenderer::Impl {
  std::unique_ptr<mrpt::opengl::CFBORender> fbo;
  mrpt::opengl::COpenGLScene scene;
  std::vector<mrpt::opengl::CSetOfTriangles::Ptr> bodies;
  mrpt::img::CImage rgb;
  mrpt::math::CMatrixFloat depth;
  // This MRPT's CFBORender makes its EGL context current only when created;
  // with several renderers in one thread, each must make its own current
  // before rendering (else it draws into the last one created, at its size).
  EGLDisplay eglDisplay = EGL_NO_DISPLAY;
  EGLContext eglContext = EGL_NO_CONTEXT;
  EGLSurface eglDraw = EGL_NO_SURFACE, eglRead = EGL_NO_SURFACE;
  void makeCurrent() const {
    if (eglContext != EGL_NO_CONTEXT && eglGetCurrentContext() != eglContext &&
        eglMakeCurrent(eglDisplay, eglDraw, eglRead, eglContext) != EGL_TRUE)
      throw srp::core::Error("SceneRenderer: cannot make its EGL context current (EGL error " +
                             std::to_string(eglGetError()) + ")");
  }
};

SceneRenderer::SceneRenderer(const srp::core::CameraIntrinsics& K, double minDepth_m, double maxDepth_m)
    : impl_(std::make_unique<Impl>()), K_(K) {
  K.validate("SceneRenderer intrinsics");
  prepareHeadlessEnvironment();
  try {
    impl_->fbo = std::make_unique<mrpt::opengl::CFBORender>(K.width_px, K.height_px);
    impl_->eglDisplay = eglGetCurrentDisplay();
    impl_->eglContext = eglGetCurrentContext();
    impl_->eglDraw = eglGetCurrentSurface(EGL_DRAW);
    impl_->eglRead = eglGetCurrentSurface(EGL_READ);
  } catch (const std::exception& e) {
    throw srp::core::Error(std::string("SceneRenderer: cannot create the off-screen EGL renderer (EGL_PLATFORM=") +
                           (std::getenv("EGL_PLATFORM") ? std::getenv("EGL_PLATFORM") : "") +
                           "; is libegl-mesa0 installed?): " + e.what());
  }
  auto vp = impl_->scene.getViewport();
  vp->setViewportClipDistances(minDepth_m, maxDepth_m);
  vp->setCustomBackgroundColor(mrpt::img::TColorf(0.f, 0.f, 0.f, 1.f));

  // MRPT's pinhole projection puts pixel centres at +0.5 (OpenGL window
  // coordinates); shifting the principal point by half a pixel makes the
  // rendered pixel (u, v) see exactly the ray of CameraIntrinsics::backProject(u, v).
  mrpt::img::TCamera cam;
  cam.ncols = K.width_px;
  cam.nrows = K.height_px;
  cam.fx(K.fx_px);
  cam.fy(K.fy_px);
  cam.cx(K.cx_px + 0.5);
  cam.cy(K.cy_px + 0.5);
  auto& camera = impl_->fbo->getCamera(impl_->scene);
  camera.setProjectiveFromPinhole(cam);
  camera.set6DOFMode(true);
}

SceneRenderer::~SceneRenderer() {
  // MRPT deletes the FBO in whatever context is current: make it ours. When
  // another renderer's destruction already terminated the shared EGL display
  // (and with it this context), release the thread's context instead, so the
  // deletions are no-ops rather than GL errors in a foreign context (MRPT
  // throws those from its destructor, which terminates the program).
  if (!impl_ || !impl_->fbo) return;
  if (impl_->eglContext != EGL_NO_CONTEXT && eglGetCurrentContext() != impl_->eglContext &&
      eglMakeCurrent(impl_->eglDisplay, impl_->eglDraw, impl_->eglRead, impl_->eglContext) != EGL_TRUE)
    eglReleaseThread();
  impl_->fbo.reset();
}

int SceneRenderer::addBody(const std::string& name, const srp::kb::TriangleMesh& mesh,
                           const Eigen::Vector3d& rgb) {
  return addBody(name, mesh, std::vector<Eigen::Vector3d>(mesh.size(), rgb));
}

int SceneRenderer::addBody(const std::string& name, const srp::kb::TriangleMesh& mesh,
                           const std::vector<Eigen::Vector3d>& triangleRgb) {
  srp::core::require(triangleRgb.size() == mesh.size(),
                     "SceneRenderer::addBody '" + name + "': one colour per triangle needed");
  auto body = mrpt::opengl::CSetOfTriangles::Create();
  body->setName(name);
  std::vector<mrpt::opengl::TTriangle> tris;
  tris.reserve(mesh.size());
  for (std::size_t i = 0; i < mesh.size(); ++i) {
    const auto& t = mesh.triangles()[i];
    const Eigen::Vector3d n = mesh.normal(i);
    mrpt::opengl::TTriangle tri;
    for (int v = 0; v < 3; ++v) {
      tri.vertex(v) = mrpt::math::TPoint3Df(static_cast<float>(t[v].x()), static_cast<float>(t[v].y()),
                                            static_cast<float>(t[v].z()));
      tri.vertices[v].normal = mrpt::math::TVector3Df(static_cast<float>(n.x()), static_cast<float>(n.y()),
                                                      static_cast<float>(n.z()));
    }
    const Eigen::Vector3d& c = triangleRgb[i];
    tri.setColor(mrpt::img::TColor(toU8(c.x()), toU8(c.y()), toU8(c.z()), 255));
    tris.push_back(tri);
  }
  body->insertTriangles(tris.begin(), tris.end());
  impl_->scene.insert(body);
  impl_->bodies.push_back(body);
  return static_cast<int>(impl_->bodies.size()) - 1;
}

void SceneRenderer::setBodyPose(int body, const srp::core::Pose3& X_world_body) {
  impl_->bodies.at(body)->setPose(srp::interop::toMrpt(X_world_body));
}

void SceneRenderer::setBodyVisible(int body, bool visible) { impl_->bodies.at(body)->setVisibility(visible); }

int SceneRenderer::bodyCount() const { return static_cast<int>(impl_->bodies.size()); }

void SceneRenderer::setLighting(const srp::core::SceneLighting& lighting, const Eigen::Vector3d& rgb) {
  auto& light = impl_->scene.getViewport()->lightParameters();
  auto scaled = [&](double intensity) {
    return mrpt::img::TColorf(static_cast<float>(intensity * rgb.x()), static_cast<float>(intensity * rgb.y()),
                              static_cast<float>(intensity * rgb.z()), 1.f);
  };
  light.ambient = scaled(lighting.ambient);
  light.diffuse = scaled(lighting.diffuse);
  light.specular = mrpt::img::TColorf(0.f, 0.f, 0.f, 1.f);
  const Eigen::Vector3d dir = lighting.direction_world.normalized();
  light.direction = mrpt::math::TVector3Df(static_cast<float>(dir.x()), static_cast<float>(dir.y()),
                                           static_cast<float>(dir.z()));
}

void SceneRenderer::setBackground(const Eigen::Vector3d& rgb) {
  impl_->scene.getViewport()->setCustomBackgroundColor(mrpt::img::TColorf(
      static_cast<float>(rgb.x()), static_cast<float>(rgb.y()), static_cast<float>(rgb.z()), 1.f));
}

srp::rawlog::RgbdFrame SceneRenderer::render(const srp::core::Pose3& X_world_camera) {
  impl_->makeCurrent();
  impl_->fbo->getCamera(impl_->scene).setPose(srp::interop::toMrpt(X_world_camera));
  impl_->fbo->render_RGBD(impl_->scene, impl_->rgb, impl_->depth);
  srp::rawlog::RgbdFrame frame;
  frame.intrinsics = K_;
  frame.colour_bgr8 = impl_->rgb.asCvMat<cv::Mat>(mrpt::img::DEEP_COPY);
  if (frame.colour_bgr8.channels() == 1) cv::cvtColor(frame.colour_bgr8, frame.colour_bgr8, cv::COLOR_GRAY2BGR);
  frame.depth_m.create(K_.height_px, K_.width_px, CV_32FC1);
  for (int r = 0; r < K_.height_px; ++r)  // CMatrixFloat is row-major
    std::memcpy(frame.depth_m.ptr<float>(r), &impl_->depth(r, 0), sizeof(float) * K_.width_px);
  return frame;
}

}  // namespace srp::synth
