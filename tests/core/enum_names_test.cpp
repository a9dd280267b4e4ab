#include "meadow/core/enum_names.h"

#include <gtest/gtest.h>

namespace meadow {
namespace {

enum class Colour { Red, Green };
constexpr EnumNames<Colour, 2> kColourNames{{{{Colour::Red, "red"}, {Colour::Green, "green"}}}};

TEST(EnumNames, NamesAndParsesBothWays) {
    static_assert(kColourNames.name(Colour::Green) == "green");
    EXPECT_EQ(kColourNames.parse("red"), Colour::Red);
    EXPECT_EQ(kColourNames.parse("blue"), std::nullopt);
    EXPECT_EQ(kColourNames.names(), (std::vector<std::string>{"red", "green"}));
    EXPECT_EQ(kColourNames.list(), "red, green");
    EXPECT_THROW((void)kColourNames.name(static_cast<Colour>(7)), std::logic_error);
}

}  // namespace
}  // namespace meadow
