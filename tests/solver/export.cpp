// certipose-export's formats (io/plan_export.hpp, io/moveit_yaml.hpp, io/plan_gltf.hpp): what a
// robot cell or a fitter is handed is inside what was certified. The MoveIt constraints are read
// back from the YAML and re-proven: the BOX and the rotation-vector tolerance, enclosed in a 6D
// box, are certified by pose_solver::certify for the camera's facet, and sampled poses of that
// box (corners included) pass the plain evaluator and ray caster. The CSV and the glTF scene are
// read back and compared with what was exported.
#include "solver_support.hpp"

#include <certipose/coverage/inspection.hpp>
#include <certipose/io/moveit_yaml.hpp>
#include <certipose/io/plan_export.hpp>
#include <certipose/io/plan_gltf.hpp>
#include <certipose/io/plan_sheet.hpp>
#include <certipose/pose/quaternion.hpp>

#include <tiny_gltf.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <random>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace solver_test;

namespace {

using I = boost_interval;

/// A plan whose cameras are the largest VALID boxes of the case study's facet, each with every
/// facet it certifies (C(B), as certipose-plan computes it).
struct case_study_plan {
    thin_lens_camera camera{design_camera_parameters()};
    pose_solver<> solver{part().mesh, camera, {.min_view_angle = 0.35}};
    std::size_t facet = part().facet_of_interest;
    plan_document plan;

    case_study_plan() {
        const auto result = solver.solve(facet, {.position_eps = 0.1, .orientation_eps = 0.38});
        std::vector<pose_box<I>> valid;
        for (const auto& b : result.boxes)
            if (b.cls == box_class::valid) valid.push_back(b.box);
        std::sort(valid.begin(), valid.end(), [](const auto& a, const auto& b) { return volume(a) > volume(b); });
        valid.resize(std::min<std::size_t>(valid.size(), 6));
        plan.mesh.faces = part().mesh.num_faces();
        plan.mesh.scale = 1;
        plan.camera.width_px = 2448, plan.camera.height_px = 2048;
        plan.camera.K = {{{3478.26, 0, 1224}, {0, 3478.26, 1024}, {0, 0, 1}}};
        plan.camera.d_min = solver.range().min, plan.camera.d_max = solver.range().max;
        plan.camera.mount_offset = {0.01, -0.02, -0.05};
        facet_inspector<> inspector(solver);
        for (const auto& b : valid) {
            plan_document::camera_box c;
            for (std::size_t i = 0; i < 3; ++i) {
                c.position[i] = {lower(b.position[i]), upper(b.position[i])};
                c.orientation[i] = {lower(b.orientation[i]), upper(b.orientation[i])};
            }
            const facet_coverage cov = inspector.inspect(b);
            c.facets = cov.certified;
            c.certified_area = cov.certified_area;
            for (std::size_t i = 0; i < 3; ++i) {
                c.nominal[i] = (c.position[i][0] + c.position[i][1]) / 2;
                c.nominal[i + 3] = (c.orientation[i][0] + c.orientation[i][1]) / 2;
            }
            c.from_facet = facet;
            c.aim = plan_aim(part().mesh, c);
            plan.cameras.push_back(c);
        }
    }
};

const case_study_plan& fixture() {
    static const case_study_plan p;
    return p;
}

/// [c − h, c + h] widened by one ulp each way: encloses the real interval the numbers describe.
I around(double c, double h) { return I(std::nextafter(c - h, -INFINITY), std::nextafter(c + h, INFINITY)); }

}  // namespace

