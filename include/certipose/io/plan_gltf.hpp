// certipose/io/plan_gltf.hpp — a plan as a glTF 2.0 binary (.glb) scene that Blender, three.js and
// CAD viewers open: the part with each facet in the colour of the camera that certifies it (grey
// when none does), each camera's frustum at its nominal pose and its position tolerance box.
// Writing goes through TinyGLTF (Debian libtinygltf-dev, MIT); link TinyGLTF::TinyGLTF.
//
// Scene (docs/conventions.md#gltf): a root node "certipose plan" turning the part frame (z up)
// into glTF's y-up convention, with children "part" (a non-indexed triangle list: triangle i is
// facet i, so a viewer's picked triangle index is the facet index; COLOR_0 and flat normals per
// facet), and per camera k "camera k frustum" and "camera k tolerance" (LINES) and "camera k view"
// (a glTF perspective camera at the nominal pose, the image's field of view), "camera k cone" (the
// circle the optical axis may sweep within the certified cone, at the frustum's depth), and the
// scene the plan was made in: "occluder i" (translucent), "keep-in i" / "keep-out i" (LINES: a
// box's edges, a sphere's three great circles) and "axes" (x, y, z of the part frame from the
// origin). Facets that no pose can see ("never visible", "rests on an occluder") are dark grey,
// the other uncovered facets light grey. The frustum is drawn from the nominal projection centre
// to the image corners at the distance of the camera's facets (clamped to its depth of field); it
// is a picture, not a certificate.
#pragma once

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/io/plan_export.hpp"

#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <utility>
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

inline int material(tinygltf::Model& model, const std::string& name, rgb c, bool lines, double alpha = 1.0) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {linear(c.r), linear(c.g), linear(c.b), alpha};
    if (alpha < 1.0) m.alphaMode = "BLEND";
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = lines ? 1.0 : 0.85;
    m.doubleSided = !lines;
    model.materials.push_back(m);
    return static_cast<int>(model.materials.size()) - 1;
}

