#include "srp/execution/RobotModel.h"

#include <urdf_parser/urdf_parser.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "srp/core/DataPaths.h"
#include "srp/core/Error.h"

namespace srp::execution {
namespace {

using srp::core::Pose3;

Pose3 toPose(const urdf::Pose& p) {
  const Eigen::Quaterniond q(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z);
  return srp::core::makePose(Eigen::Vector3d(p.position.x, p.position.y, p.position.z), q);
}

/// Mass, centre of mass and inertia about the centre of mass, in one frame.
struct Inertia {
  double m = 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
};

/// Combines two inertias given in the same frame (parallel-axis theorem).
Inertia combine(const Inertia& a, const Inertia& b) {
  Inertia r;
  r.m = a.m + b.m;
  if (r.m <= 0.0) return r;
  r.c = (a.m * a.c + b.m * b.c) / r.m;
  auto shift = [](const Inertia& x, const Eigen::Vector3d& to) {
    const Eigen::Vector3d d = x.c - to;
    return Eigen::Matrix3d(x.I + x.m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  r.I = shift(a, r.c) + shift(b, r.c);
  return r;
}

Inertia inertiaOf(const urdf::Link& link, const Pose3& X_ref_link) {
  Inertia r;
  if (!link.inertial) return r;
  const auto& in = *link.inertial;
  Eigen::Matrix3d I;
  I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  const Pose3 X_ref_inertial = X_ref_link * toPose(in.origin);
  r.m = in.mass;
  r.c = X_ref_inertial.translation();
  r.I = X_ref_inertial.linear() * I * X_ref_inertial.linear().transpose();
  return r;
}

}  // namespace

RobotModel RobotModel::fromUrdf(const std::string& urdfPath) {
  std::ifstream in(urdfPath);
  if (!in) throw srp::core::FileError(urdfPath, "cannot open the URDF file");
  const std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  if (!model) throw srp::core::FileError(urdfPath, "not a valid URDF (urdfdom could not parse it)");
  const std::filesystem::path folder = std::filesystem::path(urdfPath).parent_path();

  RobotModel r;
  r.name_ = model->getName();
  urdf::LinkConstSharedPtr link = model->getRoot();
  auto meshOf = [&](const urdf::Link& l, LinkInertia& out) {
    if (l.collision && l.collision->geometry && l.collision->geometry->type == urdf::Geometry::MESH) {
      const auto& mesh = static_cast<const urdf::Mesh&>(*l.collision->geometry);
      out.collisionMesh = (folder / mesh.filename).string();
      out.X_link_mesh = toPose(l.collision->origin);
    }
  };

  // Lumps `l` and its fixed descendants (recording tool0 / tcp) into one inertia.
  std::function<Inertia(const urdf::Link&, const Pose3&)> lump = [&](const urdf::Link& l,
                                                                    const Pose3& X_ref_l) {
    Inertia total = inertiaOf(l, X_ref_l);
    if (l.name == "tool0") r.X_wrist3_tool0_ = X_ref_l;
    if (l.name == "tcp") r.X_wrist3_tcp_ = X_ref_l;
    for (const auto& j : l.child_joints) {
      if (j->type != urdf::Joint::FIXED) continue;
      const auto child = model->getLink(j->child_link_name);
      total = combine(total, lump(*child, X_ref_l * toPose(j->parent_to_joint_origin_transform)));
    }
    return total;
  };

  for (int i = 0; i <= 6; ++i) {
    LinkInertia& li = r.links_[i];
    li.name = link->name;
    meshOf(*link, li);
    const Inertia inertia = lump(*link, Pose3::Identity());
    li.mass_kg = inertia.m;
    li.p_link_com_m = inertia.c;
    li.I_com_kgm2 = inertia.I;
    if (i == 6) break;
    // The next moving joint below this link.
    urdf::JointConstSharedPtr next;
    for (const auto& j : link->child_joints)
      if (j->type == urdf::Joint::REVOLUTE || j->type == urdf::Joint::CONTINUOUS) {
        if (next)
          throw srp::core::InvalidInputError(urdfPath + ": link '" + link->name +
                                             "' has more than one moving child joint; srp needs "
                                             "a serial 6-joint arm");
        next = j;
      }
    if (!next)
      throw srp::core::InvalidInputError(urdfPath + ": the chain ends after " + std::to_string(i) +
                                         " revolute joints; srp needs a 6-joint arm");
    const Eigen::Vector3d axis(next->axis.x, next->axis.y, next->axis.z);
    if ((axis - Eigen::Vector3d::UnitZ()).norm() > 1e-9)
      throw srp::core::InvalidInputError(urdfPath + ": joint '" + next->name +
                                         "' must rotate about its z axis (axis 0 0 1)");
    ArmJoint& aj = r.joints_[i];
    aj.name = next->name;
    aj.parentLink = next->parent_link_name;
    aj.childLink = next->child_link_name;
    aj.X_parent_joint = toPose(next->parent_to_joint_origin_transform);
    if (next->type == urdf::Joint::REVOLUTE && next->limits) {
      aj.lower_rad = next->limits->lower;
      aj.upper_rad = next->limits->upper;
    } else {
      aj.lower_rad = -2.0 * M_PI;
      aj.upper_rad = 2.0 * M_PI;
    }
    if (!next->limits || next->limits->velocity <= 0.0 || next->limits->effort <= 0.0)
      throw srp::core::InvalidInputError(urdfPath + ": joint '" + next->name +
                                         "' needs <limit velocity> and <limit effort> > 0");
    aj.maxVelocity_radps = next->limits->velocity;
    aj.maxEffort_Nm = next->limits->effort;
    link = model->getLink(next->child_link_name);
  }
  if (!model->getLink("tool0") || !model->getLink("tcp"))
    throw srp::core::InvalidInputError(urdfPath +
                                       ": the last link needs fixed child links 'tool0' and 'tcp'");
  return r;
}

RobotModel RobotModel::defaultUr5() { return fromUrdf(core::DataPaths::file("sim/ur5/ur5.urdf").string()); }

std::array<srp::core::Pose3, 7> RobotModel::linkPoses(const JointVector& q) const {
  std::array<Pose3, 7> X;
  X[0] = Pose3::Identity();
  for (int i = 0; i < 6; ++i)
    X[i + 1] = X[i] * joints_[i].X_parent_joint * Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ());
  return X;
}

srp::core::Pose3 RobotModel::X_base_tool0(const JointVector& q) const {
  return linkPoses(q)[6] * X_wrist3_tool0_;
}

srp::core::Pose3 RobotModel::X_base_tcp(const JointVector& q) const {
  return linkPoses(q)[6] * X_wrist3_tcp_;
}

bool RobotModel::withinLimits(const JointVector& q) const {
  for (int i = 0; i < 6; ++i)
    if (!(q[i] >= joints_[i].lower_rad && q[i] <= joints_[i].upper_rad)) return false;
  return true;
}

JointVector RobotModel::lowerLimits_rad() const {
  JointVector v;
  for (int i = 0; i < 6; ++i) v[i] = joints_[i].lower_rad;
  return v;
}
JointVector RobotModel::upperLimits_rad() const {
  JointVector v;
  for (int i = 0; i < 6; ++i) v[i] = joints_[i].upper_rad;
  return v;
}
JointVector RobotModel::maxVelocities_radps() const {
  JointVector v;
  for (int i = 0; i < 6; ++i) v[i] = joints_[i].maxVelocity_radps;
  return v;
}

}  // namespace srp::execution