TEST_CASE("export: the MoveIt constraints read back from the YAML are certified for every facet of the camera") {
    const auto& f = fixture();
    REQUIRE(f.plan.cameras.size() >= 3);
    const YAML::Node doc = YAML::Load(plan_moveit_yaml(f.plan, {.frame_id = "part", .link = constrained_link::mount}));
    REQUIRE(doc["cameras"].size() == f.plan.cameras.size());
    std::size_t reproven = 0;
    for (std::size_t k = 0; k < f.plan.cameras.size(); ++k) {
        CAPTURE(k);
        const YAML::Node c = doc["cameras"][k]["constraints"];
        const YAML::Node pc = c["position_constraints"][0];
        CHECK(pc["link_name"].as<std::string>() == "camera_" + std::to_string(k) + "_mount");
        CHECK(pc["target_point_offset"]["z"].as<double>() == -0.05);  // the constrained point: the projection centre
        const YAML::Node prim = pc["constraint_region"]["primitives"][0];
        REQUIRE(prim["type"].as<int>() == 1);
        const YAML::Node centre = pc["constraint_region"]["primitive_poses"][0]["position"];
        const double ctr[3] = {centre["x"].as<double>(), centre["y"].as<double>(), centre["z"].as<double>()};
        const YAML::Node oc = c["orientation_constraints"][0];
        REQUIRE(oc["parameterization"].as<int>() == 1);
        const std::array<double, 4> q{oc["orientation"]["x"].as<double>(), oc["orientation"]["y"].as<double>(),
                                      oc["orientation"]["z"].as<double>(), oc["orientation"]["w"].as<double>()};
        const double tol = oc["absolute_x_axis_tolerance"].as<double>();
        CHECK(oc["absolute_y_axis_tolerance"].as<double>() == tol);
        CHECK(oc["absolute_z_axis_tolerance"].as<double>() == tol);
        CHECK(tol > 0);
        // What MoveIt accepts: the projection centre in the BOX, R = R_q·exp(v) with |v_i| ≤ tol,
        // so a rotation angle ≤ √3·tol from R_q: enclosed by zxz_enclosure.
        const zxz_angles a = zxz_from_quaternion(q);
        const double theta = std::sqrt(3.0) * tol * (1 + 1e-12);
        const auto e = zxz_enclosure({a.phi, a.gamma, a.beta}, {theta, theta});
        pose_box<I> box;
        for (std::size_t i = 0; i < 3; ++i) {
            box.position[i] = around(ctr[i], prim["dimensions"][i].as<double>() / 2);
            box.orientation[i] = I(e[i][0], e[i][1]);
        }
        const auto& facets = f.plan.cameras[k].facets;
        REQUIRE(std::count(facets.begin(), facets.end(), f.facet) == 1);
        for (std::size_t g : facets) {
            CAPTURE(g);
            CHECK(f.solver.certify(g, box));
        }
        // Independently: sampled poses of the enclosure (corners included) pass the plain check,
        // for the case study's facet and a spread of the camera's others.
        for (std::size_t i = 0; i < facets.size(); i += std::max<std::size_t>(1, facets.size() / 8)) {
            for (const std::size_t g : {facets[i], f.facet}) {
                solve_result<I> one;
                one.facet_index = g;
                one.boxes.push_back({box_class::valid, box});
                const auto s = check_valid_boxes(one, f.solver.part(), f.camera, f.solver.range(), 0.35, 100,
                                                 17 + static_cast<std::uint32_t>(k + g));
                CHECK(s.samples > 0);
                CHECK(s.violations == 0);
            }
        }
        reproven += facets.size();
    }
    CHECK(reproven > f.plan.cameras.size());  // cameras certify more than the case study's facet
}

