#pragma once
// An enum's names, written once: the name of each value for files, messages and options, and
// the value of each name when reading them back.
#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace meadow {

template <class Enum, std::size_t N>
class EnumNames {
public:
    struct Entry {
        Enum value;
        std::string_view name;
    };
    constexpr explicit EnumNames(std::array<Entry, N> entries) : entries_(entries) {}

    // Every value an enum can hold must be listed: an unlisted one is a bug in meadow.
    [[nodiscard]] constexpr std::string_view name(Enum value) const {
        for (const Entry& e : entries_)
            if (e.value == value) return e.name;
        throw std::logic_error("EnumNames: a value without a name");
    }
    [[nodiscard]] constexpr std::optional<Enum> parse(std::string_view name) const {
        for (const Entry& e : entries_)
            if (e.name == name) return e.value;
        return std::nullopt;
    }
    // The names in table order, for option checks.
    [[nodiscard]] std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const Entry& e : entries_) out.emplace_back(e.name);
        return out;
    }
    // "a, b, c": the names for a message.
    [[nodiscard]] std::string list(std::string_view separator = ", ") const {
        std::string out;
        for (const Entry& e : entries_) {
            if (!out.empty()) out += separator;
            out += e.name;
        }
        return out;
    }

private:
    std::array<Entry, N> entries_;
};

}  // namespace meadow
