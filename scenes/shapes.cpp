#include "scenes/shapes.h"

#include <tiny_obj_loader.h>

#include <cmath>

#include "core/error.h"

namespace aalab {

namespace {

void AddTri(Shape& s, uint32_t a, uint32_t b, uint32_t c) { s.triangles.emplace_back(a, b, c); }

uint32_t AddVertex(Shape& s, glm::vec3 p, glm::vec2 uv) {
  s.positions.push_back(p);
  s.uvs.push_back(uv);
  return static_cast<uint32_t>(s.positions.size() - 1);
}

}  // namespace

Shape MakeQuad(glm::vec2 size) {
  Shape s;
  s.source = "quad";
  const float hx = size.x * 0.5f, hy = size.y * 0.5f;
  const uint32_t a = AddVertex(s, {-hx, -hy, 0}, {-hx, -hy});
  const uint32_t b = AddVertex(s, {hx, -hy, 0}, {hx, -hy});
  const uint32_t c = AddVertex(s, {hx, hy, 0}, {hx, hy});
  const uint32_t d = AddVertex(s, {-hx, hy, 0}, {-hx, hy});
  AddTri(s, a, b, c);
  AddTri(s, a, c, d);
  return s;
}

Shape MakePlane(glm::vec2 size) {
  Shape s;
  s.source = "plane";
  const float hx = size.x * 0.5f, hz = size.y * 0.5f;
  const uint32_t a = AddVertex(s, {-hx, 0, -hz}, {-hx, -hz});
  const uint32_t b = AddVertex(s, {hx, 0, -hz}, {hx, -hz});
  const uint32_t c = AddVertex(s, {hx, 0, hz}, {hx, hz});
  const uint32_t d = AddVertex(s, {-hx, 0, hz}, {-hx, hz});
  AddTri(s, a, c, b);
  AddTri(s, a, d, c);
  return s;
}

Shape MakePolygon(const std::vector<glm::vec3>& points) {
  Shape s;
  s.source = "polygon";
  for (const auto& p : points) AddVertex(s, p, {p.x, p.y});
  for (uint32_t i = 1; i + 1 < points.size(); ++i) AddTri(s, 0, i, i + 1);
  return s;
}

Shape MakeBox(glm::vec3 size) {
  Shape s;
  s.source = "box";
  const glm::vec3 h = size * 0.5f;
  // Each face: axis n (0..2), sign; in-plane axes u, v chosen so (u × v) points outward.
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      glm::vec3 corner[4];
      const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
      uint32_t idx[4];
      for (int k = 0; k < 4; ++k) {
        corner[k][axis] = sign * h[axis];
        corner[k][u] = su[k] * h[u];
        corner[k][v] = sv[k] * h[v];
        idx[k] = AddVertex(s, corner[k], {corner[k][u], corner[k][v]});
      }
      if (sign > 0) {
        AddTri(s, idx[0], idx[1], idx[2]);
        AddTri(s, idx[0], idx[2], idx[3]);
      } else {
        AddTri(s, idx[0], idx[2], idx[1]);
        AddTri(s, idx[0], idx[3], idx[2]);
      }
    }
  }
  return s;
}

Shape MakeTriangles(const std::vector<glm::vec3>& vertices, const std::vector<glm::uvec3>& indices) {
  Shape s;
  s.source = "triangles";
  for (const auto& p : vertices) AddVertex(s, p, {p.x, p.y});
  s.triangles = indices;
  return s;
}

Shape MakeSphere(float radius) {
  Shape s;
  s.kind = ShapeKind::kSphere;
  s.source = "sphere";
  s.radius = radius;
  return s;
}

Shape MakeDisk(float radius) {
  Shape s;
  s.kind = ShapeKind::kDisk;
  s.source = "disk";
  s.radius = radius;
  s.normal = {0, 0, 1};
  s.tangent = {1, 0, 0};
  return s;
}

Shape MakeSegment(ShapeKind kind, glm::vec3 from, glm::vec3 to, float radius) {
  Shape s;
  s.kind = kind;
  s.source = kind == ShapeKind::kCapsule ? "capsule" : "cylinder";
  s.p0 = from;
  s.p1 = to;
  s.radius = radius;
  return s;
}