TEST_CASE("export: the fitter's CSV, read back, stays inside each camera's box from its rounded nominal") {
    const auto& f = fixture();
    const std::string csv = plan_csv(f.plan);
    std::istringstream in(csv);
    std::string line;
    REQUIRE(std::getline(in, line));
    std::map<std::string, std::size_t> col;
    for (std::istringstream h(line); std::getline(h, line, ',');) {
        // Every number a fitter reads names its unit; the unitless ones are the quaternion, the
        // rotation matrix and the counts.
        const bool unitless = line == "camera" || line == "facets" || line.size() == 2 || line.size() == 3;
        CHECK_MESSAGE((unitless || line.ends_with("_mm") || line.ends_with("_deg") || line.ends_with("_mm2")), line);
        col[line] = col.size();
    }
    for (const char* c : {"x_mm", "qw", "r22", "half_z_mm", "axis_cone_half_angle_deg", "roll_half_range_deg", "aim_x_mm",
                          "aim_distance_mm", "certified_area_mm2"})
        REQUIRE_MESSAGE(col.count(c) == 1, c);
    const auto exports = camera_exports(f.plan);
    constexpr double deg = 180 / std::numbers::pi;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t rows = 0, sampled = 0;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        for (std::istringstream r(line); std::getline(r, line, ',');) cells.push_back(line);
        REQUIRE(cells.size() == col.size());
        const auto v = [&](const char* name) { return std::stod(cells[col.at(name)]); };
        const auto& e = exports[rows];
        const auto& box = f.plan.cameras[rows];
        // Rounded as a fitter reads it: 0.1 mm and 0.01°, never more digits.
        CHECK(cells[col.at("x_mm")].find('.') == cells[col.at("x_mm")].size() - 2);
        CHECK(cells[col.at("axis_cone_half_angle_deg")].find('.') == cells[col.at("axis_cone_half_angle_deg")].size() - 3);
        const char* xyz[3] = {"x_mm", "y_mm", "z_mm"};
        const char* half[3] = {"half_x_mm", "half_y_mm", "half_z_mm"};
        for (std::size_t i = 0; i < 3; ++i) {
            CHECK(std::abs(v(xyz[i]) - 1000 * e.position[i]) <= 0.05 + 1e-9);
            // The printed tolerance about the printed nominal is inside the box...
            CHECK((v(xyz[i]) - v(half[i])) / 1000 >= box.position[i][0]);
            CHECK((v(xyz[i]) + v(half[i])) / 1000 <= box.position[i][1]);
            // ...and gives up no more than the rounding needs.
            CHECK(v(half[i]) >= 1000 * e.position_half[i] - 0.15 - 1e-9);
            CHECK(v(half[i]) > 0);
        }
        const Eigen::Matrix3d r = matrix_from_quaternion({v("qx"), v("qy"), v("qz"), v("qw")});
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const std::string name = "r" + std::to_string(i) + std::to_string(j);
                CHECK(std::abs(r(i, j) - v(name.c_str())) < 1e-8);
            }
        const double cone = v("axis_cone_half_angle_deg") / deg, roll = v("roll_half_range_deg") / deg;
        CHECK(cone > 0);  // a VALID box of the case study certifies a real tilt and roll
        CHECK(roll > 0);
        CHECK(cone <= e.axis.cone);
        CHECK(roll <= e.axis.roll);
        // Orientations within the printed cone and roll of the printed quaternion lie in the box
        // (the extremes first, then random ones), read back as ZXZ angles modulo 2π.
        const auto c = zxz_centre(box.orientation);
        for (int k = 0; k < 64; ++k, ++sampled) {
            const double dir = 2 * std::numbers::pi * u(rng);
            const double swing = k < 8 ? cone : cone * std::sqrt(u(rng));
            const double twist = k < 8 ? (k % 2 ? roll : -roll) : roll * (2 * u(rng) - 1);
            const Eigen::Matrix3d rk = r * Eigen::AngleAxisd(swing, Eigen::Vector3d(std::cos(dir), std::sin(dir), 0)) *
                                       Eigen::AngleAxisd(twist, Eigen::Vector3d::UnitZ());
            const zxz_angles a = zxz_from_matrix(rk);
            const double got[3] = {a.phi, a.gamma, a.beta};
            for (std::size_t i = 0; i < 3; ++i) {
                const double d = i == 1 ? got[i] - c[i] : std::remainder(got[i] - c[i], 2 * std::numbers::pi);
                CHECK_MESSAGE(d >= box.orientation[i][0] - c[i] - 1e-12, "camera ", rows, " angle ", i, " k ", k);
                CHECK_MESSAGE(d <= box.orientation[i][1] - c[i] + 1e-12, "camera ", rows, " angle ", i, " k ", k);
            }
        }
        // The aim point is on the nominal optical axis, in front of the camera, on the part.
        REQUIRE(box.aim);
        const Eigen::Vector3d p(e.position[0], e.position[1], e.position[2]);
        const Eigen::Vector3d aim(v("aim_x_mm") / 1000, v("aim_y_mm") / 1000, v("aim_z_mm") / 1000);
        const Eigen::Vector3d axis = e.rotation.col(2);
        CHECK((aim - p).dot(axis) > f.plan.camera.d_min / 2);
        CHECK((aim - p).cross(axis).norm() < 2e-4);  // the 0.1 mm rounding of both points
        CHECK(std::abs(v("aim_distance_mm") - 1000 * (aim - p).norm()) < 0.2);
        CHECK(v("facets") == static_cast<double>(box.facets.size()));
        CHECK(std::abs(v("certified_area_mm2") - 1e6 * box.certified_area) <= 0.05 + 1e-9);
        ++rows;
    }
    CHECK(rows == f.plan.cameras.size());
    CHECK(sampled == 64 * rows);
    // A plan written before aim points were recorded leaves those cells empty, not made up.
    plan_document old = f.plan;
    for (auto& cam : old.cameras) cam.aim.reset();
    const std::string old_csv = plan_csv(old);
    CHECK(old_csv.find(",,,,") != std::string::npos);
}

