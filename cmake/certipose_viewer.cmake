# certipose_viewer: a static library defining the web viewer's HTML template and bundled script
# (extern std::string_view certipose_viewer_template, certipose_viewer_script), which
# certipose-export and the Python module embed in --format html / export("html"). The viewer
# (web/src) is bundled with three.js by Node.js from web/node_modules (`npm ci` in web/, done by
# scripts/install-deps.sh); without them both views are empty and html exports say why.
# Sets certipose_has_viewer. Included by the top-level CMakeLists.txt for the programs and the
# Python module; excluded from `all`, so it is built only for what links it.
find_program(CERTIPOSE_NODE node)
set(certipose_viewer_dir ${PROJECT_BINARY_DIR}/viewer)
set(certipose_viewer_cpp ${certipose_viewer_dir}/certipose_viewer.cpp)
file(GLOB certipose_viewer_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/web/src/*)
if(CERTIPOSE_NODE AND EXISTS ${PROJECT_SOURCE_DIR}/web/node_modules/esbuild AND EXISTS ${PROJECT_SOURCE_DIR}/web/node_modules/three)
  set(certipose_has_viewer ON)
  add_custom_command(OUTPUT ${certipose_viewer_cpp}
    COMMAND ${CERTIPOSE_NODE} ${PROJECT_SOURCE_DIR}/web/build.mjs ${certipose_viewer_dir}
    COMMAND ${CMAKE_COMMAND} -DTEMPLATE=${certipose_viewer_dir}/viewer.html -DSCRIPT=${certipose_viewer_dir}/viewer.bundle.js
            -DOUT=${certipose_viewer_cpp} -P ${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake
    DEPENDS ${certipose_viewer_sources} ${PROJECT_SOURCE_DIR}/web/build.mjs ${PROJECT_SOURCE_DIR}/web/package-lock.json
            ${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake
    COMMENT "Bundling the web viewer with three.js (web/build.mjs)"
    VERBATIM)
else()
  set(certipose_has_viewer OFF)
  message(STATUS "certipose: no Node.js or no web/node_modules (npm ci in web/): html exports are not available")
  add_custom_command(OUTPUT ${certipose_viewer_cpp}
    COMMAND ${CMAKE_COMMAND} -DOUT=${certipose_viewer_cpp} -P ${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake
    DEPENDS ${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake
    VERBATIM)
endif()
add_library(certipose_viewer STATIC EXCLUDE_FROM_ALL ${certipose_viewer_cpp})
set_target_properties(certipose_viewer PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_compile_features(certipose_viewer PRIVATE cxx_std_20)
