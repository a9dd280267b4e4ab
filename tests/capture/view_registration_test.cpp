// A turning plant's views registered to one another (view_registration.h).
#include "meadow/capture/view_registration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "meadow/capture/error.h"

namespace meadow::capture {
namespace {

// The camera's up (image up is -Y), and the turntable's axis 0.8 m before the camera.
const glm::vec3 kUp{0.f, -1.f, 0.f};
const glm::vec3 kAxis{0.f, 0.1f, 0.8f};

// A plant standing on the axis, as a dense cloud: a 0.3 m stem and five leaves leaving it at
// different heights and azimuths, each arching 0.12-0.2 m out and down, 1.5 cm wide.
std::vector<glm::vec3> plant() {
    std::vector<glm::vec3> points;
    for (int i = 0; i <= 150; ++i) points.push_back(kAxis + kUp * (0.3f * i / 150.f));
    for (int leaf = 0; leaf < 5; ++leaf) {
        const float azimuth = glm::radians(70.f * leaf + 10.f);
        const glm::vec3 out{std::cos(azimuth), 0.f, std::sin(azimuth)};
        const glm::vec3 side = glm::cross(kUp, out);
        const float reach = 0.12f + 0.02f * leaf;
        const glm::vec3 base = kAxis + kUp * (0.08f + 0.05f * leaf);
        for (int i = 0; i <= 60; ++i) {
            const float s = static_cast<float>(i) / 60.f;
            const glm::vec3 spine = base + out * (reach * s) + kUp * (0.1f * s - 0.12f * s * s);
            for (int w = -3; w <= 3; ++w) points.push_back(spine + side * (0.0025f * w));
        }
    }
    return points;
}

// The plant turned by `angle_deg` about the axis (a turntable's view).
ViewCloud turnedView(int frame, float angle_deg) {
    const glm::mat4 turn = glm::translate(glm::mat4(1.f), kAxis) *
                           glm::rotate(glm::mat4(1.f), glm::radians(angle_deg), kUp) *
                           glm::translate(glm::mat4(1.f), -kAxis);
    ViewCloud view;
    view.frame = frame;
    view.up = kUp;
    for (const glm::vec3& p : plant()) view.points_m.emplace_back(turn * glm::vec4(p, 1.f));
    return view;
}

// A view of something else: a flat board 1.5 m away, nothing like the plant.
ViewCloud board(int frame) {
    ViewCloud view;
    view.frame = frame;
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 40; ++x) view.points_m.push_back({0.01f * x, 0.01f * y, 1.5f});
    return view;
}

TEST(ViewRegistration, ATurntablesViewsComeToLieOnTheFirst) {
    std::vector<ViewCloud> views;
    for (int k = 0; k < 4; ++k) views.push_back(turnedView(k, 30.f * k));
    const std::vector<RegisteredView> registered = registerViews(views);
    ASSERT_EQ(registered.size(), 4u);
    for (int k = 1; k < 4; ++k) {
        const RegisteredView& r = registered[static_cast<std::size_t>(k)];
        EXPECT_EQ(r.chain, 0) << r.why;
        EXPECT_TRUE(r.why.empty()) << r.why;
        // The camera's view turned +30 deg, so the view is turned back by 30 deg to the one before.
        EXPECT_NEAR(std::abs(r.turn_deg), 30.f, 1.f) << "frame " << k;
        EXPECT_GT(r.inlierShare, 0.9f);
        // Every reading of view k lands within 3 mm of where it stood in view 0.
        const ViewCloud first = turnedView(0, 0.f);
        float worst = 0.f;
        for (std::size_t i = 0; i < views[k].points_m.size(); i += 37)
            worst = std::max(worst, glm::distance(glm::vec3(r.chainFromView *
                                                            glm::vec4(views[k].points_m[i], 1.f)),
                                                  first.points_m[i]));
        EXPECT_LT(worst, 0.003f) << "frame " << k;
    }
}

TEST(ViewRegistration, AViewOfSomethingElseStartsAChainAndTheNextFallsBackPastIt) {
    const ViewCloud other = board(1);
    const std::vector<RegisteredView> registered =
        registerViews({turnedView(0, 0.f), other, turnedView(2, 60.f)});
    ASSERT_EQ(registered.size(), 3u);
    EXPECT_EQ(registered[1].chain, 1);
    EXPECT_EQ(registered[1].registeredTo, -1);
    EXPECT_NE(registered[1].why.find("came to lie on frame 0's"), std::string::npos)
        << registered[1].why;
    // The plant, turned 60 deg, does not lie on the board but on the view before that.
    EXPECT_EQ(registered[2].chain, 0) << registered[2].why;
    EXPECT_EQ(registered[2].registeredTo, 0);
    EXPECT_NEAR(std::abs(registered[2].turn_deg), 60.f, 1.f);

    // Without falling back, it starts a chain of its own.
    ViewRegistrationParams params;
    params.fallbackViews = 0;
    const std::vector<RegisteredView> alone =
        registerViews({turnedView(0, 0.f), other, turnedView(2, 60.f)}, params);
    EXPECT_EQ(alone[2].chain, 2);
    EXPECT_EQ(alone[2].chainFromView, glm::mat4(1.f));
}

TEST(ViewRegistration, AViewWithoutPlantReadingsIsNotRegistered) {
    ViewCloud empty;
    empty.frame = 1;
    const std::vector<RegisteredView> registered = registerViews({turnedView(0, 0.f), empty});
    ASSERT_EQ(registered.size(), 2u);
    EXPECT_EQ(registered[1].chain, 1);
    EXPECT_NE(registered[1].why.find("too few plant readings"), std::string::npos);
}

// How far (degrees) a view's place in its chain is turned from its true one: the view was the
// plant turned by `angle_deg`, the chain's first view the plant unturned.
float placeError_deg(const RegisteredView& view, float angle_deg) {
    const glm::mat4 trueTurn = glm::translate(glm::mat4(1.f), kAxis) *
                               glm::rotate(glm::mat4(1.f), glm::radians(angle_deg), kUp) *
                               glm::translate(glm::mat4(1.f), -kAxis);
    return glm::degrees(glm::angle(glm::quat_cast(glm::mat3(view.chainFromView * trueTurn))));
}

// Registration that keeps the sweep's turn: ICP pairs only readings 0.1 mm apart (the stem on
// the axis, which every turn leaves in place), and a view 3 deg off still counts as lying on.
ViewRegistrationParams sweepTurnsOnly() {
    ViewRegistrationParams params;
    params.maxPairing_m = 0.0001f;
    params.minInlierShare = 0.3f;
    return params;
}

TEST(ViewRegistration, AChainRoundThePlantSpreadsItsDriftOverItsViews) {
    // The plant turns 33 deg a view; ICP that pairs only readings 0.1 mm apart (the stem on the
    // axis) keeps the sweep's 30 deg, so each view drifts 3 deg further from the truth. The
    // twelfth view (363 deg) lies on the first 3 deg off: closing the loop takes back nearly all
    // of the 33 deg gathered.
    ViewRegistrar registrar(sweepTurnsOnly());
    constexpr int kViews = 12;
    for (int k = 0; k < kViews; ++k) registrar.add(turnedView(k, 33.f * k));
    const std::vector<RegisteredView> chained = registrar.views();
    for (const RegisteredView& v : chained) ASSERT_EQ(v.chain, 0) << v.why;
    EXPECT_GT(placeError_deg(chained.back(), 33.f * (kViews - 1)), 25.f);

    const LoopClosure& loop = registrar.closeLoop();
    EXPECT_TRUE(loop.closed) << loop.why;
    EXPECT_FALSE(loop.joinedChains);
    EXPECT_EQ(loop.firstFrame, 0);
    EXPECT_EQ(loop.lastFrame, kViews - 1);
    EXPECT_NEAR(std::abs(loop.chainTurn_deg), 330.f, 1.f);
    EXPECT_NEAR(loop.drift_deg, 30.f, 1.f);
    for (int k = 1; k < kViews; ++k)
        EXPECT_LT(placeError_deg(registrar.views()[static_cast<std::size_t>(k)], 33.f * k), 4.f)
            << "frame " << k;
}

TEST(ViewRegistration, ALoopClosesPastAViewOfSomethingElse) {
    // As above, with a view of something else halfway: it starts a chain of its own, the next
    // view falls back past it to the first chain, and that chain still closes round the plant.
    const ViewCloud other = board(6);
    ViewRegistrar registrar(sweepTurnsOnly());
    std::vector<float> angle_deg;  // per frame, of the plant
    for (int frame = 0, k = 0; frame < 13; ++frame) {
        if (frame == other.frame) {
            registrar.add(other);
            angle_deg.push_back(0.f);
            continue;
        }
        angle_deg.push_back(33.f * k);
        registrar.add(turnedView(frame, 33.f * k++));
    }
    ASSERT_EQ(registrar.views()[6].chain, 1);
    ASSERT_EQ(registrar.views()[7].chain, 0) << registrar.views()[7].why;
    const LoopClosure& loop = registrar.closeLoop();
    EXPECT_TRUE(loop.closed) << loop.why;
    for (std::size_t frame = 1; frame < 13; ++frame) {
        if (frame == 6) continue;
        EXPECT_LT(placeError_deg(registrar.views()[frame], angle_deg[frame]), 5.f)
            << "frame " << frame;
    }
}

TEST(ViewRegistration, AChainShortOfHalfATurnIsNoLoop) {
    ViewRegistrar registrar;
    for (int k = 0; k < 4; ++k) registrar.add(turnedView(k, 30.f * k));
    const LoopClosure& loop = registrar.closeLoop();
    EXPECT_FALSE(loop.closed);
    EXPECT_NE(loop.why.find("turned"), std::string::npos) << loop.why;
    EXPECT_LT(placeError_deg(registrar.views().back(), 90.f), 1.f);
}

TEST(ViewRegistration, AChainThatEndsWhereTheFirstBeganJoinsIt) {
    // Views at 0 and 30 deg, then something else, then the plant at -30 deg: with no falling
    // back it starts a chain of its own, 30 deg from the first view.
    const ViewCloud other = board(2);
    ViewRegistrationParams params;
    params.fallbackViews = 0;
    ViewRegistrar registrar(params);
    for (const ViewCloud& v :
         {turnedView(0, 0.f), turnedView(1, 30.f), other, turnedView(3, -30.f)})
        registrar.add(v);
    ASSERT_EQ(registrar.views()[3].chain, 2);
    const LoopClosure& loop = registrar.closeLoop();
    EXPECT_TRUE(loop.joinedChains) << loop.why;
    EXPECT_EQ(loop.firstFrame, 0);
    const std::vector<RegisteredView>& views = registrar.views();
    EXPECT_EQ(views[3].chain, 0);
    EXPECT_EQ(views[2].chain, 1);  // the board stays apart
    EXPECT_LT(placeError_deg(views[3], -30.f), 1.f);
}

TEST(ViewRegistration, TheTrueTurnSaysWhetherAPairCanBeRegistered) {
    const ViewCloud before = turnedView(0, 0.f);
    const ViewCloud after = turnedView(1, 30.f);
    const glm::mat4 turnBack = glm::translate(glm::mat4(1.f), kAxis) *
                               glm::rotate(glm::mat4(1.f), glm::radians(-30.f), kUp) *
                               glm::translate(glm::mat4(1.f), -kAxis);
    EXPECT_GT(shareLyingOn(after, before, turnBack), 0.99f);
    EXPECT_LT(shareLyingOn(after, before, glm::mat4(1.f)), 0.5f);  // not turned back

    // A sensor that scatters every other reading 2 cm along its ray: at the true turn only the
    // rest lie on the view before, too few to register the pair.
    ViewCloud scattered = after;
    for (std::size_t i = 0; i < scattered.points_m.size(); i += 2)
        scattered.points_m[i] *= 1.f + 0.02f / glm::length(scattered.points_m[i]);
    const float share = shareLyingOn(scattered, before, turnBack);
    EXPECT_NEAR(share, 0.5f, 0.05f);
    EXPECT_LT(share, ViewRegistrationParams{}.minInlierShare);

    // The share a registered pair reports is this share at its registered turn.
    const std::vector<RegisteredView> registered = registerViews({before, after});
    ASSERT_TRUE(registered[1].why.empty()) << registered[1].why;
    EXPECT_FLOAT_EQ(shareLyingOn(after, before, registered[1].chainFromView),
                    registered[1].inlierShare);
}

TEST(ViewRegistration, UnusableParametersAreRefused) {
    ViewRegistrationParams params;
    params.sweepStep_deg = 0.f;
    EXPECT_NE(params.problem(), "");
    EXPECT_THROW(registerViews({}, params), CaptureError);
    params = {};
    params.minInlierShare = 1.5f;
    EXPECT_NE(params.problem(), "");
    params = {};
    params.fallbackViews = -1;
    EXPECT_THROW(ViewRegistrar{params}, CaptureError);
    EXPECT_THROW(shareLyingOn(turnedView(0, 0.f), turnedView(1, 0.f), glm::mat4(1.f), params),
                 CaptureError);
}

}  // namespace
}  // namespace meadow::capture