TEST_CASE("export: the URDF is a whole robot rooted at the parent frame, or with snippet only the cameras") {
    const auto& f = fixture();
    const std::size_t n = f.plan.cameras.size();
    const auto count = [](const std::string& s, const std::string& what) {
        std::size_t k = 0;
        for (auto at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++k;
        return k;
    };
    const std::string whole = plan_urdf(f.plan, {.parent_frame = "base_link", .link_prefix = "cell1_cam", .robot_name = "cell1"});
    CHECK(whole.rfind("<?xml", 0) == 0);
    CHECK(count(whole, "<robot name=\"cell1\">") == 1);
    CHECK(count(whole, "</robot>") == 1);
    CHECK(count(whole, "<link name=\"base_link\"/>") == 1);  // the root link is declared
    CHECK(count(whole, "<link name=") == 1 + 2 * n);
    CHECK(count(whole, "<parent link=\"base_link\"/>") == n);
    CHECK(count(whole, "<child link=\"cell1_cam0_optical_frame\"/>") == 1);
    const std::string snippet = plan_urdf(f.plan, {.snippet = true});
    CHECK(count(snippet, "<robot name") == 0);
    CHECK(count(snippet, "<link name=\"world\"/>") == 0);  // the robot it is pasted into has it
    CHECK(count(snippet, "<parent link=\"world\"/>") == n);
    CHECK(count(snippet, "<link name=\"camera_0_mount\"/>") == 1);
    CHECK_THROWS_AS(plan_urdf(f.plan, {.robot_name = "two words"}), invalid_argument);
    CHECK_THROWS_AS(plan_urdf(f.plan, {.link_prefix = "cam<"}), invalid_argument);
}

TEST_CASE("export: the glTF scene holds the part facet by facet and each camera's frustum and box") {
    const auto& f = fixture();
    const std::string glb = plan_glb(part().mesh, f.plan);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    REQUIRE(loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                        static_cast<unsigned int>(glb.size())));
    CHECK(err.empty());
    std::vector<std::string> names;
    for (const auto& n : model.nodes) names.push_back(n.name);
    CHECK(std::count(names.begin(), names.end(), "part") == 1);
    CHECK(std::count(names.begin(), names.end(), "camera 0 frustum") == 1);
    CHECK(std::count(names.begin(), names.end(), "camera " + std::to_string(f.plan.cameras.size() - 1) + " tolerance") == 1);
    // A glTF camera object per plan camera at its nominal pose, looking down the optical axis
    // (glTF cameras look down their −z), with the image's vertical field of view.
    REQUIRE(model.cameras.size() == f.plan.cameras.size());
    const auto exports = camera_exports(f.plan);
    for (const auto& e : exports) {
        const auto node = std::find_if(model.nodes.begin(), model.nodes.end(), [&](const tinygltf::Node& n) {
            return n.name == "camera " + std::to_string(e.index) + " view";
        });
        REQUIRE(node != model.nodes.end());
        REQUIRE(node->camera >= 0);
        const auto& cam = model.cameras[static_cast<std::size_t>(node->camera)];
        CHECK(cam.type == "perspective");
        CHECK(cam.perspective.yfov == doctest::Approx(2 * std::atan(1024 / 3478.26)));
        CHECK(cam.perspective.znear > 0);
        REQUIRE(node->translation.size() == 3);
        REQUIRE(node->rotation.size() == 4);
        for (std::size_t i = 0; i < 3; ++i) CHECK(node->translation[i] == e.position[i]);
        const Eigen::Quaterniond q(node->rotation[3], node->rotation[0], node->rotation[1], node->rotation[2]);
        CHECK((q * -Eigen::Vector3d::UnitZ() - e.rotation.col(2)).norm() < 1e-12);  // looks along the axis
        CHECK((q * Eigen::Vector3d::UnitY() + e.rotation.col(1)).norm() < 1e-12);   // up is the image's −v
    }
    const auto& prim = model.meshes[0].primitives[0];
    CHECK(model.accessors[static_cast<std::size_t>(prim.attributes.at("POSITION"))].count == 3 * part().mesh.num_faces());
    // A plan facet beyond the part is refused, naming it.
    plan_document bad = f.plan;
    bad.cameras[0].facets.push_back(part().mesh.num_faces());
    CHECK_THROWS_AS(plan_glb(part().mesh, bad), out_of_range);
}