Shape LoadObjMesh(const std::string& path) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    throw UserError("mesh '" + path +
                    "': " + (reader.Error().empty() ? std::string("cannot read file") : reader.Error()));
  }
  const auto& attrib = reader.GetAttrib();
  Shape s;
  s.source = "mesh";
  const bool has_normals = !attrib.normals.empty();
  for (const auto& shape : reader.GetShapes()) {
    const auto& mesh = shape.mesh;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      if (mesh.num_face_vertices[f] != 3) {
        throw UserError("mesh '" + path + "': face " + std::to_string(f) + " is not a triangle after triangulation");
      }
      uint32_t idx[3];
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t i = mesh.indices[f * 3 + k];
        if (i.vertex_index < 0 || static_cast<size_t>(3 * i.vertex_index + 2) >= attrib.vertices.size()) {
          throw UserError("mesh '" + path + "': face " + std::to_string(f) + " has a vertex index out of range");
        }
        glm::vec3 p(attrib.vertices[3 * i.vertex_index], attrib.vertices[3 * i.vertex_index + 1],
                    attrib.vertices[3 * i.vertex_index + 2]);
        for (int c = 0; c < 3; ++c) {
          if (!std::isfinite(p[c])) throw UserError("mesh '" + path + "': non-finite vertex coordinate");
        }
        glm::vec2 uv(p.x, p.y);
        if (i.texcoord_index >= 0 && static_cast<size_t>(2 * i.texcoord_index + 1) < attrib.texcoords.size()) {
          uv = {attrib.texcoords[2 * i.texcoord_index], attrib.texcoords[2 * i.texcoord_index + 1]};
        }
        idx[k] = AddVertex(s, p, uv);
        if (has_normals) {
          glm::vec3 n(0, 0, 1);
          if (i.normal_index >= 0 && static_cast<size_t>(3 * i.normal_index + 2) < attrib.normals.size()) {
            n = {attrib.normals[3 * i.normal_index], attrib.normals[3 * i.normal_index + 1],
                 attrib.normals[3 * i.normal_index + 2]};
          }
          s.normals.push_back(n);
        }
      }
      AddTri(s, idx[0], idx[1], idx[2]);
    }
  }
  if (s.triangles.empty()) throw UserError("mesh '" + path + "' has no triangles");
  return s;
}

glm::mat4 MakeTransform(glm::vec3 translate, glm::vec3 rotate_deg, glm::vec3 scale) {
  glm::mat4 m(1.0f);
  const glm::vec3 r = glm::radians(rotate_deg);
  auto rot = [](float a, int axis) {
    glm::mat4 R(1.0f);
    const float c = std::cos(a), s = std::sin(a);
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    R[i][i] = c;
    R[j][i] = -s;
    R[i][j] = s;
    R[j][j] = c;
    return R;
  };
  glm::mat4 T(1.0f);
  T[3] = glm::vec4(translate, 1.0f);
  glm::mat4 S(1.0f);
  S[0][0] = scale.x;
  S[1][1] = scale.y;
  S[2][2] = scale.z;
  m = T * rot(r.z, 2) * rot(r.y, 1) * rot(r.x, 0) * S;
  return m;
}

bool TransformShape(Shape& s, const glm::mat4& m) {
  const glm::mat3 linear(m);
  // The normal matrix in double: the inverse of a 1e-30 scale is 1e30, whose square
  // overflows float and normalize() would return a zero normal.
  const glm::dmat3 normal_m = glm::transpose(glm::inverse(glm::dmat3(linear)));
  auto point = [&m](glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); };
  if (s.kind == ShapeKind::kTriangles) {
    for (auto& p : s.positions) p = point(p);
    for (auto& n : s.normals) {
      const glm::dvec3 t = normal_m * glm::dvec3(n);
      const double len = glm::length(t);
      n = len > 0.0 ? glm::vec3(t / len) : glm::vec3(0, 0, 1);
    }
    for (auto& t4 : s.tangents) {  // tangents follow the surface: the linear part, handedness kept
      const glm::dvec3 t = glm::dmat3(linear) * glm::dvec3(glm::vec3(t4));
      const double len = glm::length(t);
      const float w = glm::determinant(glm::dmat3(linear)) < 0.0 ? -t4.w : t4.w;
      t4 = glm::vec4(len > 0.0 ? glm::vec3(t / len) : glm::vec3(1, 0, 0), w);
    }
    return true;
  }
  // Column lengths in double: in float, a scale of 1e-30 squares to 0 and was reported as a
  // non-uniform scale (the caller checks the scaled radius for float under/overflow).
  const double sx = glm::length(glm::dvec3(linear[0])), sy = glm::length(glm::dvec3(linear[1])),
               sz = glm::length(glm::dvec3(linear[2]));
  const double smax = std::max(sx, std::max(sy, sz)), smin = std::min(sx, std::min(sy, sz));
  if (!(smin > 0.0) || (smax - smin) > 1e-5 * smax) return false;
  s.center = point(s.center);
  s.p0 = point(s.p0);
  s.p1 = point(s.p1);
  s.radius = static_cast<float>(s.radius * sx);
  s.normal = glm::vec3(glm::normalize(normal_m * glm::dvec3(s.normal)));
  s.tangent = glm::vec3(glm::normalize(glm::dmat3(linear) * glm::dvec3(s.tangent)));
  return true;
}

}  // namespace aalab
