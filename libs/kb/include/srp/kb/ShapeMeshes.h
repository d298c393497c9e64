#pragma once
/// \file ShapeMeshes.h
/// \brief Generators of the knowledge base's CAD models: closed, outward
/// oriented triangle meshes in the object frame of ObjectCatalogue.h (origin at
/// the centre of the bottom face of the bounding box, z up, x along the longest
/// horizontal side), exactly filling the class' `dimensions_m` bounding box.

#include <Eigen/Core>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/kb/TriangleMesh.h"

namespace srp::kb {

/// Solid box spanning [min_m, max_m].
TriangleMesh makeBoxMesh(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m);

/// Prism extruded along z from 0 to height_m over a simple polygon given
/// counter-clockwise in the xy plane, star-shaped with respect to its
/// vertex centroid (caps are fanned from it): stars, convex polygons.
TriangleMesh makePrismMesh(const std::vector<Eigen::Vector2d>& polygon_m, double height_m);

/// Open box (container): floor and four walls of thickness wall_m, open at the
/// top, outer size dimensions_m, bottom face centred at the origin.
TriangleMesh makeOpenBoxMesh(const Eigen::Vector3d& dimensions_m, double wall_m);

/// Outline (counter-clockwise, metres, centred on the bounding box) of the
/// prism shapes: "star" (five points), "parallelogram" (sides skewed by a
/// quarter of the length), "octagon" (regular, flat sides on the axes),
/// "cuboid" (rectangle), scaled to fill size_m = (x, y).
/// Throws InvalidInputError naming the shape when it is not one of these.
std::vector<Eigen::Vector2d> shapeOutline(const std::string& shape, const Eigen::Vector2d& size_m);

/// The mesh of a catalogue class from its `shape` and dimensions ("open_box"
/// uses wall_thickness_m, "hull" its footprint_object). Throws InvalidInputError naming the class and shape
/// for an unknown shape or non-positive dimensions.
TriangleMesh makeClassMesh(const srp::core::ObjectClass& objectClass);

}  // namespace srp::kb