TEST_CASE("export: URDF roll-pitch-yaw rebuild the nominal rotation, also next to pitch ±π/2") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> any(-3.1, 3.1), near(-1e-6, 1e-6);
    const auto rebuild = [](const std::array<double, 3>& rpy) {
        return Eigen::Matrix3d(Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()));
    };
    for (int n = 0; n < 400; ++n) {
        // Random rotations, and rotations within 1e-6 of the lock (pitch = ±π/2).
        const double pitch = n % 2 ? any(rng) / 2 : (n % 4 ? 1 : -1) * (std::numbers::pi / 2 + near(rng));
        const Eigen::Matrix3d r = rebuild({any(rng), pitch, any(rng)});
        CAPTURE(pitch);
        CHECK((rebuild(urdf_rpy(r)) - r).cwiseAbs().maxCoeff() < 1e-12);
    }
}

/// How many times `what` occurs in `s`.
static std::size_t occurrences(const std::string& s, const std::string& what) {
    std::size_t k = 0;
    for (auto at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++k;
    return k;
}

TEST_CASE("export: the glTF scene draws the occluders, the camera regions, the axes and each axis cone") {
    const auto& f = fixture();
    plan_document plan = f.plan;
    plan.scene.regions.keep_out.push_back(camera_region::box({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.0}));
    plan.scene.regions.keep_in.push_back(camera_region::sphere({0, 0, 0}, 2.0));
    plan.uncovered = {{0, uncovered_reason::rests_on_occluder}, {1, uncovered_reason::not_solved}};
    const triangle_mesh plate({{-1, -1, -0.01}, {1, -1, -0.01}, {1, 1, -0.01}, {-1, 1, -0.01}},
                              {face_indices{0, 1, 2}, face_indices{0, 2, 3}});
    const std::vector<triangle_mesh> occluders{plate};
    const std::string glb = plan_glb(part().mesh, plan, occluders);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    REQUIRE(loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                        static_cast<unsigned int>(glb.size())));
    const auto node = [&](const std::string& name) {
        const auto it = std::find_if(model.nodes.begin(), model.nodes.end(), [&](const tinygltf::Node& n) { return n.name == name; });
        return it == model.nodes.end() ? nullptr : &*it;
    };
    const tinygltf::Node* occ = node("occluder 0");
    REQUIRE(occ != nullptr);
    const auto& occ_prim = model.meshes[static_cast<std::size_t>(occ->mesh)].primitives[0];
    CHECK(model.accessors[static_cast<std::size_t>(occ_prim.attributes.at("POSITION"))].count == 6);
    CHECK(model.materials[static_cast<std::size_t>(occ_prim.material)].alphaMode == "BLEND");
    REQUIRE(node("keep-out 0") != nullptr);
    REQUIRE(node("keep-in 0") != nullptr);
    const auto lines = [&](const tinygltf::Node* n) {
        const auto& prim = model.meshes[static_cast<std::size_t>(n->mesh)].primitives[0];
        CHECK(prim.mode == TINYGLTF_MODE_LINE);
        return model.accessors[static_cast<std::size_t>(prim.indices)].count / 2;
    };
    CHECK(lines(node("keep-out 0")) == 12);       // a box's edges
    CHECK(lines(node("keep-in 0")) == 3 * 48);    // a sphere's three great circles
    REQUIRE(node("axes") != nullptr);
    CHECK(node("axes")->children.size() == 3);
    REQUIRE(node("axis z") != nullptr);
    // A cone for each camera whose certified axis cone is not a point.
    for (const auto& e : camera_exports(plan))
        CHECK((node("camera " + std::to_string(e.index) + " cone") != nullptr) == (e.axis.cone > 0));
    // Facet 0 (rests on an occluder) is darker than facet 1 (not solved); both grey.
    const auto& part_prim = model.meshes[0].primitives[0];
    const auto& acc = model.accessors[static_cast<std::size_t>(part_prim.attributes.at("COLOR_0"))];
    const auto& view = model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
    const auto* colours = reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset + acc.byteOffset);
    const auto by = plan_first_cameras(part().mesh.num_faces(), plan);
    if (by[0] >= plan.cameras.size() && by[1] >= plan.cameras.size()) CHECK(colours[0] < colours[9]);
}