/// A node holding a mesh of the one primitive `prim`, both named `name`; returns the node's index.
inline int primitive_node(tinygltf::Model& model, const std::string& name, tinygltf::Primitive prim) {
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(std::move(prim));
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = name;
    node.mesh = static_cast<int>(model.meshes.size()) - 1;
    model.nodes.push_back(node);
    return static_cast<int>(model.nodes.size()) - 1;
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
    return primitive_node(model, name, std::move(prim));
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

/// A triangle mesh node with flat normals (an occluder: not pickable, drawn translucent).
inline int solid_node(tinygltf::Model& model, buffer_builder& buf, const std::string& name, const triangle_mesh& m, int mat) {
    std::vector<float> xyz, normals;
    for (std::size_t f = 0; f < m.num_faces(); ++f) {
        const auto& fa = m.facet(f);
        for (const auto& v : fa.v)
            for (int i = 0; i < 3; ++i) {
                xyz.push_back(static_cast<float>(v[i]));
                normals.push_back(static_cast<float>(fa.normal[i]));
            }
    }
    tinygltf::Primitive prim;
    prim.attributes["POSITION"] = buf.positions(xyz);
    prim.attributes["NORMAL"] = buf.add(normals, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size() / 3,
                                        TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = mat;
    return primitive_node(model, name, std::move(prim));
}

/// A circle of `segments` points about `centre` in the plane spanned by unit `u` and `v`, as the
/// points and the index pairs of its segments (appended, indices offset by what is there).
inline void circle(std::vector<Eigen::Vector3d>& points, std::vector<std::uint16_t>& pairs, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& u, const Eigen::Vector3d& v, double radius, int segments = 48) {
    const auto first = static_cast<std::uint16_t>(points.size());
    for (int i = 0; i < segments; ++i) {
        const double a = 2 * std::numbers::pi * i / segments;
        points.push_back(centre + radius * (std::cos(a) * u + std::sin(a) * v));
        pairs.push_back(static_cast<std::uint16_t>(first + i));
        pairs.push_back(static_cast<std::uint16_t>(first + (i + 1) % segments));
    }
}

/// The LINES node of a camera region: a box's 12 edges, a sphere's 3 great circles.
inline int region_node(tinygltf::Model& model, buffer_builder& buf, const std::string& name, const camera_region& r, int mat) {
    std::vector<Eigen::Vector3d> pts;
    std::vector<std::uint16_t> pairs;
    const auto& x = r.values;
    if (r.is_box()) {
        for (int i = 0; i < 8; ++i) pts.emplace_back(x[(i & 1) ? 3 : 0], x[(i & 2) ? 4 : 1], x[(i & 4) ? 5 : 2]);
        pairs = {0, 1, 2, 3, 4, 5, 6, 7, 0, 2, 1, 3, 4, 6, 5, 7, 0, 4, 1, 5, 2, 6, 3, 7};
    } else {
        const Eigen::Vector3d c(x[0], x[1], x[2]), ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY(),
                                                   ez = Eigen::Vector3d::UnitZ();
        circle(pts, pairs, c, ex, ey, x[3]);
        circle(pts, pairs, c, ey, ez, x[3]);
        circle(pts, pairs, c, ez, ex, x[3]);
    }
    return line_node(model, buf, name, pts, pairs, mat);
}

}  // namespace detail::gltf

/// The plan's scene as a .glb file's bytes. `occluders`: the plan's occluder meshes, to draw
/// (read_plan_occluders; none: not drawn). Throws out_of_range for a plan facet beyond `mesh`.
inline std::string plan_glb(const triangle_mesh& mesh, const plan_document& plan,
                            std::span<const triangle_mesh> occluders = {}) {
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

    const std::vector<char> unseen = plan_unseen_facets(mesh.num_faces(), plan);

    // The part: three vertices per facet, so each facet keeps its own colour and normal.
    std::vector<float> xyz, normals, colours;
    xyz.reserve(9 * mesh.num_faces());
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
        const auto& fa = mesh.facet(f);
        Eigen::Vector3d n = (fa.v[1] - fa.v[0]).cross(fa.v[2] - fa.v[0]);
        n = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d(0, 0, 1);
        const rgb c = by[f] < plan.cameras.size() ? plan_camera_colour(by[f]) : unseen[f] ? plan_unseen_colour : plan_uncovered_colour;
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
        // The axis cone: where the optical axis may point, drawn as a circle at the frustum's depth.
        if (e.axis.cone > 0) {
            std::vector<Eigen::Vector3d> cone{p};
            std::vector<std::uint16_t> pairs;
            const Eigen::Vector3d z = e.rotation.col(2), x = e.rotation.col(0), y = e.rotation.col(1);
            circle(cone, pairs, p + depth * z, x, y, depth * std::tan(std::min(e.axis.cone, 1.5)));
            for (std::uint16_t i : {1, 13, 25, 37}) pairs.insert(pairs.end(), {0, i});
            root.children.push_back(line_node(model, buf, "camera " + std::to_string(e.index) + " cone", cone, pairs, mat));
        }
    }

    // The scene the plan was made in: occluders, camera regions, and the part frame's axes.
    for (std::size_t i = 0; i < occluders.size(); ++i)
        root.children.push_back(solid_node(model, buf, "occluder " + std::to_string(i), occluders[i],
                                           material(model, "occluder", rgb{120, 126, 138}, false, 0.45)));
    if (!plan.scene.regions.keep_in.empty() || !plan.scene.regions.keep_out.empty()) {
        const int in = material(model, "keep-in", rgb{40, 160, 80}, true), out = material(model, "keep-out", rgb{210, 50, 50}, true);
        for (std::size_t i = 0; i < plan.scene.regions.keep_in.size(); ++i)
            root.children.push_back(region_node(model, buf, "keep-in " + std::to_string(i), plan.scene.regions.keep_in[i], in));
        for (std::size_t i = 0; i < plan.scene.regions.keep_out.size(); ++i)
            root.children.push_back(region_node(model, buf, "keep-out " + std::to_string(i), plan.scene.regions.keep_out[i], out));
    }
    {
        Eigen::AlignedBox3d extent;
        for (std::size_t f = 0; f < mesh.num_faces(); ++f) extent.extend(mesh.facet(f).bbox);
        const double len = mesh.num_faces() ? 0.6 * extent.diagonal().norm() : 0.1;  // out of the part
        tinygltf::Node axes;
        axes.name = "axes";
        const rgb colours[3] = {{220, 50, 47}, {60, 160, 60}, {38, 110, 220}};
        for (int k = 0; k < 3; ++k)
            axes.children.push_back(line_node(model, buf, std::string("axis ") + "xyz"[k],
                                              std::vector<Eigen::Vector3d>{Eigen::Vector3d::Zero(), Eigen::Vector3d(len * Eigen::Vector3d::Unit(k))},
                                              {0, 1},
                                              material(model, std::string("axis ") + "xyz"[k], colours[k], true)));
        model.nodes.push_back(axes);
        root.children.push_back(static_cast<int>(model.nodes.size()) - 1);
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
