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
#include <certipose/pose/quaternion.hpp>

#include <tiny_gltf.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
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
            c.from_facet = facet;
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

TEST_CASE("export: the CSV rows are the nominal poses and tolerances of the plan's cameras") {
    const auto& f = fixture();
    const std::string csv = plan_csv(f.plan);
    std::istringstream in(csv);
    std::string line;
    REQUIRE(std::getline(in, line));
    CHECK(line.rfind("camera,x,y,z,qx,qy,qz,qw,m00,", 0) == 0);
    std::vector<std::string> header;
    for (std::istringstream h(line); std::getline(h, line, ',');) header.push_back(line);
    CHECK(header.size() == 34);
    const auto exports = camera_exports(f.plan);
    std::size_t rows = 0;
    while (std::getline(in, line)) {
        std::vector<double> v;
        for (std::istringstream r(line); std::getline(r, line, ',');) v.push_back(std::stod(line));
        REQUIRE(v.size() == header.size());
        const auto& e = exports[rows];
        const auto& box = f.plan.cameras[rows];
        for (std::size_t i = 0; i < 3; ++i) {
            CHECK(v[1 + i] == e.position[i]);
            CHECK(v[1 + i] - v[24 + i] >= box.position[i][0]);  // the half-widths stay in the box
            CHECK(v[1 + i] + v[24 + i] <= box.position[i][1]);
            CHECK(v[8 + 4 * i + 3] == e.position[i]);  // the 4×4's translation column
        }
        const Eigen::Matrix3d r = matrix_from_quaternion({v[4], v[5], v[6], v[7]});
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) CHECK(std::abs(r(i, j) - v[8 + 4 * i + j]) < 1e-12);
        CHECK(v[27] == e.axis.cone);
        CHECK(v[28] == e.axis.roll);
        CHECK(v[27] > 0);  // a VALID box of the case study certifies a real tilt and roll
        CHECK(v[28] > 0);
        ++rows;
    }
    CHECK(rows == f.plan.cameras.size());
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