TEST_CASE("export: the installation sheet has a page per camera with the CSV's numbers and a view") {
    const auto& f = fixture();
    const std::string sheet = plan_sheet(part().mesh, f.plan, {.title = "cell <1>"});
    CHECK(occurrences(sheet, "<section class=\"page\"") == f.plan.cameras.size());
    CHECK(occurrences(sheet, "<svg class=\"view\"") == f.plan.cameras.size());
    CHECK(occurrences(sheet, "cell &lt;1&gt;") >= 1);  // the title is escaped
    CHECK(occurrences(sheet, "<script") == 0);         // nothing to run, nothing to fetch
    CHECK(occurrences(sheet, "http://") == occurrences(sheet, "http://www.w3.org/2000/svg"));
    // Each page's numbers are the CSV's row: the same text, cell by cell.
    std::istringstream csv(plan_csv(f.plan));
    std::string line;
    std::getline(csv, line);
    std::vector<std::string> header;
    for (std::istringstream h(line); std::getline(h, line, ',');) header.push_back(line);
    std::size_t rows = 0;
    while (std::getline(csv, line)) {
        std::vector<std::string> cells;
        for (std::istringstream r(line); std::getline(r, line, ',');) cells.push_back(line);
        const std::string page_start = "<section class=\"page\" data-camera=\"" + cells[0] + "\">";
        const auto from = sheet.find(page_start);
        REQUIRE(from != std::string::npos);
        const std::string page = sheet.substr(from, sheet.find("</section>", from) - from);
        std::size_t fields = 0;
        for (std::size_t c = 1; c < header.size() && c < cells.size(); ++c) {
            const std::string cell = "data-field=\"" + header[c] + "\">";
            const auto at = page.find(cell);
            if (at == std::string::npos) continue;
            ++fields;
            const auto v = at + cell.size();
            CHECK(page.substr(v, page.find('<', v) - v) == cells[c]);
        }
        CHECK(fields >= 20);  // position, mount, quaternion, tolerances, aim, facets, area
        CHECK(occurrences(page, "<polygon") > 10);  // the view draws facets
        ++rows;
    }
    CHECK(rows == f.plan.cameras.size());
    plan_document bad = f.plan;
    bad.cameras[0].facets.push_back(part().mesh.num_faces());
    CHECK_THROWS_AS(plan_sheet(part().mesh, bad), out_of_range);
}
