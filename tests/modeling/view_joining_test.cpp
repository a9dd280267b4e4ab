// A turning plant's archetypes of one leaf joined across its registered views (view_joining.h).
#include "meadow/modeling/view_joining.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace meadow::modeling {
namespace {

// The turn of view 1 against view 0 (chain space = view 0's camera).
const glm::mat4 kTurn = glm::translate(glm::mat4(1.f), {0.f, 0.1f, 0.8f}) *
                        glm::rotate(glm::mat4(1.f), glm::radians(30.f), {0.f, -1.f, 0.f}) *
                        glm::translate(glm::mat4(1.f), {0.f, -0.1f, -0.8f});

// A straight archetype of `length_m` from `root` along `direction`, given in chain space and
// placed in the camera of `frame` (chainFromView of that frame).
Archetype leaf(const std::string& name, int frame, const glm::mat4& chainFromView, glm::vec3 root,
               glm::vec3 direction, float length_m) {
    Archetype a;
    a.name = name;
    a.spine_m = {{0.f, 0.f, 0.f}, {0.f, 0.5f * length_m, 0.f}, {0.f, length_m, 0.f}};
    // Blade-local +Y along `direction`.
    const glm::vec3 y = glm::normalize(direction);
    const glm::vec3 x = glm::normalize(glm::cross(y, glm::vec3(0.f, 0.f, 1.f)));
    const glm::vec3 z = glm::cross(x, y);
    glm::mat4 chainFromBlade(glm::vec4(x, 0.f), glm::vec4(y, 0.f), glm::vec4(z, 0.f),
                             glm::vec4(root, 1.f));
    a.source.frame = frame;
    a.source.bladeId = static_cast<int>(name.back());
    a.source.placed = true;
    a.source.cameraFromBlade = glm::inverse(chainFromView) * chainFromBlade;
    return a;
}

std::vector<capture::RegisteredView> twoViews(int secondChain = 0) {
    capture::RegisteredView first, second;
    first.frame = 0;
    second.frame = 1, second.chain = secondChain, second.chainFromView = kTurn;
    return {first, second};
}

// Two views, and a third at the second turn against the first.
std::vector<capture::RegisteredView> threeViews() {
    std::vector<capture::RegisteredView> views = twoViews();
    capture::RegisteredView third;
    third.frame = 2, third.chainFromView = kTurn * kTurn;
    views.push_back(third);
    return views;
}

const glm::vec3 kRoot{0.f, 0.f, 0.8f};
const glm::vec3 kLeft{-1.f, -1.f, 0.f}, kRight{1.f, -1.f, 0.2f};

TEST(ViewJoining, OneLeafSeenInThreeViewsIsKeptOnceAtTheLengthTwoOfThemShow) {
    const std::vector<capture::RegisteredView> views = threeViews();
    std::vector<Archetype> archetypes{
        leaf("a0", 0, glm::mat4(1.f), kRoot, kLeft, 0.12f),  // the left leaf, cut short
        leaf("b0", 0, glm::mat4(1.f), kRoot, kRight, 0.15f),
        leaf("a1", 1, kTurn, kRoot, kLeft, 0.2f),  // the left leaf whole, seen turned
        leaf("a2", 2, kTurn * kTurn, kRoot, kLeft, 0.19f),
    };
    EXPECT_EQ(joinSameLeafAcrossViews(archetypes, views).leftOut, 2);
    ASSERT_EQ(archetypes.size(), 2u);
    EXPECT_EQ(archetypes[0].name, "b0");
    EXPECT_EQ(archetypes[1].name, "a1");
    ASSERT_EQ(archetypes[1].source.alsoSeenIn.size(), 2u);
    EXPECT_EQ(archetypes[1].source.alsoSeenIn[0].frame, 2);
    EXPECT_EQ(archetypes[1].source.alsoSeenIn[1].frame, 0);
    EXPECT_TRUE(archetypes[0].source.alsoSeenIn.empty());
}

TEST(ViewJoining, ALengthNoOtherViewNearlyShowsIsKeptForNoOther) {
    // View 1's archetype runs 0.3 m along the leaf (as one running on into another leaf would):
    // no other view shows 80 % of that, so view 0's 0.12 m piece is not left out for it. Seen
    // again in view 2 at 0.11 m, the piece is confirmed and view 2's is left out for it.
    const std::vector<capture::RegisteredView> views = threeViews();
    std::vector<Archetype> archetypes{leaf("a0", 0, glm::mat4(1.f), kRoot, kLeft, 0.12f),
                                      leaf("f1", 1, kTurn, kRoot, kLeft, 0.3f)};
    EXPECT_EQ(joinSameLeafAcrossViews(archetypes, views).leftOut, 0);
    EXPECT_EQ(archetypes.size(), 2u);
    archetypes.push_back(leaf("a2", 2, kTurn * kTurn, kRoot, kLeft, 0.11f));
    EXPECT_EQ(joinSameLeafAcrossViews(archetypes, views).leftOut, 1);
    ASSERT_EQ(archetypes.size(), 2u);
    EXPECT_EQ(archetypes[0].name, "a0");
    EXPECT_EQ(archetypes[1].name, "f1");
}

TEST(ViewJoining, LeavesOfOneBaseThatPartAreBothKept) {
    // Two leaves from one root, 20 deg apart: their upper parts lie 25-60 mm apart.
    const glm::vec3 turned{std::sin(glm::radians(20.f)) - 1.f, -1.f, 0.f};
    std::vector<Archetype> archetypes{leaf("a0", 0, glm::mat4(1.f), kRoot, kLeft, 0.2f),
                                      leaf("c1", 1, kTurn, kRoot, turned, 0.2f)};
    EXPECT_EQ(joinSameLeafAcrossViews(archetypes, twoViews()).leftOut, 0);
    EXPECT_EQ(archetypes.size(), 2u);
}

TEST(ViewJoining, ViewsOfTwoChainsOrUnregisteredFramesAreNeverJoined) {
    std::vector<Archetype> archetypes{leaf("a0", 0, glm::mat4(1.f), kRoot, kLeft, 0.18f),
                                      leaf("a1", 1, kTurn, kRoot, kLeft, 0.2f)};
    const ViewJoinResult apart = joinSameLeafAcrossViews(archetypes, twoViews(1));
    EXPECT_EQ(apart.leftOut, 0);
    EXPECT_EQ(archetypes.size(), 2u);
    // Each alone in its chain: no other view could have shown it.
    EXPECT_TRUE(apart.seenOnce.empty());
    // Frame 2 was not among the registered views.
    archetypes.push_back(leaf("a2", 2, glm::mat4(1.f), kRoot, kLeft, 0.3f));
    EXPECT_EQ(joinSameLeafAcrossViews(archetypes, twoViews()).leftOut, 1);
    ASSERT_EQ(archetypes.size(), 2u);
    EXPECT_EQ(archetypes[0].name, "a1");
    EXPECT_EQ(archetypes[1].name, "a2");
}

TEST(ViewJoining, AnArchetypeNoOtherViewShowsIsToldApart) {
    // The left leaf in three views, and in view 0 a blade along nothing another view shows; the
    // unregistered frame 3's blade is not judged.
    const std::vector<capture::RegisteredView> views = threeViews();
    std::vector<Archetype> archetypes{
        leaf("b0", 0, glm::mat4(1.f), kRoot, kRight, 0.15f),
        leaf("a0", 0, glm::mat4(1.f), kRoot, kLeft, 0.19f),
        leaf("a1", 1, kTurn, kRoot, kLeft, 0.2f),
        leaf("a2", 2, kTurn * kTurn, kRoot, kLeft, 0.12f),
        leaf("d3", 3, glm::mat4(1.f), kRoot, kRight, 0.1f),
    };
    const ViewJoinResult joined = joinSameLeafAcrossViews(archetypes, views);
    EXPECT_EQ(joined.leftOut, 2);
    ASSERT_EQ(archetypes.size(), 3u);
    ASSERT_EQ(joined.seenOnce.size(), 1u);
    EXPECT_EQ(archetypes[joined.seenOnce[0]].name, "b0");
    // Two leaves that part are each seen once.
    const glm::vec3 turned{std::sin(glm::radians(20.f)) - 1.f, -1.f, 0.f};
    archetypes = {leaf("a0", 0, glm::mat4(1.f), kRoot, kLeft, 0.2f),
                  leaf("c1", 1, kTurn, kRoot, turned, 0.2f)};
    EXPECT_EQ(joinSameLeafAcrossViews(archetypes, twoViews()).seenOnce,
              (std::vector<std::size_t>{0, 1}));
}

}  // namespace
}  // namespace meadow::modeling
