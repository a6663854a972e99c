// certipose/io/plan_gltf.hpp — a plan as a glTF 2.0 binary (.glb) scene that Blender, three.js and
// CAD viewers open: the part with each facet in the colour of the camera that certifies it (grey
// when none does), each camera's frustum at its nominal pose and its position tolerance box.
// Writing goes through TinyGLTF (Debian libtinygltf-dev, MIT); link TinyGLTF::TinyGLTF.
//
// Scene (docs/conventions.md#gltf): a root node "certipose plan" turning the part frame (z up)
// into glTF's y-up convention, with children "part" (a non-indexed triangle list: triangle i is
// facet i, so a viewer's picked triangle index is the facet index; COLOR_0 and flat normals per
// facet), and per camera k "camera k frustum" and "camera k tolerance" (LINES) and "camera k view"
// (a glTF perspective camera at the nominal pose, the image's field of view). The frustum is
// drawn from the nominal projection centre to the image corners at the distance of the camera's
// facets (clamped to its depth of field); it is a picture, not a certificate.
#pragma once

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/io/plan_export.hpp"

#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace certipose {

namespace detail::gltf {

/// Appends raw values to the single binary buffer and describes them as a view + accessor.
struct buffer_builder {
    tinygltf::Model& model;

    template <class T>
    int add(const std::vector<T>& data, int component, int type, std::size_t count, int target,
            std::vector<double> min = {}, std::vector<double> max = {}) {
        auto& bytes = model.buffers[0].data;
        while (bytes.size() % 4) bytes.push_back(0);  // accessor alignment
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = bytes.size();
        view.byteLength = data.size() * sizeof(T);
        view.target = target;
        const auto* raw = reinterpret_cast<const unsigned char*>(data.data());
        bytes.insert(bytes.end(), raw, raw + view.byteLength);
        model.bufferViews.push_back(view);
        tinygltf::Accessor a;
        a.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
        a.byteOffset = 0;
        a.componentType = component;
        a.type = type;
        a.count = count;
        a.minValues = std::move(min);
        a.maxValues = std::move(max);
        model.accessors.push_back(a);
        return static_cast<int>(model.accessors.size()) - 1;
    }

    int positions(const std::vector<float>& xyz) {
        std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
        for (std::size_t i = 0; i < xyz.size(); ++i)
            lo[i % 3] = std::min<double>(lo[i % 3], xyz[i]), hi[i % 3] = std::max<double>(hi[i % 3], xyz[i]);
        return add(xyz, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, xyz.size() / 3, TINYGLTF_TARGET_ARRAY_BUFFER,
                   lo, hi);
    }
};

/// glTF colours are linear; our palette is sRGB (what the PLY and the viewer's panel show).
inline double linear(std::uint8_t srgb) {
    const double c = srgb / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

inline int material(tinygltf::Model& model, const std::string& name, rgb c, bool lines) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {linear(c.r), linear(c.g), linear(c.b), 1.0};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = lines ? 1.0 : 0.85;
    m.doubleSided = !lines;
    model.materials.push_back(m);
    return static_cast<int>(model.materials.size()) - 1;
}

/// A LINES mesh node from points and index pairs.
inline int line_node(tinygltf::Model& model, buffer_builder& buf, const std::string& name,
                     const std::vector<Eigen::Vector3d>& points, const std::vector<std::uint16_t>& pairs, int mat) {
    std::vector<float> xyz;
    for (const auto& p : points)
        for (int i = 0; i < 3; ++i) xyz.push_back(static_cast<float>(p[i]));
    tinygltf::Primitive prim;
    prim.attributes["POSITION"] = buf.positions(xyz);
    prim.indices = buf.add(pairs, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, pairs.size(),
                           TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    prim.mode = TINYGLTF_MODE_LINE;
    prim.material = mat;
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = name;
    node.mesh = static_cast<int>(model.meshes.size()) - 1;
    model.nodes.push_back(node);
    return static_cast<int>(model.nodes.size()) - 1;
}

/// A glTF camera object looking from camera `e`'s nominal pose, so that a CAD or render tool can
/// look through it. glTF cameras look down their −z with +y up; our optical frame looks down +z
/// with y down, so the node turns by π about the optical x axis. The field of view is the image's
/// (yfov from fy and the height; aspectRatio makes the horizontal extent w/fx too). A principal
/// point off the centre or a skew cannot be said in glTF: the view is a picture, not a certificate.
inline int camera_node(tinygltf::Model& model, const plan_document& plan, const camera_export& e) {
    const auto& K = plan.camera.K;
    tinygltf::Camera cam;
    cam.name = "camera " + std::to_string(e.index);
    cam.type = "perspective";
    cam.perspective.yfov = 2 * std::atan(plan.camera.height_px / (2 * K[1][1]));
    cam.perspective.aspectRatio = (plan.camera.width_px / K[0][0]) / (plan.camera.height_px / K[1][1]);
    cam.perspective.znear = std::max(1e-3, plan.camera.d_min / 2);
    if (std::isfinite(plan.camera.d_max) && plan.camera.d_max > cam.perspective.znear)
        cam.perspective.zfar = 2 * plan.camera.d_max;  // else 0: glTF's infinite projection
    model.cameras.push_back(cam);
    const Eigen::Matrix3d look = e.rotation * Eigen::Vector3d(1, -1, -1).asDiagonal();
    Eigen::Quaterniond q(look);
    q.normalize();
    tinygltf::Node node;
    node.name = "camera " + std::to_string(e.index) + " view";
    node.camera = static_cast<int>(model.cameras.size()) - 1;
    node.translation = {e.position[0], e.position[1], e.position[2]};
    node.rotation = {q.x(), q.y(), q.z(), q.w()};
    model.nodes.push_back(node);
    return static_cast<int>(model.nodes.size()) - 1;
}

}  // namespace detail::gltf

/// The plan's scene as a .glb file's bytes. Throws out_of_range for a plan facet beyond `mesh`.
inline std::string plan_glb(const triangle_mesh& mesh, const plan_document& plan) {
    using namespace detail::gltf;
    const auto exports = camera_exports(plan);
    const auto by = plan_first_cameras(mesh.num_faces(), plan);
    const certipose::detail::round_to_nearest_scope nearest;
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "certipose-export";
    model.buffers.emplace_back();
    buffer_builder buf{model};

    tinygltf::Node root;
    root.name = "certipose plan";
    const double h = std::numbers::sqrt2 / 2;  // −90° about x: part z (up) → glTF y (up)
    root.rotation = {-h, 0.0, 0.0, h};

    // The part: three vertices per facet, so each facet keeps its own colour and normal.
    std::vector<float> xyz, normals, colours;
    xyz.reserve(9 * mesh.num_faces());
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
        const auto& fa = mesh.facet(f);
        Eigen::Vector3d n = (fa.v[1] - fa.v[0]).cross(fa.v[2] - fa.v[0]);
        n = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d(0, 0, 1);
        const rgb c = by[f] < plan.cameras.size() ? plan_camera_colour(by[f]) : rgb{150, 150, 150};
        for (const auto& v : fa.v)
            for (int i = 0; i < 3; ++i) {
                xyz.push_back(static_cast<float>(v[i]));
                normals.push_back(static_cast<float>(n[i]));
                colours.push_back(static_cast<float>(linear(i == 0 ? c.r : i == 1 ? c.g : c.b)));
            }
    }
    tinygltf::Primitive part;
    part.attributes["POSITION"] = buf.positions(xyz);
    part.attributes["NORMAL"] = buf.add(normals, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size() / 3,
                                        TINYGLTF_TARGET_ARRAY_BUFFER);
    part.attributes["COLOR_0"] = buf.add(colours, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                                         colours.size() / 3, TINYGLTF_TARGET_ARRAY_BUFFER);
    part.mode = TINYGLTF_MODE_TRIANGLES;
    part.material = material(model, "part", rgb{255, 255, 255}, false);
    tinygltf::Mesh part_mesh;
    part_mesh.name = "part";
    part_mesh.primitives.push_back(part);
    model.meshes.push_back(part_mesh);
    tinygltf::Node part_node;
    part_node.name = "part";
    part_node.mesh = 0;
    model.nodes.push_back(part_node);
    root.children.push_back(0);

