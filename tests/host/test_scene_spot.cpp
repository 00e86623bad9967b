// Scene files' spot lights (host/src/scene.cpp, docs/SCENES.md): type = "spot" is a point light
// with a cone (parsed direction and angles, inner defaulting to outer), errors naming file, line
// and key; the example examples/scenes/fog_spots.toml parses.
#include <string>

#include <gtest/gtest.h>

#include "scene.hpp"

namespace {

const std::string kHead = "name = \"x\"\n[[medium]]\nname = \"h\"\nsigma_s_per_m = 0.1\nsigma_a_per_m = 0\n"
                          "viewer_inside = true\n[[light]]\nname = \"s\"\ntype = \"spot\"\nintensity_W_per_sr = 1\n"
                          "distance_m = [1, 2]\n";

std::string error_of(const std::string &text) {
    try {
        scatterlut::parse_scene(text, "spot.toml");
    } catch (const scatterlut::SceneError &e) {
        return e.what();
    }
    return "";
}

TEST(SceneSpot, ParsesAsAPointLightWithACone) {
    const scatterlut::Scene s = scatterlut::parse_scene(kHead + "direction = [0, -2, 0]\nouter_angle_deg = 30\n", "spot.toml");
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(s.lights[0].type == scatterlut::LightType::Point);
    EXPECT_TRUE(s.lights[0].spot);
    EXPECT_EQ(s.lights[0].spot_direction[1], -2.0);
    EXPECT_EQ(s.lights[0].outer_angle_deg, 30.0);
    EXPECT_EQ(s.lights[0].inner_angle_deg, 30.0); // default: the outer
    const scatterlut::Scene example =
        scatterlut::load_scene_file(std::string(SLUT_SOURCE_DIR) + "/examples/scenes/fog_spots.toml");
    EXPECT_EQ(example.lights.size(), 2u);
    EXPECT_EQ(example.lights[0].inner_angle_deg, 8.0);
}

TEST(SceneSpot, ErrorsNameFileLineAndKey) {
    EXPECT_NE(error_of(kHead + "outer_angle_deg = 30\n").find("spot.toml:7:1: key 'light[0].direction'"), std::string::npos);
    EXPECT_NE(error_of(kHead + "direction = [0, 0, 0]\nouter_angle_deg = 30\n").find("spot.toml:12:13: key 'light[0].direction'"),
              std::string::npos);
    EXPECT_NE(error_of(kHead + "direction = [0, 1]\nouter_angle_deg = 30\n").find("key 'light[0].direction'"), std::string::npos);
    EXPECT_NE(error_of(kHead + "direction = [0, \"a\", 1]\nouter_angle_deg = 30\n").find("key 'light[0].direction[1]'"),
              std::string::npos);
    EXPECT_NE(error_of(kHead + "direction = [0, 0, 1]\n").find("key 'light[0].outer_angle_deg'"), std::string::npos);
    EXPECT_NE(error_of(kHead + "direction = [0, 0, 1]\nouter_angle_deg = 190\n").find("key 'light[0].outer_angle_deg'"),
              std::string::npos);
    EXPECT_NE(error_of(kHead + "direction = [0, 0, 1]\nouter_angle_deg = 10\ninner_angle_deg = 20\n")
                  .find("spot.toml:14:19: key 'light[0].inner_angle_deg'"),
              std::string::npos);
    EXPECT_NE(error_of(kHead + "direction = [0, 0, 1]\nouter_angle_deg = 10\ncone = 1\n").find("light[0]"), std::string::npos);
}

} // namespace
