// certipose/io/step_path.hpp — which files are STEP files, without OpenCASCADE: a program decides
// by the name whether a part is read by read_step (io/read_step.hpp, target certipose::step) or by
// read_mesh (io/read_mesh.hpp), and can say which reader a build lacks.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace certipose {

/// True when `path` ends in .step or .stp (any letter case): the files read_step reads.
inline bool is_step_path(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".step" || ext == ".stp";
}

}  // namespace certipose
