// Temporary smoke test.
#include <gtest/gtest.h>

#include "projection/camera.h"

using namespace overlayd;

TEST(Smoke, CentreProjectsToPrincipalPoint)
{
    auto pose = poseLookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
    auto proj = Projection::pinhole({500, 500, 319.5, 239.5, 0, 640, 480}, 0.1, 100, DepthRange::ZeroToOne);
    auto vp = Viewport::create({640, 480});
    ASSERT_TRUE(pose && proj && vp);
    auto cam = Camera::create(*pose, *proj, Distortion{}, *vp);
    ASSERT_TRUE(cam);
    auto p = cam->project(glm::dvec3(0, 0, 0));
    EXPECT_EQ(p.status, PointStatus::Visible);
    EXPECT_NEAR(p.pixel.x, 319.5, 1e-9);
    EXPECT_NEAR(p.pixel.y, 239.5, 1e-9);
}
