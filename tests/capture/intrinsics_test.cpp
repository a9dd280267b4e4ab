#include "meadow/capture/intrinsics.h"

#include <gtest/gtest.h>

#include <limits>

using meadow::capture::Intrinsics;

TEST(Intrinsics, BackProjectThenProjectIsIdentity) {
    const Intrinsics k = Intrinsics::kinectV1();
    for (float u : {0.f, 100.5f, 639.f})
        for (float v : {0.f, 239.5f, 479.f})
            for (float z : {0.5f, 1.2f, 4.f}) {
                const glm::vec2 uv = k.project(k.backProject(u, v, z));
                EXPECT_NEAR(uv.x, u, 1e-3f) << "u " << u << " v " << v << " z " << z;
                EXPECT_NEAR(uv.y, v, 1e-3f) << "u " << u << " v " << v << " z " << z;
            }
}

TEST(Intrinsics, PrincipalPointBackProjectsOntoTheOpticalAxis) {
    const glm::vec3 p = Intrinsics::kinectV1().backProject(319.5f, 239.5f, 2.f);
    EXPECT_FLOAT_EQ(p.x, 0.f);
    EXPECT_FLOAT_EQ(p.y, 0.f);
    EXPECT_FLOAT_EQ(p.z, 2.f);
}

TEST(Intrinsics, ProblemNamesTheBadField) {
    EXPECT_EQ(Intrinsics::kinectV1().problem(), "");
    Intrinsics nanFx;
    nanFx.fx_px = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(nanFx.problem().find("fx_px"), std::string::npos) << nanFx.problem();
    Intrinsics negativeFy;
    negativeFy.fy_px = -1.f;
    EXPECT_NE(negativeFy.problem().find("fy_px"), std::string::npos) << negativeFy.problem();
    Intrinsics zeroWidth;
    zeroWidth.width_px = 0;
    EXPECT_NE(zeroWidth.problem().find("width_px"), std::string::npos);
}
