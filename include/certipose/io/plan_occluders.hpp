// certipose/io/plan_occluders.hpp — the occluder meshes a plan was made with, read again from the
// paths PLAN.json records, for the pictures that draw them (glb, html, sheet). A picture is not
// a certificate: an occluder that has moved or changed is left out of the drawing, with a
// message saying which and why, rather than stopping the export.
#pragma once

#include "certipose/io/plan_files.hpp"
#include "certipose/io/read_mesh.hpp"

#include <string>
#include <vector>

namespace certipose {

/// The occluders read, and why any was left out.
struct plan_occluders {
    std::vector<triangle_mesh> meshes;
    std::vector<std::string> left_out;  ///< one message per occluder not drawn
};

/// Reads each of `plan.scene.occluders` from its recorded path (a relative path from the current
/// directory, as the run was given it) with its recorded scale, and keeps it only when its digest
/// is the recorded one.
inline plan_occluders read_plan_occluders(const plan_document& plan) {
    plan_occluders out;
    for (const auto& o : plan.scene.occluders) {
        try {
            triangle_mesh m = read_mesh(o.path, {.scale = o.scale});
            if (!o.digest.empty() && mesh_digest(m) != o.digest) {
                out.left_out.push_back("occluder " + o.path + " is not drawn: its digest " + mesh_digest(m) +
                                       " is not the plan's " + o.digest + " (the file changed since the run)");
                continue;
            }
            out.meshes.push_back(std::move(m));
        } catch (const std::exception& e) {
            out.left_out.push_back("occluder " + o.path + " is not drawn: " + e.what());
        }
    }
    return out;
}

}  // namespace certipose