    // Cameras: frustum to the image corners, and the position box's 12 edges.
    const auto& K = plan.camera.K;
    const double corners[4][2] = {{0, 0}, {plan.camera.width_px, 0}, {plan.camera.width_px, plan.camera.height_px},
                                  {0, plan.camera.height_px}};
    for (const auto& e : exports) {
        const auto& cam = plan.cameras[e.index];
        const Eigen::Vector3d p(e.position[0], e.position[1], e.position[2]);
        double depth = 0;  // mean distance along the axis to the camera's facets
        for (std::size_t f : cam.facets) {
            const auto& fa = mesh.facet(f);
            depth += (e.rotation.transpose() * ((fa.v[0] + fa.v[1] + fa.v[2]) / 3 - p)).z();
        }
        depth = cam.facets.empty() ? plan.camera.d_min : depth / static_cast<double>(cam.facets.size());
        if (std::isfinite(plan.camera.d_max)) depth = std::min(depth, plan.camera.d_max);
        depth = std::max({depth, plan.camera.d_min, 1e-3});
        std::vector<Eigen::Vector3d> pts{p};
        for (const auto& uv : corners) {
            // K⁻¹(u, v, 1) for an upper-triangular K, scaled to the depth.
            const double y = (uv[1] - K[1][2]) / K[1][1];
            const double x = (uv[0] - K[0][2] - K[0][1] * y) / K[0][0];
            pts.push_back(p + e.rotation * Eigen::Vector3d(x * depth, y * depth, depth));
        }
        const int mat = material(model, "camera " + std::to_string(e.index), plan_camera_colour(e.index), true);
        root.children.push_back(line_node(model, buf, "camera " + std::to_string(e.index) + " frustum", pts,
                                          {0, 1, 0, 2, 0, 3, 0, 4, 1, 2, 2, 3, 3, 4, 4, 1}, mat));
        std::vector<Eigen::Vector3d> box;
        for (int i = 0; i < 8; ++i)
            box.emplace_back(cam.position[0][i & 1], cam.position[1][(i >> 1) & 1], cam.position[2][(i >> 2) & 1]);
        root.children.push_back(line_node(model, buf, "camera " + std::to_string(e.index) + " tolerance", box,
                                          {0, 1, 2, 3, 4, 5, 6, 7, 0, 2, 1, 3, 4, 6, 5, 7, 0, 4, 1, 5, 2, 6, 3, 7}, mat));
        root.children.push_back(camera_node(model, plan, e));
    }
    model.nodes.push_back(root);
    tinygltf::Scene scene;
    scene.name = "certipose plan";
    scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    while (model.buffers[0].data.size() % 4) model.buffers[0].data.push_back(0);

    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, false, true))
        throw io_error("glb", "plan_glb: TinyGLTF could not write the scene");
    return out.str();
}

}  // namespace certipose
