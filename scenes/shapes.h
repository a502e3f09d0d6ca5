/// Procedural shapes in object space and their transformation to world space.
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace aalab {

/// Quad of size w × h centred at the origin in the XY plane, normal +Z; uv = local (x, y).
Shape MakeQuad(glm::vec2 size);
/// Plane of size w × d centred at the origin in the XZ plane, normal +Y; uv = local (x, z).
Shape MakePlane(glm::vec2 size);
/// Convex planar polygon, fan-triangulated from the first point; uv = local (x, y).
Shape MakePolygon(const std::vector<glm::vec3>& points);
/// Axis-aligned box centred at the origin; uv per face = the face's two in-plane axes.
Shape MakeBox(glm::vec3 size);
/// Triangle soup from explicit vertices and indices (degenerate triangles allowed).
Shape MakeTriangles(const std::vector<glm::vec3>& vertices, const std::vector<glm::uvec3>& indices);
/// Analytic sphere / disk (normal +Z) / capsule / cylinder (flat caps).
Shape MakeSphere(float radius);
Shape MakeDisk(float radius);
Shape MakeSegment(ShapeKind kind, glm::vec3 from, glm::vec3 to, float radius);

/// Loads an OBJ file (tinyobjloader), triangulated; normals and uvs when present.
/// Throws UserError naming the file for unreadable files or empty meshes.
Shape LoadObjMesh(const std::string& path);

/// Builds the object matrix T · Rz · Ry · Rx · S (rotations in degrees about X, then Y, then Z).
glm::mat4 MakeTransform(glm::vec3 translate, glm::vec3 rotate_deg, glm::vec3 scale);

/// Applies the matrix to a shape in place. Analytic shapes (sphere, disk, capsule, cylinder)
/// need a uniform scale; returns false when the scale is not uniform (caller reports it).
bool TransformShape(Shape& shape, const glm::mat4& m);

}  // namespace aalab
